//! The WGSL tracer is composed with naga_oil (as Bevy does) and validated with naga for every
//! shader-def combination, without a GPU; the uniform layout naga computes must equal what
//! the Rust packer writes.

use bevy::shader::ShaderDefVal;
use bevy_curved_spaces::bench::BASELINE_WGSL;
use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::plugin::render::gpu::{
    GpuScene, MAX_GPU_BUDGET, ShaderKey, TEXTURE_SLOTS, TRACER_WGSL, UPSCALE_WGSL, VIEW_WORDS,
    compose_wgsl, undecorated,
};
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::{CurvedScene, SceneParts, Shading};
use bevy_curved_spaces::space::SEED_SPACES;

fn compose(key: &ShaderKey) -> Result<naga::Module, String> {
    compose_wgsl(TRACER_WGSL, "shaders/curved_space.wgsl", &key.shader_defs())
        .map_err(|e| format!("{key:?}: {e}"))
}

/// Validates a composed module and returns the size naga lays `SpaceUniform` out with.
pub(crate) fn validate(key: &ShaderKey) -> usize {
    let module = compose(key).unwrap_or_else(|e| panic!("composing failed: {e}"));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{key:?} does not validate: {e:?}"));
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .expect("layout of a validated module");
    let (handle, _) = module
        .types
        .iter()
        .find(|(_, t)| t.name.as_deref().map(undecorated) == Some("SpaceUniform"))
        .expect("the shader declares SpaceUniform");
    layouter[handle].size as usize
}

/// Each typed struct of the packer has the size and member offsets naga lays its WGSL twin
/// out with, in a variant that declares them all.
#[test]
fn the_typed_gpu_structs_match_their_wgsl_twins() {
    use bevy_curved_spaces::plugin::render::layout::{
        GpuBall, GpuDisc, GpuGlobe, GpuInstance, GpuShading, GpuTube, GpuView,
    };
    let key = ShaderKey {
        faces: 6,
        balls: 1,
        tubes: 1,
        globes: 1,
        discs: 1,
        instances: 1,
        lights: 1,
        light_images: 2,
        avatar: true,
        textures: true,
        ..ShaderKey::empty(Geometry::Hyperbolic)
    };
    let module = compose(&key).unwrap_or_else(|e| panic!("composing failed: {e}"));
    let mut layouter = naga::proc::Layouter::default();
    layouter.update(module.to_ctx()).expect("layout");
    let wgsl = |name: &str| -> (usize, Vec<(String, u32)>) {
        let (handle, ty) = module
            .types
            .iter()
            .find(|(_, t)| t.name.as_deref().map(undecorated) == Some(name))
            .unwrap_or_else(|| panic!("the shader declares {name}"));
        let naga::TypeInner::Struct { members, .. } = &ty.inner else {
            panic!("{name} is a struct");
        };
        let offsets = members
            .iter()
            .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
            .collect();
        (layouter[handle].size as usize, offsets)
    };
    macro_rules! check {
        ($wgsl:literal, $rust:ty, [$($field:ident),+]) => {{
            let (size, members) = wgsl($wgsl);
            assert_eq!(size, size_of::<$rust>(), "{}: size", $wgsl);
            let rust = [$((stringify!($field), std::mem::offset_of!($rust, $field) as u32)),+];
            let names: Vec<(&str, u32)> = members.iter().map(|(n, o)| (n.as_str(), *o)).collect();
            assert_eq!(names, rust, "{}: members and offsets", $wgsl);
        }};
    }
    check!(
        "View",
        GpuView,
        [frames, lens, viewport, split, anaglyph, avatar, avatar_info]
    );
    check!("Shading", GpuShading, [fog, params, exact]);
    check!("Ball", GpuBall, [centre, colour, emission]);
    check!("Tube", GpuTube, [a, towards_b, colour, length, emission]);
    check!("Globe", GpuGlobe, [centre, colour, emission, spin, inverse]);
    check!(
        "Disc",
        GpuDisc,
        [centre, normal, covector, colour, emission]
    );
    check!("Instance", GpuInstance, [frame, inverse, info]);
}

