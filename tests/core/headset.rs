//! Headset poses → frames in the curved space, without an XR runtime: sequences of head
//! translations and rotations in the room, with face crossings and holonomy.

use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{Space, seed_space};
use bevy_curved_spaces::view::TraceCamera;
use bevy_curved_spaces::view::headset::{HeadTracker, RoomPose, local_motion};
use bevy_curved_spaces::view::stereo::{HUMAN_IPD_METRES, default_ipd, eye_frames};
use glam::{DMat4, DQuat, DVec3};

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array()
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
}

/// The tracker's frame undone by its holonomy: where the head is in the universal cover.
fn in_cover(space: &Space, head: &HeadTracker) -> DMat4 {
    space.geometry().inverse(head.holonomy.matrix) * head.frame
}

/// A tracker at the space's default view, at the default world scale.
fn tracker(space: &Space) -> HeadTracker {
    let scale = default_ipd(inradius(space)) / HUMAN_IPD_METRES;
    HeadTracker::new(TraceCamera::default_for(space).frame, scale, 1e-4)
}

#[test]
fn walking_straight_in_the_room_walks_one_geodesic_through_faces() {
    for id in [
        "torus",
        "quarter-turn",
        "seifert-weber",
        "poincare",
        "mirrored-cube",
    ] {
        let space = seed_space(id).expect("seed");
        let mut head = tracker(&space);
        let start = head.frame;
        head.track(&space, RoomPose::IDENTITY);
        // 6 m forward in 600 steps, looking ahead: 4 inradii at the default scale.
        let metres = 6.0;
        let steps = 600;
        for k in 1..=steps {
            let z = -metres * f64::from(k) / f64::from(steps);
            head.track(
                &space,
                RoomPose::new(DVec3::new(0.0, 0.0, z), DQuat::IDENTITY),
            );
        }
        assert!(head.holonomy.crossings > 0, "{id}: the walk crosses faces");
        assert!(
            space.outside_by(head.frame.w_axis) <= 1e-4 + 1e-12,
            "{id}: inside"
        );
        let g = space.geometry();
        let one_step = start * g.translation(-DVec3::Z, metres * head.units_per_metre);
        let gap = max_entry(in_cover(&space, &head) - one_step);
        assert!(gap < 1e-9, "{id}: {gap:e} from the single geodesic step");
        println!("{id}: {} crossings in {metres} m", head.holonomy.crossings);
    }
}

#[test]
fn turning_on_the_spot_turns_without_moving() {
    let space = seed_space("seifert-weber").expect("seed");
    let mut head = tracker(&space);
    let start = head.frame;
    head.track(&space, RoomPose::IDENTITY);
    // A full turn about the room's up axis in 36 steps, with some nodding.
    for k in 1..=36 {
        let yaw = DQuat::from_rotation_y(f64::from(k) * 10f64.to_radians());
        let nod = DQuat::from_rotation_x(0.2 * (f64::from(k) * 0.5).sin());
        head.track(&space, RoomPose::new(DVec3::ZERO, yaw * nod));
    }
    head.track(&space, RoomPose::IDENTITY);
    assert_eq!(head.holonomy.crossings, 0);
    assert!(max_entry(head.frame - start) < 1e-12);
}

/// Walks a square of side `side` (space units) in the room: forward, turn left 90°, four
/// times, in `substeps` poses per leg and per turn. In the room the head is back where it
/// started; returns the rotation angle of the head's frame in the cover relative to its
/// start, about its up axis, counted in the direction of the turns.
fn room_square(space: &Space, side: f64, substeps: u32) -> f64 {
    let mut head = tracker(space);
    let start = head.frame;
    let metres = side / head.units_per_metre;
    let mut pose = RoomPose::IDENTITY;
    head.track(space, pose);
    for _ in 0..4 {
        for _ in 0..substeps {
            let step = pose.orientation * DVec3::new(0.0, 0.0, -metres / f64::from(substeps));
            pose = RoomPose::new(pose.position + step, pose.orientation);
            head.track(space, pose);
        }
        for _ in 0..substeps {
            let turn = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2 / f64::from(substeps));
            pose = RoomPose::new(pose.position, pose.orientation * turn);
            head.track(space, pose);
        }
    }
    assert!(pose.position.length() < 1e-12, "the room path is closed");
    assert!(
        (pose.orientation.dot(DQuat::IDENTITY).abs() - 1.0).abs() < 1e-12,
        "the head faces as at the start"
    );
    let g = space.geometry();
    let m = g.inverse(start) * in_cover(space, &head);
    m.z_axis.x.atan2(m.z_axis.z)
}

