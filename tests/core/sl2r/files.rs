//! SL̃(2,R)'s scene files: a tube written anywhere is brought into the polygon and drawn
//! with its images under the surface group; the start view stands where the file says,
//! looking along `e`; what is not written for the family yet, and bad values, are refused
//! with the line.

use bevy_curved_spaces::space::FrameSpace;
use bevy_curved_spaces::space::sl2r::Sl2rWalker;
use bevy_curved_spaces::trace::sl2r::file::{MAX_SL2R_TUBES, parse_sl2r_scene};

const HEAD: &str = "space = \"unit-tangent-bitorus\"\nedges = false\n";

#[test]
fn a_tube_comes_with_its_images_and_the_start_stands_where_written() {
    let text = format!(
        "{HEAD}[start]\nposition = [0.2, -0.1, 0.5]\nfov = 60\n\
         [[object]]\ntype = \"tube\"\nposition = [0.9, 0.3]\nradius = 0.4\ncolour = [1, 0, 0]\n"
    );
    let file = parse_sl2r_scene(&text, "t.toml").expect("a scene");
    let tubes = &file.scene.tubes;
    // The written base point (inside the octagon) is kept, and images of it beyond sides it
    // comes within 0.4 of.
    let written = [0.9, 0.3, (1.0f64 + 0.81 + 0.09).sqrt()];
    assert!(
        tubes
            .iter()
            .any(|t| (0..3).all(|i| (t.base[i] - written[i]).abs() < 1e-12))
    );
    assert!(tubes.len() > 1, "no image through the near side");
    let circum = file.space.circumradius();
    for t in tubes {
        // On the hyperboloid, the same tube, and near enough to reach the cell.
        let p = t.base;
        assert!((p[0] * p[0] + p[1] * p[1] - p[2] * p[2] + 1.0).abs() < 1e-9);
        assert_eq!(t.radius, 0.4);
        assert!(p[2].acosh() <= circum + 0.4 + 1e-9);
        // An image of the written point: brought back into the cell by the pairings, it is
        // the written point.
        let ray = file
            .space
            .chart_ray(glam::DVec3::new(p[0], p[1], 0.0), glam::DVec3::X)
            .expect("a chart point");
        let back = Sl2rWalker::<glam::DVec4>::sl2r_ray(&ray).frame[2];
        assert!(
            (0..3).all(|i| (back[i] - written[i]).abs() < 1e-9),
            "{p:?} is not an image of the written point"
        );
    }
    let f = file.start.frame;
    let want = [0.2, -0.1, (1.0f64 + 0.04 + 0.01).sqrt()];
    for (i, w) in want.iter().enumerate() {
        assert!((f.w_axis[i] - w).abs() < 1e-12, "{f}");
    }
    assert_eq!(file.start.fov_y_degrees, 60.0);
    // Looking along e: back = −X, up = V.
    assert_eq!(f.z_axis.truncate(), glam::DVec3::new(-1.0, 0.0, 0.0));
    assert_eq!(f.y_axis.truncate(), glam::DVec3::new(0.0, 0.0, 1.0));
}

#[test]
fn what_is_not_written_yet_and_bad_values_are_refused_with_the_line() {
    for (body, says, line) in [
        (
            "[[light]]\nposition = [0, 0, 0]\n[[light]]\nposition = [0.1, 0, 0]\n",
            "has one light",
            5,
        ),
        ("[[light]]\nposition = [1e200, 0, 0]\n", "too far", 3),
        ("[[light]]\nposition = [0, 0]\n", "length", 3),
        ("[lighting]\nlamp_radius = 0.2\n", "lamp is a point", 4),
        ("[lighting]\nshadows = 100\n", "shadows must be", 4),
        ("[lighting]\npaths = \"all\"\n", "light paths", 4),
        ("[lighting]\nreach = -1\n", "reach", 4),
        ("walls = 2\n", "between 0 (solid walls) and 1", 3),
        (
            "[[object]]\ntype = \"tube\"\nposition = [0, 0]\nradius = 5\n",
            "at most",
            3,
        ),
        (
            "[[object]]\ntype = \"ball\"\nposition = [0, 0]\nradius = 0.1\n",
            "length",
            3,
        ),
        (
            "[[object]]\ntype = \"ball\"\nposition = [0, 0, 0]\nradius = 0.7\n",
            "largest ball radius",
            3,
        ),
        (
            "[[object]]\ntype = \"globe\"\nposition = [0, 0, 0]\nradius = 0.1\n",
            "unknown variant",
            3,
        ),
        ("fog = -1\n", "positive", 3),
        (
            "[start]\nposition = [0, 0, 0]\nfov = 400\n",
            "field of view",
            3,
        ),
        ("[start]\nposition = [1e200, 0, 0]\n", "too far", 3),
        (
            "[start]\nposition = [0, 0, 0]\nlook_at = [20, 0, 0]\n",
            "3 or more from the eye",
            3,
        ),
        (
            "[start]\nposition = [0, 0, 0]\nlook_at = [0, 0, 0]\n",
            "its own position",
            3,
        ),
        ("colour_fog = [1, 1, 1]\n", "fog_colour", 3),
    ] {
        let text = format!("{HEAD}{body}");
        let e = parse_sl2r_scene(&text, "t.toml")
            .expect_err(body)
            .to_string();
        assert!(e.contains(says), "{body}: {e}");
        assert!(
            e.contains(&format!("t.toml:{line}")) || e.contains("t.toml"),
            "{e}"
        );
    }
    let e = parse_sl2r_scene("space = \"unit-tangent-abAB\"\n", "t.toml")
        .expect_err("flat")
        .to_string();
    assert!(e.contains("flat"), "{e}");
    // Too many tubes with their images.
    let mut many = String::from(HEAD);
    for i in 0..MAX_SL2R_TUBES {
        many.push_str(&format!(
            "[[object]]\ntype = \"tube\"\nposition = [{}, 0.1]\nradius = 0.5\n",
            0.001 * i as f64
        ));
    }
    let e = parse_sl2r_scene(&many, "t.toml")
        .expect_err("too many")
        .to_string();
    assert!(e.contains("more than"), "{e}");
}

