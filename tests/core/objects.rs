//! Objects as entities in a headless app (MinimalPlugins, fixed steps): flying through faces,
//! long flights, spawning and despawning, changed materials, shortest geodesics between
//! entities, and Bevy meshes against our own.

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_curved_spaces::plugin::objects::{
    ActiveSightlines, CurvedObject, CurvedTransform, CurvedVelocity, EntityObjects,
    ObjectCrossedFace, add_entity_objects, bevy_mesh_from_model, model_from_bevy_mesh,
};
use bevy_curved_spaces::plugin::render::PreparedScene;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::TracedModel;
use bevy_curved_spaces::scene::mesh::cube_source;
use bevy_curved_spaces::space::invariants::{circumradius, elements_near, inradius};
use bevy_curved_spaces::space::motion::{MOTION_STEP, Sightlines, Velocity, fly};
use bevy_curved_spaces::trace::trace_pixel;
use glam::{DMat4, DVec3, DVec4};
use std::time::Duration;

/// An app whose every update advances the clock by `steps` fixed steps.
fn test_app(space: &str, steps: u32) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            MOTION_STEP * f64::from(steps),
        )))
        .add_plugins(CurvedSpacesPlugin {
            space: space.into(),
            controls: false,
            ..default()
        });
    app.finish();
    // The first update starts the clock (its delta is zero).
    app.update();
    app
}

fn max_diff(a: DMat4, b: DMat4) -> f64 {
    (a - b)
        .to_cols_array()
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()))
}

fn crossings(app: &mut App) -> Vec<ObjectCrossedFace> {
    app.world_mut()
        .resource_mut::<Messages<ObjectCrossedFace>>()
        .drain()
        .collect()
}

/// An object flying straight out of the cell comes back in through the partner face, its
/// frame turned by exactly the pairing of the face it left by, in every geometry (and through
/// a mirror, where the frame turns left-handed).
#[test]
fn an_object_flying_through_a_face_comes_back_turned_by_its_pairing() {
    for id in ["seifert-weber", "poincare", "half-turn", "mirrored-cube"] {
        let mut app = test_app(id, 1);
        let active = app.world().resource::<ActiveSpace>().clone();
        let (space, g) = (
            active.constant().unwrap(),
            active.constant().unwrap().geometry(),
        );
        let r = active.inradius;
        let start = CurvedTransform::from_geodesic(space, DVec3::new(0.1, -0.05, 0.02) * r);
        let velocity = Velocity {
            linear: DVec3::new(0.3, 0.2, -1.0).normalize() * r,
            angular: DVec3::ZERO,
        };
        let entity = app
            .world_mut()
            .spawn((
                CurvedObject::ball(0.1 * r, DVec3::ONE),
                start,
                CurvedVelocity(velocity),
            ))
            .id();
        crossings(&mut app);
        // The same motion without wrapping, step for step.
        let mut unwrapped = start.0;
        let mut seen = Vec::new();
        for _ in 0..400 {
            app.update();
            unwrapped = g.orthonormalize_frame(velocity.step(g, unwrapped, MOTION_STEP));
            seen = crossings(&mut app);
            if !seen.is_empty() {
                break;
            }
        }
        assert_eq!(seen.len(), 1, "{id}: one crossing, got {seen:?}");
        let crossed = seen[0];
        assert_eq!(crossed.entity, entity);
        let face = &space.faces()[crossed.face];
        assert_eq!(crossed.pairing, face.pairing);
        let frame = app.world().get::<CurvedTransform>(entity).unwrap().0;
        let expected = face.pairing * unwrapped;
        assert!(
            max_diff(frame, expected) < 1e-9,
            "{id}: frame after the crossing is the pairing times the unwrapped frame ({:e})",
            max_diff(frame, expected)
        );
        let holonomy = app.world().get::<Holonomy>(entity).unwrap();
        assert_eq!(holonomy.crossings, 1);
        assert_eq!(holonomy.last_face, Some(crossed.face));
        assert!(max_diff(holonomy.matrix, face.pairing) < 1e-15);
        assert!(space.outside_by(g.project_point(frame.w_axis)) <= 1e-9);
        // A mirror turns the frame's handedness.
        let det = frame.determinant() * g.project_point(frame.w_axis).w.signum();
        let mirrored = face.pairing.determinant() < 0.0;
        assert_eq!(
            det < 0.0,
            mirrored,
            "{id}: handedness after crossing face {}",
            crossed.face
        );
    }
}

