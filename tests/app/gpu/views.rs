//! The teaching views on the GPU against the CPU reference: colour-by, Clifford parallels
//! and the gyroscope, walls with windows, the globe and the galaxy.

use super::*;

/// The teaching views (`--colour-by crossings|face|holonomy`) on the GPU as on the CPU
/// reference, in a space of each geometry (a flat one with rotations, a spherical one and
/// the twisted hyperbolic Seifert–Weber space), and each differs from the plain picture.
#[test]
fn colour_by_views_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::scene::ColourBy;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["quarter-turn", "poincare", "seifert-weber"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let camera = TraceCamera::default_for(&space);
        let plain_scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 12,
        };
        let plain = render(&space, &plain_scene, &camera, &settings);
        for by in [ColourBy::Crossings, ColourBy::Face, ColourBy::Holonomy] {
            let mut scene = plain_scene.clone();
            scene.shading.colour_by = by;
            let cpu = render(&space, &scene, &camera, &settings);
            let gpu = renderer
                .render(&OffscreenRender {
                    colour_by: by,
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        12,
                    )
                })
                .expect("renders");
            let (c, _) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id} coloured by {}: differing {:.3} %, mean error {:.3}/255",
                by.name(),
                100.0 * c.differing,
                c.mean_error
            );
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            let _ = std::fs::create_dir_all(&out);
            let _ = gpu.save(out.join(format!("colour-by-{}-{id}-gpu.png", by.name())));
            let _ = cpu.save(out.join(format!("colour-by-{}-{id}-cpu.png", by.name())));
            assert!(
                c.differing <= MAX_DIFFERING,
                "{id} by {}: {:.3} % differ",
                by.name(),
                100.0 * c.differing
            );
            let (d, _) = compare(&cpu, &plain, TOLERANCE);
            assert!(
                d.differing > 0.05,
                "{id} by {}: like the plain picture",
                by.name()
            );
        }
    }
}

/// Clifford parallels (spherical spaces; absent elsewhere) and the gyroscope on the GPU as
/// on the CPU.
#[test]
fn clifford_parallels_and_the_gyroscope_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let clifford = SceneParts {
        clifford: true,
        ..SceneParts::default()
    };
    let gyroscope = SceneParts {
        centrepiece: Centrepiece::Gyroscope,
        ..SceneParts::default()
    };
    for (id, parts) in [
        ("poincare", clifford),
        ("lens-7-1", clifford),
        ("seifert-weber", gyroscope),
        ("mirrored-cube", gyroscope),
    ] {
        let space = bevy_curved_spaces::space::resolve_space(
            id,
            std::path::Path::new(""),
            &Default::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let plain = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let with = CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), parts);
        assert!(
            with.objects.len() >= plain.objects.len() + 6,
            "{id}: the parts are there"
        );
        let differing = parts_render_alike(&mut renderer, id, &space, parts);
        println!("{id} with {parts:?}: differing {:.3} %", 100.0 * differing);
        assert!(
            differing <= MAX_DIFFERING,
            "{id}: {:.3} % differ",
            100.0 * differing
        );
    }
    let torus = bevy_curved_spaces::space::seed_space("torus").unwrap();
    assert!(bevy_curved_spaces::scene::clifford_parallels(&torus).is_empty());
}

/// The walls with windows, closed and half open, on the GPU as on the CPU reference, in a
/// space of each geometry and one with mirrors; each differs from the plain picture.
#[test]
fn walls_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::scene::WallStyle;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["half-turn", "poincare", "seifert-weber", "mirrored-cube"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let camera = TraceCamera::default_for(&space);
        let plain_scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 12,
        };
        let plain = render(&space, &plain_scene, &camera, &settings);
        for opening in [0.0, 0.5] {
            let walls = WallStyle::new(opening).expect("in range");
            let mut scene = plain_scene.clone();
            scene.shading.walls = Some(walls);
            let cpu = render(&space, &scene, &camera, &settings);
            let gpu = renderer
                .render(&OffscreenRender {
                    walls: Some(walls),
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        12,
                    )
                })
                .expect("renders");
            let (c, _) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id} with walls {opening} open: differing {:.3} %, mean error {:.3}/255",
                100.0 * c.differing,
                c.mean_error
            );
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            let _ = std::fs::create_dir_all(&out);
            let _ = gpu.save(out.join(format!("walls-{opening}-{id}-gpu.png")));
            let _ = cpu.save(out.join(format!("walls-{opening}-{id}-cpu.png")));
            assert!(
                c.differing <= MAX_DIFFERING,
                "{id} walls {opening}: {:.3} % differ",
                100.0 * c.differing
            );
            let (d, _) = compare(&cpu, &plain, TOLERANCE);
            assert!(
                d.differing > 0.3,
                "{id} walls {opening}: like the plain picture"
            );
        }
    }
}