/// A ball written near a side comes with its images: each is the written point of the
/// manifold (moved back by the pairing it came by, its frame — base point and `e` — is the
/// written frame), and each reaches into the cell.
#[test]
fn a_ball_comes_with_its_images_each_the_same_point_of_the_bundle() {
    use bevy_curved_spaces::space::sl2r::chart_frame;
    let text =
        format!("{HEAD}[[object]]\ntype = \"ball\"\nposition = [0.85, 0.2, 2.0]\nradius = 0.3\n");
    let file = parse_sl2r_scene(&text, "t.toml").expect("a scene");
    let balls = &file.scene.balls;
    assert!(balls.len() > 1, "no image through the near side");
    let written = chart_frame(0.85, 0.2, 2.0);
    let circum = file.space.circumradius();
    let mut found_written = false;
    for b in balls {
        assert_eq!(b.radius, 0.3);
        assert!(b.centre[2][2].acosh() <= circum + 0.3 + 1e-9);
        // Brought into the cell by the pairings, the centre is the written frame.
        let [e, _, p] = b.centre;
        let back = file
            .space
            .into_cell(&bevy_curved_spaces::space::sl2r::Sl2rRay {
                frame: b.centre,
                velocity: [1.0, 0.0, 0.0],
            })
            .frame;
        for (got, want) in [(back[0], written[0]), (back[2], written[2])] {
            assert!(
                (0..3).all(|i| (got[i] - want[i]).abs() < 1e-9),
                "{p:?} {e:?} is no image of the written frame"
            );
        }
        found_written |= (0..3).all(|i| (p[i] - written[2][i]).abs() < 1e-12);
    }
    assert!(found_written, "the written ball is not among them");
}

/// An SL̃(2,R) flight: between two keys the eye is on the shortest geodesic joining them
/// (its distances to the two keys add up to theirs), looks along the shortest geodesic to the
/// target between theirs, and its frames lie in the cell; the first frame is the view
/// `render --eye --look-at` sets up; keys too far apart for the inverse exponential map are
/// refused with the reason.
#[test]
fn an_sl2r_flight_flies_the_geodesic_between_its_keys() {
    use bevy_curved_spaces::scene::flight::parse_flight;
    use bevy_curved_spaces::space::motion::CoverFlight;
    use bevy_curved_spaces::space::sl2r::chart_frame;
    use bevy_curved_spaces::space::sl2r::distance::shortest;
    use bevy_curved_spaces::trace::sl2r::Sl2rCamera;
    use bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight;
    let text = "space = \"unit-tangent-bitorus\"\n[[key]]\ntime = 0.0\n\
                position = [-0.6, 0.0, 0.0]\nlook_at = [0.0, 0.84, 0.0]\n[[key]]\ntime = 2.0\n\
                position = [2.0, 2.0, 0.5]\nlook_at = [2.6, 2.4, 0.5]\n";
    let file = parse_flight(text, "f.toml").expect("a flight");
    let space = bevy_curved_spaces::space::sl2r::sl2r_space("unit-tangent-bitorus")
        .unwrap()
        .unwrap();
    let flight = Sl2rFlight::new(&file).expect("an SL̃(2,R) flight");
    let a = chart_frame(-0.6, 0.0, 0.0);
    let b = chart_frame(2.0, 2.0, 0.5);
    let d = |x: &[[f64; 3]; 3], y: &[[f64; 3]; 3]| shortest(x, y).expect("near").0;
    let whole = d(&a, &b);
    let mut crossed_any = false;
    for i in 0..=20 {
        let t = 0.1 * f64::from(i);
        let f = flight.cover_frame(t);
        let p = [f.w_axis.x, f.w_axis.y, f.w_axis.z];
        let e = [f.x_axis.w, f.y_axis.w, f.z_axis.w];
        let frame = [e, bevy_curved_spaces::space::sl2r::flow::perp(p, e), p];
        let sum = d(&a, &frame) + d(&frame, &b);
        assert!(
            (sum - whole).abs() < 1e-9,
            "at {t} s: {sum} against {whole}"
        );
        let (inside, crossed) = flight.frame_in_cell(&space, t);
        let q = inside.w_axis;
        assert!(
            space.sides().iter().all(|s| s
                .normal
                .iter()
                .zip([q.x, q.y, q.z])
                .map(|(n, x)| n.hi * x)
                .sum::<f64>()
                <= 1e-9),
            "at {t} s the frame is outside the polygon"
        );
        crossed_any |= !crossed.is_empty();
    }
    assert!(crossed_any, "the last key lies beyond a side");
    let first = Sl2rCamera::looking_at(
        &space,
        glam::DVec3::new(-0.6, 0.0, 0.0),
        glam::DVec3::new(0.0, 0.84, 0.0),
        70.0,
    )
    .expect("a view");
    let gap = (flight.frame_in_cell(&space, 0.0).0 - first.frame)
        .to_cols_array()
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    assert!(gap < 1e-12, "the first frame is {gap:e} from the view");
    let far = "space = \"unit-tangent-bitorus\"\n[[key]]\ntime = 0.0\nposition = [0, 0, 0]\n\
               look_at = [0.5, 0, 0]\n[[key]]\ntime = 1.0\nposition = [20, 0, 0]\n\
               look_at = [21, 0, 0]\n";
    let e = Sl2rFlight::new(&parse_flight(far, "f.toml").unwrap()).expect_err("too far");
    assert!(e.contains("add keys between"), "{e}");
}