#[test]
fn every_shader_def_combination_validates_and_matches_the_packed_layout() {
    let mut checked = 0;
    for geometry in Geometry::ALL {
        for faces in [1, 6, 8, 12, 128] {
            for balls in [0, 1, 21] {
                for tubes in [0, 1, 30] {
                    // Culling masks balls and tubes: with them, and without.
                    let cullings: &[bool] = if balls + tubes > 0 {
                        &[false, true]
                    } else {
                        &[false]
                    };
                    for &culling in cullings {
                        let key = ShaderKey {
                            geometry,
                            faces,
                            balls,
                            tubes,
                            lights: 1,
                            light_images: faces + 1,
                            culling,
                            ..ShaderKey::empty(geometry)
                        };
                        assert_eq!(
                            validate(&key),
                            key.uniform_bytes(),
                            "{key:?}: naga's layout differs from the packer's size"
                        );
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 3 * 5 * (3 * 3 + 8));
}

/// The lighting variants in every geometry: the nearest copy or every image, hard shadows
/// and soft ones (`LIGHT_IMAGES_SUM`, `SHADOWS`, `SOFT_SHADOWS`), with several lights: each
/// validates (plain and with `HIT_ID`) and naga's layout of the uniform is the packer's.
#[test]
fn lighting_variants_validate_and_match_the_packed_layout() {
    let mut checked = 0;
    for geometry in Geometry::ALL {
        for (light_sum, shadows, soft_samples) in [
            (false, 0, 0),
            (true, 0, 0),
            (false, 2, 0),
            (true, 4, 0),
            (true, 4, 8),
            (false, 1, 3),
        ] {
            let key = ShaderKey {
                faces: 12,
                balls: 2,
                tubes: 1,
                discs: 1,
                lights: 2,
                light_images: 20,
                light_sum,
                shadows,
                soft_samples,
                ..ShaderKey::empty(geometry)
            };
            validates_with_hit_id(&key);
            checked += 1;
        }
    }
    assert_eq!(checked, 3 * 6);
}

/// The cells beyond the chart in S³: the 3-sphere (no face, one unused slot), projective
/// space (one face) and a lens (two), with rays stepping at most π/4 (`STEP_CAP`), plain
/// and with `HIT_ID`, with and without objects: each validates and matches the packer.
#[test]
fn cells_reaching_the_equator_validate_and_match_the_packed_layout() {
    for faces in [0, 1, 2] {
        for (balls, tubes) in [(0, 0), (1, 0), (2, 1)] {
            let key = ShaderKey {
                faces,
                balls,
                tubes,
                lights: 1,
                light_images: 2,
                step_cap: true,
                ..ShaderKey::empty(Geometry::Spherical)
            };
            validates_with_hit_id(&key);
        }
    }
}

/// Spaces of several cells (`CELLS`: each face's cell packed beside the partners) in every
/// geometry, with walls, mirrors, shadows, the straightforward tracer and `STEP_CAP`: each
/// validates (plain and with `HIT_ID`) and naga's layout of the uniform is the packer's.
#[test]
fn spaces_of_several_cells_validate_and_match_the_packed_layout() {
    for geometry in Geometry::ALL {
        for faces in [8, 12, 13, 128] {
            for (walls, mirrors, shadows) in [(false, false, 0), (true, false, 0), (true, true, 2)]
            {
                let key = ShaderKey {
                    faces,
                    balls: 2,
                    tubes: 1,
                    lights: 1,
                    light_images: 3,
                    shadows,
                    walls,
                    mirrors,
                    cells: true,
                    step_cap: geometry == Geometry::Spherical && faces == 8,
                    ..ShaderKey::empty(geometry)
                };
                validates_with_hit_id(&key);
            }
            let straightforward = ShaderKey {
                faces,
                balls: 2,
                cells: true,
                straightforward: true,
                ..ShaderKey::empty(geometry)
            };
            validates_with_hit_id(&straightforward);
        }
    }
}

/// Globes, discs, meshes, the avatar, textures and several lights, alone and together, in
/// every geometry: each combination validates (plain and with `HIT_ID`) and naga's layout
/// of the uniform is the packer's.
#[test]
fn scene_content_variants_validate_and_match_the_packed_layout() {
    let mut checked = 0;
    for geometry in Geometry::ALL {
        for (globes, discs, instances, avatar, textures, lights) in [
            (1, 0, 0, false, true, 1),
            (0, 2, 0, false, false, 3),
            (0, 0, 3, false, false, 1),
            (0, 0, 0, true, false, 1),
            (0, 0, 2, false, true, 0),
            (2, 3, 4, true, true, 4),
        ] {
            let key = ShaderKey {
                faces: 12,
                balls: 2,
                tubes: 1,
                globes,
                discs,
                instances,
                avatar,
                textures,
                lights,
                light_images: 13,
                ..ShaderKey::empty(geometry)
            };
            validates_with_hit_id(&key);
            checked += 1;
        }
    }
    assert_eq!(checked, 18);
}

#[test]
fn each_geometry_compiles_only_its_own_formulas() {
    // The hyperbolic shader has no sin/atan2, the spherical none of sinh/asinh/log, and the
    // flat one neither: the defs select the formulas at compile time, not at run time.
    for (geometry, present, absent) in [
        (
            Geometry::Spherical,
            &["Sin", "Atan2"][..],
            &["Sinh", "Asinh", "Log"][..],
        ),
        (
            Geometry::Euclidean,
            &[][..],
            &["Sin", "Sinh", "Atan2", "Asinh", "Log"][..],
        ),
        (
            Geometry::Hyperbolic,
            &["Sinh", "Asinh", "Log"][..],
            &["Sin", "Atan2"][..],
        ),
    ] {
        // Lit, so that the light's falloff S(d) is used: naga_oil keeps only what is used.
        let key = ShaderKey {
            geometry,
            faces: 6,
            balls: 1,
            tubes: 1,
            lights: 1,
            light_images: 1,
            ..ShaderKey::empty(geometry)
        };
        let module = compose(&key).expect("composes");
        let text = format!("{:?}", module.functions);
        for f in present {
            assert!(
                text.contains(&format!("fun: {f},")),
                "{geometry:?} shader lacks its own {f}"
            );
        }
        for f in absent {
            let pattern = format!("fun: {f},");
            assert!(
                !text.contains(&pattern),
                "{geometry:?} shader uses {f} of another geometry"
            );
        }
    }
    // A scene without tubes compiles no tube code.
    let key = ShaderKey {
        geometry: Geometry::Hyperbolic,
        faces: 12,
        balls: 3,
        tubes: 0,
        ..ShaderKey::empty(Geometry::Hyperbolic)
    };
    let module = compose(&key).expect("composes");
    assert!(
        module
            .functions
            .iter()
            .all(|(_, f)| !f.name.as_deref().unwrap_or("").contains("tube"))
    );
}

#[test]
fn every_seed_scene_packs_to_the_shader_layout() {
    for seed in SEED_SPACES {
        let space = seed.build().expect("seed space builds");
        for parts in [
            SceneParts::default(),
            SceneParts {
                edges: false,
                centrepiece: Centrepiece::Ball,
                avatar: false,
                clifford: false,
            },
            SceneParts {
                edges: true,
                centrepiece: Centrepiece::None,
                avatar: false,
                clifford: false,
            },
        ] {
            let scene =
                CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), parts);
            let gpu = GpuScene::new(&space, &scene, 24).expect("packs");
            assert_eq!(gpu.key.geometry, space.geometry());
            assert_eq!(gpu.key.faces as usize, space.faces().len());
            assert_eq!(
                (gpu.key.balls + gpu.key.tubes) as usize,
                scene.objects.len(),
                "{}: every object is packed once",
                seed.id
            );
            assert_eq!(
                (gpu.words.len() + VIEW_WORDS) * 4,
                validate(&gpu.key),
                "{}: packed words differ from the shader's uniform size",
                seed.id
            );
            // The edges hug the faces: they are culled (but in a space of several cells,
            // where every object is tested in every cell); the same scene unculled packs too.
            let one_cell = space.cells().len() == 1;
            assert_eq!(gpu.key.culling, parts.edges && one_cell, "{}", seed.id);
            assert_eq!(gpu.key.cells, !one_cell, "{}", seed.id);
            let unculled = gpu.without_culling();
            assert_eq!(
                (unculled.words.len() + VIEW_WORDS) * 4,
                validate(&unculled.key),
                "{}: unculled words differ from the shader's uniform size",
                seed.id
            );
        }
    }
}

#[test]
fn a_scene_without_objects_and_a_zero_budget_are_refused_or_handled() {
    let space = SEED_SPACES[0].build().expect("seed space builds");
    let scene = CurvedScene::with_parts(
        &space,
        1.0,
        SceneParts {
            edges: false,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        },
    );
    let gpu = GpuScene::new(&space, &scene, 8).expect("an empty scene shows fog");
    assert_eq!((gpu.key.balls, gpu.key.tubes), (0, 0));
    validate(&gpu.key);
    assert!(GpuScene::new(&space, &scene, 0).is_err());
    // Every shader loop is bounded: the budget by MAX_GPU_BUDGET, faces and objects by the
    // counts the shader is compiled with.
    assert!(GpuScene::new(&space, &scene, MAX_GPU_BUDGET).is_ok());
    let too_many = GpuScene::new(&space, &scene, MAX_GPU_BUDGET + 1);
    assert!(
        too_many
            .as_ref()
            .is_err_and(|e| e.to_string().contains("more than the GPU tracer takes")),
        "{too_many:?}"
    );
    // A large texture in one of the texture slots is a GPU texture of its own: accepted,
    // its texels kept out of the scene data buffer.
    let texture = |side: u32| {
        std::sync::Arc::new(bevy_curved_spaces::scene::texture::Texture {
            width: side,
            height: side,
            texels: vec![0; (side * side) as usize],
        })
    };
    let mut heavy = scene.clone();
    heavy.textures.push(texture(6000));
    let slotted = GpuScene::new(&space, &heavy, 8).expect("a slot takes a large texture");
    assert_eq!(slotted.textures.len(), 1);
    assert!(slotted.data.len() < 1 << 20, "{} words", slotted.data.len());
    // Past the slots, scene data beyond what a GPU is guaranteed to bind is refused with
    // its size named.
    let mut heavy = scene.clone();
    heavy
        .textures
        .extend((0..TEXTURE_SLOTS).map(|_| texture(1)));
    heavy.textures.push(texture(6000));
    let refused = GpuScene::new(&space, &heavy, 8);
    assert!(
        refused
            .as_ref()
            .is_err_and(|e| e.to_string().contains("meshes and textures need")),
        "{:?}",
        refused.map(|g| g.key)
    );
}

#[test]
fn the_upscaling_and_benchmark_baseline_shaders_validate() {
    let upscale = |defs: &[&str]| {
        let defs: Vec<ShaderDefVal> = defs.iter().map(|d| (*d).into()).collect();
        compose_wgsl(UPSCALE_WGSL, "upscale.wgsl", &defs).expect("composes")
    };
    let baseline = compose_wgsl(BASELINE_WGSL, "bench_baseline.wgsl", &[]).expect("composes");
    // Mono, side by side and top and bottom (the halves kept apart).
    for module in [
        upscale(&[]),
        upscale(&["SPLIT_X"]),
        upscale(&["SPLIT_Y"]),
        baseline,
    ] {
        naga::valid::Validator::new(
            naga::valid::ValidationFlags::all(),
            naga::valid::Capabilities::default(),
        )
        .validate(&module)
        .expect("validates");
        assert_eq!(module.entry_points.len(), 2);
    }
}

/// `key`'s shader validates, plain and with `HIT_ID`, and naga's layout of the uniform is
/// the packer's.
fn validates_with_hit_id(key: &ShaderKey) {
    assert_eq!(
        validate(key),
        key.uniform_bytes(),
        "{key:?}: naga's layout differs from the packer's size"
    );
    hit_id_module(key);
}

/// The `HIT_ID` variant of a key, composed and validated.
fn hit_id_module(key: &ShaderKey) -> naga::Module {
    let mut defs = key.shader_defs();
    defs.push(ShaderDefVal::from("HIT_ID"));
    let module = compose_wgsl(TRACER_WGSL, "curved_space.wgsl", &defs)
        .unwrap_or_else(|e| panic!("{key:?} with HIT_ID: {e}"));
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .unwrap_or_else(|e| panic!("{key:?} with HIT_ID does not validate: {e:?}"));
    module
}

/// The benchmark's `HIT_ID` variant writes what each ray met as `vec4<u32>`.
#[test]
fn the_hit_id_variant_validates_and_writes_four_integers() {
    for geometry in Geometry::ALL {
        for (balls, tubes) in [(0, 0), (3, 0), (0, 2), (3, 2)] {
            let key = ShaderKey {
                geometry,
                faces: 12,
                balls,
                tubes,
                ..ShaderKey::empty(geometry)
            };
            let module = hit_id_module(&key);
            let fragment = module
                .entry_points
                .iter()
                .find(|e| e.name == "fragment")
                .expect("a fragment entry point");
            let result = fragment.function.result.as_ref().expect("returns a value");
            assert_eq!(
                module.types[result.ty].inner,
                naga::TypeInner::Vector {
                    size: naga::VectorSize::Quad,
                    scalar: naga::Scalar::U32
                },
                "{key:?}"
            );
        }
    }
}

/// The benchmark's unspecialised variant compiles every geometry's formulas, validates, and
/// the generalised packing of every seed scene has naga's layout.
#[test]
fn the_general_variant_holds_every_geometry_and_packs_to_its_layout() {
    for seed in SEED_SPACES {
        let space = seed.build().expect("seed space builds");
        let scene = CurvedScene::default_for(&space, Shading::default_fog_distance(&space));
        let gpu = GpuScene::new(&space, &scene, 16).expect("packs");
        // The general variant walks one cell.
        if space.cells().len() > 1 {
            assert_eq!(gpu.generalised(), None, "{}", seed.id);
            continue;
        }
        let general = gpu.generalised().expect("fits the general capacity");
        assert!(general.key.general);
        assert_eq!(
            (general.words.len() + VIEW_WORDS) * 4,
            validate(&general.key),
            "{}: generalised words differ from the general shader's uniform",
            seed.id
        );
        assert_eq!(general.generalised(), None, "already general");
    }
    let key = GpuScene::new(
        &SEED_SPACES[0].build().expect("builds"),
        &CurvedScene::default_for(&SEED_SPACES[0].build().expect("builds"), 1.0),
        4,
    )
    .expect("packs")
    .generalised()
    .expect("general")
    .key;
    let text = format!("{:?}", compose(&key).expect("composes").functions);
    for f in ["Sin", "Sinh", "Atan2", "Asinh", "Log"] {
        assert!(
            text.contains(&format!("fun: {f},")),
            "general shader lacks {f}"
        );
    }
}

/// The stereo variants (eyes in two halves, or two eyes per pixel for an anaglyph) compose,
/// validate and keep the packed layout.
#[test]
fn stereo_variants_validate_with_the_same_layout() {
    use bevy_curved_spaces::plugin::render::gpu::view_shader_defs;
    use bevy_curved_spaces::view::ViewKind;
    for geometry in Geometry::ALL {
        for kind in [ViewKind::Split, ViewKind::Anaglyph] {
            let key = ShaderKey {
                geometry,
                faces: 12,
                balls: 3,
                tubes: 2,
                lights: 2,
                light_images: 13,
                ..ShaderKey::empty(geometry)
            };
            let defs = [key.shader_defs(), view_shader_defs(kind)].concat();
            let module = compose_wgsl(TRACER_WGSL, "curved_space.wgsl", &defs)
                .unwrap_or_else(|e| panic!("{key:?} {kind:?}: {e}"));
            naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::default(),
            )
            .validate(&module)
            .unwrap_or_else(|e| panic!("{key:?} {kind:?} does not validate: {e:?}"));
            let mut layouter = naga::proc::Layouter::default();
            layouter.update(module.to_ctx()).expect("layout");
            let (handle, _) = module
                .types
                .iter()
                .find(|(_, t)| t.name.as_deref().map(undecorated) == Some("SpaceUniform"))
                .expect("SpaceUniform");
            assert_eq!(layouter[handle].size as usize, key.uniform_bytes());
        }
        assert!(view_shader_defs(ViewKind::Mono).is_empty());
    }
}

/// The benchmark's straightforward tracer (`STRAIGHTFORWARD`) in every geometry, with and
/// without lights, validates and keeps the packer's layout.
#[test]
fn the_straightforward_variant_validates_and_matches_the_packed_layout() {
    for geometry in Geometry::ALL {
        for lights in [0, 1] {
            let key = ShaderKey {
                faces: 12,
                balls: 1,
                lights,
                light_images: 2 * lights,
                straightforward: true,
                ..ShaderKey::empty(geometry)
            };
            assert_eq!(validate(&key), key.uniform_bytes(), "{key:?}");
        }
    }
}

/// The teaching views (`COLOUR_BY` 1 to 3, `COLOUR_HOLONOMY`) in every geometry, with and
/// without objects and culling, plain and with `HIT_ID`: each validates and keeps the
/// packer's layout.
#[test]
fn colour_by_variants_validate_and_match_the_packed_layout() {
    for geometry in Geometry::ALL {
        for colour_by in 1..=3 {
            for (balls, tubes, culling) in [(0, 0, false), (2, 3, true), (1, 0, false)] {
                let key = ShaderKey {
                    faces: 6,
                    balls,
                    tubes,
                    culling,
                    lights: 1,
                    light_images: 2,
                    colour_by,
                    ..ShaderKey::empty(geometry)
                };
                validates_with_hit_id(&key);
            }
        }
    }
}

/// The walls with windows (`WALLS`) in every geometry, alone and with objects, culling, a
/// teaching view, stereo-free and with `HIT_ID`: each validates and keeps the packer's
/// layout, and a seed scene with walls packs to it.
#[test]
fn wall_variants_validate_and_match_the_packed_layout() {
    for geometry in Geometry::ALL {
        for (balls, tubes, culling, colour_by) in
            [(0, 0, false, 0), (2, 3, true, 2), (1, 0, false, 0)]
        {
            let key = ShaderKey {
                faces: 6,
                balls,
                tubes,
                culling,
                colour_by,
                walls: true,
                ..ShaderKey::empty(geometry)
            };
            validates_with_hit_id(&key);
        }
    }
    for seed in SEED_SPACES {
        let space = seed.build().expect("builds");
        let mut scene = CurvedScene::default_for(&space, Shading::default_fog_distance(&space));
        scene.shading.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.5).unwrap());
        let gpu = GpuScene::new(&space, &scene, 16).expect("packs");
        assert!(gpu.key.walls, "{}", seed.id);
        assert_eq!(
            (gpu.words.len() + VIEW_WORDS) * 4,
            validate(&gpu.key),
            "{}: packed words differ from the shader's uniform size",
            seed.id
        );
    }
}