/// 10⁵ fixed steps of a spinning, moving object: its frame stays an orthonormal frame inside
/// the cell and every crossing is reported once; the scene files' rule ([`fly`]) agrees with
/// the systems.
/// An entity given a velocity too fast to follow (a fixed step past a few cells: in H³ it
/// would leave f64 within a few steps) stays where it is, a valid frame in the cell, while a
/// slow one beside it flies on; once slowed down, it moves again.
#[test]
fn an_entity_too_fast_to_follow_stays_where_it_is() {
    let mut app = test_app("seifert-weber", 1);
    let active = app.world().resource::<ActiveSpace>().clone();
    let space = active.constant().unwrap().clone();
    let r = active.inradius;
    let start = CurvedTransform::from_geodesic(&space, DVec3::new(0.2, 0.1, -0.3) * r);
    let fast = Velocity {
        linear: DVec3::new(0.0, 0.0, -1.2e8),
        angular: DVec3::ZERO,
    };
    let slow = Velocity {
        linear: DVec3::new(0.0, 0.0, -0.5 * r),
        angular: DVec3::ZERO,
    };
    let spawn = |app: &mut App, v: Velocity| {
        app.world_mut()
            .spawn((
                CurvedObject::ball(0.1 * r, DVec3::ONE),
                start,
                CurvedVelocity(v),
            ))
            .id()
    };
    let (a, b) = (spawn(&mut app, fast), spawn(&mut app, slow));
    for _ in 0..20 {
        app.update();
    }
    let frame = |app: &App, e| app.world().get::<CurvedTransform>(e).unwrap().0;
    assert_eq!(frame(&app, a), start.0, "the fast entity stayed");
    assert!(
        max_diff(frame(&app, b), start.0) > 1e-3,
        "the slow one moved"
    );
    let g = space.geometry();
    assert!(g.frame_defect(frame(&app, a)) < 1e-12);
    app.world_mut().get_mut::<CurvedVelocity>(a).unwrap().0 = slow;
    for _ in 0..5 {
        app.update();
    }
    assert!(
        max_diff(frame(&app, a), start.0) > 1e-3,
        "slowed down, it moves"
    );
}

#[test]
fn a_long_flight_keeps_a_valid_frame_and_matches_fly() {
    // A hundred steps an update (past Bevy's default clamp of the virtual clock, 0.25 s).
    let mut app = test_app("seifert-weber", 100);
    app.world_mut()
        .resource_mut::<Time<Virtual>>()
        .set_max_delta(Duration::from_secs(10));
    let active = app.world().resource::<ActiveSpace>().clone();
    let (space, g) = (
        active.constant().unwrap(),
        active.constant().unwrap().geometry(),
    );
    let r = active.inradius;
    let start = CurvedTransform::from_geodesic(space, DVec3::new(0.2, 0.1, -0.3) * r);
    let velocity = Velocity {
        linear: DVec3::new(0.4, -0.7, -1.3) * r,
        angular: DVec3::new(0.3, 1.1, -0.2),
    };
    let entity = app
        .world_mut()
        .spawn((
            CurvedObject::ball(0.1 * r, DVec3::ONE),
            start,
            CurvedVelocity(velocity),
        ))
        .id();
    let fixed_time = |app: &App| app.world().resource::<Time<Fixed>>().elapsed_secs_f64();
    let t0 = fixed_time(&app);
    let mut reported = 0;
    for update in 0..1000 {
        app.update();
        reported += crossings(&mut app).len() as u64;
        if update == 6 {
            // After eleven seconds (a few crossings), the pure rule of scene files lands in the
            // same place. (Not after 10⁵ steps: the geodesic flow of a hyperbolic manifold
            // is chaotic, and rounding differences grow like e^t.)
            let frame = app.world().get::<CurvedTransform>(entity).unwrap().0;
            let holonomy = *app.world().get::<Holonomy>(entity).unwrap();
            let mut h = Holonomy::default();
            let flown = fly(
                &**space,
                start.0,
                &velocity,
                fixed_time(&app) - t0,
                1e-4,
                &mut h,
            )
            .unwrap();
            assert!(holonomy.crossings >= 3, "{} crossings", holonomy.crossings);
            assert_eq!(h.crossings, holonomy.crossings);
            assert!(
                max_diff(flown, frame) < 1e-9,
                "fly and the systems differ by {:e}",
                max_diff(flown, frame)
            );
        }
    }
    assert!(
        fixed_time(&app) - t0 > 0.99e5 * MOTION_STEP,
        "10⁵ fixed steps ran"
    );
    let frame = app.world().get::<CurvedTransform>(entity).unwrap().0;
    let holonomy = *app.world().get::<Holonomy>(entity).unwrap();
    assert!(g.frame_defect(frame) < 1e-9, "{:e}", g.frame_defect(frame));
    assert!(space.outside_by(g.project_point(frame.w_axis)) <= 2e-4);
    assert!(
        holonomy.crossings > 1000,
        "crossings {}",
        holonomy.crossings
    );
    assert_eq!(reported, holonomy.crossings);
}

