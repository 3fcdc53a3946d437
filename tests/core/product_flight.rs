//! Flights through product spaces (`trace::product::flight`): the camera at a key is at the
//! key's point, frames between keys stay in the cell and orthonormal, a flight up the fibre
//! arrives turned by the top's gluing, and keys no geodesic joins are refused by name.

use bevy_curved_spaces::scene::flight::{load_flight_file, parse_flight};
use bevy_curved_spaces::space::FrameSpace;
use bevy_curved_spaces::space::product::ProductSpace;
use bevy_curved_spaces::trace::product::flight::ProductFlight;
use glam::{DMat4, DVec4};
use std::path::Path;

use crate::common::product;
use bevy_curved_spaces::space::motion::CoverFlight as _;

fn asset(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("assets/flights")
        .join(name)
}

fn defect(space: &ProductSpace, f: DMat4) -> f64 {
    crate::common::product_frame_defect(space.base(), f)
}

#[test]
fn the_shipped_flights_stay_in_the_cell_and_start_at_their_first_key() {
    for name in [
        "bitorus_through_a_side.toml",
        "turned_sphere_up_the_fibre.toml",
    ] {
        let file = load_flight_file(&asset(name)).expect("a flight file");
        let space = product(file.space.as_deref().expect("a space"));
        let flight = ProductFlight::new(&space, &file).expect("a product flight");
        // The first key, in the cell: the camera is there, looking at its target.
        let (_, p, _) = file.keys[0];
        let s = space.scale();
        let start = flight.frame(&space, 0.0).w_axis;
        let base = (start.x.powi(2) + start.y.powi(2)).sqrt();
        let d = match space.base() {
            bevy_curved_spaces::geometry::Geometry::Spherical => base.asin(),
            _ => base.asinh(),
        };
        assert!((d - p.truncate().length() * s).abs() < 1e-9, "{name}: {d}");
        assert!((start.z - p.z * s).abs() < 1e-12, "{name}");
        let mut t = 0.0;
        while t <= flight.duration() {
            let f = flight.frame(&space, t);
            assert!(
                space.outside_by(f.w_axis) <= 1e-9,
                "{name} at {t} s: outside"
            );
            assert!(
                defect(&space, f) < 1e-9,
                "{name} at {t} s: {}",
                defect(&space, f)
            );
            // The fibre is up: the view's right is horizontal.
            assert!(f.x_axis.z.abs() < 1e-9, "{name} at {t} s: rolled");
            t += 0.05;
        }
    }
}

#[test]
fn flying_up_through_the_top_arrives_turned() {
    let file = load_flight_file(&asset("turned_sphere_up_the_fibre.toml")).expect("flight");
    let space = product("sphere-circle-turn");
    let flight = ProductFlight::new(&space, &file).expect("flight");
    let end = flight.duration();
    let cover = flight.cover_camera(end).point;
    let cell = flight.frame(&space, end).w_axis;
    // Once through the top: (p, z) ↦ (R⁻¹p, z − L).
    assert!(cover.z > 0.5 * space.length());
    assert!((cell.z - (cover.z - space.length())).abs() < 1e-9);
    let turned = space.top_pairing().round_f64() * DVec4::new(cover.x, cover.y, 0.0, cover.w);
    let got = DVec4::new(cell.x, cell.y, 0.0, cell.w);
    assert!((turned - got).length() < 1e-9, "{turned:?} against {got:?}");
    assert!((turned - DVec4::new(cover.x, cover.y, 0.0, cover.w)).length() > 0.1);
}

#[test]
fn keys_no_geodesic_joins_are_refused() {
    let space = product("sphere-circle");
    let opposite = "space = \"sphere-circle\"\n[[key]]\ntime = 0\nposition = [0.5, 0, 0]\nlook_at = [0, 0, 0]\n[[key]]\ntime = 1\nposition = [-0.5, 0.0, 0]\nlook_at = [0, 0, 0]\n";
    let s = space.scale();
    // Half a turn of the sphere each way: 0.5 is π/2 when the scale is π (no circle limit).
    let file = parse_flight(
        &opposite.replace("0.5", &format!("{}", 0.5 * std::f64::consts::PI / s)),
        "opposite.toml",
    )
    .expect("parses");
    let e = ProductFlight::new(&space, &file).expect_err("opposite keys");
    assert!(e.contains("opposite"), "{e}");
    let far = "space = \"sphere-circle\"\n[[key]]\ntime = 0\nposition = [90, 0, 0]\nlook_at = [0, 0, 0]\n";
    let file = parse_flight(far, "far.toml").expect("parses");
    let e = ProductFlight::new(&space, &file).expect_err("past the antipode");
    assert!(
        e.contains("key 1: position") && e.contains("π or more"),
        "{e}"
    );
}