/// A closed walk in the room comes back turned by the curvature enclosed: after a small
/// "square" of geodesic legs and 90° left turns the head has turned by `K·area` more than
/// the full turn (Gauss–Bonnet: in S³ the turns overshoot, in H³ they fall short), and not
/// at all in flat space.
#[test]
fn a_closed_walk_in_the_room_shows_the_curvature_as_holonomy() {
    let torus = seed_space("torus").expect("seed");
    assert!(room_square(&torus, 0.3, 5).abs() < 1e-12);
    for (id, kappa) in [("seifert-weber", -1.0), ("poincare", 1.0)] {
        let space = seed_space(id).expect("seed");
        let side: f64 = 0.06;
        let angle = room_square(&space, side, 4);
        let half = room_square(&space, side / 2.0, 4);
        println!(
            "{id}: square of side {side}: turned {angle:.6e} rad (K·area = {:.6e}); half side {half:.6e}",
            kappa * side * side
        );
        assert!(
            (angle / (kappa * side * side) - 1.0).abs() < 0.02,
            "{id}: turned {angle}, expected about {}",
            kappa * side * side
        );
        assert!(
            (angle / half - 4.0).abs() < 0.05,
            "{id}: the defect scales as the area"
        );
        // The same walk in other substeps gives the same frame: only the path counts.
        assert!((room_square(&space, side, 1) - angle).abs() < 1e-12);
    }
}

#[test]
fn crossing_a_twisted_face_turns_the_frame_and_records_the_pairing() {
    let space = seed_space("quarter-turn").expect("seed");
    let g = space.geometry();
    // Start at the centre looking up the z axis (back = −z), walk 0.6 m... in space units
    // 0.6 along −back = +z: through the z face, glued with a quarter turn.
    let frame = g.rotation(DVec3::X, std::f64::consts::PI);
    let mut head = HeadTracker::new(frame, 1.0, 1e-4);
    head.track(&space, RoomPose::IDENTITY);
    let crossed = head.track(
        &space,
        RoomPose::new(DVec3::new(0.0, 0.0, -0.6), DQuat::IDENTITY),
    );
    assert_eq!(crossed.len(), 1);
    let face = crossed[0];
    assert_eq!(head.holonomy.last_face, Some(face));
    let pairing = space.faces()[face].pairing;
    let unwrapped = frame * g.translation(-DVec3::Z, 0.6);
    assert!(max_entry(head.frame - g.orthonormalize_frame(pairing * unwrapped)) < 1e-12);
    // The quarter turn shows in the frame: its right tangent is no longer the chart's ±x.
    let right = head.frame.x_axis.truncate();
    assert!(
        right.x.abs() < 1e-9 && (right.y.abs() - 1.0).abs() < 1e-9,
        "{right:?}"
    );
    assert!(g.distance(head.frame.w_axis, ORIGIN) < 0.5);
}

/// The headset's eyes, ±IPD/2 from the head in the room, are the desktop stereo's eyes.
#[test]
fn headset_eyes_match_the_desktop_stereo_eyes() {
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = seed_space(id).expect("seed");
        let head = tracker(&space);
        let ipd_m = 0.063;
        let head_pose = RoomPose::new(DVec3::new(0.2, 1.6, -0.3), DQuat::from_rotation_y(0.4));
        let eye = |side: f64| {
            RoomPose::new(
                head_pose.position
                    + head_pose.orientation * DVec3::new(side * ipd_m / 2.0, 0.0, 0.0),
                head_pose.orientation,
            )
        };
        let xr = [eye(-1.0), eye(1.0)].map(|e| head.eye(&space, &head_pose, &e));
        let desktop = eye_frames(&space, head.frame, ipd_m * head.units_per_metre);
        for (a, b) in xr.iter().zip(&desktop) {
            assert!(max_entry(a.frame - b.frame) < 1e-12, "{id}");
            assert_eq!(a.crossed, b.crossed);
        }
        // The head between the eyes is the head.
        let between = RoomPose::between(&eye(-1.0), &eye(1.0));
        assert!((between.position - head_pose.position).length() < 1e-12);
    }
}