/// `walk --record` in an SL̃(2,R) space: a walk's frame, carried back through the sides it
/// crossed into `UT H²`, is written as a key whose replay is the walk's frame again (its
/// base point, its `e` and where it looks).
#[test]
fn a_recorded_sl2r_key_replays_the_walk() {
    use bevy_curved_spaces::scene::flight::parse_flight;
    use bevy_curved_spaces::space::motion::CoverFlight;
    use bevy_curved_spaces::space::{FrameMotion, FrameSpace, Holonomy};
    use bevy_curved_spaces::trace::sl2r::default_camera;
    use bevy_curved_spaces::trace::sl2r::flight::{Sl2rFlight, recorded_sl2r_key};
    use glam::DVec3;
    // In the double cover the walk climbs past a sheet: the key's angle is lifted.
    for (id, climb) in [
        ("unit-tangent-bitorus", 0.01),
        ("unit-tangent-bitorus-cover-2", 0.08),
    ] {
        let space = bevy_curved_spaces::space::sl2r::sl2r_space(id)
            .unwrap()
            .unwrap();
        let mut frame = default_camera(&space).frame;
        let mut holonomy = Holonomy::default();
        // Forward, climbing a little and turning: through at least one side.
        for k in 0..120 {
            frame = space.step_frame(
                frame,
                &FrameMotion {
                    translation: DVec3::new(0.0, climb, -0.05),
                    rotation: DVec3::new(0.0, if k % 3 == 0 { 0.01 } else { 0.0 }, 0.0),
                    level: true,
                },
            );
            let (wrapped, crossed) = space.wrap_frame(frame, 0.0);
            for c in &crossed {
                holonomy.record_crossing(c);
            }
            frame = wrapped;
        }
        assert!(holonomy.crossings >= 1, "the walk crossed no side");
        let (at, ahead, above) = recorded_sl2r_key(&space, frame, &holonomy).expect("a key");
        let text = format!(
            "space = \"{id}\"\n[[key]]\ntime = 0.0\nposition = [{:?}, {:?}, {:?}]\n\
         look_at = [{:?}, {:?}, {:?}]\nup = [{:?}, {:?}, {:?}]\n",
            at.x, at.y, at.z, ahead.x, ahead.y, ahead.z, above.x, above.y, above.z
        );
        let flight = Sl2rFlight::new(&parse_flight(&text, "r.toml").unwrap())
            .expect("a flight")
            .in_space(&space);
        if space.sheets() > 1 {
            let sheet = bevy_curved_spaces::trace::sl2r::camera_sheet(&frame);
            // The walk climbed past the cut: the key's angle is a turn up (or down), lifted.
            assert!(
                at.z.abs() > std::f64::consts::PI,
                "{id}: sheet {sheet}, key {at:?}"
            );
        }
        let (replayed, _) = flight.frame_in_cell(&space, 0.0);
        let gap = (replayed.w_axis - frame.w_axis)
            .abs()
            .max_element()
            .max((replayed.x_axis.w - frame.x_axis.w).abs())
            .max((replayed.y_axis.w - frame.y_axis.w).abs())
            .max((replayed.z_axis.w - frame.z_axis.w).abs())
            .max(
                (replayed.z_axis.truncate() - frame.z_axis.truncate())
                    .abs()
                    .max_element(),
            );
        assert!(
            gap < 1e-9,
            "{id}: the replay is {gap:e} from the walk:\n{replayed}\n{frame}"
        );
    }
}
