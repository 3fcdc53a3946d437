//! What the WGSL tracer needs, packed for its uniform: the shader key (geometry, face count,
//! object kinds and counts → shader defs) and the words of `SpaceUniform` in
//! `shaders/curved_space.wgsl`, in the same order and layout.
//!
//! Every member of the WGSL struct is a `vec4` or a `mat4x4` (or an array of them), so the
//! layout has no padding: the buffer is the members' components one after another.

use super::layout::{
    AVATAR_SLOTS, GpuBall, GpuDisc, GpuGlobe, GpuInstance, GpuShading, GpuTube, GpuView, Mat4F,
    UniformWriter, Vec4F, colour, mat4, vec4,
};
use crate::geometry::Geometry;
use crate::scene::culling::MAX_CULLED_FACES;
use crate::scene::{CurvedScene, FaceCulling, Object, WallPanels};
use crate::space::{CellWalker, Space};
use crate::view::{ViewKind, ViewLayout};
use bevy::shader::ShaderDefVal;
use glam::{DMat4, DVec4, Mat4, Vec4};
use std::sync::Arc;

mod key;
mod nil;
mod pack;
mod product;
mod sl2r;
mod view;

pub use key::{GENERAL_CAPACITY, ShaderKey};
#[cfg(feature = "bench")]
pub use key::{compose_wgsl, undecorated};

use pack::*;
pub use pack::{cull_buckets, padded_count};
pub use view::{ViewExtras, view_shader_defs, view_words};

/// The WGSL source of the tracer's entry points; it `#import`s the [`SHADER_MODULES`].
pub const TRACER_WGSL: &str = include_str!("../../../../shaders/curved_space.wgsl");

/// The tracer's WGSL modules (`#define_import_path curved_spaces::…`), each the twin of a
/// Rust module, in the order they import each other: the plugin registers them all, so a
/// game that embeds the crate needs no shader files.
pub const SHADER_MODULES: [(&str, &str); 20] = [
    (
        "shaders/layout.wgsl",
        include_str!("../../../../shaders/layout.wgsl"),
    ),
    (
        "shaders/geometry.wgsl",
        include_str!("../../../../shaders/geometry.wgsl"),
    ),
    (
        "shaders/object.wgsl",
        include_str!("../../../../shaders/object.wgsl"),
    ),
    (
        "shaders/texture.wgsl",
        include_str!("../../../../shaders/texture.wgsl"),
    ),
    (
        "shaders/mesh.wgsl",
        include_str!("../../../../shaders/mesh.wgsl"),
    ),
    (
        "shaders/hit_id.wgsl",
        include_str!("../../../../shaders/hit_id.wgsl"),
    ),
    (
        "shaders/walk.wgsl",
        include_str!("../../../../shaders/walk.wgsl"),
    ),
    (
        "shaders/culling.wgsl",
        include_str!("../../../../shaders/culling.wgsl"),
    ),
    (
        "shaders/scene.wgsl",
        include_str!("../../../../shaders/scene.wgsl"),
    ),
    (
        "shaders/lighting.wgsl",
        include_str!("../../../../shaders/lighting.wgsl"),
    ),
    (
        "shaders/shading.wgsl",
        include_str!("../../../../shaders/shading.wgsl"),
    ),
    (
        "shaders/walls.wgsl",
        include_str!("../../../../shaders/walls.wgsl"),
    ),
    (
        "shaders/trace.wgsl",
        include_str!("../../../../shaders/trace.wgsl"),
    ),
    (
        "shaders/product_walk.wgsl",
        include_str!("../../../../shaders/product_walk.wgsl"),
    ),
    (
        "shaders/product_objects.wgsl",
        include_str!("../../../../shaders/product_objects.wgsl"),
    ),
    (
        "shaders/product.wgsl",
        include_str!("../../../../shaders/product.wgsl"),
    ),
    (
        "shaders/nil_geometry.wgsl",
        include_str!("../../../../shaders/nil_geometry.wgsl"),
    ),
    (
        "shaders/nil.wgsl",
        include_str!("../../../../shaders/nil.wgsl"),
    ),
    (
        "shaders/sl2r_geometry.wgsl",
        include_str!("../../../../shaders/sl2r_geometry.wgsl"),
    ),
    (
        "shaders/sl2r.wgsl",
        include_str!("../../../../shaders/sl2r.wgsl"),
    ),
];

