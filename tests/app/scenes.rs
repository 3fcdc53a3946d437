//! Scene content on the CPU reference: the mesh hierarchy against brute force, a cube's
//! copies in the 3-torus, the avatar seen round the space, globe texture coordinates, lights
//! lit from their nearest copy, and scene files (the examples load; bad files and glTFs get
//! errors that name the line and the problem).

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::assets::torus_knot;
use bevy_curved_spaces::scene::file::{load_scene_file, parse_scene};
use bevy_curved_spaces::scene::gltf::{self, GlbMesh, write_glb};
use bevy_curved_spaces::scene::mesh::{Mesh, MeshSource, Triangle, cube_source};
use bevy_curved_spaces::scene::{
    BallTexture, CurvedScene, Light, MeshInstance, Object, SceneParts, Shading, SurfaceMaterial,
};
use bevy_curved_spaces::space::CellWalker;
use bevy_curved_spaces::space::seed_space;
use bevy_curved_spaces::trace::{RayEnd, first_hit, first_hit_traced};
use glam::{DMat4, DVec2, DVec3, DVec4};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn manifest() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn soup(coords: &[f64]) -> Vec<Triangle> {
    coords
        .chunks_exact(9)
        .map(|c| Triangle {
            corners: [
                DVec3::new(c[0], c[1], c[2]),
                DVec3::new(c[3], c[4], c[5]),
                DVec3::new(c[6], c[7], c[8]),
            ],
            normals: [DVec3::Z; 3],
            uvs: [DVec2::ZERO; 3],
            material: 0,
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The hierarchy finds the same first hit as testing every triangle, for random
    /// triangle soups and random lines (most of which miss: both must agree on that too).
    #[test]
    fn the_hierarchy_gives_the_same_hits_as_brute_force(
        coords in prop::collection::vec(-1.0..1.0f64, 9..9 * 300),
        rays in prop::collection::vec((prop::array::uniform3(-2.0..2.0f64), prop::array::uniform3(-1.0..1.0f64)), 64),
    ) {
        let Ok(mesh) = Mesh::new(soup(&coords)) else { return Ok(()); };
        for (o, d) in rays {
            let (o, d) = (DVec3::from_array(o), DVec3::from_array(d));
            if d.length() < 1e-6 { continue; }
            let a = mesh.intersect(o, d, f64::INFINITY);
            let b = mesh.intersect_brute_force(o, d, f64::INFINITY);
            match (a, b) {
                (None, None) => {}
                (Some(a), Some(b)) => prop_assert!((a.t - b.t).abs() <= 1e-12 * (1.0 + b.t), "{a:?} vs {b:?}"),
                _ => prop_assert!(false, "hierarchy {a:?}, brute force {b:?}"),
            }
        }
    }
}

#[test]
fn the_hierarchy_of_a_smooth_mesh_agrees_with_brute_force_on_rays_that_hit() {
    let mesh = torus_knot(3, 2, 96, 10)
        .place(Geometry::Euclidean, 1.0)
        .expect("places");
    assert!(mesh.depth() <= 32 && mesh.nodes.len() > 100);
    let mut hits = 0;
    let mut rng = bevy_curved_spaces::random::SplitMix64(7);
    for _ in 0..4000 {
        let o = DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, 3.0);
        let target = DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5) * 1.6;
        let d = target - o;
        let a = mesh.intersect(o, d, f64::INFINITY);
        let b = mesh.intersect_brute_force(o, d, f64::INFINITY);
        assert_eq!(a.map(|h| h.triangle), b.map(|h| h.triangle));
        hits += usize::from(a.is_some());
    }
    assert!(
        hits > 1000,
        "only {hits} rays hit: the test would prove little"
    );
}