fn prepared(app: &App) -> std::sync::Arc<bevy_curved_spaces::plugin::render::gpu::GpuScene> {
    app.world().resource::<PreparedScene>().0.clone()
}

/// Spawning adds an object to the GPU scene (padded counts), despawning removes it, and a
/// moved object keeps the scene data and the shader key.
#[test]
fn spawn_move_and_despawn_update_the_gpu_scene() {
    let mut app = test_app("seifert-weber", 1);
    let before = prepared(&app);
    let r = app.world().resource::<ActiveSpace>().inradius;
    let space = crate::common::shown_constant(&app);
    let model = std::sync::Arc::new(
        TracedModel::new(
            space.geometry(),
            &bevy_curved_spaces::scene::Model {
                source: cube_source(0.5, 0),
                materials: vec![SurfaceMaterial::default()],
                textures: Vec::new(),
            },
            0.2 * r,
        )
        .unwrap(),
    );
    let ball = app
        .world_mut()
        .spawn((
            CurvedObject::ball(0.1 * r, DVec3::X),
            CurvedTransform::from_geodesic(&space, DVec3::new(0.3 * r, 0.0, 0.0)),
        ))
        .id();
    let cube = app
        .world_mut()
        .spawn((
            CurvedObject::traced(model),
            CurvedTransform::from_geodesic(&space, DVec3::new(-0.3 * r, 0.0, 0.0)),
        ))
        .id();
    app.update();
    let with = prepared(&app);
    assert!(with.key.balls > before.key.balls);
    assert_eq!(with.key.balls.count_ones(), 1, "padded to a power of two");
    assert_eq!(with.key.instances, 4, "one cube, padded to 4");
    assert!(app.world().resource::<EntityObjects>().problems.is_empty());
    // Move the cube a little: new words, the same data and key.
    app.world_mut().get_mut::<CurvedTransform>(cube).unwrap().0 *=
        space.geometry().translation(DVec3::Y, 0.05 * r);
    app.update();
    let moved = prepared(&app);
    assert_ne!(moved.words, with.words);
    assert!(std::sync::Arc::ptr_eq(&moved.data, &with.data));
    assert_eq!(moved.key, with.key);
    // Nothing changed: nothing packed again.
    app.update();
    assert!(std::sync::Arc::ptr_eq(&prepared(&app), &moved));
    app.world_mut().despawn(ball);
    app.world_mut().despawn(cube);
    app.update();
    let after = prepared(&app);
    assert_eq!(after.key, before.key);
    assert_eq!(after.words, before.words);
    assert!(app.world().resource::<EntityObjects>().objects.is_empty());
}