/// The product variant (H²×R, S²×R) validates for every library product space's default
/// scene, and the packer writes exactly the layout naga computes; a stereo view of it too.
#[test]
fn product_variants_validate_and_match_the_packed_layout() {
    use bevy_curved_spaces::space::product::PRODUCT_ALIASES;
    use bevy_curved_spaces::trace::product::default_scene;
    for alias in PRODUCT_ALIASES {
        let space = crate::common::product(alias.id);
        let scene = default_scene(&space);
        let gpu = GpuScene::product(&space, &scene, 32).expect("packs");
        assert!(gpu.key.product && gpu.key.faces as usize == space.side_faces().len());
        let bytes = validate(&gpu.key);
        assert_eq!(bytes, gpu.key.uniform_bytes(), "{}", alias.id);
        assert_eq!((gpu.words.len() + VIEW_WORDS) * 4, bytes, "{}", alias.id);
    }
    // Every optional part of the product tracer, in both geometries: walls, shadowed lamp
    // images, the teaching views' colours, all at once.
    for id in ["bitorus-circle", "sphere-circle-turn"] {
        let space = crate::common::product(id);
        let mut scene = default_scene(&space);
        scene.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.5).expect("style"));
        scene
            .set_lighting(
                &space,
                scene.light,
                bevy_curved_spaces::scene::lighting::Lighting {
                    shadows: 8,
                    ..Default::default()
                },
            )
            .expect("lighting");
        scene.colour_by = bevy_curved_spaces::scene::ColourBy::Holonomy;
        let gpu = GpuScene::product(&space, &scene, 32).expect("packs");
        assert_eq!(
            validate(&gpu.key),
            (gpu.words.len() + VIEW_WORDS) * 4,
            "{id}"
        );
    }
    // No objects at all still has an array slot, and the budget is checked as for any scene.
    let space = crate::common::product("bitorus-circle");
    let mut scene = default_scene(&space);
    scene.objects.clear();
    let gpu = GpuScene::product(&space, &scene, 8).expect("packs");
    assert_eq!(validate(&gpu.key), (gpu.words.len() + VIEW_WORDS) * 4);
    assert!(GpuScene::product(&space, &scene, 0).is_err());
    assert!(GpuScene::product(&space, &scene, MAX_GPU_BUDGET + 1).is_err());
}

