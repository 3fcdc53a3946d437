//! Metric balls of `UT Σ`: the points within `r` of a centre by the Sasaki distance itself
//! ([`super::distance`]), not a chart solid. Where a geodesic ray first meets one, and the
//! ball's outward normal there.
//!
//! Along a unit-speed geodesic `γ`, `f(t) = d(γ(t), c) − r` changes at rate at most 1 (the
//! distance is 1-Lipschitz), so no root of `f` lies before `t + f(t)`: far from the ball
//! (where only the root-free floor of the distance is known, [`distance_floor`]) steps of
//! the floor's gap are safe.
//!
//! **Near the ball, Newton's steps are safe.** The sectional curvature is at most ¼, so by
//! the Hessian comparison the distance to the centre is convex along a geodesic while it is
//! below `π` (its Hessian is at least `½ cot(d/2)` across the geodesic's direction). So where
//! the distance is solved (`d < r + ½ < π`) and falls (`f′ < 0`), the tangent line lies below
//! `f`: Newton's step `−f/f′` lands at or before the first root and never passes it, and it
//! converges quadratically to a transversal hit, to the last bit. Where it grows (`f′ ≥ 0`)
//! the ray keeps moving away until it is `π` from the centre, and must come back from there
//! to reach the ball: no hit before another `(π − d) + (π − r)`. A ray that grazes the ball
//! (a double root) is met where the gap falls below the precision. Radii are at most
//! [`MAX_SL2R_BALL_RADIUS`], well inside the injectivity radius of `UT H²` (`π`), where the
//! shortest geodesic is the one the solver finds.

use super::distance::{Frame, distance_floor, shortest, shortest_within};
use super::flow::{Sl2rRay, flow};
use crate::space::roots::count_safe_step;
use std::f64::consts::PI;

/// The largest radius of a ball (half a unit: its distance is then always solved within
/// the trusted length, with room for the images of the surface group to stay apart).
pub const MAX_SL2R_BALL_RADIUS: f64 = 0.5;

/// Most safe steps a ball hit takes.
const MAX_BALL_STEPS: usize = 400;

/// Beyond this gap over the radius the floor alone gives the step.
const FAR: f64 = 0.5;

/// The ball's outward unit normal at the frame `at` (in `at`'s body frame): the velocity
/// there of the shortest geodesic from the centre, the gradient of the distance to it.
/// `None` where the distance is beyond what the solver trusts.
#[must_use]
pub fn normal(centre: &Frame, at: &Frame) -> Option<[f64; 3]> {
    let (length, velocity) = shortest(centre, at)?;
    Some(
        flow(
            &Sl2rRay {
                frame: *centre,
                velocity,
            },
            length,
        )
        .velocity,
    )
}

/// `f(t) = d(γ(t), c) − r` and its rate where the distance is solved (`None` where only the
/// floor is known: far from the ball).
fn gap_and_rate(ray: &Sl2rRay<f64>, centre: &Frame, radius: f64, t: f64) -> (f64, Option<f64>) {
    let at = flow(ray, t);
    let floor = distance_floor(centre, &at.frame);
    if floor > radius + FAR {
        return (floor - radius, None);
    }
    match shortest_within(centre, &at.frame, radius + FAR) {
        Some((length, velocity)) => {
            let n = flow(
                &Sl2rRay {
                    frame: *centre,
                    velocity,
                },
                length,
            )
            .velocity;
            let v = at.velocity;
            (
                length - radius,
                Some(n[0] * v[0] + n[1] * v[1] + n[2] * v[2]),
            )
        }
        // No geodesic shorter than the bound: the distance is at least the bound.
        None => ((floor - radius).max(FAR), None),
    }
}

/// The first time `t` in `[0, t_max]` at which `ray` (a unit body velocity) meets the
/// metric ball of `radius` about `centre`; `Some(0)` for a start inside it, `None` for a
/// miss (see the module).
#[must_use]
pub fn ball_hit(ray: &Sl2rRay<f64>, centre: &Frame, radius: f64, t_max: f64) -> Option<f64> {
    let mut t = 0.0;
    for _ in 0..MAX_BALL_STEPS {
        let (gap, rate) = gap_and_rate(ray, centre, radius, t);
        if gap <= 4.0 * f64::EPSILON * (1.0 + t) {
            return Some(t);
        }
        t += match rate {
            // Moving away at d = gap + radius < π (see the module).
            Some(rate) if rate >= 0.0 => 2.0 * PI - (gap + radius) - radius,
            // Newton's step: safe where the distance is convex.
            Some(rate) => {
                crate::space::roots::count_root_iteration();
                -gap / rate
            }
            None => {
                count_safe_step();
                gap
            }
        };
        if t > t_max {
            return None;
        }
    }
    None
}