/// The WGSL source of the upscaling pass (the resolution scale).
pub const UPSCALE_WGSL: &str = include_str!("../../../../shaders/upscale.wgsl");

/// wgpu's default `max_uniform_buffer_binding_size`: the tracer's data must fit in it.
pub const MAX_UNIFORM_BYTES: usize = 64 << 10;

/// wgpu's default `max_storage_buffer_binding_size`: the scene data (meshes, and the
/// textures past the first [`TEXTURE_SLOTS`]) must fit in it.
pub const MAX_SCENE_DATA_BYTES: usize = 128 << 20;

/// The scene's textures that the GPU reads from textures of their own (bindings 2 to 9,
/// `texture_2d<f32>`, RGBA8 unorm, read texel by texel and filtered as the CPU does):
/// each may be as large as a GPU's 2D texture (8192 texels a side is guaranteed), beyond
/// the storage buffer's guaranteed 128 MiB. Further textures keep their texels in the
/// scene data buffer.
pub const TEXTURE_SLOTS: usize = 8;

/// The largest crossing budget the GPU tracer takes: every loop of the shader is bounded by
/// it (and by the face and object counts), so no frame can run away.
pub const MAX_GPU_BUDGET: u32 = 4096;

/// Words of the per-view part at the start of the uniform ([`GpuView`]).
pub const VIEW_WORDS: usize = size_of::<GpuView>() / 4;

/// The scene cannot be given to the GPU tracer.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GpuSceneError {
    /// The scene needs `bytes` bytes of uniform data (`faces` faces, `objects` objects with their images, `lights` lights), more than the `limit` bytes a GPU is guaranteed to bind.
    #[error(
        "the scene needs {bytes} bytes of uniform data ({faces} faces, {objects} objects with their images, {lights} lights), more than the {limit} bytes a GPU is guaranteed to bind; show fewer objects"
    )]
    TooLarge {
        bytes: usize,
        limit: usize,
        faces: u32,
        objects: usize,
        lights: u32,
    },
    /// The scene's meshes and the textures past the first [`TEXTURE_SLOTS`] need `bytes` bytes (`triangles` triangles), more than the `limit` bytes a GPU is guaranteed to bind.
    #[error(
        "the scene's meshes and textures need {bytes} bytes ({triangles} triangles), more than the {limit} bytes a GPU is guaranteed to bind; use smaller meshes, or fewer or smaller textures (the first {TEXTURE_SLOTS} are GPU textures of their own, up to 8192 texels a side; the rest share this buffer with the meshes)"
    )]
    DataTooLarge {
        bytes: usize,
        limit: usize,
        triangles: usize,
    },
    /// The crossing budget must be at least 1 (the budget given is attached).
    #[error("the crossing budget must be at least 1, got {0}")]
    NoCrossings(u32),
    /// The crossing budget (attached) is more than the GPU tracer takes, [`MAX_GPU_BUDGET`]: a frame could run for seconds.
    #[error(
        "a crossing budget of {0} is more than the GPU tracer takes ({MAX_GPU_BUDGET}): a frame could run for seconds; the fog ends rays long before"
    )]
    BudgetTooLarge(u32),
}

/// A crossing budget the GPU tracer takes: 1 to [`MAX_GPU_BUDGET`].
fn check_budget(max_crossings: u32) -> Result<(), GpuSceneError> {
    if max_crossings == 0 {
        return Err(GpuSceneError::NoCrossings(max_crossings));
    }
    if max_crossings > MAX_GPU_BUDGET {
        return Err(GpuSceneError::BudgetTooLarge(max_crossings));
    }
    Ok(())
}

