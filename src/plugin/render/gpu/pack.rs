//! Packing a scene's parts into the uniform and the scene data buffer: objects, walls,
//! culling masks, meshes, materials and textures, in the shader's order and layout.

use super::*;

/// What the scene data buffer was packed from: the meshes and textures (by identity) and
/// the materials (by value), and the root node of each mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct DataSources {
    pub(super) meshes: Vec<usize>,
    pub(super) textures: Vec<usize>,
    pub(super) materials: Vec<crate::scene::SurfaceMaterial>,
    pub(super) roots: Vec<u32>,
}

impl DataSources {
    /// Packed from nothing (a scene without meshes, textures or materials).
    pub(super) fn empty() -> Self {
        Self {
            meshes: Vec::new(),
            textures: Vec::new(),
            materials: Vec::new(),
            roots: Vec::new(),
        }
    }

    pub(super) fn of(scene: &CurvedScene, roots: Vec<u32>) -> Self {
        Self {
            meshes: scene
                .meshes
                .iter()
                .map(|m| Arc::as_ptr(m) as usize)
                .collect(),
            textures: scene
                .textures
                .iter()
                .map(|t| Arc::as_ptr(t) as usize)
                .collect(),
            materials: scene.materials.clone(),
            roots,
        }
    }

    /// Whether `scene` would pack to the same data.
    pub(super) fn same_as(&self, scene: &CurvedScene) -> bool {
        self.meshes.len() == scene.meshes.len()
            && self.textures.len() == scene.textures.len()
            && self.materials == scene.materials
            && scene
                .meshes
                .iter()
                .zip(&self.meshes)
                .all(|(m, &p)| Arc::as_ptr(m) as usize == p)
            && scene
                .textures
                .iter()
                .zip(&self.textures)
                .all(|(t, &p)| Arc::as_ptr(t) as usize == p)
    }
}

/// The object lists of each kind as the GPU holds them: indices into the scene's objects,
/// balls, tubes, globes, discs, mesh instances.
pub(super) fn kind_lists(scene: &CurvedScene, padded: bool) -> [Vec<usize>; 5] {
    let mut lists: [Vec<usize>; 5] = Default::default();
    for (i, o) in scene.objects.iter().enumerate() {
        lists[gpu_kind(o) as usize].push(i);
    }
    if padded {
        for list in &mut lists {
            if let Some(&last) = list.last() {
                list.resize(padded_count(list.len()), last);
            }
        }
    }
    lists
}

/// The count a padded list of `n` objects is given: the next power of two, at least 4.
/// The shader is specialised on the counts, so a scene whose moving objects gain and lose
/// images near the faces keeps its compiled pipeline while its counts stay within one step.
#[must_use]
pub fn padded_count(n: usize) -> usize {
    if n == 0 {
        0
    } else {
        n.next_power_of_two().max(4)
    }
}

/// `x` rounded to an f32 no larger (`down`) or no smaller than it: node boxes stay
/// conservative in f32.
pub(super) fn f32_rounded(x: f64, down: bool) -> f32 {
    let y = x as f32;
    match (down, f64::from(y).partial_cmp(&x)) {
        (true, Some(std::cmp::Ordering::Greater)) => y.next_down(),
        (false, Some(std::cmp::Ordering::Less)) => y.next_up(),
        _ => y,
    }
}

