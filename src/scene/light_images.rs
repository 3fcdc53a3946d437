//! The light a point of a closed manifold receives from a point lamp along **every**
//! geodesic joining them: through every image `g·L` of the lamp in the universal cover
//! (`g` in the deck group), each dimmed by the falloff `1/S(d)²` and by the fog's
//! absorption `e^(−d/λ)` along its path.
//!
//! The **fluence** at `x` of a unit lamp at `L` is
//!
//! ```text
//! Φ(x) = Σ_g e^(−d_g/λ) / max(S(d_g), S(r₀))²        d_g = d(x, g·L)
//! ```
//!
//! (no Lambert factor; `r₀` the lamp's radius, which keeps a lamp finite at its own place
//! and, on S³, where its light focuses again). It is summed in two parts:
//!
//! - **Exactly** over the images within the reach `R` (the deck group's elements whose cell
//!   comes near enough, [`lamp_images`], then those images nearer than `R`). In a
//!   spherical space every image is summed: the group is finite, and each image is
//!   reached along the short arc `d`, the long one `2π − d`, and each of those after any number of whole turns round the great circle: the turns sum to
//!   `(e^(−d/λ) + e^(−(2π−d)/λ)) / (1 − e^(−2π/λ))`, so nothing is left over.
//! - **The tail** beyond `R` in E³ and H³, by its mean: images spread through the cover with
//!   density `1/vol(M)`, and a sphere of radius `r` has area `4π S(r)²`, which cancels the
//!   falloff, so each shell `dr` adds `4π e^(−r/λ) dr / vol(M)` and the tail is
//!   `4πλ e^(−R/λ) / vol(M)`. (Without fog the sum diverges in both: every shell adds the
//!   same.)
//!
//! **The tail's error bound.** Let `N(r)` count the images within `r` of `x` and `ρ` bound
//! the distance from the lamp to any point of the cell. Every point of the ball `B(x, r−ρ)`
//! lies in some image cell `g·D`, whose lamp is within `ρ` of it, hence within `r` of `x`;
//! and the image cells of the lamps within `r` are disjoint, of volume `vol(M)`, inside
//! `B(x, r+ρ)`. So `V(r−ρ)/vol(M) ≤ N(r) ≤ V(r+ρ)/vol(M)` with `V` a ball's volume. The
//! true tail is `∫_R^∞ f dN = −f(R) N(R) + ∫_R^∞ N (−f′) dr` (`f` the falloff, decreasing,
//! `N(R)` known exactly from the sum), so it lies between the integrals with those two
//! counts; `bound` is the larger distance from the mean to either (integrated numerically).

use crate::geometry::Geometry;
use crate::space::Space;
use crate::space::invariants::{circumradius, elements_near, volume};
use glam::DVec4;

/// The fluence at a point from a unit lamp ([the module's description](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fluence {
    /// How many images were summed exactly.
    pub images: usize,
    /// Their sum.
    pub exact: f64,
    /// The mean-field rest beyond the reach (0 in a spherical space).
    pub tail: f64,
    /// The stated error of `tail` (0 in a spherical space).
    pub bound: f64,
    /// The reach the images were summed within (π in a spherical space: all of them).
    pub reach: f64,
}

impl Fluence {
    /// The whole fluence: the exact sum and the tail.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.exact + self.tail
    }
}

/// Why a fluence cannot be summed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FluenceError {
    /// The fog distance is not a positive number (infinite fog is no fog: the sum
    /// diverges in E³ and H³).
    #[error(
        "the fog distance must be a positive, finite number, got {0} (without fog the sum over \
         a flat or hyperbolic space's images diverges: every shell of images adds the same)"
    )]
    Fog(f64),
    /// The reach is not a positive number.
    #[error("the reach must be a positive, finite number, got {0}")]
    Reach(f64),
    /// The lamp's radius is not a positive number.
    #[error("the lamp's radius must be a positive, finite number, got {0}")]
    Radius(f64),
    /// More group elements than the limit come within the reach.
    #[error(
        "more than {limit} images of the lamp lie within the reach {reach}: ask for a smaller \
         reach (the tail past it is summed by its mean, with its error bound)"
    )]
    TooMany {
        /// The reach asked for.
        reach: f64,
        /// The limit.
        limit: usize,
    },
}

