//! The player systems in a headless app (MinimalPlugins + input, fake key presses and mouse
//! motion, a fixed time step), and long random walks of the pure frame functions.

use bevy::input::InputPlugin;
use bevy::input::mouse::MouseMotion;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_curved_spaces::plugin::components::PlayerSettings;
use bevy_curved_spaces::plugin::player::step_frame;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::invariants::{circumradius, inradius};
use bevy_curved_spaces::space::wrap_into_cell;
use glam::{DMat4, DVec3};
use std::time::Duration;

/// Seconds per update.
const DT: f64 = 0.02;

fn test_app(space: &str) -> (App, Entity) {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, InputPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            DT,
        )))
        .add_plugins(CurvedSpacesPlugin {
            space: space.into(),
            ..default()
        });
    let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
    // The first update starts the clock (its delta is zero).
    app.update();
    (app, camera)
}

fn frame(app: &App, camera: Entity) -> DMat4 {
    app.world()
        .get::<PlayerFrame>(camera)
        .expect("camera has a frame")
        .0
}

fn holonomy(app: &App, camera: Entity) -> Holonomy {
    *app.world()
        .get::<Holonomy>(camera)
        .expect("camera has holonomy")
}

fn set_frame(app: &mut App, camera: Entity, f: DMat4) {
    app.world_mut()
        .get_mut::<PlayerFrame>(camera)
        .expect("frame")
        .0 = f;
}

/// Speed such that one update moves exactly `step` (geodesic units).
fn set_step(app: &mut App, step: f64) {
    let r = app.world().resource::<ActiveSpace>().inradius;
    app.world_mut().resource_mut::<PlayerSettings>().speed = step / (r * DT);
}

fn hold(app: &mut App, key: KeyCode, updates: usize) {
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .press(key);
    for _ in 0..updates {
        app.update();
    }
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .release(key);
    app.update();
}