/// A cube mesh at the centre of the 3-torus is seen again at every lattice translate: a ray
/// aimed at the copy at `L` meets it after crossing the faces between, at the distance where
/// the straight line enters the translated box.
#[test]
fn a_cube_mesh_in_the_torus_shows_its_copies_where_the_lattice_puts_them() {
    let space = seed_space("torus").expect("seed");
    let g = space.geometry();
    let h = 0.15;
    let mut scene = CurvedScene::new(
        Vec::new(),
        Vec::new(),
        Shading {
            fog_distance: 10.0,
            ..Shading::default()
        },
    );
    scene.materials.push(SurfaceMaterial::default());
    scene.meshes.push(std::sync::Arc::new(
        cube_source(h, 0).place(g, 1.0).expect("cube"),
    ));
    let radius = scene.meshes[0].radius;
    scene.objects.push(Object::Mesh(MeshInstance::new(
        g,
        0,
        DMat4::IDENTITY,
        radius,
    )));
    let walker = CellWalker::<DVec4>::new(&space);
    let eye = DVec3::new(0.1, -0.05, 0.4);
    let mut checked = 0;
    for l in [
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::new(0.0, 0.0, -2.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-2.0, 1.0, 1.0),
        DVec3::new(3.0, -1.0, -2.0),
    ] {
        let dir = (l - eye).normalize();
        // Where the line enters the box [L − h, L + h] (slab test) and whether an earlier
        // copy is in the way (then the ray must hit that one: skip such a direction).
        let entry = |c: DVec3| {
            let t0 = (c - DVec3::splat(h) - eye) / dir;
            let t1 = (c + DVec3::splat(h) - eye) / dir;
            let near = t0.min(t1).max_element();
            let far = t0.max(t1).min_element();
            (near <= far && far > 0.0).then_some(near)
        };
        let expected = entry(l).expect("aimed at its centre");
        let blocked = (-4..=4)
            .flat_map(|x| {
                (-4..=4).flat_map(move |y| {
                    (-4..=4).map(move |z| DVec3::new(x as f64, y as f64, z as f64))
                })
            })
            .filter(|c| *c != l)
            .any(|c| entry(c).is_some_and(|t| t < expected));
        if blocked {
            continue;
        }
        // Faces crossed on the way: the half-integer planes between the eye and the entry.
        let end = eye + dir * expected;
        let crossed: f64 = (0..3)
            .map(|k| ((end[k] + 0.5).floor() - (eye[k] + 0.5).floor()).abs())
            .sum();
        let ray = bevy_curved_spaces::geometry::chart_ray(g, eye, dir).expect("ray");
        match first_hit(&walker, &scene, ray, 32) {
            RayEnd::Hit(hit) => {
                assert_eq!(hit.object, 0, "towards {l}");
                assert_eq!(hit.crossings, crossed as usize, "towards {l}");
                assert!(
                    (hit.distance - expected).abs() < 1e-9,
                    "towards {l}: {} vs {expected}",
                    hit.distance
                );
            }
            other => panic!("towards {l}: {other:?}"),
        }
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} copies were unobstructed");
}

