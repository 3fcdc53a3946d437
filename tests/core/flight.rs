//! Flights: keyframes through the universal cover, brought back into the cell.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::flight::{Flight, FlightFile, load_flight_file, parse_flight};
use bevy_curved_spaces::space::motion::CoverFlight as _;
use bevy_curved_spaces::space::seed_space;
use glam::DMat4;

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array()
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
}

/// A flight through a face arrives turned by that face's pairing: the frame in the cell is
/// the pairing times the frame in the cover.
#[test]
fn a_flight_through_a_face_arrives_turned_by_its_pairing() {
    let space = seed_space("seifert-weber").unwrap();
    let text = "space = \"seifert-weber\"\n[[key]]\ntime = 0.0\nposition = [0.45, 0.1, 0.5]\n\
                look_at = [0.45, 0.1, -1.0]\n[[key]]\ntime = 2.0\nposition = [0.45, 0.1, -2.0]\n\
                look_at = [0.45, 0.1, -3.0]\n";
    let flight = Flight::new(&space, &parse_flight(text, "t.toml").unwrap()).unwrap();
    let (before, after) = (flight.frame(&space, 0.0), flight.frame(&space, 2.0));
    assert!(space.outside_by(before.w_axis) <= 0.0 && space.outside_by(after.w_axis) <= 1e-12);
    let cover = flight.cover_frame(2.0);
    assert!(
        space.outside_by(cover.w_axis) > 0.0,
        "the last key lies beyond a face"
    );
    let (wrapped, crossed) = bevy_curved_spaces::space::wrap_into_cell(&space, cover, 0.0);
    assert!(!crossed.is_empty());
    let holonomy = crossed
        .iter()
        .fold(DMat4::IDENTITY, |h, &f| space.faces()[f].pairing * h);
    let expected = Geometry::Hyperbolic.orthonormalize_frame(holonomy * cover);
    assert!(max_entry(after - expected) < 1e-9 && max_entry(wrapped - after) < 1e-12);
    assert_eq!(flight.frame_count(10.0), 20);
}

/// Every shipped flight file loads and flies in its space, each frame inside the cell.
#[test]
fn every_example_flight_file_flies_inside_its_cell() {
    use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
    use bevy_curved_spaces::trace::product::flight::ProductFlight;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/flights");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let file = load_flight_file(&path).unwrap_or_else(|e| panic!("{e}"));
        let id = file.space.as_deref().unwrap();
        // A product space's flight (H²×R, S²×R): `ProductFlight`, inside its cell.
        if let Some(Ok(ProductOrFlat::Product(space))) = product_space(id) {
            let flight = ProductFlight::new(&space, &file).unwrap_or_else(|e| panic!("{e}"));
            for k in 0..flight.frame_count(10.0) {
                let f = flight.frame(&space, k as f64 / 10.0);
                assert!(
                    space.outside_by(f.w_axis) <= 1e-9,
                    "{}: frame {k}",
                    path.display()
                );
                assert!(crate::common::product_frame_defect(space.base(), f) < 1e-9);
            }
            n += 1;
            continue;
        }
        // An SL̃(2,R) space's flight: `Sl2rFlight`, inside its cell with orthonormal frames.
        if let Some(Ok(space)) = bevy_curved_spaces::space::sl2r::sl2r_space(id) {
            use bevy_curved_spaces::space::FrameSpace;
            use bevy_curved_spaces::space::motion::CoverFlight;
            let flight = bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight::new(&file)
                .unwrap_or_else(|e| panic!("{e}"));
            for k in 0..flight.frame_count(10.0) {
                let f = flight.camera(&space, k as f64 / 10.0).frame;
                assert!(
                    space.outside_by(f.w_axis) <= 1e-9,
                    "{}: frame {k}",
                    path.display()
                );
                assert!(space.frame_defect(f) < 1e-9);
            }
            n += 1;
            continue;
        }
        let space = seed_space(id).unwrap();
        let flight = Flight::new(&space, &file).unwrap_or_else(|e| panic!("{e}"));
        for k in 0..flight.frame_count(10.0) {
            let f = flight.frame(&space, k as f64 / 10.0);
            assert!(
                space.outside_by(f.w_axis) <= 1e-9,
                "{}: frame {k}",
                path.display()
            );
            assert!(space.geometry().frame_defect(f) < 1e-9);
        }
        n += 1;
    }
    assert!(n >= 4, "the shipped flights: {n}");
}

