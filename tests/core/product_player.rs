//! The plugin in a product space (H²×R, S²×R): `CurvedSpacesPlugin { space:
//! "bitorus-circle" }` shows a product space as its `ActiveSpace`, its players walk with the fibre up, climb
//! along it through the top (with the turn), and switching to and from a constant-curvature
//! space at run time puts them at the new start view; in a Nil space they walk with E₃ up.
//! Headless: MinimalPlugins, fake keys.

use bevy::input::InputPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::plugin::components::PlayerSettings;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::space::Limit;
use bevy_curved_spaces::space::product::ProductWalker;
use bevy_curved_spaces::space::product::motion::product_dot;
use glam::{DMat4, DVec4};
use std::time::Duration;

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
    app.update();
    (app, camera)
}

fn frame(app: &App, camera: Entity) -> DMat4 {
    app.world().get::<PlayerFrame>(camera).expect("a frame").0
}

fn holonomy(app: &App, camera: Entity) -> Holonomy {
    *app.world().get::<Holonomy>(camera).expect("holonomy")
}

/// Speed such that one update moves `step`.
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

/// The frame's defect from orthonormal in the active product space's metric.
fn frame_defect(app: &App, f: DMat4) -> f64 {
    let g = app
        .world()
        .resource::<ActiveSpace>()
        .product()
        .unwrap()
        .base();
    crate::common::product_frame_defect(g, f)
}

#[test]
fn the_plugin_starts_in_a_named_product_space_at_its_default_view() {
    let (app, camera) = test_app("bitorus-circle");
    let active = app.world().resource::<ActiveSpace>();
    assert_eq!(active.family(), Family::Product);
    assert_eq!(active.space.geometry_name(), "H2xR");
    let space = active.product().unwrap();
    let f = frame(&app, camera);
    let start = BaseProductScene::start_frame(None, space);
    assert!((f.w_axis - start.w_axis).length() < 1e-9);
    assert!(space.outside_by(f.w_axis) < 0.0);
}

#[test]
fn walking_ahead_keeps_the_height_and_follows_the_horizontal_geodesic() {
    for id in ["bitorus-circle", "crosscaps-circle", "sphere-circle-turn"] {
        let (mut app, camera) = test_app(id);
        let space = crate::common::shown_product(&app);
        let start = frame(&app, camera);
        // The default view looks down a little: walking follows its horizontal part.
        let back = start.z_axis;
        let ahead = -DVec4::new(back.x, back.y, 0.0, back.w);
        let g = space.base();
        let ahead = ahead / product_dot(g, ahead, ahead).sqrt();
        let (steps, step) = (400, 0.01);
        set_step(&mut app, step);
        hold(&mut app, KeyCode::KeyW, steps);
        let f = frame(&app, camera);
        let h = holonomy(&app, camera);
        // The whole sphere has no sides: a horizontal walk never leaves its cell.
        let sides = space.polygon().sides.len();
        assert_eq!(
            h.crossings > 0,
            sides > 0,
            "{id}: {} crossings in {}",
            h.crossings,
            steps as f64 * step
        );
        assert!(
            (f.w_axis.z - start.w_axis.z).abs() < 1e-9,
            "{id}: the height went from {} to {}",
            start.w_axis.z,
            f.w_axis.z
        );
        let walker = ProductWalker::<DVec4>::new(&space);
        let (end, _) = walker.walk(
            Ray {
                point: start.w_axis,
                tangent: ahead,
            },
            Limit::Distance(steps as f64 * step),
            |_| true,
        );
        let gap = (f.w_axis - end.point).length();
        assert!(gap < 1e-7, "{id}: {gap} from the walker's geodesic");
        assert!(space.outside_by(f.w_axis) < 1e-3, "{id}: outside the cell");
        assert!(frame_defect(&app, f) < 1e-9, "{id}");
    }
}