/// Glued faces share a colour, read off the GPU's picture: with solid, opaque walls, no
/// objects and black fog, each pixel shows the wall of the first face its ray leaves by
/// (known from the CPU walker), in that panel's colour times its light. Pixels of a face and
/// of its partner have the same hue; pixels of different pairs do not; mirrors are silver.
#[test]
fn walls_of_glued_faces_share_a_colour_in_the_picture() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::BaseScene;
    use bevy_curved_spaces::scene::walls::MIRROR_COLOUR;
    use bevy_curved_spaces::scene::{WallPanels, WallStyle};
    use bevy_curved_spaces::space::CellWalker;
    use bevy_curved_spaces::view::PixelRays;
    use glam::{DVec3, DVec4};
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let nothing = SceneParts {
        edges: false,
        centrepiece: Centrepiece::None,
        avatar: false,
        clifford: false,
    };
    let walls = WallStyle::with_opacity(0.0, 1.0).expect("in range");
    for id in ["seifert-weber", "quarter-turn", "poincare", "mirrored-cube"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let mut base =
            CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), nothing);
        base.shading.fog_colour = DVec3::ZERO;
        let camera = TraceCamera::default_for(&space);
        let gpu = renderer
            .render(&OffscreenRender {
                walls: Some(walls),
                parts: nothing,
                base: BaseScene {
                    space_id: id.into(),
                    scene: Some(std::sync::Arc::new(base.clone())),
                    parts: Some(nothing),
                    ..Default::default()
                },
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    12,
                )
            })
            .expect("renders");
        let panels = WallPanels::new(&space, walls, &base.shading).expect("walls");
        let walker = CellWalker::<DVec4>::new(&space);
        let layout = camera.layout(WIDTH, HEIGHT);
        let g = space.geometry();
        // Per face: the sum of its pixels' unit colours, and how many.
        let mut hues = vec![(DVec3::ZERO, 0usize); space.faces().len()];
        for j in 0..HEIGHT {
            for i in 0..WIDTH {
                let PixelRays::One(ray) = layout.rays_at(g, i, j) else {
                    unreachable!("a mono view")
                };
                let ray = walker.normalized(ray);
                let face = walker.exit(&ray, None).expect("a face ahead").face;
                let p = gpu.get_pixel(i, j).0.map(f64::from);
                let rgb = DVec3::new(p[0], p[1], p[2]);
                // Dark pixels (far walls, faint in the fog) carry little hue.
                if rgb.max_element() < 60.0 {
                    continue;
                }
                let hue = rgb.normalize();
                let expected = panels.faces[face].colour.normalize();
                assert!(
                    hue.distance(expected) < 0.08,
                    "{id} pixel ({i}, {j}) over face {face}: hue {hue} against the panel's {expected}"
                );
                hues[face].0 += hue;
                hues[face].1 += 1;
            }
        }
        let seen: Vec<(usize, DVec3)> = hues
            .iter()
            .enumerate()
            .filter(|(_, (_, n))| *n > 0)
            .map(|(f, (sum, n))| (f, *sum / *n as f64))
            .collect();
        assert!(seen.len() >= 2, "{id}: walls of several faces in view");
        for &(f, a) in &seen {
            for &(h, b) in &seen {
                let glued = space.faces()[f].partner == h || f == h;
                let same_hue = a.distance(b) < 0.08;
                if glued {
                    assert!(
                        same_hue,
                        "{id}: faces {f} and {h} are glued, hues {a} and {b}"
                    );
                } else if !(space.faces()[f].is_mirror(f) && space.faces()[h].is_mirror(h)) {
                    assert!(
                        !same_hue,
                        "{id}: faces {f} and {h} are not glued, hues {a} and {b}"
                    );
                }
            }
            if space.faces()[f].is_mirror(f) {
                assert!(
                    a.distance(MIRROR_COLOUR.normalize()) < 0.05,
                    "{id}: mirror {f} is silver"
                );
            }
        }
        println!("{id}: walls of {} faces seen, glued ones alike", seen.len());
    }
}

/// The globe and the galaxy centrepieces on the GPU as on the CPU reference, in a space of
/// each geometry.
#[test]
fn the_globe_and_the_galaxy_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["quarter-turn", "poincare", "seifert-weber"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        for centrepiece in [Centrepiece::Globe, Centrepiece::Galaxy] {
            let parts = SceneParts {
                centrepiece,
                ..SceneParts::default()
            };
            let differing = parts_render_alike(&mut renderer, id, &space, parts);
            println!(
                "{id} with the {}: differing {:.3} %",
                centrepiece.name(),
                100.0 * differing
            );
            assert!(
                differing <= MAX_DIFFERING,
                "{id} {}: {:.3} % differ",
                centrepiece.name(),
                100.0 * differing
            );
        }
    }
}