/// The avatar is passed through where the eye sits in it and seen where a ray comes back
/// round the space: in the torus, looking straight ahead, the ray returns after one
/// crossing and meets the ship's tail one cell length away.
#[test]
fn the_avatar_is_seen_round_the_space_and_not_from_inside() {
    let space = seed_space("torus").expect("seed");
    let g = space.geometry();
    let ship_only = || {
        CurvedScene::with_parts(
            &space,
            2.0,
            SceneParts {
                edges: false,
                centrepiece: Centrepiece::None,
                avatar: true,
                clifford: false,
            },
        )
    };
    let mut scene = ship_only();
    let frame = DMat4::IDENTITY;
    scene.set_avatar_frame(&space, frame);
    let avatar = scene.avatar.clone().expect("asked for");
    assert_eq!(
        avatar.instances.len(),
        1,
        "the ship at the centre sticks out of no face"
    );
    let walker = CellWalker::<DVec4>::new(&space);
    let forward = bevy_curved_spaces::geometry::chart_ray(g, DVec3::ZERO, -DVec3::Z).expect("ray");
    let traced = first_hit_traced(&walker, &scene, forward, 8);
    let RayEnd::Hit(hit) = traced.end else {
        panic!("the ray should come back to the ship: {:?}", traced.end)
    };
    assert_eq!(hit.object, scene.objects.len(), "the avatar's own index");
    assert_eq!(hit.crossings, 1);
    let radius = scene.meshes[avatar.mesh as usize].radius;
    assert!(
        hit.distance < 1.0 && hit.distance > 1.0 - radius,
        "{}",
        hit.distance
    );
    // Without the avatar the same ray meets nothing (fog or budget).
    scene.avatar = None;
    assert!(!matches!(
        first_hit(&walker, &scene, forward, 8),
        RayEnd::Hit(_)
    ));
    // Moved next to a face, the ship gets an image through it.
    let mut scene = ship_only();
    scene.set_avatar_frame(&space, g.translation(DVec3::X, 0.49));
    assert!(scene.avatar.expect("asked for").instances.len() >= 2);
}

#[test]
fn globe_coordinates_put_the_prime_meridian_ahead_and_the_pole_up() {
    let g = Geometry::Hyperbolic;
    let centre = g.translation(DVec3::new(0.2, 0.1, -0.3), 0.4) * glam::DVec4::W;
    let frame = g.translation_to(centre);
    let t = BallTexture {
        texture: 0,
        frame,
        spin: 0.5,
    };
    let at = |dir: DVec3| frame * g.translation(dir, 0.1) * glam::DVec4::W;
    let uv = t.uv(g, at(DVec3::Z), 0.0);
    assert!(
        (uv.x - 0.5).abs() < 1e-9 && (uv.y - 0.5).abs() < 1e-9,
        "{uv}"
    );
    assert!(t.uv(g, at(DVec3::Y), 0.0).y < 1e-6);
    assert!((t.uv(g, at(DVec3::X), 0.0).x - 0.75).abs() < 1e-9);
    // After time s the meridian has turned by 0.5·s radians towards +x.
    let turned = DVec3::new(1.0f64.sin(), 0.0, 1.0f64.cos());
    assert!((t.uv(g, at(turned), 2.0).x - 0.5).abs() < 1e-9);
}

/// A light just inside a face lights a point just across the face (in the neighbouring
/// copy, which the ray reaches through the pairing) from its nearest image, as brightly as
/// a point at the same distance on its own side.
#[test]
fn lights_shine_from_their_nearest_copy() {
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = seed_space(id).expect("seed");
        let g = space.geometry();
        let r = bevy_curved_spaces::space::invariants::inradius(&space);
        let n = space.faces()[0].covector.truncate().normalize();
        let light_at = g.translation(n, 0.95 * r) * space.centre();
        let light = Light::new(&space, light_at, DVec3::ONE, 1.0);
        assert!(light.images.len() > 1);
        // A point a little beyond the face, mapped back into the cell by the pairing of the
        // face it is beyond: it is near the light's image, not the light.
        let beyond = g.translation(n, 1.05 * r) * space.centre();
        let inside = g.project_point(space.faces()[0].pairing * beyond);
        assert!(space.outside_by(inside) < 1e-9, "{id}");
        let (_, d_near) = light.nearest(g, inside);
        assert!(
            (d_near - 0.1 * r).abs() < 1e-9,
            "{id}: nearest copy at {d_near}"
        );
        assert!(
            g.distance(inside, light_at) > 0.1 * r + 1e-6,
            "{id}: the light itself is farther"
        );
    }
}

