//! Scenes on the GPU against the CPU reference: placed objects, glTF models, the example
//! scene files, large textures, scenes too large for the GPU, and entities.

use super::*;

/// Your own objects through the plugin (`SceneObjects`): a ball over a corner of the torus
/// cell and one sticking out of a Seifert–Weber face are drawn through their images on the
/// GPU exactly as the CPU reference draws the same placed scene, and a ball outside the cell
/// is left out with a message.
#[test]
fn placed_objects_straddling_faces_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::TracerSettings;
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::{Ball, Object};
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for (id, at, radius) in [
        ("torus", DVec3::new(0.45, 0.45, 0.4), 0.25),
        ("seifert-weber", DVec3::new(0.0, 0.3, 0.55), 0.35),
    ] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let centre = g.from_chart(at).expect("chart point");
        let ball = Object::Ball(Ball::new(g, centre, radius, DVec3::new(0.3, 0.9, 0.5)));
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let settings = TracerSettings {
            fog_distance: None,
            max_crossings: Some(24),
            quality: bevy_curved_spaces::plugin::components::Quality::High,
            resolution_scale: 1.0,
            parts,
            time: None,
            colour_by: Default::default(),
            walls: None,
            lighting: None,
        };
        let (scene, problems) = build_scene(&space, &settings, &[ball], None);
        assert_eq!(problems, None, "{id}");
        let defaults = CurvedScene::with_parts(&space, settings.fog_for(&space, None), parts);
        assert!(
            scene.objects.len() >= defaults.objects.len() + 2,
            "{id}: the ball needs at least one image"
        );
        let camera = TraceCamera::default_for(&space);
        let cpu = render(
            &space,
            &scene,
            &camera,
            &RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                max_crossings: 24,
            },
        );
        let request = OffscreenRender {
            parts,
            objects: vec![ball],
            ..OffscreenRender::new(
                ActiveSpace::new(id, space.clone()),
                camera,
                (WIDTH, HEIGHT),
                24,
            )
        };
        let gpu = renderer.render(&request).expect("renders");
        let (c, _) = compare(&gpu, &cpu, TOLERANCE);
        println!(
            "{id} with a straddling ball: differing {:.3} %, mean error {:.3}/255",
            100.0 * c.differing,
            c.mean_error
        );
        assert!(
            c.differing <= MAX_DIFFERING,
            "{id}: {:.2} %",
            100.0 * c.differing
        );
        // Without the ball the picture changes: the test sees the objects.
        let mut plain = request.clone();
        plain.objects.clear();
        let (without, _) = compare(&renderer.render(&plain).expect("renders"), &gpu, TOLERANCE);
        assert!(without.differing > 0.02, "{id}: the ball is not visible");
    }
    let space = SEED_SPACES[0].build().expect("builds");
    let far = space
        .geometry()
        .from_chart(DVec3::new(2.0, 0.0, 0.0))
        .expect("chart point");
    let settings = TracerSettings {
        fog_distance: None,
        max_crossings: None,
        quality: bevy_curved_spaces::plugin::components::Quality::Medium,
        resolution_scale: 1.0,
        parts: SceneParts::default(),
        time: None,
        colour_by: Default::default(),
        walls: None,
        lighting: None,
    };
    let outside = Object::Ball(Ball::new(space.geometry(), far, 0.1, DVec3::ONE));
    let (scene, problems) = build_scene(&space, &settings, &[outside], None);
    assert!(
        problems.is_some_and(|p| p.contains("scene object 0") && p.contains("not inside the cell")),
        "a misplaced object is named"
    );
    assert_eq!(
        scene.objects.len(),
        CurvedScene::with_parts(&space, settings.fog_for(&space, None), settings.parts)
            .objects
            .len()
    );
}