/// The colour the CPU reference sees straight ahead from the centre, looking at the
/// entities' objects as the plugin gathered them.
fn centre_pixel(app: &App) -> DVec3 {
    let active = app.world().resource::<ActiveSpace>();
    let space = active.constant().unwrap();
    let mut scene = CurvedScene::with_parts(
        space,
        Shading::default_fog_distance(space),
        SceneParts {
            edges: false,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        },
    );
    let problems = add_entity_objects(
        &mut scene,
        space,
        &app.world().resource::<EntityObjects>().objects,
    );
    assert!(problems.is_empty(), "{problems:?}");
    let camera = TraceCamera::default_for(space);
    let walker = CellWalker::<DVec4>::new(space);
    let g = space.geometry();
    let p = g.project_point(camera.frame.w_axis);
    let ray = Ray {
        point: p,
        tangent: g.unit_tangent(p, -camera.frame.z_axis),
    };
    trace_pixel(&walker, &scene, ray, 8)
}

/// A changed colour is what the next frame shows.
#[test]
fn a_changed_material_shows_in_the_next_frame() {
    let mut app = test_app("torus", 1);
    let active = app.world().resource::<ActiveSpace>().clone();
    let g = active.constant().unwrap().geometry();
    let camera = TraceCamera::default_for(active.constant().unwrap());
    // A ball straight ahead of the default view.
    let ahead = CurvedTransform(translate_ahead(g, camera.frame, 0.5 * active.inradius));
    let ball = app
        .world_mut()
        .spawn((CurvedObject::ball(0.2 * active.inradius, DVec3::X), ahead))
        .id();
    app.update();
    let red = centre_pixel(&app);
    let before = prepared(&app);
    app.world_mut()
        .get_mut::<CurvedObject>(ball)
        .unwrap()
        .colour = Some(DVec3::Z);
    app.update();
    let blue = centre_pixel(&app);
    // Lit red, then lit blue (the fog adds a little of its blue-grey to both).
    assert!(red.x > 0.2 && red.x > 10.0 * red.z, "red ball: {red}");
    assert!(blue.z > 0.2 && blue.z > 10.0 * blue.x, "blue ball: {blue}");
    assert_ne!(prepared(&app).words, before.words);
}

/// The frame `distance` ahead (along −back) of `frame`.
fn translate_ahead(g: Geometry, frame: DMat4, distance: f64) -> DMat4 {
    frame * g.translation(DVec3::NEG_Z, distance)
}

/// The shortest geodesic between two entities against a search over many more images
/// (every copy of the cell within twice the cell's diameter), in each geometry.
#[test]
fn sightlines_are_the_shortest_geodesics_through_the_faces() {
    for id in [
        "seifert-weber",
        "poincare",
        "quarter-turn",
        "mirrored-dodecahedron",
    ] {
        let space = seed_space(id).unwrap();
        let g = space.geometry();
        let sightlines = Sightlines::new(&space);
        // Every copy of the cell whose centre is within 4R of the cell's: a superset of the
        // copies any two points of the cell can see each other in (d(a, h·b) ≤ 2R).
        let many = elements_near(&space, 2.0 * circumradius(&space), 2_000_000).unwrap();
        let mut rng = SplitMix64(17);
        let r = inradius(&space);
        let point = |rng: &mut SplitMix64| loop {
            let d = rng.direction() * rng.unit();
            let f = CurvedTransform::from_geodesic(&space, d * 1.6 * r).0;
            if space.outside_by(g.project_point(f.w_axis)) <= 0.0 {
                return f;
            }
        };
        for _ in 0..40 {
            let (a, b) = (point(&mut rng), point(&mut rng));
            let s = sightlines.between(a, b.w_axis);
            let pa = g.project_point(a.w_axis);
            let brute = many
                .iter()
                .map(|h| g.distance(pa, g.project_point(*h * b.w_axis)))
                .fold(f64::INFINITY, f64::min);
            assert!(
                (s.distance - brute).abs() < 1e-9,
                "{id}: {} against {brute}",
                s.distance
            );
            // The direction, followed for the distance from a, reaches the image.
            let local = s.direction;
            let end = a * g.translation(local, s.distance) * bevy_curved_spaces::geometry::ORIGIN;
            let target = g.project_point(s.element * b.w_axis);
            assert!(
                g.distance(g.project_point(end), target) < 1e-7,
                "{id}: direction misses by {:e}",
                g.distance(g.project_point(end), target)
            );
        }
    }
}