#[test]
fn every_example_scene_file_loads() {
    let dir = manifest().join("assets/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).expect("assets/scenes") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|x| x == "toml") {
            use bevy_curved_spaces::trace::product::file::load_product_scene_file;
            if let Some(product) = load_product_scene_file(&path).unwrap_or_else(|e| panic!("{e}"))
            {
                assert!(!product.scene.objects.is_empty() && product.start.is_some());
                n += 1;
                continue;
            }
            use bevy_curved_spaces::trace::nil::file::load_nil_scene_file;
            if let Some(nil) = load_nil_scene_file(&path).unwrap_or_else(|e| panic!("{e}")) {
                assert!(!nil.scene.objects.is_empty() && nil.start.is_some());
                n += 1;
                continue;
            }
            use bevy_curved_spaces::trace::sl2r::file::load_sl2r_scene_file;
            if let Some(sl2r) = load_sl2r_scene_file(&path).unwrap_or_else(|e| panic!("{e}")) {
                assert!(!sl2r.scene.tubes.is_empty());
                n += 1;
                continue;
            }
            let file = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                !file.base.objects.is_empty() && !file.base.lights.is_empty(),
                "{}",
                path.display()
            );
            assert!(file.start.is_some());
            n += 1;
        }
    }
    assert!(n >= 2);
}

/// A scene file's error: its line and message.
fn error_of(text: &str, base: &Path) -> (Option<usize>, String) {
    let e = parse_scene(text, base, "test.toml").expect_err("the file is bad");
    assert!(e.to_string().starts_with("test.toml"), "{e}");
    (e.line, e.message)
}