fn max_diff(a: DMat4, b: DMat4) -> f64 {
    (a - b)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

#[test]
fn walking_one_unit_in_the_torus_returns_to_the_start() {
    let (mut app, camera) = test_app("torus");
    let space = crate::common::shown_constant(&app);
    set_frame(&mut app, camera, DMat4::IDENTITY);
    set_step(&mut app, 0.01);
    hold(&mut app, KeyCode::KeyW, 100);
    let f = frame(&app, camera);
    let h = holonomy(&app, camera);
    // The cube has side 1: one unit forward (−z) comes back to the centre, one face crossed.
    assert!(
        max_diff(f, DMat4::IDENTITY) < 1e-9,
        "frame after one unit: {f:?}"
    );
    assert_eq!(h.crossings, 1);
    let face = h.last_face.expect("a face was crossed");
    assert!(
        space.faces()[face].normal.dot(DVec3::NEG_Z) > 0.99,
        "left through the −z face"
    );
    assert_eq!(h.matrix, space.faces()[face].pairing);
    // Holonomy · unwrapped frame = frame: the unwrapped walk went one unit along −z.
    let unwrapped = Geometry::Euclidean.translation(DVec3::NEG_Z, 1.0);
    assert!(max_diff(h.matrix * unwrapped, f) < 1e-9);
}

#[test]
fn crossing_a_seifert_weber_face_applies_exactly_its_pairing() {
    let (mut app, camera) = test_app("seifert-weber");
    let space = crate::common::shown_constant(&app);
    let g = space.geometry();
    let target = 3;
    let n = space.faces()[target].normal;
    // Face the centre of face 3 from the cell's centre, then walk straight through it.
    let start = g
        .look_at(DVec3::ZERO, n * 0.1, n.any_orthonormal_vector())
        .expect("valid view");
    set_frame(&mut app, camera, start);
    let step = 0.01;
    set_step(&mut app, step);
    let steps = (inradius(&space) / step).ceil() as usize + 3;
    hold(&mut app, KeyCode::KeyW, steps);
    let h = holonomy(&app, camera);
    assert_eq!(h.crossings, 1, "one face crossed");
    assert_eq!(h.last_face, Some(target));
    assert_eq!(h.matrix, space.faces()[target].pairing);
    let unwrapped = step_frame(
        g,
        start,
        &bevy_curved_spaces::plugin::components::PlayerMotion {
            translation: DVec3::new(0.0, 0.0, -(steps as f64) * step),
            rotation: DVec3::ZERO,
        },
    );
    assert!(
        max_diff(h.matrix * unwrapped, frame(&app, camera)) < 1e-8,
        "the frame is the pairing applied to the straight walk"
    );
    assert!(space.outside_by(frame(&app, camera).w_axis) <= 1e-4);
}

#[test]
fn walking_through_edges_and_vertices_lands_inside_the_cell() {
    for id in [
        "torus",
        "seifert-weber",
        "poincare",
        "mirrored-cube",
        "hantzsche-wendt",
    ] {
        let (mut app, camera) = test_app(id);
        let space = crate::common::shown_constant(&app);
        let g = space.geometry();
        let margin = app.world().resource::<PlayerSettings>().wrap_margin;
        let edge = &space.edges()[0];
        let midpoint =
            (space.vertex_point(edge.vertices[0]) + space.vertex_point(edge.vertices[1])) / 2.0;
        for target in [
            g.to_chart(space.vertex_point(0)),
            g.to_chart(g.project_point(midpoint)),
        ] {
            let start = g
                .look_at(DVec3::ZERO, target, target.any_orthonormal_vector())
                .expect("valid view");
            set_frame(&mut app, camera, start);
            app.world_mut()
                .entity_mut(camera)
                .insert(Holonomy::default());
            let step = 0.02 * inradius(&space);
            set_step(&mut app, step);
            let steps = (1.5 * circumradius(&space) / step).ceil() as usize;
            hold(&mut app, KeyCode::KeyW, steps);
            let f = frame(&app, camera);
            assert!(
                space.outside_by(f.w_axis) <= margin,
                "{id}: ended outside the cell by {}",
                space.outside_by(f.w_axis)
            );
            assert!(
                g.frame_defect(f) < 1e-9,
                "{id}: frame defect {}",
                g.frame_defect(f)
            );
            assert!(
                holonomy(&app, camera).crossings >= 1,
                "{id}: crossed nothing"
            );
        }
    }
}

fn handedness(f: DMat4) -> f64 {
    // Sign of det(right, up, back, position) in R⁴: flips with a reflection.
    f.determinant().signum()
}

#[test]
fn crossing_a_mirror_flips_handedness_and_the_controls_stay_natural() {
    let (mut app, camera) = test_app("mirrored-cube");
    let space = crate::common::shown_constant(&app);
    let g = space.geometry();
    set_frame(&mut app, camera, DMat4::IDENTITY);
    assert_eq!(handedness(frame(&app, camera)), 1.0);
    let step = 0.01;
    set_step(&mut app, step);
    hold(&mut app, KeyCode::KeyW, 60);
    let h = holonomy(&app, camera);
    assert_eq!(h.crossings, 1);
    let mirror = h.matrix;
    assert_eq!(
        handedness(frame(&app, camera)),
        -1.0,
        "a mirror crossing makes the frame left-handed"
    );
    // Now strafe right and look right with the mouse: in the universal cover this must be
    // the same as doing so without the wrap (the picture is drawn from local axes only).
    app.world_mut()
        .resource_mut::<PlayerSettings>()
        .look_without_grab = true;
    hold(&mut app, KeyCode::KeyD, 10);
    app.world_mut().write_message(MouseMotion {
        delta: Vec2::new(150.0, 0.0),
    });
    app.update();
    let sensitivity = app.world().resource::<PlayerSettings>().mouse_sensitivity;
    let motions = [
        DVec3::new(0.0, 0.0, -60.0 * step),
        DVec3::new(10.0 * step, 0.0, 0.0),
    ];
    let mut unwrapped = DMat4::IDENTITY;
    for t in motions {
        unwrapped = step_frame(
            g,
            unwrapped,
            &bevy_curved_spaces::plugin::components::PlayerMotion {
                translation: t,
                rotation: DVec3::ZERO,
            },
        );
    }
    unwrapped = step_frame(
        g,
        unwrapped,
        &bevy_curved_spaces::plugin::components::PlayerMotion {
            translation: DVec3::ZERO,
            rotation: DVec3::new(0.0, -150.0 * sensitivity, 0.0),
        },
    );
    let f = frame(&app, camera);
    assert!(
        max_diff(mirror * unwrapped, f) < 1e-9,
        "after the mirror, the walk continues as in the cover"
    );
    // Looking right: the new view direction leans towards the old right.
    let view = -(mirror * unwrapped).z_axis;
    let old_right = (mirror * DMat4::IDENTITY).x_axis;
    assert!(g.form(view, old_right) > 0.3);
}

#[test]
fn switching_space_at_run_time_resets_the_player() {
    let (mut app, camera) = test_app("torus");
    set_step(&mut app, 0.05);
    hold(&mut app, KeyCode::KeyW, 30);
    assert!(holonomy(&app, camera).crossings > 0);
    app.world_mut()
        .insert_resource(ActiveSpace::seed("poincare").expect("seed space"));
    app.update();
    let active = app.world().resource::<ActiveSpace>();
    assert_eq!(active.constant().unwrap().geometry(), Geometry::Spherical);
    assert_eq!(holonomy(&app, camera).crossings, 0);
    let f = frame(&app, camera);
    assert!(active.constant().unwrap().outside_by(f.w_axis) < 0.0);
    assert!(Geometry::Spherical.frame_defect(f) < 1e-12);
    // On to spaces from groups, walking through faces in each.
    for id in ["weeks", "lens-7-2", "second-amphidicosm"] {
        app.world_mut()
            .insert_resource(ActiveSpace::named(id).expect("library space"));
        app.update();
        assert_eq!(holonomy(&app, camera).crossings, 0, "{id}");
        hold(&mut app, KeyCode::KeyW, 60);
        let active = app.world().resource::<ActiveSpace>();
        let f = frame(&app, camera);
        assert!(
            holonomy(&app, camera).crossings > 0,
            "{id}: no face crossed"
        );
        assert!(
            active.constant().unwrap().outside_by(f.w_axis) < 1e-3,
            "{id}"
        );
        assert!(
            active.constant().unwrap().geometry().frame_defect(f) < 1e-9,
            "{id}"
        );
    }
}

#[test]
fn a_million_random_steps_keep_the_frame_orthonormal_and_inside() {
    let margin = PlayerSettings::default().wrap_margin;
    for seed in SEED_SPACES {
        let space = seed.build().expect("seed space builds");
        let g = space.geometry();
        let r = inradius(&space);
        let mut rng = SplitMix64(0xC0FFEE);
        let mut next = || 2.0 * rng.unit() - 1.0;
        let mut f = bevy_curved_spaces::view::TraceCamera::default_for(&space).frame;
        let mut worst_defect = 0.0f64;
        let mut worst_outside = f64::NEG_INFINITY;
        let mut crossings = 0;
        for _ in 0..1_000_000 {
            let motion = bevy_curved_spaces::plugin::components::PlayerMotion {
                translation: DVec3::new(next(), next(), next()) * 0.05 * r,
                rotation: DVec3::new(next(), next(), next()) * 0.2,
            };
            let (next, crossed) = wrap_into_cell(&space, step_frame(g, f, &motion), margin);
            crossings += crossed.len();
            f = next;
            worst_defect = worst_defect.max(g.frame_defect(f));
            worst_outside = worst_outside.max(space.outside_by(f.w_axis));
        }
        assert!(
            worst_defect < 1e-6,
            "{}: frame defect {worst_defect}",
            seed.id
        );
        assert!(
            worst_outside <= margin,
            "{}: outside the cell by {worst_outside}",
            seed.id
        );
        assert!(
            crossings > 100,
            "{}: the walk crossed only {crossings} faces",
            seed.id
        );
    }
}

/// Stereo settings change at run time; an eye distance the cell cannot take is named in
/// `TracerStatus::stereo_error` and the default is used meanwhile.
#[test]
fn an_unusable_eye_distance_is_reported_and_replaced_by_the_default() {
    use bevy_curved_spaces::plugin::components::TracerStatus;
    use bevy_curved_spaces::view::stereo::default_ipd;
    let (mut app, _) = test_app("torus");
    let inradius = app.world().resource::<ActiveSpace>().inradius;
    {
        let mut stereo = app.world_mut().resource_mut::<StereoSettings>();
        stereo.mode = StereoMode::SideBySide;
        stereo.ipd = Some(3.0);
    }
    app.update();
    let error = app.world().resource::<TracerStatus>().stereo_error.clone();
    assert!(
        error
            .as_deref()
            .is_some_and(|e| e.contains("more than the cell's inradius") && e.contains("default")),
        "{error:?}"
    );
    let stereo = *app.world().resource::<StereoSettings>();
    assert_eq!(stereo.ipd_for(inradius), default_ipd(inradius));
    app.world_mut().resource_mut::<StereoSettings>().ipd = Some(0.05);
    app.update();
    assert_eq!(app.world().resource::<TracerStatus>().stereo_error, None);
    assert_eq!(
        app.world().resource::<StereoSettings>().ipd_for(inradius),
        0.05
    );
}

/// The fog in use has one rule: the setting, else the base scene's own, else three inradii;
/// the status reports the one the tracer packed.
#[test]
fn the_fog_in_use_is_the_setting_then_the_scene_files_then_the_default() {
    let (mut app, _camera) = test_app("torus");
    let default_fog =
        Shading::DEFAULT_FOG_INRADII * inradius(&seed_space("torus").expect("builds"));
    let status_fog = |app: &App| app.world().resource::<TracerStatus>().fog_distance;
    assert!(
        (status_fog(&app) - default_fog).abs() < 1e-12,
        "{}",
        status_fog(&app)
    );

    let space = seed_space("torus").expect("builds");
    let mut scene = CurvedScene::default_for(&space, 1.234);
    scene.shading.fog_distance = 1.234;
    app.insert_resource(BaseScene {
        space_id: "torus".into(),
        scene: Some(std::sync::Arc::new(scene)),
        start: None,
        parts: None,
        fov: None,
        moving: Vec::new(),
    });
    app.update();
    assert_eq!(status_fog(&app), 1.234, "the base scene's own fog");

    app.world_mut()
        .resource_mut::<TracerSettings>()
        .fog_distance = Some(2.5);
    app.update();
    assert_eq!(status_fog(&app), 2.5, "the setting wins");
}

/// A base scene's start view brings its field of view: a camera spawned in its space takes
/// it, one in another space keeps its own.
#[test]
fn a_camera_takes_the_base_scenes_field_of_view_in_its_space() {
    for (space, expected) in [("torus", 40.0), ("poincare", 70.0)] {
        let mut app = App::new();
        app.add_plugins((MinimalPlugins, InputPlugin))
            .insert_resource(BaseScene {
                space_id: "torus".into(),
                fov: Some(40.0),
                ..default()
            })
            .add_plugins(CurvedSpacesPlugin {
                space: space.into(),
                ..default()
            });
        let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
        app.update();
        let fov = app
            .world()
            .get::<CurvedSpaceCamera>(camera)
            .expect("the camera")
            .fov_y_degrees;
        assert_eq!(fov, expected, "{space}");
    }
}