/// The plugin keeps the active space's sightlines for the game.
#[test]
fn the_plugin_offers_sightlines_between_entities() {
    let mut app = test_app("poincare", 1);
    app.update();
    let active = app.world().resource::<ActiveSpace>().clone();
    let r = active.inradius;
    let a =
        CurvedTransform::from_geodesic(active.constant().unwrap(), DVec3::new(0.5, 0.0, 0.0) * r);
    let b =
        CurvedTransform::from_geodesic(active.constant().unwrap(), DVec3::new(-0.5, 0.0, 0.0) * r);
    let s = app
        .world()
        .resource::<ActiveSightlines>()
        .between(&a, &b)
        .unwrap();
    assert!(s.distance <= r + 1e-9, "{}", s.distance);
    assert!((s.direction.length() - 1.0).abs() < 1e-12);
}

/// A Bevy mesh of our model traces to exactly the same mesh as the model itself: the asset
/// path and the file path meet.
#[test]
fn a_bevy_mesh_traces_like_our_model() {
    let model = bevy_curved_spaces::scene::Model {
        source: cube_source(0.5, 0),
        materials: vec![SurfaceMaterial::default()],
        textures: Vec::new(),
    };
    let back = model_from_bevy_mesh(&bevy_mesh_from_model(&model), None).unwrap();
    for g in [
        Geometry::Spherical,
        Geometry::Euclidean,
        Geometry::Hyperbolic,
    ] {
        let a = TracedModel::new(g, &model, 0.3).unwrap();
        let b = TracedModel::new(g, &back, 0.3).unwrap();
        assert_eq!(a.mesh, b.mesh, "{g:?}");
    }
}

/// A scene file's moving globe: at time T it is where its motion took it (through the faces,
/// its picture turned by the pairings), and the plugin's entity for it is in the same place
/// after T seconds of fixed steps.
#[cfg(feature = "scene-files")]
#[test]
fn a_scene_files_moving_object_is_where_its_motion_took_it() {
    use bevy_curved_spaces::plugin::objects::SceneMover;
    use bevy_curved_spaces::scene::file::parse_scene;
    let assets = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let text = r#"
        space = "seifert-weber"
        [[object]]
        type = "globe"
        position = [0.2, 0.0, 0.0]
        radius = 0.2
        texture = "../textures/globe.png"
        velocity = [0.3, 0.1, -1.0]
    "#;
    let file = parse_scene(text, &assets, "moving.toml").unwrap();
    assert_eq!(file.moving.len(), 1);
    assert!(
        file.base.objects.is_empty(),
        "the moving globe is not in the base"
    );
    let space = &file.space;
    let g = space.geometry();
    let m = &file.moving[0];
    let t = 3.0;
    let (frame, holonomy) = m.frame_at(space, t).unwrap();
    assert!(holonomy.crossings >= 1, "it left the cell");
    let scene = file.scene_at(t).unwrap();
    let globe = scene
        .objects
        .iter()
        .find_map(|o| match o {
            Object::Ball(b)
                if b.texture.is_some()
                    && (b.centre - g.project_point(frame.w_axis)).length() < 1e-9 =>
            {
                Some(*b)
            }
            _ => None,
        })
        .expect("the globe at its flown place");
    // Its picture's frame is the flown frame: turned by every pairing crossed.
    assert!(max_diff(globe.texture.unwrap().frame, frame) < 1e-9);
    // At time 0 it is where the file put it.
    let start = file.scene_at(0.0).unwrap();
    assert!(start.objects.iter().any(|o| matches!(o, Object::Ball(b) if (b.centre - g.project_point(m.frame.w_axis)).length() < 1e-12)));

    // The plugin spawns it as an entity that flies the same way.
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            MOTION_STEP,
        )))
        .insert_resource(ActiveSpace::new(&file.space_id, file.space.clone()))
        .insert_resource(BaseScene::from_file(&file))
        .add_plugins(CurvedSpacesPlugin {
            controls: false,
            ..default()
        });
    app.finish();
    app.update();
    let fixed = |app: &App| app.world().resource::<Time<Fixed>>().elapsed_secs_f64();
    let t0 = fixed(&app);
    for _ in 0..192 {
        app.update();
    }
    let mut movers = app
        .world_mut()
        .query::<(&SceneMover, &CurvedTransform, &Holonomy)>();
    let (_, transform, h) = movers.single(app.world()).unwrap();
    let (expected, eh) = m.frame_at(space, fixed(&app) - t0).unwrap();
    assert_eq!(h.crossings, eh.crossings);
    assert!(
        max_diff(transform.0, expected) < 1e-9,
        "{:e}",
        max_diff(transform.0, expected)
    );
}