#[test]
fn bad_scene_files_get_errors_naming_the_line_and_the_problem() {
    let dir = tempdir();
    let models = manifest().join("assets/models");
    let base = models.as_path();
    let cases: Vec<(&str, usize, &str)> = vec![
        ("space = \"klein-bottle\"\n", 1, "unknown space"),
        ("space = \"torus\"\nfog = -1\n", 2, "fog distance"),
        (
            "space = \"torus\"\nwalls = 1.5\n",
            2,
            "opening must be between 0",
        ),
        (
            "space = \"torus\"\nwalls = 0.5\nwall_opacity = 0\n",
            3,
            "opacity must be above 0",
        ),
        ("space = \"torus\"\nwall_opacity = 0.5\n", 2, "needs walls"),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nradius = 0.2\nreflectance = 1.5\n",
            2,
            "reflectance must be between 0 and 1, got 1.5",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"disc\"\nnormal = [0, 1, 0]\nradius = 0.2\nreflectance = nan\n",
            2,
            "reflectance must be between 0 and 1",
        ),
        (
            "space = \"torus\"\n[lighting]\npaths = \"all\"\n",
            3,
            "light paths must be \"images\" or \"nearest\"",
        ),
        (
            "space = \"torus\"\n[lighting]\nreach = 0\n",
            3,
            "the light reach must be more than 0",
        ),
        (
            "space = \"torus\"\n[lighting]\nreach = 1e300\n",
            3,
            "at most 64 inradii",
        ),
        (
            "space = \"torus\"\n[lighting]\nshadows = -1\n",
            3,
            "shadows must be 0 to 64",
        ),
        (
            "space = \"torus\"\n[lighting]\nshadows = 65\n",
            3,
            "shadows must be 0 to 64",
        ),
        (
            "space = \"torus\"\n[lighting]\nlamp_radius = -0.1\n",
            3,
            "a lamp's radius must be 0 to 1 inradii, got -0.1",
        ),
        (
            "space = \"torus\"\n[lighting]\nshadows = 2\nlamp_radius = nan\n",
            4,
            "a lamp's radius must be 0 to 1 inradii, got NaN",
        ),
        (
            "space = \"torus\"\n[lighting]\nsoft_samples = 0\n",
            3,
            "soft_samples must be 1 to 64 shadow rays per image, got 0",
        ),
        (
            "space = \"torus\"\n[lighting]\nsoft_samples = 65\n",
            3,
            "soft_samples must be 1 to 64",
        ),
        (
            "space = \"torus\"\n[lighting]\nshadow = 2\n",
            3,
            "unknown field `shadow`",
        ),
        (
            "space = \"torus\"\ncentrepiece = \"comet\"\n",
            2,
            "unknown centrepiece `comet`; choose one of none, ball, globe, gyroscope, galaxy",
        ),
        (
            "space = \"torus\"\ngyroscope = true\ncentrepiece = \"globe\"\n",
            3,
            "give the centrepiece once",
        ),
        (
            "space = \"torus\"\n\n[[object]]\ntype = \"cube\"\nradius = 1\n",
            4,
            "unknown variant",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nradius = 0.2\ncolor = [1, 0, 0]\n",
            2,
            "unknown field `color` (did you mean `colour`?)",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nposition = [3.0, 0, 0]\nradius = 0.2\n",
            2,
            "not inside the cell",
        ),
        // Numbers that are not numbers, or too large for the geometry.
        (
            "space = \"torus\"\n[[object]]\ntype = \"mesh\"\npath = \"cube.glb\"\nsize = 0.2\nyaw = nan\n",
            2,
            "yaw must be a finite angle",
        ),
        (
            "space = \"torus\"\n[start]\nposition = [0, 0, 0]\nroll = inf\n",
            2,
            "roll must be a finite angle",
        ),
        (
            "space = \"seifert-weber\"\n[[object]]\ntype = \"ball\"\nposition = [1e200, 0, 0]\nradius = 0.2\n",
            2,
            "too far from the centre",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nposition = [1e200, 0, 0]\nradius = 0.2\n",
            2,
            "position [1e200, 0.0, 0.0] is too far",
        ),
        (
            "space = \"torus\"\n[start]\nposition = [0, 0, 0]\nfov = 200\n",
            2,
            "fov must be an angle between 0 and 180",
        ),
        (
            "space = \"torus\"\n[[light]]\nposition = [1000, 0, 0]\n",
            2,
            "the light is not inside the cell",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nradius = 0.2\ncolour = [nan, 0, 0]\n",
            2,
            "colours must be finite",
        ),
        (
            "space = \"torus\"\n\n\n[[object]]\ntype = \"mesh\"\npath = \"missing.glb\"\nsize = 0.3\n",
            4,
            "mesh not found",
        ),
        (
            "space = \"torus\"\n[[object]]\ntype = \"ball\"\nradius = -0.2\n",
            2,
            "radius must be a positive",
        ),
        (
            "space = \"torus\"\n[[light]]\nposition = [0, 0, 0]\nintensity = -2\n",
            2,
            "intensity",
        ),
        ("space = \"torus\"\nedges = maybe\n", 2, ""),
    ];
    for (text, line, needle) in cases {
        let (l, message) = error_of(text, base);
        assert!(message.contains(needle), "{text:?}: {message}");
        let l = l.unwrap_or_else(|| panic!("{text:?}: no line in {message}"));
        assert!(
            l == line || (needle.is_empty() && l == 2),
            "{text:?}: line {l}, expected {line}: {message}"
        );
    }
    // A glTF without positions.
    let broken = dir.join("no_positions.glb");
    write_glb(
        &broken,
        &GlbMesh {
            positions: &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
            indices: &[0, 1, 2],
            base_colour: [1.0; 4],
            omit_positions: true,
            ..GlbMesh::default()
        },
    )
    .expect("write");
    let err = gltf::load(&broken).expect_err("no positions");
    assert!(err.to_string().contains("no positions"), "{err}");
    let text =
        "space = \"torus\"\n[[object]]\ntype = \"mesh\"\npath = \"no_positions.glb\"\nsize = 0.3\n";
    let (line, message) = error_of(text, &dir);
    assert_eq!(line, Some(2));
    assert!(message.contains("no positions"), "{message}");
    // A file that is not glTF at all.
    std::fs::write(dir.join("junk.glb"), b"not a model").expect("write");
    let (_, message) = error_of(&text.replace("no_positions", "junk"), &dir);
    assert!(message.contains("cannot read the glTF"), "{message}");
    // And a missing scene file.
    let err = load_scene_file(&dir.join("nope.toml")).expect_err("missing");
    assert!(
        err.to_string().contains("cannot read the scene file"),
        "{err}"
    );
    // A directory, /dev/zero (endless) and a sparse file over the limit are refused before
    // anything is read.
    let err = load_scene_file(&dir).expect_err("a directory");
    assert!(err.to_string().contains("a directory"), "{err}");
    if std::path::Path::new("/dev/zero").exists() {
        let err = load_scene_file(std::path::Path::new("/dev/zero")).expect_err("/dev/zero");
        assert!(err.to_string().contains("not a regular file"), "{err}");
    }
    let huge = dir.join("huge.toml");
    std::fs::File::create(&huge)
        .expect("create")
        .set_len(bevy_curved_spaces::files::MAX_SCENE_FILE_BYTES + 1)
        .expect("grow");
    let err = load_scene_file(&huge).expect_err("too large");
    assert!(err.to_string().contains("more than the limit"), "{err}");
}