/// Packs the meshes, materials and textures into the scene data buffer (the texels of
/// the textures past the first [`super::TEXTURE_SLOTS`], which are GPU textures); returns it with
/// the offsets of its parts (triangles, materials, texture table, texels, in vec4) and each
/// mesh's root node.
pub(super) fn pack_scene_data(scene: &CurvedScene) -> (Vec<u32>, [u32; 4], Vec<u32>) {
    let f = |x: f64| (x as f32).to_bits();
    let node_count: usize = scene.meshes.iter().map(|m| m.nodes.len()).sum();
    let tri_count: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();
    let mut data = Vec::with_capacity(8 * node_count + 32 * tri_count + 64);
    let mut roots = Vec::with_capacity(scene.meshes.len());
    let (mut node_base, mut tri_base) = (0u32, 0u32);
    for mesh in &scene.meshes {
        roots.push(node_base);
        for n in &mesh.nodes {
            let index = if n.count > 0 {
                n.index + tri_base
            } else {
                n.index + node_base
            };
            let (lo, hi) = (n.bounds.min, n.bounds.max);
            data.extend([
                f32_rounded(lo.x, true).to_bits(),
                f32_rounded(lo.y, true).to_bits(),
                f32_rounded(lo.z, true).to_bits(),
                index,
            ]);
            data.extend([
                f32_rounded(hi.x, false).to_bits(),
                f32_rounded(hi.y, false).to_bits(),
                f32_rounded(hi.z, false).to_bits(),
                n.count,
            ]);
        }
        node_base += mesh.nodes.len() as u32;
        tri_base += mesh.triangles.len() as u32;
    }
    let triangles = (data.len() / 4) as u32;
    for mesh in &scene.meshes {
        for t in &mesh.triangles {
            let [a, b, c] = t.corners;
            data.extend([f(a.x), f(a.y), f(a.z), t.material]);
            for e in [b - a, c - a] {
                data.extend([f(e.x), f(e.y), f(e.z), 0]);
            }
            for n in t.normals {
                data.extend([f(n.x), f(n.y), f(n.z), 0]);
            }
            let [u0, u1, u2] = t.uvs;
            data.extend([f(u0.x), f(u0.y), f(u1.x), f(u1.y)]);
            data.extend([f(u2.x), f(u2.y), 0, 0]);
        }
    }
    let materials = (data.len() / 4) as u32;
    for m in &scene.materials {
        let c = m.colour;
        data.extend([f(c.x), f(c.y), f(c.z), m.texture.unwrap_or(u32::MAX)]);
        let e = m.emission;
        data.extend([f(e.x), f(e.y), f(e.z), f(m.reflectance)]);
    }
    // The first TEXTURE_SLOTS textures are GPU textures of their own (their slot in the
    // table's last word); any further ones keep their texels in this buffer (u32::MAX).
    let table = (data.len() / 4) as u32;
    let mut texel_offset = 0u32;
    for (i, t) in scene.textures.iter().enumerate() {
        if i < super::TEXTURE_SLOTS {
            data.extend([0, t.width, t.height, i as u32]);
        } else {
            data.extend([texel_offset, t.width, t.height, u32::MAX]);
            texel_offset += t.texels.len() as u32;
        }
    }
    let texels = (data.len() / 4) as u32;
    for t in scene.textures.iter().skip(super::TEXTURE_SLOTS) {
        data.extend_from_slice(&t.texels);
    }
    data.resize(data.len().div_ceil(4).max(1) * 4, 0);
    (data, [triangles, materials, table, texels], roots)
}

/// Appends the walls: per face the unit covector, the colour with `S(w)` of the margin, the
/// opacity and whether it is a mirror; then the share of light below which a ray stops.
pub(super) fn pack_walls(out: &mut UniformWriter, walls: &WallPanels) {
    for face in &walls.faces {
        out.push(&vec4(face.unit));
    }
    for face in &walls.faces {
        out.push(&colour(face.colour, face.margin));
    }
    for face in &walls.faces {
        out.push(&vec4(DVec4::new(
            face.opacity,
            if face.mirror { 1.0 } else { 0.0 },
            0.0,
            0.0,
        )));
    }
    out.push(&vec4(DVec4::new(walls.stop_below, 0.0, 0.0, 0.0)));
}

