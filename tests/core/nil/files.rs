//! Nil's scene files and flights: a file's objects come with their lattice images, the
//! plugin starts at the file's view, a recorded walk replays to the walk's own frames, and
//! a flight's frames lie in the box on the way between its keys.

use bevy_curved_spaces::scene::flight::parse_flight;
use bevy_curved_spaces::space::FrameSpace;
use bevy_curved_spaces::space::motion::CoverFlight;
use bevy_curved_spaces::space::nil::{NilSpace, distance, group_product};
use bevy_curved_spaces::trace::nil::NilShape;
use bevy_curved_spaces::trace::nil::file::parse_nil_scene;
use bevy_curved_spaces::trace::nil::flight::NilFlight;
use glam::DMat4;

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()))
}

/// A ball written outside the box is brought in, and a ball reaching through the top comes
/// with its image below: every image of the file's ball that meets the box is there, each
/// a lattice element times the ball (the chart points within its radius of some kept centre
/// are the points within its radius of the cover's copies).
#[test]
fn a_scene_files_ball_comes_with_its_lattice_images() {
    let text = "space = \"nil-2\"\nedges = false\n[[object]]\ntype = \"ball\"\n\
                position = [1.1, -2.0, 0.24]\nradius = 0.1\n";
    let file = parse_nil_scene(text, "t.toml").expect("a scene");
    let space = NilSpace::new(2);
    let centres: Vec<[f64; 3]> = file
        .scene
        .objects
        .iter()
        .filter_map(|o| match o.shape {
            NilShape::Ball(c) => Some(c),
            _ => None,
        })
        .collect();
    let written = space.into_box([1.1, -2.0, 0.24]);
    assert!(centres.contains(&written), "{centres:?}");
    // Every kept centre is a lattice image of the written one.
    for c in &centres {
        let g = group_product(*c, written.map(|x| -x));
        let (p, q) = (g[0].round(), g[1].round());
        let m = (g[2] - 0.5 * p * q) * 2.0;
        assert!(
            (g[0] - p).abs() < 1e-12 && (g[1] - q).abs() < 1e-12 && (m - m.round()).abs() < 1e-9,
            "{c:?} is no image of {written:?}"
        );
    }
    // Sample the box: a point within the radius of a copy in the cover (the written centre
    // moved by A^p B^q C^m) is within the radius of a kept centre.
    let h = space.half_height();
    let mut inside = 0;
    for i in 0..4000 {
        let f = |k: u32| ((i * k) % 997) as f64 / 997.0 - 0.5;
        let x = [f(13), f(31), 2.0 * h * f(71)];
        let near_cover = (-2i32..=2).any(|p| {
            (-2i32..=2).any(|q| {
                (-8i64..=8).any(|m| {
                    let g = space.element(f64::from(p), f64::from(q), m);
                    distance(x, group_product(g, written)) < 0.1
                })
            })
        });
        let near_kept = centres.iter().any(|c| distance(x, *c) < 0.1);
        assert_eq!(near_cover, near_kept, "at {x:?}");
        inside += usize::from(near_kept);
    }
    assert!(inside > 10, "only {inside} samples in the ball");
}

/// A moving ball is where the Nil geodesic of its velocity has taken it, brought into the
/// box by the lattice, and drawn there with its images.
#[test]
fn a_moving_ball_flies_its_geodesic() {
    use bevy_curved_spaces::space::nil::{NilRay, flow};
    let text = "space = \"nil-3\"\nedges = false\n[[object]]\ntype = \"ball\"\n\
                position = [0.1, 0.2, 0.05]\nradius = 0.05\nvelocity = [0.3, -0.4, 0.5]\n";
    let file = parse_nil_scene(text, "t.toml").expect("a scene");
    let space = NilSpace::new(3);
    assert_eq!(file.moving.len(), 1);
    assert!(
        file.scene.objects.is_empty(),
        "the mover is not in the still scene"
    );
    let speed = (0.3f64 * 0.3 + 0.4 * 0.4 + 0.5 * 0.5).sqrt();
    for t in [0.0, 0.5, 3.0] {
        let ball = file.moving[0].object_at(&space, t).expect("a time");
        let NilShape::Ball(at) = ball.shape else {
            panic!("a ball");
        };
        let cover = flow(
            &NilRay {
                point: [0.1, 0.2, 0.05],
                velocity: [0.3 / speed, -0.4 / speed, 0.5 / speed],
            },
            speed * t,
        )
        .point;
        let want = space.into_box(cover);
        let gap = (0..3).map(|i| (at[i] - want[i]).abs()).fold(0.0, f64::max);
        assert!(gap < 1e-9, "at {t} s the ball is {gap:e} off its geodesic");
        let scene = file.scene_at(t).expect("a scene");
        assert!(scene.objects.iter().any(|o| o.shape == NilShape::Ball(at)));
    }
}