#[test]
fn a_glb_written_by_the_generator_reads_back_with_its_texture() {
    let dir = tempdir();
    let path = dir.join("cube.glb");
    let png = bevy_curved_spaces::scene::assets::png_bytes(
        &bevy_curved_spaces::scene::assets::crate_texture(16),
    );
    bevy_curved_spaces::scene::assets::write_source_glb(
        &path,
        &cube_source(0.5, 0),
        [0.5, 1.0, 1.0, 1.0],
        Some(&png),
    )
    .expect("write");
    let model = gltf::load(&path).expect("reads");
    assert_eq!(model.source.indices.len(), 12);
    assert_eq!(model.textures.len(), 1);
    assert_eq!(
        (model.textures[0].width, model.textures[0].height),
        (16, 16)
    );
    assert_eq!(model.materials[0].texture, Some(0));
    assert!((model.materials[0].colour - DVec3::new(0.5, 1.0, 1.0)).length() < 1e-6);
    let normals = model.source.normals.as_ref().expect("normals");
    assert_eq!(normals.len(), model.source.positions.len());
    let _ = MeshSource::default();
}

fn tempdir() -> PathBuf {
    crate::common::scratch_dir("scenes")
}

/// A scene file's space may be a library id or a generator file beside it.
#[test]
fn scene_files_take_spaces_from_groups() {
    let census = manifest().join("assets/spaces/census");
    let text = "space = \"m003_-3_1.gen\"\n\n[[object]]\ntype = \"ball\"\nradius = 0.2\n";
    let file = parse_scene(text, &census, "weeks.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(file.space.faces().len(), 18);
    let text = "space = \"lens-7-2\"\n\n[[object]]\ntype = \"ball\"\nradius = 0.2\n";
    let file = parse_scene(text, &census, "lens.toml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        bevy_curved_spaces::space::invariants::group_order(&file.space),
        Some(7)
    );
    let (line, message) = error_of("space = \"lens-6-3\"\n", &census);
    assert_eq!(line, Some(1));
    assert!(message.contains("common factor"), "{message}");
}

#[test]
fn scene_files_choose_walls_and_a_centrepiece() {
    use bevy_curved_spaces::scene::{Centrepiece, WallStyle};
    let here = manifest();
    let file = parse_scene(
        "space = \"poincare\"\navatar = false\nwalls = 0.25\nwall_opacity = 0.6\ncentrepiece = \"galaxy\"\n",
        &here,
        "a.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        file.base.shading.walls,
        Some(WallStyle::with_opacity(0.25, 0.6).unwrap())
    );
    assert_eq!(file.parts.centrepiece, Centrepiece::Galaxy);
    // The whole scene has the galaxy: one mesh object.
    let scene = file.scene();
    assert_eq!(scene.meshes.len(), 1);
    assert_eq!(
        scene.meshes[0].triangles.len(),
        8 * bevy_curved_spaces::scene::centrepiece::GALAXY_STARS
    );
    for (text, expected) in [
        ("space = \"torus\"\n", Centrepiece::None),
        ("space = \"torus\"\ncentre_ball = true\n", Centrepiece::Ball),
        (
            "space = \"torus\"\ngyroscope = true\n",
            Centrepiece::Gyroscope,
        ),
        (
            "space = \"torus\"\ncentrepiece = \"globe\"\n",
            Centrepiece::Globe,
        ),
        (
            "space = \"torus\"\ncentrepiece = \"none\"\n",
            Centrepiece::None,
        ),
    ] {
        let file = parse_scene(text, &here, "b.toml").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(file.parts.centrepiece, expected, "{text}");
        assert_eq!(file.base.shading.walls, None);
    }
}

#[test]
fn scene_files_choose_the_lighting() {
    use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting};
    let here = manifest();
    let read = |text: &str| {
        parse_scene(text, &here, "a.toml")
            .unwrap_or_else(|e| panic!("{e}"))
            .base
    };
    let plain = read("space = \"torus\"\n[[light]]\nposition = [0.1, 0.2, 0.0]\n");
    assert_eq!(plain.shading.lighting, Lighting::default());
    let lit = read(
        "space = \"torus\"\n[lighting]\nreach = 1.5\ntail = false\nshadows = 9\nlamp_radius = 0.25\nsoft_samples = 12\n\n[[light]]\nposition = [0.1, 0.2, 0.0]\n",
    );
    assert_eq!(
        lit.shading.lighting,
        Lighting {
            paths: LightPaths::Images,
            reach_inradii: 1.5,
            tail: false,
            shadows: 9,
            lamp_radius_inradii: 0.25,
            soft_samples: 12,
        }
    );
    // The lamps take the radius in the space's units: the torus's inradius is ½.
    assert!((lit.lights[0].radius - 0.125).abs() < 1e-12);
    // The lamp's images in the cover follow the reach: a shorter one keeps fewer.
    let (short, long) = (&lit.lights[0], &plain.lights[0]);
    assert!((short.reach - 0.75).abs() < 1e-12, "{}", short.reach);
    assert!(short.cover.len() < long.cover.len());
    let nearest =
        read("space = \"torus\"\n[lighting]\npaths = \"nearest\"\ntail = false\nshadows = 0\n");
    assert_eq!(nearest.shading.lighting, Lighting::NEAREST);
}

