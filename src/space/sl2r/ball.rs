//! Metric balls of `UT Σ`: the points within `r` of a centre by the Sasaki distance itself
//! ([`super::distance`]), not a chart solid. Where a geodesic ray first meets one, and the
//! ball's outward normal there.
//!
//! Along a unit-speed geodesic `γ`, `f(t) = d(γ(t), c) − r` changes at rate at most 1 (the
//! distance is 1-Lipschitz), so no root of `f` lies before `t + f(t)`: steps of `f(t)` are
//! safe and approach the first root from outside (far from the ball the root-free floor of
//! the distance, [`distance_floor`], gives the step). Once a Newton step from there lands
//! inside the ball, the root is bracketed with no other before it, and bisection
//! safeguarding Newton's steps finds it to the last bit (the rate `f′` is the cosine between
//! the ray and the ball's normal). A ray that only grazes the ball is a miss where the safe
//! steps shrink below the precision without entering. Radii are at most
//! [`MAX_SL2R_BALL_RADIUS`], well inside the injectivity radius of `UT H²` (`π`), where the
//! shortest geodesic is the one the solver finds.

use super::distance::{Frame, distance_floor, shortest, shortest_within};
use super::flow::{Sl2rRay, flow};
use crate::space::roots::{bracketed_root, count_safe_step};

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
/// miss or a graze (see the module).
#[must_use]
pub fn ball_hit(ray: &Sl2rRay<f64>, centre: &Frame, radius: f64, t_max: f64) -> Option<f64> {
    let mut t = 0.0;
    for _ in 0..MAX_BALL_STEPS {
        let (gap, rate) = gap_and_rate(ray, centre, radius, t);
        if gap <= 0.0 {
            return Some(t);
        }
        let closing = rate.filter(|&r| r < 0.0);
        if gap <= 4.0 * f64::EPSILON * (1.0 + t) {
            // On the sphere to the last bit: a hit where the ray enters, a graze otherwise.
            return closing.filter(|&r| r < -1e-6).map(|_| t);
        }
        if let Some(rate) = closing {
            // Newton's step, and twice it (the distance is convex near the sphere, so
            // Newton's steps from outside stay outside): the first that lands inside
            // brackets the root.
            let newton = -gap / rate;
            for step in [newton, 2.0 * newton] {
                let guess = t + step;
                if guess <= t_max && gap_and_rate(ray, centre, radius, guess).0 <= 0.0 {
                    let f = |s: f64| {
                        let (g, r) = gap_and_rate(ray, centre, radius, s);
                        (g, r.unwrap_or(1.0))
                    };
                    return Some(bracketed_root(&f, (t, guess), t + gap, |v| v > 0.0));
                }
            }
        }
        count_safe_step();
        t += gap;
        if t > t_max {
            return None;
        }
    }
    None
}