/// The plugin's players start at a Nil scene file's `[start]` (the base scene), with its
/// field of view.
#[test]
fn the_plugin_starts_at_a_nil_scene_files_view() {
    use bevy::prelude::*;
    use bevy_curved_spaces::prelude::*;
    let text = "space = \"nil-3\"\n[start]\nposition = [0.2, -0.3, 0.05]\n\
                look_at = [0.0, 0.2, 0.0]\nfov = 55\n";
    let file = parse_nil_scene(text, "t.toml").expect("a scene");
    let start = file.start.expect("a start view");
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, bevy::input::InputPlugin))
        .insert_resource(BaseNilScene::from_file(&file))
        .add_plugins(CurvedSpacesPlugin {
            space: "nil-3".into(),
            ..default()
        });
    let camera = app.world_mut().spawn(CurvedSpaceCamera::default()).id();
    app.update();
    let frame = app.world().get::<PlayerFrame>(camera).expect("a frame").0;
    assert!(max_entry(frame - start.frame) < 1e-12, "{frame:?}");
    let fov = app
        .world()
        .get::<CurvedSpaceCamera>(camera)
        .expect("a camera")
        .fov_y_degrees;
    assert_eq!(fov, 55.0);
}

/// A walk in a Nil space recorded as a flight (`walk --record`) replays to the walk's own
/// frames at every key: up through the top and across the sides (the lattice's shifts
/// undone by the holonomy), turning about `E₃` and pitched.
#[test]
fn a_recorded_nil_walk_replays_to_the_same_frames() {
    for id in ["nil-1", "nil-3"] {
        let (app, frames, file) = crate::flight::recorded_walk(
            id,
            glam::DVec3::new(0.1, 0.5, -0.8),
            glam::DVec3::new(0.08, 0.25, 0.0),
        );
        let space = NilSpace::new(id[4..].parse().unwrap());
        let flight = NilFlight::new(&space, &file).expect("a Nil flight");
        let first = frames.len() - file.keys.len();
        let mut worst: f64 = 0.0;
        for (k, &(t, _, _)) in file.keys.iter().enumerate() {
            let walked = space.wrap_frame(frames[first + k], 0.0).0;
            let replayed = flight.frame_in_cell(&space, t).0;
            let gap = max_entry(replayed - walked);
            worst = worst.max(gap);
            assert!(
                gap < 1e-8,
                "{id}: key {k} at {t} s differs by {gap:e}\nwalked {walked:?}\nreplayed {replayed:?}"
            );
        }
        drop(app);
        eprintln!("{id}: {} keys, worst {worst:e}", file.keys.len());
    }
}

/// A flight's frames lie in the box, start at the first key's view, and between two keys
/// the eye is on the shortest geodesic joining them: its cover point's distances to the two
/// keys add up to theirs.
#[test]
fn a_nil_flight_flies_the_geodesic_between_its_keys() {
    let text = "space = \"nil-3\"\n[[key]]\ntime = 0.0\nposition = [0.1, -0.4, 0.05]\n\
                look_at = [0.0, 0.0, 0.0]\n[[key]]\ntime = 2.0\nposition = [1.6, 0.7, 0.9]\n\
                look_at = [2.5, 0.5, 0.0]\n";
    let file = parse_flight(text, "f.toml").expect("a flight");
    let space = NilSpace::new(3);
    let flight = NilFlight::new(&space, &file).expect("a Nil flight");
    let a = [0.1, -0.4, 0.05];
    let b = [1.6, 0.7, 0.9];
    let whole = distance(a, b);
    for i in 0..=20 {
        let t = 0.1 * f64::from(i);
        let cover = flight.cover_frame(t).w_axis.truncate().to_array();
        let sum = distance(a, cover) + distance(cover, b);
        assert!(
            (sum - whole).abs() < 1e-9,
            "at {t} s: {sum} against {whole}"
        );
        let (inside, crossed) = flight.frame_in_cell(&space, t);
        assert!(space.outside_by(inside.w_axis) <= 1e-12, "at {t} s");
        assert!(space.frame_defect(inside) < 1e-12);
        if i == 20 {
            assert!(!crossed.is_empty(), "the last key lies in another box");
        }
    }
    let first = bevy_curved_spaces::trace::nil::NilCamera::looking_at(
        &space,
        glam::DVec3::from_array(a),
        glam::DVec3::ZERO,
        70.0,
    )
    .expect("a view");
    assert!(max_entry(flight.frame_in_cell(&space, 0.0).0 - first.frame) < 1e-12);
}