/// The kinds of the GPU's object lists, in their order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum GpuKind {
    Ball,
    Tube,
    Globe,
    Disc,
    Instance,
}

fn gpu_kind(o: &Object) -> GpuKind {
    match o {
        Object::Ball(b) if b.texture.is_some() => GpuKind::Globe,
        Object::Ball(_) => GpuKind::Ball,
        Object::Tube(_) => GpuKind::Tube,
        Object::Disc(_) => GpuKind::Disc,
        Object::Mesh(_) => GpuKind::Instance,
    }
}

/// The index each scene object has in the shader's lists, which [`GpuScene::new`] fills with
/// the plain balls first, then the tubes, the textured balls (globes), the discs and the
/// meshes, each in scene order (the `HIT_ID` output reports it). The avatar's images come
/// after all of them, as in [`crate::trace::SceneHit::object`].
#[must_use]
pub fn gpu_object_indices(scene: &CurvedScene) -> Vec<u32> {
    let kinds: Vec<GpuKind> = scene.objects.iter().map(gpu_kind).collect();
    kinds
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let before = kinds.iter().filter(|x| *x < k).count();
            let same = kinds[..i].iter().filter(|x| *x == k).count();
            (before + same) as u32
        })
        .collect()
}

/// The avatar as the GPU draws it: its mesh's root node and the distance within which its
/// hits are passed through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GpuAvatar {
    /// Index into the scene's meshes.
    pub mesh: u32,
    /// The root node of its mesh in the scene data.
    pub root: u32,
    /// Its bounding radius.
    pub radius: f64,
    /// Hits nearer than this to the eye are passed through.
    pub skip: f64,
}

/// A space and its scene, packed for the GPU (everything but the per-view camera part).
#[derive(Clone, Debug, PartialEq)]
pub struct GpuScene {
    /// The shader variant it needs.
    pub key: ShaderKey,
    /// The words of `SpaceUniform` after `view`.
    pub words: Vec<u32>,
    /// The scene data buffer (`scene_data`): hierarchy nodes, triangles, materials, the
    /// texture table and texels. At least one vec4, so it can always be bound. Shared
    /// with the scene it was packed for when only objects moved ([`GpuScene::reusing`]):
    /// the GPU keeps its buffer then.
    pub data: Arc<Vec<u32>>,
    /// The textures bound as GPU textures, slot by slot (the first [`TEXTURE_SLOTS`] of the
    /// scene's); shared with the scene data like `data`.
    pub textures: Arc<Vec<Arc<crate::scene::texture::Texture>>>,
    /// The player's ship, if the scene draws it.
    pub avatar: Option<GpuAvatar>,
    /// What `data` was packed from and each mesh's root node.
    sources: DataSources,
}

impl GpuScene {
    /// Packs a space and a scene with a crossing budget per ray.
    pub fn new(
        space: &Space,
        scene: &CurvedScene,
        max_crossings: u32,
    ) -> Result<Self, GpuSceneError> {
        Self::build(space, scene, max_crossings, None, false)
    }

    /// Packs a scene whose objects move (the plugin's entities): the scene data of
    /// `previous` is shared when the meshes, materials and textures are the same ones
    /// (moving an object rewrites its instance, not its mesh), and each object list is
    /// padded to [`padded_count`] with copies of its last object (never the nearest hit:
    /// the original comes first; the culling's lists leave them out), so that the shader's
    /// counts change rarely.
    pub fn reusing(
        space: &Space,
        scene: &CurvedScene,
        max_crossings: u32,
        previous: Option<&GpuScene>,
    ) -> Result<Self, GpuSceneError> {
        Self::build(space, scene, max_crossings, previous, true)
    }

