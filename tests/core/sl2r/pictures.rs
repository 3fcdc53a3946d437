//! The CPU reference tracer of the SL̃(2,R) spaces: fibre tubes are met where the base
//! point first comes within their radius, and balls where the point first comes within
//! theirs (against dense sampling of the walked geodesic, not the closed form or the safe
//! steps), the ray straight ahead of the default camera meets the centre's
//! pillar at the distance the geometry says, and the ray up the fibre meets nothing.

use super::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::sl2r::distance::{shortest, shortest_within};
use bevy_curved_spaces::space::sl2r::flow::base_point;
use bevy_curved_spaces::space::sl2r::{Sl2rWalker, UnitTangentSpace};
use bevy_curved_spaces::space::{CellWalk, NextExit};
use bevy_curved_spaces::trace::sl2r::{
    Sl2rObject, camera_ray, default_camera, default_scene, first_hit,
};
use glam::DVec4;

/// The first distance along the walk of `ray` at which some tube's `−⟨p, q⟩ ≤ cosh r` or
/// some ball's centre is within its radius, found by sampling every `step` and bisecting,
/// over `crossings` crossings and `far`.
fn sampled_hit(
    walker: &Sl2rWalker<DVec4>,
    scene: &bevy_curved_spaces::trace::sl2r::Sl2rScene,
    ray: Sl2rRay<f64>,
    crossings: usize,
    far: f64,
) -> Option<f64> {
    let inside = |r: &Sl2rRay<f64>, t: f64| {
        let at = flow(r, t);
        let p = at.frame[2];
        scene.tubes.iter().any(|t| {
            let q = t.base;
            -(p[0] * q[0] + p[1] * q[1] - p[2] * q[2]) <= t.radius.cosh()
        }) || scene
            .balls
            .iter()
            .any(|b| shortest_within(&b.centre, &at.frame, b.radius).is_some())
    };
    let mut walk = Sl2rWalker::<DVec4>::ray_of(&ray);
    let (mut walked, mut entered) = (0.0, None);
    for _ in 0..=crossings {
        let r = Sl2rWalker::<DVec4>::sl2r_ray(&walk);
        let (length, exit) = match walker.next_exit(&walk, entered, 0) {
            NextExit::Exit(e) => (e.t, Some(e)),
            _ => (far - walked, None),
        };
        let length = length.min(far - walked);
        let step = 1e-3;
        let n = (length / step).ceil().max(1.0) as usize;
        let mut before = 0.0;
        for i in 0..=n {
            let t = length * i as f64 / n as f64;
            if inside(&r, t) {
                // Bisect between the last sample outside and this one.
                let (mut lo, mut hi) = (before, t);
                if i == 0 {
                    return Some(walked);
                }
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if inside(&r, mid) {
                        hi = mid;
                    } else {
                        lo = mid;
                    }
                }
                return Some(walked + hi);
            }
            before = t;
        }
        walked += length;
        let e = exit?;
        if walked >= far {
            return None;
        }
        walk = walker.through(&walk, &e);
        entered = walker.skip_after(&e);
    }
    None
}

#[test]
fn tubes_and_balls_are_met_where_the_ray_first_comes_within_their_radius() {
    let mut rng = SplitMix64(81);
    for word in ["abABcdCD", "abABcdCDefEF"] {
        let space = UnitTangentSpace::new(word).unwrap();
        let walker = Sl2rWalker::<DVec4>::new(&space);
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let far = 4.0;
        let (mut hits, mut balls) = (0, 0);
        for _ in 0..80 {
            let (x, y) = (rng.unit() - 0.5, rng.unit() - 0.5);
            let ray = camera_ray(&camera.frame, 1.6 * x, 1.6 * y);
            let ours = first_hit(&walker, &scene, ray, 12).filter(|h| h.distance <= far);
            let sampled = sampled_hit(&walker, &scene, ray, 12, far);
            match (ours, sampled) {
                (Some(h), Some(s)) => {
                    hits += 1;
                    balls += usize::from(matches!(h.object, Sl2rObject::Ball(_)));
                    // Sampling every 10⁻³ can step over a grazing dip: it finds the hit
                    // later or not at all, never earlier.
                    assert!(
                        (h.distance - s).abs() < 1e-9 || s > h.distance,
                        "{word}: the object is met at {} but sampled at {s}",
                        h.distance
                    );
                }
                (None, Some(s)) => panic!("{word}: an object sampled at {s} was not met"),
                (Some(h), None) => {
                    // A grazing hit sampling stepped over: it is on the object's surface.
                    let gap = match h.object {
                        Sl2rObject::Tube(tube) => {
                            let p = base_point(&h.segment, h.t);
                            let q = tube.base;
                            -(p[0] * q[0] + p[1] * q[1] - p[2] * q[2]) - tube.radius.cosh()
                        }
                        Sl2rObject::Ball(ball) => {
                            let at = flow(&h.segment, h.t);
                            shortest(&ball.centre, &at.frame).expect("near the ball").0
                                - ball.radius
                        }
                    };
                    assert!(
                        gap.abs() < 1e-9,
                        "{word}: met at {} off the object, where sampling saw nothing",
                        h.distance
                    );
                }
                (None, None) => {}
            }
        }
        assert!(hits >= 20, "{word}: only {hits} rays met an object");
        assert!(balls >= 1, "{word}: no ray met a ball");
    }
}

#[test]
fn straight_ahead_is_the_centres_pillar_and_straight_up_is_nothing() {
    let space = UnitTangentSpace::new("abABcdCD").unwrap();
    let walker = Sl2rWalker::<DVec4>::new(&space);
    let scene = default_scene(&space);
    let camera = default_camera(&space);
    let rho = space.inradius();
    // A horizontal geodesic through the centre: 0.7ρ to the centre, less the pillar's 0.1ρ.
    let ahead = first_hit(&walker, &scene, camera_ray(&camera.frame, 0.0, 0.0), 8)
        .expect("the pillar ahead");
    assert!(
        (ahead.distance - 0.6 * rho).abs() < 1e-13,
        "{}",
        ahead.distance
    );
    assert!(matches!(ahead.object, Sl2rObject::Tube(t) if t.base == [0.0, 0.0, 1.0]));
    // The fibre through the eye: its base point never moves.
    let mut up = camera_ray(&camera.frame, 0.0, 0.0);
    up.velocity = [0.0, 0.0, 1.0];
    assert!(first_hit(&walker, &scene, up, 8).is_none());
}