/// Appends the culling's per-face thresholds (rounded up to f32, four to a `vec4`) and the
/// masks of the balls, then the tubes (a `u32` each, four to a `vec4`), in the GPU's order.
pub(super) fn pack_culling(
    out: &mut UniformWriter,
    lists: [&[usize]; 2],
    culling: &FaceCulling,
    faces: usize,
    list_vecs: usize,
) {
    let mut thresholds: Vec<u32> = (0..4 * faces.div_ceil(4))
        .map(|f| {
            culling
                .thresholds
                .get(f)
                .map_or(0, |&t| f32_rounded(t, false).to_bits())
        })
        .collect();
    out.words.append(&mut thresholds);
    let of_kind = |list: &[usize]| -> Vec<u32> { list.iter().map(|&i| culling.masks[i]).collect() };
    let (balls, tubes) = (of_kind(lists[0]), of_kind(lists[1]));
    let mut masks: Vec<u32> = balls.iter().chain(&tubes).copied().collect();
    masks.resize(4 * masks.len().div_ceil(4), 0);
    out.words.append(&mut masks);
    // The object lists: an object whose mask names two faces or more is in the bucket of
    // one pair f < g of them (bucket g(g−1)/2 + f; the emptiest so far, to balance them),
    // the rest in the last bucket. A segment visits the buckets of the pairs of faces it
    // comes near and the last: the tube along the edge between the faces it enters and
    // leaves by is visited alone.
    let culled = faces.min(MAX_CULLED_FACES);
    let buckets = cull_buckets(faces);
    // A padding copy of an object (the same scene index again, [`GpuScene::reusing`]) is in
    // no list: it is never the nearest hit, and testing it costs as much as the original
    // (with one entity's ball added, the default Seifert–Weber scene's 22 balls are padded
    // to 32: ten copies of that ball, which were all tested in every cell).
    let bucketed = |masks: &[u32], objects: &[usize]| -> Vec<Vec<u32>> {
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); buckets];
        for (i, &m) in masks.iter().enumerate() {
            if i > 0 && objects[i] == objects[i - 1] {
                continue;
            }
            let bits: Vec<usize> = (0..culled).filter(|&f| m & (1 << f) != 0).collect();
            let b = bits
                .iter()
                .enumerate()
                .flat_map(|(k, &f)| bits[k + 1..].iter().map(move |&g| g * (g - 1) / 2 + f))
                .min_by_key(|&pair| lists[pair].len())
                .unwrap_or(buckets - 1);
            lists[b].push(i as u32);
        }
        lists
    };
    let lists = [bucketed(&balls, lists[0]), bucketed(&tubes, lists[1])];
    let mut words: Vec<u32> = Vec::new();
    let mut at = 2 * (buckets as u32 + 1);
    for kind in &lists {
        for list in kind {
            words.push(at);
            at += list.len() as u32;
        }
        words.push(at);
    }
    for kind in &lists {
        words.extend(kind.iter().flatten());
    }
    // The lists' full size (ShaderKey::list_vecs), copies left out or not.
    words.resize(4 * list_vecs, 0);
    out.words.append(&mut words);
}

/// Buckets of the culling's object lists for a cell of `faces` faces: one per pair f < g
/// of the faces masks name, and one for the objects whose mask names fewer than two.
#[must_use]
pub fn cull_buckets(faces: usize) -> usize {
    let f = faces.min(MAX_CULLED_FACES);
    f * f.saturating_sub(1) / 2 + 1
}

/// Appends the objects' arrays to the uniform, kind by kind (balls, tubes, globes, discs,
/// mesh instances), each element a typed struct of [`super::layout`].
pub(super) fn pack_objects(
    out: &mut UniformWriter,
    g: Geometry,
    kinds: [&[&Object]; 5],
    roots: &[u32],
) {
    let [balls, tubes, globes, discs, instances] = kinds;
    let size = |r: f64| match g {
        Geometry::Euclidean => r,
        _ => g.cs(r).0,
    };
    for o in balls {
        if let Object::Ball(ball) = o {
            out.push(&GpuBall {
                centre: vec4(ball.centre),
                colour: colour(ball.colour, size(ball.radius)),
                emission: colour(ball.emission, ball.reflectance),
            });
        }
    }
    for o in tubes {
        if let Object::Tube(tube) = o {
            let (c, s) = tube.cs_length();
            out.push(&GpuTube {
                a: vec4(tube.a),
                towards_b: vec4(tube.towards_b()),
                colour: colour(tube.colour, size(tube.radius).powi(2)),
                length: vec4(DVec4::new(c, s, 0.0, 0.0)),
                emission: colour(tube.emission, 0.0),
            });
        }
    }
    for o in globes {
        if let Object::Ball(ball) = o
            && let Some(t) = ball.texture
        {
            out.push(&GpuGlobe {
                centre: vec4(ball.centre),
                colour: colour(ball.colour, size(ball.radius)),
                emission: colour(ball.emission, f64::from(t.texture)),
                spin: vec4(DVec4::new(t.spin, ball.reflectance, 0.0, 0.0)),
                inverse: mat4(g.inverse(t.frame)),
            });
        }
    }
    for o in discs {
        if let Object::Disc(disc) = o {
            out.push(&GpuDisc {
                centre: vec4(disc.centre),
                normal: vec4(disc.normal),
                covector: vec4(disc.covector(g)),
                colour: colour(disc.colour, disc.radius),
                emission: colour(disc.emission, disc.reflectance),
            });
        }
    }
    for o in instances {
        if let Object::Mesh(m) = o {
            out.push(&GpuInstance {
                frame: mat4(m.frame),
                inverse: mat4(m.inverse),
                info: [
                    roots.get(m.mesh as usize).copied().unwrap_or(0),
                    m.material.unwrap_or(u32::MAX),
                    m.material_base,
                    0,
                ],
            });
        }
    }
}