/// The most group elements summed over.
pub const MAX_IMAGES: usize = 200_000;

/// The volume of a geodesic ball of radius `r` (E³, H³, S³ up to π).
#[must_use]
pub fn ball_volume(g: Geometry, r: f64) -> f64 {
    use std::f64::consts::PI;
    let r = r.max(0.0);
    match g {
        Geometry::Euclidean => 4.0 / 3.0 * PI * r.powi(3),
        Geometry::Hyperbolic => PI * ((2.0 * r).sinh() - 2.0 * r),
        Geometry::Spherical => {
            let r = r.min(PI);
            PI * (2.0 * r - (2.0 * r).sin())
        }
    }
}

/// The fluence at `at` from a unit lamp at `lamp` (both model points of the cell), through
/// every image within `reach` summed exactly and the rest by its mean, in fog of distance
/// `fog`, the lamp of radius `radius`.
pub fn fluence(
    space: &Space,
    lamp: DVec4,
    at: DVec4,
    fog: f64,
    reach: f64,
    radius: f64,
) -> Result<Fluence, FluenceError> {
    if !(fog > 0.0 && fog.is_finite()) {
        return Err(FluenceError::Fog(fog));
    }
    if !(reach > 0.0 && reach.is_finite()) {
        return Err(FluenceError::Reach(reach));
    }
    if !(radius > 0.0 && radius.is_finite()) {
        return Err(FluenceError::Radius(radius));
    }
    let g = space.geometry;
    let s2 = |d: f64| {
        g.s(d)
            .abs()
            .max(g.s(radius.min(0.5 * std::f64::consts::PI)))
            .powi(2)
    };
    if g == Geometry::Spherical {
        let elements =
            elements_near(space, f64::INFINITY, MAX_IMAGES).ok_or(FluenceError::TooMany {
                reach: std::f64::consts::PI,
                limit: MAX_IMAGES,
            })?;
        let turns = 1.0 - (-std::f64::consts::TAU / fog).exp();
        let exact = elements
            .iter()
            .map(|h| {
                let d = g.distance(at, *h * lamp);
                ((-d / fog).exp() + (-(std::f64::consts::TAU - d) / fog).exp()) / (turns * s2(d))
            })
            .sum();
        return Ok(Fluence {
            images: elements.len(),
            exact,
            tail: 0.0,
            bound: 0.0,
            reach: std::f64::consts::PI,
        });
    }
    let near = lamp_images(space, lamp, reach + g.distance(DVec4::W, at), MAX_IMAGES).ok_or(
        FluenceError::TooMany {
            reach,
            limit: MAX_IMAGES,
        },
    )?;
    let f = |d: f64| (-d / fog).exp() / s2(d);
    let mut images = 0usize;
    let mut exact = 0.0;
    for (q, _) in &near {
        let d = g.distance(at, *q);
        if d <= reach {
            images += 1;
            exact += f(d);
        }
    }
    let vol = volume(space);
    let tail = 4.0 * std::f64::consts::PI * fog * (-reach / fog).exp() / vol;
    let rho = g.distance(lamp, DVec4::W) + circumradius(space);
    let (lo, hi) = tail_range(g, reach, rho, vol, images as f64, fog, &f);
    let bound = (hi - tail).max(tail - lo).max(0.0);
    Ok(Fluence {
        images,
        exact,
        tail,
        bound,
        reach,
    })
}