/// The Nil variant validates for nil-1, nil-3 and nil-50's default scenes, with the lamp's
/// images, shadows, the nearest copy only, and no objects, and the packer writes exactly the
/// layout naga computes.
#[test]
fn nil_variants_validate_and_match_the_packed_layout() {
    use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting};
    use bevy_curved_spaces::space::nil::NilSpace;
    use bevy_curved_spaces::trace::nil::default_scene;
    for k in [1, 3, 50] {
        let space = NilSpace::new(k);
        let mut scene = default_scene(&space);
        let gpu = GpuScene::nil(&space, &scene, 32).expect("packs");
        assert!(gpu.key.nil && gpu.key.nil_images > 0);
        let bytes = validate(&gpu.key);
        assert_eq!(bytes, gpu.key.uniform_bytes(), "nil-{k}");
        assert_eq!((gpu.words.len() + VIEW_WORDS) * 4, bytes, "nil-{k}");
        for lighting in [
            Lighting {
                shadows: 4,
                ..Default::default()
            },
            Lighting {
                paths: LightPaths::Nearest,
                ..Default::default()
            },
        ] {
            let light = scene.light;
            scene
                .set_lighting(&space, light, lighting)
                .expect("lighting");
            let gpu = GpuScene::nil(&space, &scene, 32).expect("packs");
            assert_eq!(
                validate(&gpu.key),
                (gpu.words.len() + VIEW_WORDS) * 4,
                "nil-{k}"
            );
        }
        // Walls: six face slots for their colours and margins.
        scene.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.5).expect("an opening"));
        let gpu = GpuScene::nil(&space, &scene, 32).expect("packs");
        assert!(gpu.key.walls && gpu.key.faces == 6);
        assert_eq!(
            validate(&gpu.key),
            (gpu.words.len() + VIEW_WORDS) * 4,
            "nil-{k} with walls"
        );
        scene.walls = None;
        scene.objects.clear();
        let gpu = GpuScene::nil(&space, &scene, 8).expect("packs");
        assert_eq!(validate(&gpu.key), (gpu.words.len() + VIEW_WORDS) * 4);
        assert!(GpuScene::nil(&space, &scene, 0).is_err());
    }
}
