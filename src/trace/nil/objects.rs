//! The objects of a Nil scene and where a geodesic segment first meets each.
//!
//! Three shapes, each the set where a function of the point is at most zero:
//! - a **ball**: the metric ball `d(p, c) ≤ r` by Nil's own distance, met by
//!   [`crate::space::nil::ball_hit`];
//! - a **fibre tube**: the points within `r` of a vertical line `{(b₁, b₂, z)}` (a fibre of
//!   the projection to the plane). The projection is a Riemannian submersion onto the
//!   Euclidean plane, so the distance to a fibre is the plane distance `|(x, y) − b|`: the
//!   tube is an exact metric tube, a round cylinder in the chart;
//! - a **swept disc**: a chart solid, named as such. For a horizontal segment
//!   `e(s) = (s, y₀, h)` of the chart (or `(x₀, s, h)` along `y`), `|s| ≤ ½`, it is the set
//!   of `e(s)·(0, a, b)` (resp. `e(s)·(a, 0, b)`) with `a² + b² ≤ r²`: a small upright disc
//!   left-translated along the segment. The box's horizontal edges are such segments but no
//!   geodesics, so their metric tubes have no closed form; this set is the same for every
//!   lattice image of the edge (a left translation carries it along) and exact to compute.
//!
//! Along a unit-speed geodesic every such function `g` changes at most at a known rate `L`
//! (1 for balls and fibre tubes; for a swept disc the bound below), so no root lies before
//! `t + g(t)/L`: such steps are safe, and they approach the first root from outside. Where
//! one lands inside (`g ≤ 0`), or a Newton step does, the first root is bracketed and
//! bisection safeguarding Newton's steps finds it to the last bit. A ray that only grazes
//! is a miss once the safe steps fall below the precision.

use crate::space::nil::{
    NilRay, ball_hit_between, ball_meets_between, flow, group_product, horizontal_exit,
    normal as ball_normal, shadow_within,
};
use glam::DVec3;

/// What an object of a Nil scene surrounds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NilShape {
    /// A metric ball about a chart point.
    Ball([f64; 3]),
    /// The vertical line over a point of the plane (an exact metric tube).
    Fibre([f64; 2]),
    /// A swept disc (see the module): about the horizontal chart segment through
    /// `γ·(…)` of the box's top, `along` 0 (the segment `(s, offset, height)`) or 1
    /// (`(offset, s, height)`), `|s| ≤ ½`, moved by the lattice element `image`.
    Edge {
        /// The lattice element the edge is carried by (a chart point of the group).
        image: [f64; 3],
        /// The chart axis the segment runs along: 0 (`x`) or 1 (`y`).
        along: usize,
        /// Its other horizontal coordinate.
        offset: f64,
        /// Its height.
        height: f64,
    },
}

/// An object: the points within `radius` of its shape (by the shape's measure, above).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NilObject {
    /// What it surrounds.
    pub shape: NilShape,
    /// Its radius.
    pub radius: f64,
    /// Its colour, linear RGB.
    pub colour: DVec3,
}

/// Most safe steps one meeting takes.
const MAX_STEPS: usize = 4000;

/// A swept disc's coordinates of a point `p` (already moved back by the edge's image): the
/// position along the segment, and the disc's two coordinates `(a, b)`.
fn disc_coordinates(along: usize, offset: f64, height: f64, p: [f64; 3]) -> (f64, [f64; 2]) {
    let s = p[along];
    let e = if along == 0 {
        [s, offset, height]
    } else {
        [offset, s, height]
    };
    let q = group_product(e.map(|x| -x), p);
    (s, [q[1 - along], q[2]])
}

/// The first time in `[from, to]` at which `ray` is within the heights of the ball of
/// `radius` about `centre` (`|z| ≤ r + r²/4` seen from the centre: a unit-speed geodesic
/// from it climbs at most `1 + t/2`), in closed form ([`horizontal_exit`]); `None` where it
/// never is. No point of the ball lies outside them.
fn ball_slab_entry(
    ray: &NilRay<f64>,
    centre: [f64; 3],
    radius: f64,
    from: f64,
    to: f64,
) -> Option<f64> {
    let reach = radius + 0.25 * radius * radius;
    let at = flow(ray, from);
    let seen = NilRay {
        point: group_product(inverse(centre), at.point),
        velocity: at.velocity,
    };
    let z = seen.point[2];
    if z.abs() <= reach {
        return Some(from);
    }
    horizontal_exit(&seen, reach.copysign(z), to - from).map(|dt| from + dt)
}