/// The range of the true tail beyond `reach`: `−f(R) N(R) + ∫_R^∞ N (−f′) dr` with `N`
/// between `V(r ∓ ρ)/vol`, integrated by Simpson's rule in steps of a fortieth of the fog
/// distance (or of `ρ`, if smaller) out to where the integrand has fallen by e⁻⁶⁰.
fn tail_range(
    g: Geometry,
    reach: f64,
    rho: f64,
    vol: f64,
    counted: f64,
    fog: f64,
    f: &impl Fn(f64) -> f64,
) -> (f64, f64) {
    // −f′ = f · (1/λ + 2 C/S), C/S = 1/r (E³) or coth r (H³).
    let minus_df = |r: f64| {
        let cot = match g {
            Geometry::Euclidean => 1.0 / r,
            _ => 1.0 / r.tanh(),
        };
        f(r) * (1.0 / fog + 2.0 * cot)
    };
    // N's bounds grow like r³ (E³) or e^(2r) (H³), −f′ falls like e^(−r/λ) r⁻² or
    // e^(−2r − r/λ): sixty fog distances leave e⁻⁶⁰ of the integrand.
    let end = reach + 60.0 * fog;
    let step = (fog / 40.0).min(rho.max(1e-3));
    let n = (((end - reach) / step).ceil() as usize).clamp(2, 2_000_000) & !1;
    let h = (end - reach) / n as f64;
    let integrate = |count: &dyn Fn(f64) -> f64| {
        let at = |k: usize| {
            let r = reach + h * k as f64;
            count(r) * minus_df(r)
        };
        let mut sum = at(0) + at(n);
        for k in 1..n {
            sum += if k % 2 == 1 { 4.0 } else { 2.0 } * at(k);
        }
        sum * h / 3.0
    };
    let start = -f(reach) * counted;
    let lo = start + integrate(&|r| ball_volume(g, r - rho) / vol);
    let hi = start + integrate(&|r| ball_volume(g, r + rho) / vol);
    (lo, hi)
}

/// The images `g·L` of a lamp at `lamp` (a model point of the cell) that lie within `radius`
/// of the model's origin, nearest first, each with its distance from the origin; at most
/// `limit` group elements are visited (`None` if more are needed). In a spherical space
/// every image (the group is finite; `radius` is not used).
///
/// The walk goes from cell to neighbouring cell through the face pairings and keeps the
/// cells whose centre is within `radius + ρ` of the origin (`ρ` the circumradius): a cell
/// that meets the ball of `radius` has its centre that near, and the cells that a geodesic
/// between two points of the ball passes through all meet the ball too (it is convex; a
/// geodesic moved off the edges and vertices crosses faces only), so none is missed.
#[must_use]
pub fn lamp_images(
    space: &Space,
    lamp: DVec4,
    radius: f64,
    limit: usize,
) -> Option<Vec<(DVec4, f64)>> {
    let g = space.geometry;
    let origin = crate::geometry::ORIGIN;
    let elements = if g == Geometry::Spherical {
        elements_near(space, f64::INFINITY, limit)?
    } else {
        let rho = circumradius(space);
        let keep = radius + rho + 1e-9;
        let generators: Vec<glam::DMat4> = space.faces.iter().map(|f| f.pairing).collect();
        let mut seen = crate::space::orbit::OrbitPoints::new(g, 1e-5);
        seen.push(origin);
        let mut out = vec![glam::DMat4::IDENTITY];
        let mut queue = std::collections::VecDeque::from([glam::DMat4::IDENTITY]);
        while let Some(m) = queue.pop_front() {
            for generator in &generators {
                let next = m * *generator;
                let centre = next * origin;
                if !(g.distance(origin, centre) <= keep) || !seen.insert(centre) {
                    continue;
                }
                out.push(next);
                if out.len() > limit {
                    return None;
                }
                queue.push_back(next);
            }
        }
        out
    };
    let mut images: Vec<(DVec4, f64)> = elements
        .iter()
        .map(|h| {
            // Not `project_point`: in S³ it takes a point to the hemisphere w > 0 (a cell's
            // chart), and −1 in the group would fold each image onto its antipode's.
            let q = *h * lamp;
            let q = match g {
                Geometry::Spherical => q / q.length(),
                _ => g.project_point(q),
            };
            (q, g.distance(origin, q))
        })
        .filter(|(_, d)| g == Geometry::Spherical || *d <= radius)
        .collect();
    images.sort_by(|a, b| a.1.total_cmp(&b.1));
    Some(images)
}