/// The textured cube of `assets/models/cube.glb`, loaded with the glTF reader and placed
/// turned at the cell's centre with two lights, draws alike on the GPU and the CPU in a
/// flat, a hyperbolic and a spherical space: same hierarchy, triangles, texture sampling
/// and shading.
#[test]
fn a_gltf_from_assets_renders_alike_on_gpu_and_cpu_in_three_geometries() {
    use bevy_curved_spaces::scene::gltf;
    use bevy_curved_spaces::scene::{Light, MeshInstance, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let model =
        gltf::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/models/cube.glb"))
            .expect("the asset loads");
    assert!(!model.textures.is_empty(), "the cube carries its texture");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("seed");
        let g = space.geometry();
        let r = inradius(&space);
        let mut scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts {
                edges: true,
                centrepiece: Centrepiece::None,
                avatar: false,
                clifford: false,
            },
        );
        let mesh = scene
            .add_model(g, &model, 0.3 * r / 3f64.sqrt())
            .expect("places");
        let frame = g.rotation(DVec3::new(1.0, 2.0, 0.5), 0.7);
        let radius = scene.meshes[mesh as usize].radius;
        scene
            .place(
                &space,
                Object::Mesh(MeshInstance::new(g, mesh, frame, radius)),
            )
            .expect("inside");
        let at = |v: DVec3| g.translation(v, v.length() * r) * space.centre();
        scene.lights.push(Light::new(
            &space,
            at(DVec3::new(-0.5, 0.4, 0.6)),
            DVec3::new(0.4, 0.5, 1.0),
            g.s(r).powi(2) * 0.5,
        ));
        let camera = TraceCamera::default_for(&space);
        failures.extend(compare_scene(
            &mut renderer,
            id,
            &space,
            &scene,
            camera.frame,
            0.0,
            &format!("cube-{id}"),
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every example scene in `assets/scenes/` (globes at a spun time, glTF meshes, discs,
/// emission, several lights, the avatar) draws alike on the GPU and the CPU.
#[test]
fn the_example_scene_files_render_alike_on_gpu_and_cpu() {
    use bevy_curved_spaces::scene::file::load_scene_file;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("assets/scenes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 2, "the examples ship");
    let mut failures = Vec::new();
    for path in &files {
        // Product scene files are compared in products.rs (their own renderer).
        if bevy_curved_spaces::trace::product::file::load_product_scene_file(path)
            .unwrap_or_else(|e| panic!("{e}"))
            .is_some()
        {
            continue;
        }
        // A Nil scene file: its start view on the GPU against the f64 CPU reference.
        if let Some(nil) = bevy_curved_spaces::trace::nil::file::load_nil_scene_file(path)
            .unwrap_or_else(|e| panic!("{e}"))
        {
            let camera = nil.start.expect("a start view");
            let budget = bevy_curved_spaces::plugin::nil::default_nil_budget(&nil.space);
            let size = (64, 36);
            let layout = bevy_curved_spaces::view::ViewLayout::new(
                Default::default(),
                false,
                [camera.frame; 2],
                camera.fov_y_degrees,
                size.0,
                size.1,
            );
            let cpu = bevy_curved_spaces::trace::nil::render_nil_view(
                &nil.space,
                &nil.scene,
                &layout,
                budget as usize,
            );
            let gpu = renderer
                .render_nil(
                    &nil.space,
                    &nil.scene,
                    &camera,
                    size,
                    budget,
                    Default::default(),
                )
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let name = path.file_stem().expect("name").to_string_lossy();
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            super::judge(&name, &gpu, &cpu, &out, &mut failures);
            continue;
        }
        // An SL̃(2,R) scene (its GPU test also draws it in stereo: gpu/sl2r.rs).
        if let Some(file) = bevy_curved_spaces::trace::sl2r::file::load_sl2r_scene_file(path)
            .unwrap_or_else(|e| panic!("{e}"))
        {
            let size = (64, 36);
            let layout = bevy_curved_spaces::view::ViewLayout::new(
                bevy_curved_spaces::view::StereoMode::Mono,
                false,
                [file.start.frame; 2],
                file.start.fov_y_degrees,
                size.0,
                size.1,
            );
            let cpu = bevy_curved_spaces::trace::sl2r::render_sl2r_view(
                &file.space,
                &file.scene,
                &layout,
                24,
            );
            let gpu = renderer
                .render_sl2r(
                    &file.space,
                    &file.scene,
                    &file.start,
                    size,
                    24,
                    Default::default(),
                )
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let name = path.file_stem().expect("name").to_string_lossy();
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            super::judge(&name, &gpu, &cpu, &out, &mut failures);
            continue;
        }
        let file = load_scene_file(path).unwrap_or_else(|e| panic!("{e}"));
        let frame = file
            .start
            .unwrap_or_else(|| TraceCamera::default_for(&file.space).frame);
        let name = path
            .file_stem()
            .expect("name")
            .to_string_lossy()
            .to_string();
        failures.extend(compare_scene(
            &mut renderer,
            &file.space_id,
            &file.space,
            &file.scene(),
            frame,
            2.5,
            &name,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The globe of `assets/scenes/torus_globe.toml` with its picture scaled up to 8192×8192
/// texels (256 MiB, past the 128 MiB a storage binding is guaranteed: the GPU reads it from
/// a texture of its own), and with its picture as the scene's tenth texture (past the
/// texture slots: its texels go in the scene data buffer), draws alike on the GPU and the
/// CPU.
#[test]
fn a_globe_texture_of_8192_texels_a_side_and_one_past_the_slots_render_alike() {
    use bevy_curved_spaces::plugin::render::gpu::TEXTURE_SLOTS;
    use bevy_curved_spaces::scene::Object;
    use bevy_curved_spaces::scene::file::load_scene_file;
    use bevy_curved_spaces::scene::texture::{MAX_TEXTURE_SIDE, Texture};
    use std::sync::Arc;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/torus_globe.toml");
    let file = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let scene = file.scene();
    let globe = scene
        .objects
        .iter()
        .find_map(|o| match o {
            Object::Ball(b) => b.texture.map(|t| t.texture as usize),
            _ => None,
        })
        .expect("the scene has a globe");
    let picture = scene.textures[globe].clone();
    // Nearest-texel scaling: the same picture, each texel read from the large texture.
    let side = MAX_TEXTURE_SIDE;
    let texels = (0..side * side)
        .map(|i| {
            let (x, y) = (i % side, i / side);
            let (u, v) = (
                (u64::from(x) * u64::from(picture.width) / u64::from(side)) as u32,
                (u64::from(y) * u64::from(picture.height) / u64::from(side)) as u32,
            );
            picture.texels[(v * picture.width + u) as usize]
        })
        .collect();
    let large = Arc::new(Texture {
        width: side,
        height: side,
        texels,
    });
    assert!(4 * large.texels.len() > 128 << 20, "past a storage binding");
    let retextured = |texture: usize| {
        let mut s = scene.clone();
        for o in &mut s.objects {
            if let Object::Ball(b) = o
                && let Some(t) = &mut b.texture
            {
                t.texture = texture as u32;
            }
        }
        s
    };
    let mut with_large = retextured(globe);
    with_large.textures[globe] = large;
    let mut past_the_slots = retextured(TEXTURE_SLOTS + 1);
    while past_the_slots.textures.len() <= TEXTURE_SLOTS {
        past_the_slots.textures.push(Arc::new(Texture {
            width: 1,
            height: 1,
            texels: vec![0xff00_ff00],
        }));
    }
    past_the_slots.textures.push(picture);
    let frame = file
        .start
        .unwrap_or_else(|| TraceCamera::default_for(&file.space).frame);
    let mut failures = Vec::new();
    for (name, s) in [
        ("globe-8192", &with_large),
        ("globe-past-the-slots", &past_the_slots),
    ] {
        failures.extend(compare_scene(
            &mut renderer,
            &file.space_id,
            &file.space,
            s,
            frame,
            2.5,
            name,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A scene the GPU cannot take (scene data past what a GPU is guaranteed to bind) is
/// refused at once with the reason, not after waiting for a picture: a 6000×6000 texture
/// past the texture slots puts 137 MiB of texels in the scene data buffer.
#[test]
fn an_offscreen_render_of_a_scene_too_large_for_the_gpu_says_why() {
    use bevy_curved_spaces::plugin::components::BaseScene;
    use bevy_curved_spaces::plugin::offscreen::OffscreenError;
    use bevy_curved_spaces::plugin::render::gpu::TEXTURE_SLOTS;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = bevy_curved_spaces::space::seed_space("torus").expect("seed");
    let mut scene = CurvedScene::default_for(&space, 1.5);
    while scene.textures.len() < TEXTURE_SLOTS {
        scene.textures.push(std::sync::Arc::new(
            bevy_curved_spaces::scene::texture::Texture {
                width: 1,
                height: 1,
                texels: vec![0],
            },
        ));
    }
    scene.textures.push(std::sync::Arc::new(
        bevy_curved_spaces::scene::texture::Texture {
            width: 6000,
            height: 6000,
            texels: vec![0; 6000 * 6000],
        },
    ));
    let started = std::time::Instant::now();
    let result = renderer.render(&OffscreenRender {
        base: BaseScene {
            space_id: "torus".into(),
            scene: Some(std::sync::Arc::new(scene)),
            start: None,
            parts: None,
            fov: None,
            moving: Vec::new(),
        },
        ..OffscreenRender::new(
            ActiveSpace::new("torus", space.clone()),
            TraceCamera {
                frame: TraceCamera::default_for(&space).frame,
                fov_y_degrees: 70.0,
            },
            (WIDTH, HEIGHT),
            16,
        )
    });
    match result {
        Err(OffscreenError::Scene(why)) => assert!(why.contains("meshes and textures"), "{why}"),
        other => panic!("{:?}", other.map(|i| i.dimensions())),
    }
    assert!(started.elapsed().as_secs() < 30);
}

/// Entities ([`bevy_curved_spaces::plugin::objects`]) as a game spawns them: balls, a tube, a disc and
/// two meshes (shared traced models, so material bases and padded lists are exercised) in
/// Seifert–Weber with its edges (culled lists) and in the torus, one ball straddling a face.
/// The GPU draws them as the CPU reference draws the same objects.
#[test]
fn entities_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::objects::{
        CurvedObject, CurvedTransform, ReadyObject, ReadyShape, add_entity_objects,
    };
    use bevy_curved_spaces::scene::mesh::cube_source;
    use bevy_curved_spaces::scene::{Model, SurfaceMaterial, TracedModel};
    use glam::DVec3;
    use std::sync::Arc;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["seifert-weber", "torus"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = bevy_curved_spaces::space::invariants::inradius(&space);
        let model = |colour: DVec3| {
            Arc::new(
                TracedModel::new(
                    g,
                    &Model {
                        source: cube_source(0.5, 0),
                        materials: vec![SurfaceMaterial {
                            colour,
                            ..SurfaceMaterial::default()
                        }],
                        textures: Vec::new(),
                    },
                    0.2 * r,
                )
                .expect("cube"),
            )
        };
        let (green, blue) = (
            model(DVec3::new(0.2, 0.9, 0.3)),
            model(DVec3::new(0.2, 0.3, 0.9)),
        );
        let at = |x: f64, y: f64, z: f64| {
            CurvedTransform::from_geodesic(&space, DVec3::new(x, y, z) * r).0
        };
        let objects: Vec<(CurvedObject, glam::DMat4)> = vec![
            (
                CurvedObject::ball(0.15 * r, DVec3::new(0.9, 0.3, 0.2)),
                at(0.3, 0.1, -0.6),
            ),
            // Over a face: drawn through its images too.
            (
                CurvedObject::ball(0.3 * r, DVec3::new(0.9, 0.8, 0.2)),
                at(0.0, 0.3, -0.9),
            ),
            (
                CurvedObject::tube(0.6 * r, 0.05 * r, DVec3::new(0.8, 0.2, 0.8)),
                at(-0.4, 0.0, -0.5),
            ),
            // A half mirror: an entity's reflectance reaches both tracers.
            (
                CurvedObject::disc(0.2 * r, DVec3::new(0.3, 0.8, 0.8)).with_reflectance(0.5),
                at(0.0, -0.4, -0.5),
            ),
            (CurvedObject::traced(green.clone()), at(0.4, -0.3, -0.4)),
            (CurvedObject::traced(blue.clone()), at(-0.4, 0.35, -0.45)),
            (CurvedObject::traced(green), at(-0.2, -0.35, -0.7)),
        ];
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let mut scene =
            CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), parts);
        let ready: Vec<ReadyObject> = objects
            .iter()
            .enumerate()
            .map(|(i, (o, frame))| ReadyObject {
                entity: bevy::prelude::Entity::from_raw_u32(i as u32 + 1).unwrap(),
                shape: match &o.shape {
                    bevy_curved_spaces::plugin::objects::CurvedShape::Ball { radius } => {
                        ReadyShape::Ball(*radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Tube { length, radius } => {
                        ReadyShape::Tube(*length, *radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Disc { radius } => {
                        ReadyShape::Disc(*radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Traced(m) => {
                        ReadyShape::Mesh(m.clone())
                    }
                    other => panic!("{other:?}"),
                },
                frame: *frame,
                colour: o.colour,
                emission: o.emission,
                reflectance: o.reflectance,
            })
            .collect();
        let problems = add_entity_objects(&mut scene, &space, &ready);
        assert!(problems.is_empty(), "{id}: {problems:?}");
        assert!(scene.has_mirrors(), "{id}: the mirror disc is drawn as one");
        let camera = TraceCamera::default_for(&space);
        let cpu = render(
            &space,
            &scene,
            &camera,
            &RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                max_crossings: 16,
            },
        );
        let gpu = renderer
            .render(&OffscreenRender {
                parts,
                entities: objects,
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    16,
                )
            })
            .expect("renders");
        let (c, _) = compare(&gpu, &cpu, TOLERANCE);
        println!(
            "{id} with entities: differing {:.3} %, mean error {:.3}/255",
            100.0 * c.differing,
            c.mean_error
        );
        let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
        let _ = std::fs::create_dir_all(&out);
        let _ = gpu.save(out.join(format!("entities-{id}-gpu.png")));
        let _ = cpu.save(out.join(format!("entities-{id}-cpu.png")));
        assert!(
            c.differing <= MAX_DIFFERING,
            "{id}: {:.3} % differ",
            100.0 * c.differing
        );
    }
}