#[test]
fn flight_files_with_mistakes_are_named() {
    for (text, needle) in [
        (
            "[[key]]\ntime = 0\nposition = [0,0,0]\nlook_at = [0,0,-1]\n",
            "name a space",
        ),
        (
            "space = \"torus\"\nscene = \"x.toml\"\n",
            "either space or scene",
        ),
        ("space = \"torus\"\nfov = 200\n", "fov"),
        (
            "space = \"torus\"\n[[key]]\ntime = -1\nposition = [0,0,0]\nlook_at = [0,0,-1]\n",
            "key 1: time",
        ),
        (
            "space = \"torus\"\n[[key]]\ntime = 0\nposition = [0,0,0]\nlook_at = [0,0,0]\n",
            "look_at is the position",
        ),
        (
            "space = \"torus\"\n[[key]]\ntime = 0\nposition = [nan,0,0]\nlook_at = [0,0,-1]\n",
            "finite",
        ),
        ("space = \"torus\"\nspeed = 3\n", "unknown field"),
    ] {
        let e = parse_flight(text, "f.toml").unwrap_err();
        assert!(e.starts_with("f.toml") && e.contains(needle), "{text}: {e}");
    }
    // In S³ a key must stay within the hemisphere of the cell's centre.
    let poincare = seed_space("poincare").unwrap();
    let file = parse_flight(
        "space = \"poincare\"\n[[key]]\ntime = 0\nposition = [0,0,9]\nlook_at = [0,0,-1]\n",
        "f.toml",
    )
    .unwrap();
    let e = Flight::new(&poincare, &file).unwrap_err();
    assert!(e.contains("hemisphere"), "{e}");
}

/// `walk --replay`: with a [`FlightReplay`] the plugin drives the camera along the flight,
/// frame for frame, looping at the end; the player's keys do not move it.
#[test]
fn a_replayed_flight_drives_the_camera_frame_for_frame() {
    use bevy::input::InputPlugin;
    use bevy::prelude::*;
    use bevy::time::TimeUpdateStrategy;
    use bevy_curved_spaces::plugin::flight::FlightReplay;
    use bevy_curved_spaces::prelude::*;
    use std::time::Duration;
    const DT: f64 = 0.25;
    let space = seed_space("seifert-weber").unwrap();
    let text = "space = \"seifert-weber\"\n[[key]]\ntime = 0.0\nposition = [0.45, 0.1, 0.5]\n\
                look_at = [0.45, 0.1, -1.0]\n[[key]]\ntime = 2.0\nposition = [0.45, 0.1, -2.0]\n\
                look_at = [0.45, 0.1, -3.0]\n";
    let flight = Flight::new(&space, &parse_flight(text, "t.toml").unwrap()).unwrap();
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, InputPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            DT,
        )))
        .add_plugins(CurvedSpacesPlugin {
            space: "seifert-weber".into(),
            ..default()
        })
        .insert_resource(FlightReplay::new(flight.clone(), true));
    let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
    app.update();
    app.world_mut()
        .resource_mut::<ButtonInput<KeyCode>>()
        .press(KeyCode::KeyW);
    for n in 0..12 {
        app.update();
        let t = ((n + 1) as f64 * DT) % flight.duration();
        let f = app.world().get::<PlayerFrame>(camera).unwrap().0;
        let expected = flight.frame(&space, t);
        assert!(max_entry(f - expected) < 1e-9, "update {n}: t = {t}");
        // The camera's holonomy is the way's: crossings and the product of their pairings.
        let h = *app
            .world()
            .get::<bevy_curved_spaces::space::Holonomy>(camera)
            .unwrap();
        let (_, crossed) = flight.frame_and_crossings(&space, t);
        assert_eq!(h.crossings, crossed.len() as u64);
        let cover = flight.cover_frame(t);
        let turned = Geometry::Hyperbolic.orthonormalize_frame(h.matrix * cover);
        assert!(max_entry(turned - f) < 1e-9, "update {n}");
    }
}

