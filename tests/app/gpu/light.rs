//! Light on the GPU against the CPU reference: shadows through the faces, and mirrors.

use super::*;

/// Shadows walked through the faces: a ball between the lamp and the centre ball shadows it
/// (and its images shadow the lamp's other images), on the GPU as on the CPU, in the three
/// geometries; the shadows are there to see (turned off, the picture changes). A lamp with a
/// radius casts soft ones (a few shadow rays over its disc), alike on both and unlike the
/// hard ones.
#[test]
fn shadows_through_the_faces_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::lighting::Lighting;
    use bevy_curved_spaces::scene::{Ball, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = inradius(&space);
        // On the way from the default lamp to the centre.
        let towards_lamp = DVec3::new(0.45, 0.8, 0.4);
        let centre = g.translation(towards_lamp, 0.4 * r) * space.centre();
        let ball = Object::Ball(Ball::new(g, centre, 0.12 * r, DVec3::new(0.9, 0.6, 0.3)));
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::Ball,
            avatar: false,
            clifford: false,
        };
        let hard = Lighting {
            shadows: 8,
            ..Lighting::default()
        };
        let soft = Lighting {
            lamp_radius_inradii: 0.4,
            soft_samples: 4,
            ..hard
        };
        let picture = |lighting: Lighting, gpu: bool, renderer: &mut OffscreenRenderer| {
            let camera = TraceCamera::default_for(&space);
            if gpu {
                let request = OffscreenRender {
                    parts,
                    objects: vec![ball],
                    lighting: Some(lighting),
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        24,
                    )
                };
                return renderer.render(&request).expect("renders");
            }
            let settings = still(parts, Some(lighting));
            let (scene, problems) = build_scene(&space, &settings, &[ball], None);
            assert_eq!(problems, None, "{id}");
            assert_eq!(scene.shading.lighting, lighting);
            render(
                &space,
                &scene,
                &camera,
                &RenderSettings {
                    width: WIDTH,
                    height: HEIGHT,
                    max_crossings: 24,
                },
            )
        };
        let shadowed = picture(hard, false, &mut renderer);
        let none = Lighting { shadows: 0, ..hard };
        let unshadowed = picture(none, false, &mut renderer);
        changes(
            &format!("{id}: the shadows"),
            (&shadowed, &unshadowed),
            0.005,
            &mut failures,
        );
        let gpu = picture(hard, true, &mut renderer);
        judge(
            &format!("{id}-shadows"),
            &gpu,
            &shadowed,
            &out,
            &mut failures,
        );
        let softened = picture(soft, false, &mut renderer);
        changes(
            &format!("{id}: a lamp of 0.4 inradii's soft shadows"),
            (&softened, &shadowed),
            0.002,
            &mut failures,
        );
        let gpu = picture(soft, true, &mut renderer);
        judge(
            &format!("{id}-soft-shadows"),
            &gpu,
            &softened,
            &out,
            &mut failures,
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Mirrors: a mirror ball at the centre reflects the tiling (and a half mirror a mix), a
/// mirror disc beside it, on the GPU as on the CPU in the three geometries.
#[test]
fn mirrors_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::{Ball, Disc, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = inradius(&space);
        let centre = space.centre();
        let mirror = Object::Ball(
            Ball::new(g, centre, 0.45 * r, DVec3::new(0.9, 0.9, 1.0)).with_reflectance(0.85),
        );
        let at = g.translation(DVec3::new(-0.6, -0.5, 0.3), 0.6 * r) * centre;
        let normal = g.unit_tangent(at, g.translation(DVec3::Y, 0.1) * at - at);
        let disc = Object::Disc(
            Disc::new(g, at, normal, 0.25 * r, DVec3::new(0.3, 0.8, 0.5)).with_reflectance(0.5),
        );
        let objects = vec![mirror, disc];
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let camera = TraceCamera::default_for(&space);
        let (scene, problems) = build_scene(&space, &still(parts, None), &objects, None);
        assert_eq!(problems, None, "{id}");
        assert!(scene.has_mirrors());
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 24,
        };
        let cpu = render(&space, &scene, &camera, &settings);
        // The same scene with plain surfaces: the mirrors change the picture.
        let (plain, _) = build_scene(
            &space,
            &still(parts, None),
            &objects
                .iter()
                .map(|o| match o {
                    Object::Ball(b) => Object::Ball(b.with_reflectance(0.0)),
                    Object::Disc(d) => Object::Disc(d.with_reflectance(0.0)),
                    o => *o,
                })
                .collect::<Vec<_>>(),
            None,
        );
        let (changed, _) = compare(&render(&space, &plain, &camera, &settings), &cpu, TOLERANCE);
        println!(
            "{id}: the mirrors change {:.2} % of the pixels",
            100.0 * changed.differing
        );
        if changed.differing < 0.05 {
            failures.push(format!("{id}: the mirrors change too little"));
        }
        let gpu = renderer
            .render(&OffscreenRender {
                parts,
                objects: objects.clone(),
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    24,
                )
            })
            .expect("renders");
        judge(&format!("{id}-mirrors"), &gpu, &cpu, &out, &mut failures);
        if id == "seifert-weber" {
            let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
            gpu.save(dir.join("mirrors-gpu.png")).expect("write");
            cpu.save(dir.join("mirrors-cpu.png")).expect("write");
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
