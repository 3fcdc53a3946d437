//! How far a walk through the cell of `UT Σ`, in some precision, ends from the exact walk:
//! the walked end against the double-double walk from the same start (as the precision
//! rounds it), and the **conditioning limit** — how far the exact walk itself moves when its
//! start moves by one rounding of that precision — which no method in that precision can
//! beat. Along a hypercycle both grow like `e^{ωt}`, so their ratio is the measure.

use super::flow::{Sl2rRay, on_model};
use super::space::UnitTangentSpace;
use super::walk::Sl2rWalker;
use crate::geometry::{DdVec4, DoubleDouble, Real, Vector4};
use crate::random::SplitMix64;
use crate::space::walk::{CellWalk, Limit};

/// A walk's error and its conditioning limit, both as the largest entry difference of the
/// end's `p`, `e` and velocity (each relative to `1 + |entry|`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkError {
    /// The walk in the precision against the double-double walk from the same start.
    pub error: f64,
    /// The double-double walk's own spread under one rounding of the start (the largest of
    /// four random perturbations of each entry by its precision's half unit).
    pub limit: f64,
    /// The crossings walked.
    pub crossings: usize,
}

/// The end of `start` walked `distance` by `walker` (precision `V`), as an `f64` ray.
fn walked<V: Vector4>(
    walker: &Sl2rWalker<V>,
    start: &Sl2rRay<f64>,
    distance: f64,
) -> (Sl2rRay<f64>, usize) {
    let r = Sl2rRay {
        frame: start.frame.map(|c| c.map(V::Real::from_f64)),
        velocity: start.velocity.map(V::Real::from_f64),
    };
    let mut crossings = 0;
    let (end, _) = walker.walk(
        Sl2rWalker::<V>::ray_of(&r),
        Limit::Distance(distance),
        |_| {
            crossings += 1;
            true
        },
    );
    let e = Sl2rWalker::<V>::sl2r_ray(&end);
    (
        Sl2rRay {
            frame: e.frame.map(|c| c.map(|x| x.to_f64())),
            velocity: e.velocity.map(|x| x.to_f64()),
        },
        crossings,
    )
}

/// The largest entry difference of two rays' `p`, `e` and velocity, relative to `1 + |b|`.
fn gap(a: &Sl2rRay<f64>, b: &Sl2rRay<f64>) -> f64 {
    let entries = |r: &Sl2rRay<f64>| {
        let mut v = r.frame[2].to_vec();
        v.extend(r.frame[0]);
        v.extend(r.velocity);
        v
    };
    entries(a)
        .iter()
        .zip(entries(b))
        .map(|(x, y)| (x - y).abs() / (1.0 + y.abs()))
        .fold(0.0, f64::max)
}

/// `start` rounded to the precision of `V` (its entries as `V` holds them).
fn rounded<V: Vector4>(start: &Sl2rRay<f64>) -> Sl2rRay<f64> {
    let round = |x: f64| V::Real::from_f64(x).to_f64();
    Sl2rRay {
        frame: start.frame.map(|c| c.map(round)),
        velocity: start.velocity.map(round),
    }
}

/// The error of the walk of `start` over `distance` in the precision `V`, and the
/// conditioning limit at that precision.
#[must_use]
pub fn walk_error<V: Vector4>(
    space: &UnitTangentSpace,
    start: &Sl2rRay<f64>,
    distance: f64,
) -> WalkError {
    let start = rounded::<V>(start);
    let (ours, crossings) = walked(&Sl2rWalker::<V>::new(space), &start, distance);
    let reference = Sl2rWalker::<DdVec4>::new(space);
    let (exact, _) = walked(&reference, &start, distance);
    let eps = V::Real::EPSILON.to_f64();
    // Seeded by the start, so a measurement is repeatable.
    let mut rng = SplitMix64(start.frame[2][0].to_bits() ^ start.velocity[2].to_bits());
    let mut limit = 0.0_f64;
    for _ in 0..4 {
        let mut nudge = |x: f64| x * (1.0 + 0.5 * eps * (2.0 * rng.unit() - 1.0));
        let moved = Sl2rRay {
            frame: start.frame.map(|c| c.map(&mut nudge)),
            velocity: start.velocity.map(&mut nudge),
        };
        let moved = on_dd_model(&moved);
        let (end, _) = walked(&reference, &moved, distance);
        limit = limit.max(gap(&end, &exact));
    }
    WalkError {
        error: gap(&ours, &exact),
        limit,
        crossings,
    }
}

/// A ray put back on the model in double-double (a nudged start is off it by ε).
fn on_dd_model(r: &Sl2rRay<f64>) -> Sl2rRay<f64> {
    let d = Sl2rRay {
        frame: r.frame.map(|c| c.map(DoubleDouble::new)),
        velocity: r.velocity.map(DoubleDouble::new),
    };
    let m = on_model(&d);
    Sl2rRay {
        frame: m.frame.map(|c| c.map(|x| x.to_f64())),
        velocity: m.velocity.map(|x| x.to_f64()),
    }
}

/// A random ray of the cell: the base point within 0.9 inradii of the centre, `e` and the
/// direction at random (for the accuracy tables).
#[must_use]
pub fn random_start(space: &UnitTangentSpace, rng: &mut SplitMix64) -> Sl2rRay<f64> {
    let r = 0.9 * space.inradius() * rng.unit().sqrt();
    let (a, b) = (
        std::f64::consts::TAU * rng.unit(),
        std::f64::consts::TAU * rng.unit(),
    );
    let (ch, sh) = (r.cosh(), r.sinh());
    let (c, s) = (a.cos(), a.sin());
    let boost = [
        [1.0 + (ch - 1.0) * c * c, (ch - 1.0) * c * s, sh * c],
        [(ch - 1.0) * c * s, 1.0 + (ch - 1.0) * s * s, sh * s],
        [sh * c, sh * s, ch],
    ];
    let e = [b.cos(), b.sin(), 0.0];
    let origin = Sl2rRay {
        frame: [e, [-e[1], e[0], 0.0], [0.0, 0.0, 1.0]],
        velocity: rng.direction().to_array(),
    };
    on_model(&super::flow::moved_by(&boost, &origin))
}