/// The lattice element's inverse (the group's inverse is the negation).
fn inverse(g: [f64; 3]) -> [f64; 3] {
    g.map(|x| -x)
}

impl NilObject {
    /// The shape's gap at `p` (negative inside), its gradient in the left-invariant frame,
    /// and the most the gap changes per unit length along a geodesic through the cell.
    fn gap(&self, p: [f64; 3]) -> (f64, [f64; 3], f64) {
        match self.shape {
            NilShape::Ball(c) => {
                let (d, _) = crate::space::nil::shortest(c, p);
                (d - self.radius, ball_normal(c, p), 1.0)
            }
            NilShape::Fibre(b) => {
                let (dx, dy) = (p[0] - b[0], p[1] - b[1]);
                let d = dx.hypot(dy);
                let n = if d > 0.0 {
                    [dx / d, dy / d, 0.0]
                } else {
                    [1.0, 0.0, 0.0]
                };
                (d - self.radius, n, 1.0)
            }
            NilShape::Edge {
                image,
                along,
                offset,
                height,
            } => {
                let q = group_product(inverse(image), p);
                let (s, [a, b]) = disc_coordinates(along, offset, height, q);
                // Rates along a body velocity v: a changes by the across component, b by
                // v₃ ∓ v_along·(across − offset/2) (left translations keep the frame).
                let across = q[1 - along];
                let twist = across - 0.5 * offset;
                let (grad_a, grad_b) = if along == 0 {
                    ([0.0, 1.0, 0.0], [-twist, 0.0, 1.0])
                } else {
                    ([1.0, 0.0, 0.0], [0.0, twist, 1.0])
                };
                let rho = a.hypot(b);
                let end = s.abs() - 0.5;
                // Over a step of length ≤ the gap the twist changes by at most the gap (its
                // rate is the across speed, at most 1), so |b′| ≤ |v₃| + |v_along|(|twist| +
                // gap) and the gap's rate is at most √(1 + (|twist| + gap)²) over the step.
                let reach = twist.abs() + (rho - self.radius).max(end).max(0.0);
                let rate = (1.0 + reach * reach).sqrt();
                if end > rho - self.radius {
                    let mut n = [0.0; 3];
                    n[along] = s.signum();
                    (end, n, rate)
                } else {
                    let n = if rho > 0.0 {
                        [0, 1, 2].map(|i| (a * grad_a[i] + b * grad_b[i]) / rho)
                    } else {
                        [0.0, 0.0, 1.0]
                    };
                    (rho - self.radius, n, rate)
                }
            }
        }
    }

    /// The unit outward normal at a point of the surface, in the left-invariant frame.
    #[must_use]
    pub fn normal(&self, p: [f64; 3]) -> DVec3 {
        DVec3::from_array(self.gap(p).1).normalize_or(DVec3::Z)
    }

    /// The object's gap at `p`: how far outside by its own measure (a ball's and a fibre
    /// tube's distance less the radius, a swept disc's disc radius less its radius or how
    /// far past its end), negative inside.
    #[must_use]
    pub fn gap_at(&self, p: [f64; 3]) -> f64 {
        self.gap(p).0
    }

    /// Whether `p` lies in the object (its gap at most 0).
    #[must_use]
    pub fn contains(&self, p: [f64; 3]) -> bool {
        self.gap_at(p) <= 0.0
    }

    /// A lower bound on the distance from `p` to the object (0 inside, and near it: a ball's
    /// bound is root-free and loose).
    #[must_use]
    pub fn clearance(&self, p: [f64; 3]) -> f64 {
        if let NilShape::Ball(c) = self.shape {
            // The root-free floor of the distance.
            return (crate::space::nil::distance_floor(c, p) - self.radius).max(0.0);
        }
        let (g, _, rate) = self.gap(p);
        (g / rate).max(0.0)
    }

    /// The first length in `[0, t_max]` at which `ray` (a unit body velocity) meets the
    /// object; `None` for a miss or a graze.
    #[must_use]
    pub fn first_meeting(&self, ray: &NilRay<f64>, t_max: f64) -> Option<f64> {
        self.meeting(ray, t_max, true)
    }

    /// Whether `ray` meets the object within `t_max` (as [`NilObject::first_meeting`]
    /// says), without refining where: what a shadow ray needs.
    #[must_use]
    pub fn meets(&self, ray: &NilRay<f64>, t_max: f64) -> bool {
        self.meeting(ray, t_max, false).is_some()
    }