    fn build(
        space: &Space,
        scene: &CurvedScene,
        max_crossings: u32,
        previous: Option<&GpuScene>,
        padded: bool,
    ) -> Result<Self, GpuSceneError> {
        check_budget(max_crossings)?;
        let g = space.geometry;
        let lists = kind_lists(scene, padded);
        let of_kind = |k: GpuKind| -> Vec<&Object> {
            lists[k as usize]
                .iter()
                .map(|&i| &scene.objects[i])
                .collect()
        };
        let (balls, tubes, globes, discs, instances) = (
            of_kind(GpuKind::Ball),
            of_kind(GpuKind::Tube),
            of_kind(GpuKind::Globe),
            of_kind(GpuKind::Disc),
            of_kind(GpuKind::Instance),
        );
        let (data, textures, offsets, sources) = match previous {
            Some(p) if p.sources.same_as(scene) => (
                p.data.clone(),
                p.textures.clone(),
                p.offsets(),
                p.sources.clone(),
            ),
            _ => {
                let (data, offsets, roots) = pack_scene_data(scene);
                let textures = scene.textures.iter().take(TEXTURE_SLOTS).cloned().collect();
                (
                    Arc::new(data),
                    Arc::new(textures),
                    offsets,
                    DataSources::of(scene, roots),
                )
            }
        };
        let roots = &sources.roots;
        if 4 * data.len() > MAX_SCENE_DATA_BYTES {
            return Err(GpuSceneError::DataTooLarge {
                bytes: 4 * data.len(),
                limit: MAX_SCENE_DATA_BYTES,
                triangles: scene.meshes.iter().map(|m| m.triangles.len()).sum(),
            });
        }
        let culling = FaceCulling::new(space, scene);
        let walls = scene
            .shading
            .walls
            .and_then(|style| WallPanels::new(space, style, &scene.shading));
        let lighting = scene.shading.lighting;
        let summed = lighting.paths == crate::scene::LightPaths::Images;
        let images_of = |l: &crate::scene::Light| {
            if summed {
                l.cover.clone()
            } else {
                l.images.clone()
            }
        };
        let light_images = scene
            .lights
            .iter()
            .map(|l| images_of(l).len())
            .max()
            .unwrap_or(0) as u32;
        let key = ShaderKey {
            geometry: g,
            faces: space.faces.len() as u32,
            balls: balls.len() as u32,
            tubes: tubes.len() as u32,
            globes: globes.len() as u32,
            discs: discs.len() as u32,
            instances: instances.len() as u32,
            lights: scene.lights.len() as u32,
            light_images,
            light_sum: summed,
            shadows: lighting.shadows,
            // Soft shadows only where a lamp has a radius to spread them over.
            soft_samples: if scene.lights.iter().any(|l| l.radius > 0.0) {
                lighting.soft_samples
            } else {
                0
            },
            avatar: scene.avatar.is_some(),
            textures: !scene.textures.is_empty(),
            culling: culling.is_some() && balls.len() + tubes.len() > 0,
            step_cap: space.walks_in_steps(),
            cells: space.cells().len() > 1,
            colour_by: scene.shading.colour_by.index(),
            walls: walls.is_some(),
            mirrors: scene.has_mirrors(),
            general: false,
            straightforward: false,
            ..ShaderKey::empty(g)
        };
        let bytes = key.uniform_bytes();
        if bytes > MAX_UNIFORM_BYTES {
            return Err(GpuSceneError::TooLarge {
                bytes,
                limit: MAX_UNIFORM_BYTES,
                faces: key.faces,
                objects: scene.objects.len(),
                lights: key.lights,
            });
        }
        let shading = &scene.shading;
        let mut out = UniformWriter::with_capacity(bytes);
        out.push(&GpuShading {
            fog: colour(shading.fog_colour, shading.ambient),
            params: vec4(DVec4::new(
                shading.fog_distance,
                shading.cutoff_distance(),
                g.s(shading.near_light),
                f64::from(max_crossings),
            )),
            exact: vec4(DVec4::X),
        });
        out.push(&offsets);
        for light in &scene.lights {
            let images = images_of(light);
            out.push(&colour(light.colour * light.power, images.len() as f64));
            let tail = if lighting.tail {
                0.25 * crate::scene::lighting::tail_fluence(
                    g,
                    light.reach,
                    shading.fog_distance,
                    light.volume,
                )
            } else {
                0.0
            };
            // The lamp's S(radius) for soft shadows (0: a point).
            let s_radius = if light.radius > 0.0 {
                g.s(light.radius)
            } else {
                0.0
            };
            out.push(&vec4(DVec4::new(light.reach, tail, s_radius, 0.0)));
            for k in 0..light_images as usize {
                out.push(&vec4(images.get(k).copied().unwrap_or(light.position)));
            }
        }
        // The faces, or for the 3-sphere (no face) one unused slot: WGSL has no empty arrays.
        // The f32 numbers are the f32 walker's: a cell built from a closed form is rounded
        // once from double-double, covectors, pairings and what rounding each pairing left
        // out (the shader applies hi + lo compensated).
        let cell = CellWalker::<Vec4>::new(space);
        let as_f32 = |m: &Mat4| m.to_cols_array_2d();
        let faces: Vec<(Vec4F, Mat4F, Mat4F, usize)> = if space.faces.is_empty() {
            vec![([0.0; 4], as_f32(&Mat4::IDENTITY), [[0.0; 4]; 4], 0)]
        } else {
            (0..cell.covectors.len())
                .map(|f| {
                    (
                        cell.covectors[f].to_array(),
                        as_f32(&cell.pairings[f]),
                        as_f32(&cell.pairings_lo[f]),
                        cell.partners[f],
                    )
                })
                .collect()
        };
        for (covector, _, _, _) in &faces {
            out.push(covector);
        }
        for (_, pairing, _, _) in &faces {
            out.push(pairing);
        }
        for (_, _, lo, _) in &faces {
            out.push(lo);
        }
        let mut partners: Vec<u32> = faces.iter().map(|f| f.3 as u32).collect();
        partners.resize(4 * faces.len().div_ceil(4), 0);
        out.words.extend(partners);
        if key.cells {
            out.words.extend(pack_cells(space.cells()));
        }
        if let Some(walls) = &walls {
            pack_walls(&mut out, walls);
        }
        pack_objects(
            &mut out,
            g,
            [&balls, &tubes, &globes, &discs, &instances],
            roots,
        );
        if key.culling
            && let Some(culling) = &culling
        {
            pack_culling(
                &mut out,
                [&lists[0], &lists[1]],
                culling,
                space.faces.len(),
                key.list_vecs() as usize,
            );
        }
        let words = out.words;
        debug_assert_eq!(words.len() * 4 + VIEW_WORDS * 4, bytes);
        let avatar = scene.avatar.as_ref().map(|a| GpuAvatar {
            mesh: a.mesh,
            root: roots.get(a.mesh as usize).copied().unwrap_or(0),
            radius: scene.meshes.get(a.mesh as usize).map_or(0.0, |m| m.radius),
            skip: a.skip,
        });
        Ok(Self {
            key,
            words,
            data,
            textures,
            avatar,
            sources,
        })
    }