/// The headset's head in a Nil space (`walk --xr`): walking straight ahead in the room
/// walks one geodesic of Nil through the box's faces — the head's point, carried back into
/// the cover by the lattice elements it crossed, is the point one long step along the
/// geodesic reaches, its axes (body vectors) turned as parallel transport turns them — and
/// the stick's walk stays in the box with an orthonormal frame.
#[test]
fn a_headset_walks_nil_geodesics_through_the_faces() {
    use bevy_curved_spaces::space::nil::transport;
    use bevy_curved_spaces::view::headset::{HeadTracker, RoomPose};
    use glam::{DQuat, DVec3};
    let space = NilSpace::new(3);
    // Looking along E₂ and a little up: the walk climbs through the top too.
    let start = DMat4::from_cols(
        glam::DVec4::X,
        glam::DVec4::new(0.0, -0.3, 1.0, 0.0).normalize(),
        glam::DVec4::new(0.0, -1.0, -0.3, 0.0).normalize(),
        glam::DVec4::new(0.1, -0.2, 0.0, 1.0),
    );
    let units = 0.4;
    let mut head = HeadTracker::new(start, units, 1e-4);
    head.track(&space, RoomPose::IDENTITY);
    let metres = 8.0;
    let steps = 800;
    for k in 1..=steps {
        let z = -metres * f64::from(k) / f64::from(steps);
        head.track(
            &space,
            RoomPose::new(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY),
        );
        assert!(space.outside_by(head.frame.w_axis) <= 1e-4 + 1e-12);
        assert!(space.frame_defect(head.frame) < 1e-9);
    }
    assert!(
        head.holonomy.crossings >= 3,
        "{} crossings",
        head.holonomy.crossings
    );
    let mut cover = head.frame;
    cover.w_axis = head.holonomy.matrix.inverse() * head.frame.w_axis;
    let one_step = transport(start, -DVec3::Z, metres * units);
    let gap = max_entry(cover - one_step);
    assert!(gap < 1e-9, "{gap:e} from the single geodesic step");
    // The stick: forward and a turn, wrapped into the box.
    for _ in 0..50 {
        head.locomote(&space, DVec3::new(0.0, 0.0, -0.05), 0.1);
        assert!(space.outside_by(head.frame.w_axis) <= 1e-4 + 1e-12);
        assert!(space.frame_defect(head.frame) < 1e-9);
    }
}

/// In the plugin a Nil scene's moving ball flies with the app's clock: the packed scene
/// changes from frame to frame while it moves, and a still scene is packed once.
#[test]
fn the_plugin_flies_a_nil_scenes_moving_balls() {
    use bevy::prelude::*;
    use bevy::time::TimeUpdateStrategy;
    use bevy_curved_spaces::plugin::render::PreparedScene;
    use bevy_curved_spaces::prelude::*;
    let moving = "space = \"nil-3\"\nedges = false\n[[object]]\ntype = \"ball\"\n\
                  position = [0.0, 0.0, 0.0]\nradius = 0.05\nvelocity = [0.3, 0.0, 0.0]\n";
    let still = moving.replace("velocity = [0.3, 0.0, 0.0]\n", "");
    let packs = |text: &str| {
        let file = parse_nil_scene(text, "t.toml").expect("a scene");
        let mut app = App::new();
        app.add_plugins((MinimalPlugins, bevy::input::InputPlugin))
            .insert_resource(TimeUpdateStrategy::ManualDuration(
                std::time::Duration::from_secs_f64(0.1),
            ))
            .insert_resource(BaseNilScene::from_file(&file))
            .add_plugins(CurvedSpacesPlugin {
                space: "nil-3".into(),
                ..default()
            });
        app.world_mut().spawn(CurvedSpaceCamera::default());
        let mut seen: Vec<Vec<u32>> = Vec::new();
        for _ in 0..4 {
            app.update();
            let words = app.world().resource::<PreparedScene>().0.words.clone();
            if seen.last() != Some(&words) {
                seen.push(words);
            }
        }
        seen.len()
    };
    assert!(
        packs(moving) >= 3,
        "the moving ball's scene is packed again as it flies"
    );
    assert_eq!(packs(&still), 1, "a still scene is packed once");
}