    /// The first meeting within `t_max`, refined to the last bit where `precise`; else any
    /// time found in the object.
    fn meeting(&self, ray: &NilRay<f64>, t_max: f64, precise: bool) -> Option<f64> {
        match self.shape {
            // Exact: where the shadow first comes within the radius of the fibre's foot.
            NilShape::Fibre(b) => {
                let (t_in, _, _) = shadow_within(ray, b, self.radius)?;
                return (t_in <= t_max).then_some(t_in);
            }
            // Only while the shadow is within the radius of the centre's: visit by visit.
            NilShape::Ball(c) => {
                let (mut t_in, mut t_out, period) = shadow_within(ray, [c[0], c[1]], self.radius)?;
                while t_in <= t_max {
                    let end = t_out.min(t_max);
                    if let Some(from) = ball_slab_entry(ray, c, self.radius, t_in, end) {
                        if !precise {
                            if ball_meets_between(ray, c, self.radius, from, end) {
                                return Some(from);
                            }
                        } else if let Some(t) = ball_hit_between(ray, c, self.radius, from, end) {
                            return Some(t);
                        }
                    }
                    if !period.is_finite() || t_out >= t_max {
                        return None;
                    }
                    t_in += period;
                    t_out += period;
                }
                return None;
            }
            NilShape::Edge { .. } => {}
        }
        let at = |t: f64| {
            let moved = flow(ray, t);
            let (g, n, rate) = self.gap(moved.point);
            let along =
                n[0] * moved.velocity[0] + n[1] * moved.velocity[1] + n[2] * moved.velocity[2];
            (g, along, rate)
        };
        let start = self.slab_entry(ray)?;
        if start > t_max {
            return None;
        }
        let (mut t, (mut g, mut slope, mut rate)) = (start, at(start));
        if g <= 0.0 {
            return Some(if start > 0.0 && precise {
                self.refine(ray, 0.0, start)
            } else {
                start
            });
        }
        let floor = 64.0 * f64::EPSILON * (1.0 + self.radius + t_max.min(1e6));
        for _ in 0..MAX_STEPS {
            crate::space::nil::count_safe_step();
            if slope < 0.0 {
                let guess = t - g / slope;
                if guess <= t_max && at(guess).0 <= 0.0 {
                    return Some(if precise {
                        self.refine(ray, t, guess)
                    } else {
                        guess
                    });
                }
            }
            if g < floor {
                return (slope < -floor.sqrt()).then_some(t);
            }
            let before = t;
            t += g / rate;
            if t > t_max {
                return None;
            }
            (g, slope, rate) = at(t);
            if g <= 0.0 {
                return Some(if precise {
                    self.refine(ray, before, t)
                } else {
                    t
                });
            }
        }
        None
    }

    /// Where the ray first comes into the vertical slab that holds a swept disc (its points
    /// are within `r` across the edge's plane: `|y − γ_y − y₀| ≤ r` for an edge along `x`),
    /// in closed form ([`crate::space::nil::vertical_exit`]): no meeting lies before it.
    /// 0 for a start in the slab, and for the other shapes; `None` where the ray never
    /// comes into it.
    fn slab_entry(&self, ray: &NilRay<f64>) -> Option<f64> {
        let NilShape::Edge {
            image,
            along,
            offset,
            ..
        } = self.shape
        else {
            return Some(0.0);
        };
        let across = 1 - along;
        let centre = image[across] + offset;
        let (lo, hi) = (centre - self.radius, centre + self.radius);
        let x = ray.point[across];
        let mut n = [0.0; 2];
        if x < lo {
            n[across] = 1.0;
            crate::space::nil::vertical_exit(ray, n, lo)
        } else if x > hi {
            n[across] = -1.0;
            crate::space::nil::vertical_exit(ray, n, -hi)
        } else {
            Some(0.0)
        }
    }

    /// The root of the gap between `lo` (outside, no root before it) and `hi` (inside).
    fn refine(&self, ray: &NilRay<f64>, lo: f64, hi: f64) -> f64 {
        let (mut lo, mut hi) = (lo, hi);
        for _ in 0..200 {
            crate::space::nil::count_root_iteration();
            let mid = 0.5 * (lo + hi);
            if !(mid > lo && mid < hi) {
                break;
            }
            if self.gap(flow(ray, mid).point).0 > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }
}