#[test]
fn scene_files_make_mirrors() {
    use bevy_curved_spaces::scene::Object;
    let here = manifest();
    let file = parse_scene(
        "space = \"seifert-weber\"\n[[object]]\ntype = \"ball\"\nradius = 0.3\nreflectance = 0.8\n\n[[object]]\ntype = \"disc\"\nposition = [0.4, 0, 0]\nnormal = [1, 0, 0]\nradius = 0.2\nreflectance = 0.25\n\n[[object]]\ntype = \"ball\"\nposition = [0, 0.5, 0]\nradius = 0.1\n",
        &here,
        "a.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let reflectances: Vec<f64> = file
        .base
        .objects
        .iter()
        .map(|o| match o {
            Object::Ball(b) => b.reflectance,
            Object::Disc(d) => d.reflectance,
            _ => -1.0,
        })
        .collect();
    assert_eq!(reflectances, vec![0.8, 0.25, 0.0]);
    assert!(file.base.has_mirrors());
    // A mesh's materials take it too.
    let models = manifest().join("assets/models");
    let mesh = parse_scene(
        "space = \"torus\"\n[[object]]\ntype = \"mesh\"\npath = \"cube.glb\"\nsize = 0.3\nreflectance = 0.6\n",
        &models,
        "b.toml",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(!mesh.base.materials.is_empty());
    assert!(mesh.base.materials.iter().all(|m| m.reflectance == 0.6));
}