/// A Bevy mesh asset is drawn once it is loaded and again, anew, when the asset changes (hot
/// reloading); a mesh the tracer cannot take is reported by its entity.
#[test]
fn bevy_mesh_assets_are_traced_when_loaded_and_when_changed() {
    use bevy::asset::AssetPlugin;
    use bevy::mesh::Mesh;
    use bevy_curved_spaces::plugin::objects::ReadyShape;
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, AssetPlugin::default()))
        .init_asset::<Mesh>()
        .init_asset::<Image>()
        .add_plugins(CurvedSpacesPlugin {
            space: "torus".into(),
            controls: false,
            ..default()
        });
    app.finish();
    app.update();
    let active = app.world().resource::<ActiveSpace>().clone();
    let r = active.inradius;
    let cube = bevy_curved_spaces::scene::Model {
        source: cube_source(0.5, 0),
        materials: vec![SurfaceMaterial::default()],
        textures: Vec::new(),
    };
    // A mesh still loading: the object waits.
    let handle = app.world().resource::<Assets<Mesh>>().reserve_handle();
    let entity = app
        .world_mut()
        .spawn((
            CurvedObject::mesh(handle.clone(), 0.3 * r),
            CurvedTransform::from_geodesic(active.constant().unwrap(), DVec3::ZERO),
        ))
        .id();
    app.update();
    assert_eq!(app.world().resource::<EntityObjects>().pending, 1);
    assert!(app.world().resource::<EntityObjects>().objects.is_empty());
    let triangles = |app: &App| -> usize {
        let objects = &app.world().resource::<EntityObjects>().objects;
        match &objects[0].shape {
            ReadyShape::Mesh(m) => m.mesh.triangles.len(),
            other => panic!("not a mesh: {other:?}"),
        }
    };
    // Loaded: drawn.
    app.world_mut()
        .resource_mut::<Assets<Mesh>>()
        .insert(handle.id(), bevy_mesh_from_model(&cube))
        .unwrap();
    app.update();
    app.update();
    assert_eq!(app.world().resource::<EntityObjects>().pending, 0);
    assert_eq!(triangles(&app), 12);
    // Changed: half the cube's triangles now.
    let mut half = cube.clone();
    half.source.indices.truncate(6);
    half.source.materials.truncate(6);
    app.world_mut()
        .resource_mut::<Assets<Mesh>>()
        .insert(handle.id(), bevy_mesh_from_model(&half))
        .unwrap();
    app.update();
    app.update();
    assert_eq!(triangles(&app), 6);
    // A point list is not a triangle mesh: named as the entity's problem.
    let points = Mesh::new(
        bevy::mesh::PrimitiveTopology::PointList,
        bevy::asset::RenderAssetUsages::default(),
    );
    let bad = app.world_mut().resource_mut::<Assets<Mesh>>().add(points);
    app.world_mut()
        .entity_mut(entity)
        .insert(CurvedObject::mesh(bad, 0.3 * r));
    app.update();
    let problems = &app.world().resource::<EntityObjects>().problems;
    assert!(
        problems
            .iter()
            .any(|p| p.contains(&entity.to_string()) && p.contains("triangle lists")),
        "{problems:?}"
    );
}