#[test]
fn climbing_the_fibre_crosses_the_top_and_applies_the_turn() {
    let (mut app, camera) = test_app("sphere-circle-turn");
    let space = crate::common::shown_product(&app);
    let start = frame(&app, camera);
    let sides = space.polygon().sides.len();
    let length = space.length();
    let steps: u32 = 250;
    set_step(&mut app, length / f64::from(steps));
    hold(&mut app, KeyCode::Space, steps as usize);
    let f = frame(&app, camera);
    let h = holonomy(&app, camera);
    assert_eq!(h.crossings, 1, "one circle up crosses the top once");
    assert_eq!(h.last_face, Some(sides), "the top is face {sides}");
    // Back at the same height, the base point turned by the top's pairing R⁻¹.
    assert!((f.w_axis.z - start.w_axis.z).abs() < 1e-9);
    let turned = h.matrix * DVec4::new(start.w_axis.x, start.w_axis.y, 0.0, start.w_axis.w);
    let got = DVec4::new(f.w_axis.x, f.w_axis.y, 0.0, f.w_axis.w);
    assert!(
        (turned - got).length() < 1e-9,
        "turned {turned:?}, got {got:?}"
    );
    let angle = f64::atan2(got.y, got.x) - f64::atan2(start.w_axis.y, start.w_axis.x);
    let turn = std::f64::consts::TAU / f64::from(space.turn());
    let off = (angle.rem_euclid(std::f64::consts::TAU) - (std::f64::consts::TAU - turn)).abs();
    assert!(
        off < 1e-9,
        "the base point turned by {angle}, not −2π/{}",
        space.turn()
    );
}

#[test]
fn switching_between_product_and_constant_curvature_spaces_resets_the_players() {
    let (mut app, camera) = test_app("bitorus-circle");
    set_step(&mut app, 0.02);
    hold(&mut app, KeyCode::KeyW, 250);
    assert!(holonomy(&app, camera).crossings > 0);
    // To a constant-curvature space and back, as the panel's picker does it.
    app.world_mut()
        .insert_resource(ActiveSpace::seed("seifert-weber").expect("seed space"));
    app.update();
    assert_eq!(holonomy(&app, camera).crossings, 0);
    let active = app.world().resource::<ActiveSpace>();
    let space = active.constant().expect("a constant-curvature space");
    let f = frame(&app, camera);
    assert!(space.outside_by(f.w_axis) < 0.0);
    assert!(space.geometry().frame_defect(f) < 1e-12);
    hold(&mut app, KeyCode::KeyW, 5);
    let product = ActiveSpace::named("projective-plane-circle").expect("a valid product space");
    assert_eq!(product.family(), Family::Product);
    app.world_mut().insert_resource(product);
    app.update();
    let active = app.world().resource::<ActiveSpace>();
    let f = frame(&app, camera);
    let start = BaseProductScene::start_frame(None, active.product().unwrap());
    assert!((f.w_axis - start.w_axis).length() < 1e-9);
    assert_eq!(holonomy(&app, camera).crossings, 0);
    // A flat word is not a product space: it is the flat space it makes.
    let flat = ActiveSpace::named("surface-abAB-circle-1").expect("a flat space");
    assert_eq!(flat.family(), Family::Constant);
    assert!(ActiveSpace::named("surface-abc-circle-1").is_err());
}

#[test]
fn a_bad_product_id_falls_back_to_the_default_space() {
    let (app, _) = test_app("surface-aab-circle-1");
    let active = app.world().resource::<ActiveSpace>();
    assert_eq!(active.id, bevy_curved_spaces::space::DEFAULT_SPACE);
    assert_eq!(active.family(), Family::Constant);
}