/// A walk the plugin records as a flight (`walk --record`): the camera of a plugin app in
/// space `id` moves by `translation` (in inradii a second) and turns by `rotation` (radians
/// a second) for 120 updates of 0.05 s, a key each update. Returns the app, the frames
/// walked (from the first update on) and the file read back, after checking that the walk
/// crossed faces and the recording kept every key.
pub(crate) fn recorded_walk(
    id: &str,
    translation: glam::DVec3,
    rotation: glam::DVec3,
) -> (bevy::app::App, Vec<glam::DMat4>, FlightFile) {
    use bevy::prelude::*;
    use bevy::time::TimeUpdateStrategy;
    use bevy_curved_spaces::plugin::components::{PlayerFrame, PlayerMotion};
    use bevy_curved_spaces::plugin::flight::FlightRecorder;
    use bevy_curved_spaces::prelude::{
        ActiveSpace, CurvedSpaceCamera, CurvedSpacesPlugin, Holonomy,
    };
    use bevy_curved_spaces::scene::flight::FlightSource;
    const DT: f64 = 0.05;
    let dir = crate::common::scratch_dir(&format!("record-{id}"));
    let path = dir.join("walk.toml");
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .insert_resource(TimeUpdateStrategy::ManualDuration(
            std::time::Duration::from_secs_f64(DT),
        ))
        .add_plugins(CurvedSpacesPlugin {
            space: id.into(),
            controls: false,
            ..default()
        })
        .insert_resource(FlightRecorder::new(
            path.clone(),
            FlightSource::Space(id.into()),
            DT,
        ));
    app.finish();
    let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
    app.update();
    let r = app.world().resource::<ActiveSpace>().inradius;
    *app.world_mut().get_mut::<PlayerMotion>(camera).unwrap() = PlayerMotion {
        translation: translation * r * DT,
        rotation: rotation * DT,
    };
    // The first update recorded the start already.
    let mut frames = vec![app.world().get::<PlayerFrame>(camera).unwrap().0];
    for _ in 0..120 {
        app.update();
        frames.push(app.world().get::<PlayerFrame>(camera).unwrap().0);
    }
    let crossings = app.world().get::<Holonomy>(camera).unwrap().crossings;
    assert!(crossings >= 2, "{id}: {crossings} crossings");
    app.world_mut()
        .resource_mut::<FlightRecorder>()
        .write()
        .unwrap();
    let recorder = app.world().resource::<FlightRecorder>().clone();
    assert!(recorder.stopped.is_none(), "{id}: {:?}", recorder.stopped);
    let file = load_flight_file(&path).unwrap();
    assert!(file.keys.len() >= 110, "{id}: {} keys", file.keys.len());
    std::fs::remove_dir_all(&dir).ok();
    (app, frames, file)
}

/// A walk recorded as a flight (`walk --record`) replays to the walk's own frames: through
/// faces (turned by their pairings), with pitch and roll, at every recorded key.
#[test]
fn a_recorded_walk_replays_to_the_same_frames() {
    for id in ["seifert-weber", "half-turn", "mirrored-cube"] {
        // Forward, turning and rolling: through several faces in 6 s.
        let (app, frames, file) = recorded_walk(
            id,
            glam::DVec3::new(0.1, 0.0, -0.8),
            glam::DVec3::new(0.15, 0.25, 0.3),
        );
        let space = crate::common::shown_constant(&app);
        let flight = Flight::new(&space, &file).unwrap();
        // The keys are the frames from the first recorded one on, DT apart.
        let first = frames.len() - file.keys.len();
        for (k, &(t, _, _)) in file.keys.iter().enumerate() {
            let walked = frames[first + k];
            let replayed = flight.frame(&space, t);
            assert!(
                max_entry(replayed - walked) < 1e-9,
                "{id}: key {k} at {t} s differs by {:e}",
                max_entry(replayed - walked)
            );
        }
    }
}
