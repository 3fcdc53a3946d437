//! Metric balls of Nil: the points within `r` of a centre by Nil's own distance
//! ([`mod@super::distance`]), not a chart solid. Where a geodesic ray first meets one, and the
//! ball's outward normal there.
//!
//! Along a unit-speed geodesic `γ`, `f(t) = d(γ(t), c) − r` changes at rate at most 1 (the
//! distance is 1-Lipschitz), so no root of `f` lies before `t + f(t)`: steps of `f(t)` are
//! safe, and they approach the first root from outside. Once a Newton step from there lands
//! inside the ball (`f < 0`), the root is bracketed with no other before it, and bisection
//! safeguarding Newton's steps finds it to the last bit (the rate `f′` is the cosine between
//! the ray and the ball's normal, [`normal`]). A ray that only grazes the ball (`f′ → 0`
//! at a double root) is the one ill-conditioned case: it is a miss where the safe steps
//! shrink below the precision without entering.

use super::distance::shortest;
use super::flow::{NilRay, flow};
use super::{bracketed_root, half_way};
use crate::geometry::Real;

/// Most safe steps and refinements a ball hit takes (safe steps shrink linearly towards a
/// transversal hit, and only near a graze do they take many).
const MAX_BALL_STEPS: usize = 2000;

/// The ball's outward unit normal at `p` (in the left-invariant frame): the velocity at
/// `p` of the shortest geodesic from the centre, the gradient of the distance to it.
#[must_use]
pub fn normal<R: Real>(centre: [R; 3], p: [R; 3]) -> [R; 3] {
    let (length, velocity) = shortest(centre, p);
    normal_along(centre, length, velocity)
}

/// The normal at the end of the shortest geodesic from `centre` of `length` and start
/// `velocity` (what [`normal`] follows).
fn normal_along<R: Real>(centre: [R; 3], length: R, velocity: [R; 3]) -> [R; 3] {
    flow(
        &NilRay {
            point: centre,
            velocity,
        },
        length,
    )
    .velocity
}

/// `f(t) = d(γ(t), c) − r` and its rate `⟨γ′(t), normal⟩` (one inverse exponential map).
fn gap_and_rate<R: Real>(ray: &NilRay<R>, centre: [R; 3], radius: R, t: R) -> (R, R) {
    let at = flow(ray, t);
    let (length, velocity) = shortest(centre, at.point);
    let n = normal_along(centre, length, velocity);
    let rate = n[0] * at.velocity[0] + n[1] * at.velocity[1] + n[2] * at.velocity[2];
    (length - radius, rate)
}

/// A lower bound on the distance from `centre` to `p` that needs no root: with
/// `(x, y, z) = centre⁻¹·p`, `d ≥ √(x² + y²)` (the projection to the plane is a
/// Riemannian submersion) and `d ≥ 2(√(1 + |z|) − 1)` (at time `t` a unit-speed geodesic
/// from the origin has `|z| ≤ t + t²/4`).
#[must_use]
pub fn distance_floor<R: Real>(centre: [R; 3], p: [R; 3]) -> R {
    let [x, y, z] = super::flow::group_product(centre.map(|v| -v), p);
    let two = R::from_f64(2.0);
    (x * x + y * y)
        .sqrt()
        .max(two * ((R::ONE + z.abs()).sqrt() - R::ONE))
}

/// The first time `t` in `[0, t_max]` at which `ray` (a unit body velocity) meets the
/// metric ball of `radius` about `centre`; `Some(0)` for a start inside it, `None` for a
/// miss or a graze (see the module). Far from the ball the safe steps take the root-free
/// [`distance_floor`] instead of the distance.
#[must_use]
pub fn ball_hit<R: Real>(ray: &NilRay<R>, centre: [R; 3], radius: R, t_max: R) -> Option<R> {
    ball_hit_between(ray, centre, radius, R::ZERO, t_max)
}

/// [`ball_hit`] over the times `[from, to]` only, where the caller knows the ray does not
/// meet the ball before `from` (such as where its shadow comes within the radius of the
/// centre's, [`super::shadow::shadow_within`]): `Some(from)` where it is in the ball there.
#[must_use]
pub fn ball_hit_between<R: Real>(
    ray: &NilRay<R>,
    centre: [R; 3],
    radius: R,
    from: R,
    to: R,
) -> Option<R> {
    meeting(ray, centre, radius, (from, to), true)
}

/// Whether `ray` meets the ball within `[from, to]` (as [`ball_hit_between`] says), found
/// without refining the hit: a shadow ray needs only to know.
#[must_use]
pub fn ball_meets_between<R: Real>(
    ray: &NilRay<R>,
    centre: [R; 3],
    radius: R,
    from: R,
    to: R,
) -> bool {
    meeting(ray, centre, radius, (from, to), false).is_some()
}

/// The first meeting within `[from, to]`: refined to the last bit where `precise`, else any
/// time found inside the ball.
fn meeting<R: Real>(
    ray: &NilRay<R>,
    centre: [R; 3],
    radius: R,
    (from, to): (R, R),
    precise: bool,
) -> Option<R> {
    let zero = R::ZERO;
    let t_max = to;
    let (mut t, (mut f, mut rate)) = (from, gap_and_rate(ray, centre, radius, from));
    if !(f > zero) {
        return (f <= zero).then_some(from);
    }
    // The smallest safe step worth taking: below it the ray grazes.
    let floor = R::from_f64(16.0) * R::EPSILON * (R::ONE + radius + t_max.min(R::from_f64(1e6)));
    for _ in 0..MAX_BALL_STEPS {
        super::count_safe_step();
        // A Newton step: inside the ball, it brackets the first root.
        if rate < zero {
            let guess = t - f / rate;
            if guess <= t_max {
                let (g, _) = gap_and_rate(ray, centre, radius, guess);
                if g <= zero {
                    return Some(if precise {
                        refine(ray, centre, radius, t, guess)
                    } else {
                        guess
                    });
                }
            }
        }
        if f < floor {
            // At the surface to the precision: a hit where the ray enters across it, a graze
            // (a miss) where it runs along it.
            return (rate < -floor.sqrt()).then_some(t);
        }
        let mut before = t;
        t = t + f;
        // Root-free safe steps while the floor keeps the ball more than a radius away.
        loop {
            super::count_safe_step();
            if t > t_max {
                return None;
            }
            let far = distance_floor(centre, flow(ray, t).point) - radius;
            if !(far > radius) {
                break;
            }
            before = t;
            t = t + far;
        }
        (f, rate) = gap_and_rate(ray, centre, radius, t);
        if f == zero {
            return Some(t);
        }
        if f < zero {
            // Rounding put the safe step a hair past the root: it lies in (before, t].
            return Some(if precise {
                refine(ray, centre, radius, before, t)
            } else {
                t
            });
        }
    }
    None
}
/// The root of `f` between `lo` (outside, `f > 0`, no root before it) and `hi` (inside).
fn refine<R: Real>(ray: &NilRay<R>, centre: [R; 3], radius: R, lo: R, hi: R) -> R {
    let f = |t: R| gap_and_rate(ray, centre, radius, t);
    bracketed_root(&f, (lo, hi), half_way(lo, hi), |value| value > R::ZERO)
}