#[test]
fn entities_fly_through_the_product_cell_and_are_drawn_with_their_images() {
    use bevy_curved_spaces::plugin::objects::product::ProductEntityObjects;
    use bevy_curved_spaces::plugin::objects::{CurvedObject, CurvedTransform, CurvedVelocity};
    use bevy_curved_spaces::trace::product::ProductShape;
    use glam::DVec3;
    let (mut app, _camera) = test_app("bitorus-circle");
    let space = crate::common::shown_product(&app);
    let g = space.base();
    // Along its own right (+x, towards side 0) and a little up the fibre, turning slowly.
    let ball = app
        .world_mut()
        .spawn((
            CurvedObject::ball(0.1, DVec3::new(0.9, 0.2, 0.2)),
            CurvedTransform(DMat4::IDENTITY),
            CurvedVelocity(bevy_curved_spaces::space::motion::Velocity {
                linear: DVec3::new(2.0, 0.0, 0.7),
                angular: DVec3::new(0.0, 0.0, 0.5),
            }),
        ))
        .id();
    // A horizontal disc is drawn; one standing on its edge is not (product discs lie in
    // a slice).
    app.world_mut().spawn((
        CurvedObject::disc(0.3, DVec3::ONE),
        CurvedTransform(DMat4::from_cols(
            DVec4::X,
            DVec4::Y,
            DVec4::Z,
            DVec4::new(0.0, 0.0, -0.5, 1.0),
        )),
    ));
    app.world_mut().spawn((
        CurvedObject::disc(0.3, DVec3::ONE),
        CurvedTransform(DMat4::from_cols(DVec4::X, DVec4::Z, -DVec4::Y, DVec4::W)),
    ));
    let mut most = 0;
    let mut generations = std::collections::BTreeSet::new();
    for _ in 0..150 {
        app.update();
        let objects = app.world().resource::<ProductEntityObjects>();
        generations.insert(objects.generation);
        let balls = objects
            .objects
            .iter()
            .filter(|o| matches!(o.shape, ProductShape::Point(_)))
            .count();
        most = most.max(balls);
        assert_eq!(
            objects
                .objects
                .iter()
                .filter(|o| matches!(o.shape, ProductShape::Disc(_)))
                .count(),
            1,
            "only the horizontal disc"
        );
        let f = app.world().get::<CurvedTransform>(ball).unwrap().0;
        let margin = app.world().resource::<PlayerSettings>().wrap_margin;
        assert!(
            space.outside_by(f.w_axis) <= margin + 1e-9,
            "left the cell: {f}"
        );
        assert!(crate::common::product_frame_defect(g, f) < 1e-9);
    }
    // 3 s at 2.1 a second: through sides and the top, each crossing recorded.
    let crossings = app.world().get::<Holonomy>(ball).unwrap().crossings;
    assert!(crossings >= 2, "{crossings} crossings");
    // Near a face the ball is drawn with its image through it.
    assert!(most >= 2, "never more than {most} copies of the ball");
    assert!(
        generations.len() > 50,
        "the objects were gathered {} times",
        generations.len()
    );
    // The packed scene holds them: the default scene's objects and the entities'.
    let default = bevy_curved_spaces::trace::product::default_scene(&space)
        .objects
        .len();
    let drawn = app.world().resource::<ProductEntityObjects>().objects.len();
    let prepared = app
        .world()
        .resource::<bevy_curved_spaces::plugin::render::PreparedScene>();
    assert_eq!(prepared.0.key.product_objects as usize, default + drawn);
}

/// The plugin in a Nil space: `CurvedSpacesPlugin { space: "nil-3" }` starts at the default
/// view, the player walks with E₃ up through the box's faces and stays in the box, and the
/// scene is packed for the GPU's Nil variant.
#[test]
fn the_plugin_walks_a_nil_space_with_e3_up() {
    use bevy_curved_spaces::space::nil::NilSpace;
    let (mut app, camera) = test_app("nil-3");
    let active = app.world().resource::<ActiveSpace>();
    assert_eq!(active.family(), Family::Nil);
    let space = active.space.get::<NilSpace>().expect("a Nil space").clone();
    let start = bevy_curved_spaces::trace::nil::default_camera(&space).frame;
    assert!((frame(&app, camera) - start).abs_diff_eq(DMat4::ZERO, 1e-12));
    set_step(&mut app, 0.05);
    // Forward through the box's far side, turning, and up through its top.
    hold(&mut app, KeyCode::KeyW, 30);
    hold(&mut app, KeyCode::KeyD, 20);
    hold(&mut app, KeyCode::Space, 10);
    let f = frame(&app, camera);
    let h = space.half_height();
    let p = f.w_axis;
    assert!(
        p.x.abs() <= 0.5 + 1e-9 && p.y.abs() <= 0.5 + 1e-9 && p.z.abs() <= h + 1e-9,
        "left the box: {p}"
    );
    assert!(holonomy(&app, camera).crossings > 2, "crossed no faces");
    assert!(
        (f.y_axis.truncate() - glam::DVec3::Z).length() < 1e-9,
        "up left E₃"
    );
    let prepared = app
        .world()
        .get_resource::<bevy_curved_spaces::plugin::render::PreparedScene>()
        .expect("a packed scene");
    assert!(prepared.0.key.nil);
}