#[test]
fn controller_locomotion_is_local_motion_with_wrapping() {
    let space = seed_space("torus").expect("seed");
    let g = Geometry::Euclidean;
    let mut head = HeadTracker::new(DMat4::IDENTITY, 1.0, 1e-4);
    // Turn left a quarter, then stride 0.7 forward: along chart −x, through the −x face.
    head.locomote(&space, DVec3::ZERO, std::f64::consts::FRAC_PI_2);
    let crossed = head.locomote(&space, DVec3::new(0.0, 0.0, -0.7), 0.0);
    assert_eq!(crossed.len(), 1);
    let p = g.to_chart(head.frame.w_axis);
    assert!((p - DVec3::new(0.3, 0.0, 0.0)).length() < 1e-12, "{p:?}");
    // Facing −x: the back tangent is +x.
    assert!((head.frame.z_axis.truncate() - DVec3::X).length() < 1e-12);
    // A zero motion is no motion.
    assert_eq!(
        local_motion(g, head.frame, DVec3::ZERO, DQuat::IDENTITY),
        head.frame
    );
}

#[test]
fn smooth_turning_follows_the_stick_past_its_dead_zone() {
    use bevy_curved_spaces::view::headset::{DEAD_ZONE, TurnStyle, turn_yaw};
    let (speed, dt) = (1.5, 0.05);
    // Right turns clockwise seen from above (a negative yaw), in proportion to the push.
    for x in [1.0, 0.5, -0.8] {
        let (yaw, held) = turn_yaw(TurnStyle::Smooth, x, speed, dt, false);
        assert!((yaw + x * speed * dt).abs() < 1e-15, "{x}: {yaw}");
        assert!(!held);
    }
    // Resting drift turns nothing.
    let (yaw, _) = turn_yaw(TurnStyle::Smooth, 0.9 * DEAD_ZONE, speed, dt, false);
    assert_eq!(yaw, 0.0);
}

#[test]
fn snap_turning_turns_once_per_push() {
    use bevy_curved_spaces::view::headset::{TurnStyle, turn_yaw};
    let style = TurnStyle::Snap { degrees: 45.0 };
    // A push held over several frames, released, pushed the other way.
    let sticks = [0.2, 0.75, 1.0, 1.0, 0.5, 0.2, 0.0, -0.9, -0.9, 0.0];
    let mut held = false;
    let mut turns = Vec::new();
    for x in sticks {
        let (yaw, now) = turn_yaw(style, x, 1.5, 0.05, held);
        held = now;
        if yaw != 0.0 {
            turns.push(yaw.to_degrees());
        }
    }
    assert_eq!(turns.len(), 2, "{turns:?}");
    assert!((turns[0] + 45.0).abs() < 1e-12, "right first: {turns:?}");
    assert!((turns[1] - 45.0).abs() < 1e-12, "then left: {turns:?}");
    // A snap does not depend on the frame time.
    let (a, _) = turn_yaw(style, 1.0, 1.5, 0.01, false);
    let (b, _) = turn_yaw(style, 1.0, 1.5, 0.2, false);
    assert_eq!(a, b);
}

#[test]
fn a_recentred_room_does_not_move_the_head() {
    let space = seed_space("torus").expect("seed");
    let mut head = tracker(&space);
    head.track(&space, RoomPose::IDENTITY);
    head.track(
        &space,
        RoomPose::new(DVec3::new(0.0, 0.0, -0.1), DQuat::IDENTITY),
    );
    let frame = head.frame;
    // The runtime recentres: the same head is now reported at the room's origin.
    head.reanchor();
    head.track(&space, RoomPose::IDENTITY);
    assert_eq!(head.frame, frame, "the recentre moved the head");
    // Motion after it continues from there.
    head.track(
        &space,
        RoomPose::new(DVec3::new(0.0, 0.0, -0.1), DQuat::IDENTITY),
    );
    let g = space.geometry();
    let step = g.distance(frame.w_axis, head.frame.w_axis);
    assert!((step - 0.1 * head.units_per_metre).abs() < 1e-12, "{step}");
}