    /// The offsets of the scene data's parts (triangles, materials, texture table,
    /// texels), as the uniform holds them after the shading.
    fn offsets(&self) -> [u32; 4] {
        let at = size_of::<GpuShading>() / 4;
        [0, 1, 2, 3].map(|k| self.words[at + k])
    }
}

/// Each face's cell as the run of faces that bound it, `first | end << 16` (`MAX_FACES`
/// fits in 16 bits), four faces to a vec4 (the layout's `cell_ranges`).
fn pack_cells(cells: &[std::ops::Range<usize>]) -> Vec<u32> {
    let mut words: Vec<u32> = cells
        .iter()
        .flat_map(|c| std::iter::repeat_n((c.start | c.end << 16) as u32, c.len()))
        .collect();
    words.resize(4 * words.len().div_ceil(4), 0);
    words
}

impl GpuScene {
    /// The same scene with every object tested in every cell (the benchmark's comparison
    /// for [`FaceCulling`]): the culling's words dropped from the end of the uniform.
    #[must_use]
    pub fn without_culling(&self) -> GpuScene {
        let mut words = self.words.clone();
        words.truncate(words.len() - 4 * self.key.culling_vecs());
        GpuScene {
            key: ShaderKey {
                culling: false,
                ..self.key
            },
            words,
            data: self.data.clone(),
            textures: self.textures.clone(),
            avatar: self.avatar,
            sources: self.sources.clone(),
        }
    }