/// `walk --replay` in a product space: the plugin drives the cameras along the flight, so
/// each update's frame is the flight's frame at the clock's time since the replay began.
#[test]
fn the_plugin_replays_a_product_flight_on_its_cameras() {
    use bevy::prelude::*;
    use bevy::time::TimeUpdateStrategy;
    use bevy_curved_spaces::plugin::flight::ProductFlightReplay;
    use bevy_curved_spaces::prelude::*;
    use std::time::Duration;
    let file = load_flight_file(&asset("bitorus_through_a_side.toml")).expect("a flight file");
    let space = product(file.space.as_deref().expect("a space"));
    let flight = ProductFlight::new(&space, &file).expect("a product flight");
    let dt = 0.1;
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, bevy::input::InputPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            dt,
        )))
        .add_plugins(CurvedSpacesPlugin {
            space: space.name().into(),
            ..default()
        });
    let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
    app.update();
    app.insert_resource(ProductFlightReplay::new(flight.clone(), false));
    let mut seen = Vec::new();
    for _ in 0..12 {
        app.update();
        let t = app
            .world()
            .resource::<ProductFlightReplay>()
            .clone()
            .flight_time(app.world().resource::<Time>().elapsed_secs_f64());
        let f = app.world().get::<PlayerFrame>(camera).expect("a frame").0;
        let want = flight.frame(&space, t);
        let gap = (f - want)
            .to_cols_array()
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(gap < 1e-12, "at {t} s the camera is {gap:e} off the flight");
        seen.push(f.w_axis);
    }
    // It moved: the flight goes somewhere.
    assert!((seen[0] - seen[11]).length() > 1e-3);
}

/// A walk in a product space recorded as a flight (`walk --record`) replays to the walk's
/// own frames at every key: through the sides and round the fibre (the top's and bottom's
/// shifts and turns undone by the holonomy), across an orientation-reversing side, with the
/// fibre kept up and the view pitched.
#[test]
fn a_recorded_product_walk_replays_to_the_same_frames() {
    use bevy_curved_spaces::prelude::Holonomy;
    for id in ["bitorus-circle", "sphere-circle-turn", "crosscaps-circle"] {
        // Forward and up the fibre, turning about it and pitching: through sides and the top.
        let (mut app, frames, file) = crate::flight::recorded_walk(
            id,
            glam::DVec3::new(0.1, 0.5, -0.8),
            glam::DVec3::new(0.08, 0.25, 0.0),
        );
        let holonomy = *app
            .world_mut()
            .query::<&Holonomy>()
            .single(app.world())
            .expect("one camera");
        let space = crate::common::shown_product(&app);
        let flight = ProductFlight::new(&space, &file).unwrap();
        let first = frames.len() - file.keys.len();
        let mut worst: f64 = 0.0;
        for (k, &(t, _, _)) in file.keys.iter().enumerate() {
            // The walk wraps past a margin, the replay at the face: a frame within the margin
            // of a face is compared as the replay holds it.
            let walked = space.wrap_frame(frames[first + k], 0.0).0;
            let replayed = flight.frame(&space, t);
            let gap = (0..4)
                .map(|c| (replayed.col(c) - walked.col(c)).abs().max_element())
                .fold(0.0, f64::max);
            worst = worst.max(gap);
            assert!(
                gap < 1e-8,
                "{id}: key {k} at {t} s differs by {gap:e}\nwalked {walked:?}\nreplayed {replayed:?}"
            );
        }
        eprintln!(
            "{id}: {} keys, {} crossings (fibre shift {}), worst {worst:e}",
            file.keys.len(),
            holonomy.crossings,
            holonomy.fibre_shift
        );
    }
}

/// A camera looking at a target has one handedness all over the surface: its frame's
/// determinant (right, up, back and the eye as the columns) keeps the sign it has at the
/// centre, past the sphere's equator too, where the camera once saw the world mirrored.
#[test]
fn a_camera_looking_at_a_target_is_never_mirrored() {
    use bevy_curved_spaces::geometry::Geometry;
    use bevy_curved_spaces::space::product::motion::camera_frame;
    use bevy_curved_spaces::trace::product::ProductCamera;
    let mut rng = bevy_curved_spaces::random::SplitMix64(0xa11);
    for g in [Geometry::Spherical, Geometry::Hyperbolic] {
        let frame_of = |eye: DVec4, target: DVec4| {
            let c = ProductCamera::looking_at(g, eye, target, 60.0);
            camera_frame(c.point, c.frame)
        };
        let reference = frame_of(DVec4::W, DVec4::new(0.3, 0.1, 0.2, 0.95)).determinant();
        assert!(reference.abs() > 0.5, "{g:?}: {reference}");
        for _ in 0..400 {
            // A surface point up to 3 from the centre (past the sphere's equator at π/2),
            // and a target a little way off it.
            let d = 3.0 * rng.unit();
            let a = std::f64::consts::TAU * rng.unit();
            let (c, s) = g.cs(d);
            let eye = DVec4::new(s * a.cos(), s * a.sin(), 2.0 * rng.unit() - 1.0, c);
            let (c2, s2) = g.cs(d + 0.4 * rng.unit() - 0.2);
            let b = a + 0.6 * rng.unit() - 0.3;
            let target = DVec4::new(s2 * b.cos(), s2 * b.sin(), eye.z + 0.3, c2);
            let det = frame_of(eye, target).determinant();
            assert!(
                det * reference > 0.0,
                "{g:?}: the camera at {eye:?} is mirrored (determinant {det} against {reference})"
            );
        }
    }
}