/// A game's entities in a Nil space: a ball flies along its Nil geodesic through the box's
/// faces (with its holonomy's crossings), is drawn as a metric ball with each lattice image
/// that reaches into the box (every image the same point of the manifold), and the packed
/// scene holds them; a tube and a ball wider than half the box's side are left out.
#[test]
fn entities_fly_through_a_nil_box_and_are_drawn_as_metric_balls_with_their_images() {
    use bevy_curved_spaces::plugin::objects::nil::NilEntityObjects;
    use bevy_curved_spaces::plugin::objects::{CurvedObject, CurvedTransform, CurvedVelocity};
    use bevy_curved_spaces::space::nil::NilSpace;
    use bevy_curved_spaces::trace::nil::NilShape;
    use glam::DVec3;
    let (mut app, _camera) = test_app("nil-3");
    let space = app
        .world()
        .resource::<ActiveSpace>()
        .space
        .get::<NilSpace>()
        .expect("a Nil space")
        .clone();
    let ball = app
        .world_mut()
        .spawn((
            CurvedObject::ball(0.1, DVec3::new(0.9, 0.2, 0.2)),
            CurvedTransform(DMat4::IDENTITY),
            CurvedVelocity(bevy_curved_spaces::space::motion::Velocity {
                linear: DVec3::new(2.0, 0.5, 0.7),
                angular: DVec3::new(0.0, 0.0, 0.5),
            }),
        ))
        .id();
    app.world_mut().spawn((
        CurvedObject::tube(0.3, 0.05, DVec3::ONE),
        CurvedTransform(DMat4::IDENTITY),
    ));
    app.world_mut().spawn((
        CurvedObject::ball(0.7, DVec3::ONE),
        CurvedTransform(DMat4::IDENTITY),
    ));
    let (h, mut most, mut generations) =
        (space.half_height(), 0, std::collections::BTreeSet::new());
    for _ in 0..150 {
        app.update();
        let objects = app.world().resource::<NilEntityObjects>();
        generations.insert(objects.generation);
        most = most.max(objects.objects.len());
        let f = app.world().get::<CurvedTransform>(ball).unwrap().0;
        let p = f.w_axis;
        assert!(
            p.x.abs() <= 0.5 + 1e-9 && p.y.abs() <= 0.5 + 1e-9 && p.z.abs() <= h + 1e-9,
            "left the box: {p}"
        );
        assert!(!objects.objects.is_empty(), "the ball is not drawn");
        for o in &objects.objects {
            let NilShape::Ball(c) = o.shape else {
                panic!("only the ball is drawn: {o:?}");
            };
            assert_eq!(o.radius, 0.1, "only the small ball is drawn");
            // Every image is the entity's point of the manifold.
            let back = DVec3::from_array(space.into_box(c));
            let at = DVec3::from_array(space.into_box(p.truncate().to_array()));
            assert!((back - at).length() < 1e-9, "{c:?} is not an image of {p}");
        }
    }
    let crossings = app.world().get::<Holonomy>(ball).unwrap().crossings;
    assert!(crossings >= 2, "{crossings} crossings");
    assert!(most >= 2, "never more than {most} copies of the ball");
    assert!(
        generations.len() > 50,
        "gathered {} times",
        generations.len()
    );
    let default = bevy_curved_spaces::trace::nil::default_scene(&space)
        .objects
        .len();
    let drawn = app.world().resource::<NilEntityObjects>().objects.len();
    let prepared = app
        .world()
        .resource::<bevy_curved_spaces::plugin::render::PreparedScene>();
    assert_eq!(prepared.0.key.nil_objects as usize, default + drawn);
}

/// The plugin in an SL̃(2,R) space: `CurvedSpacesPlugin { space: "unit-tangent-bitorus" }`
/// starts at the default view, packs the scene for the GPU's SL2R variant, and the player
/// walks through the polygon's sides and climbs the fibre, staying in the cell and on the
/// model.
#[test]
fn the_plugin_walks_an_sl2r_space_with_the_fibre_up() {
    use bevy_curved_spaces::plugin::render::PreparedScene;
    use bevy_curved_spaces::space::FrameSpace;
    use bevy_curved_spaces::space::sl2r::UnitTangentSpace;
    let (mut app, camera) = test_app("unit-tangent-bitorus");
    let active = app.world().resource::<ActiveSpace>();
    assert_eq!(active.family(), Family::Sl2r);
    let space = active
        .space
        .get::<UnitTangentSpace>()
        .expect("an SL̃(2,R) space")
        .clone();
    let start = bevy_curved_spaces::trace::sl2r::default_camera(&space).frame;
    assert!((frame(&app, camera) - start).abs_diff_eq(DMat4::ZERO, 1e-12));
    assert!(app.world().resource::<PreparedScene>().0.key.sl2r);
    set_step(&mut app, 0.1);
    hold(&mut app, KeyCode::KeyW, 40);
    hold(&mut app, KeyCode::KeyD, 20);
    hold(&mut app, KeyCode::Space, 20);
    let f = frame(&app, camera);
    assert!(space.outside_by(f.w_axis) <= 1e-3, "left the cell: {f}");
    assert!(space.frame_defect(f) < 1e-9);
    assert!(holonomy(&app, camera).crossings > 0, "crossed no side");
}