    /// The same scene for the benchmark's straightforward tracer (shader def
    /// `STRAIGHTFORWARD`): the same walk and shading written as one would first write it, by
    /// arc length with trigonometric functions, a division a face and plain f32 pairings,
    /// and every image of a lamp summed with its distance and direction (where the tracer
    /// sums only those within the reach, from their chords), to compare the tracer with. `None` where the scene has more than balls (tubes,
    /// globes, discs, meshes, the avatar, walls), a teaching colouring, or a step cap.
    #[must_use]
    pub fn straightforward(&self) -> Option<GpuScene> {
        let plain = self.without_culling();
        let k = plain.key;
        let more = k.tubes + k.globes + k.discs + k.instances > 0
            || k.avatar
            || k.walls
            || k.colour_by != 0
            || k.step_cap
            || k.general;
        (!more).then_some(GpuScene {
            key: ShaderKey {
                straightforward: true,
                ..k
            },
            ..plain
        })
    }

    /// The same scene for the unspecialised shader variant: arrays padded to
    /// [`GENERAL_CAPACITY`] and the geometry and counts appended. `None` if the scene has
    /// more faces or objects than that, objects of other kinds, or several cells.
    #[must_use]
    pub fn generalised(&self) -> Option<GpuScene> {
        let unculled = self.without_culling();
        let k = unculled.key;
        let (cap_faces, cap_balls, cap_tubes) = GENERAL_CAPACITY;
        // Only balls and tubes have general arrays, and the faces of one cell.
        let other_kinds = k.globes + k.discs + k.instances > 0 || k.avatar || k.walls || k.cells;
        if k.general
            || other_kinds
            || k.faces > cap_faces
            || k.balls > cap_balls
            || k.tubes > cap_tubes
        {
            return None;
        }
        // The 3-sphere's one unused face slot counts as a face here.
        let faces = k.faces.max(1) as usize;
        // (words per element, elements, capacity) of each array, in uniform order.
        let words_of = |bytes: usize| bytes / 4;
        let vec4_words = words_of(size_of::<Vec4F>());
        let arrays = [
            (vec4_words, faces, cap_faces as usize),
            (words_of(size_of::<Mat4F>()), faces, cap_faces as usize),
            (words_of(size_of::<Mat4F>()), faces, cap_faces as usize),
            (
                vec4_words,
                faces.div_ceil(4),
                (cap_faces as usize).div_ceil(4),
            ),
            (
                words_of(size_of::<GpuBall>()),
                k.balls as usize,
                cap_balls as usize,
            ),
            (
                words_of(size_of::<GpuTube>()),
                k.tubes as usize,
                cap_tubes as usize,
            ),
        ];
        // Shading, data offsets and the lights.
        let header = words_of(size_of::<GpuShading>())
            + vec4_words * (1 + k.lights as usize * (2 + k.light_images.max(1) as usize));
        let mut words = unculled.words[..header].to_vec();
        let mut at = header;
        for (size, count, capacity) in arrays {
            words.extend_from_slice(&unculled.words[at..at + size * count]);
            words.resize(words.len() + size * (capacity - count), 0);
            at += size * count;
        }
        debug_assert_eq!(at, unculled.words.len());
        let general = [
            self.key.geometry.kappa() as f32,
            k.faces as f32,
            k.balls as f32,
            k.tubes as f32,
        ];
        words.extend(general.map(f32::to_bits));
        Some(GpuScene {
            key: ShaderKey { general: true, ..k },
            words,
            data: self.data.clone(),
            textures: self.textures.clone(),
            avatar: None,
            sources: self.sources.clone(),
        })
    }
}
