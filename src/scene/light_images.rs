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
    /// The lamp's radius is not a finite number of at least [`MIN_LAMP_RADIUS`].
    #[error(
        "the lamp's radius must be a finite number of at least 1e-150, got {0} (a lamp's light \
         at its own place is 1/r², which must be a number f64 can hold)"
    )]
    Radius(f64),
    /// The light summed is larger than f64 can hold.
    #[error(
        "the light's {part} is larger than f64 can hold (1.8e308): with a fog distance of \
         {fog} light is hardly absorbed, and the sum over the lamp's images grows without \
         bound as the fog thins; give a shorter --fog"
    )]
    Overflow {
        /// Which part overflowed: the exact sum, the tail or its bound.
        part: &'static str,
        /// The fog distance.
        fog: f64,
    },
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

/// The smallest lamp radius: `1/S(r)²` at the lamp must be a number f64 holds.
pub const MIN_LAMP_RADIUS: f64 = 1e-150;

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
    if !(radius >= MIN_LAMP_RADIUS && radius.is_finite()) {
        return Err(FluenceError::Radius(radius));
    }
    let g = space.geometry;
    let floor = g.s(radius.min(0.5 * std::f64::consts::PI));
    let s2 = |d: f64| g.s(d).abs().max(floor).powi(2);
    let overflow = |part| FluenceError::Overflow { part, fog };
    if g == Geometry::Spherical {
        let elements =
            elements_near(space, f64::INFINITY, MAX_IMAGES).ok_or(FluenceError::TooMany {
                reach: std::f64::consts::PI,
                limit: MAX_IMAGES,
            })?;
        // 1 − e^(−2π/λ), kept where λ is so long that the exponential rounds to 1.
        let turns = -(-std::f64::consts::TAU / fog).exp_m1();
        let exact: f64 = elements
            .iter()
            .map(|h| {
                let d = g.distance(at, *h * lamp);
                ((-d / fog).exp() + (-(std::f64::consts::TAU - d) / fog).exp()) / (turns * s2(d))
            })
            .sum();
        if !exact.is_finite() {
            return Err(overflow("sum over the images"));
        }
        return Ok(Fluence {
            images: elements.len(),
            exact,
            tail: 0.0,
            bound: 0.0,
            reach: std::f64::consts::PI,
        });
    }
    let searched = reach + g.distance(DVec4::W, at);
    let near = lamp_images(space, lamp, searched, MAX_IMAGES).ok_or(FluenceError::TooMany {
        reach,
        limit: MAX_IMAGES,
    })?;
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
    if !exact.is_finite() {
        return Err(overflow("sum over the images"));
    }
    let vol = volume(space);
    // 4πλ e^(−R/λ) / vol, through its logarithm: λ/vol alone may overflow where the
    // whole does not.
    let tail = ((4.0 * std::f64::consts::PI).ln() + fog.ln() - vol.ln() - reach / fog).exp();
    if !tail.is_finite() {
        return Err(overflow("mean beyond the reach"));
    }
    let rho = lamp_cell_reach(space, lamp);
    let packing = packing_radius(g, lamp, &near, searched);
    let (lo, hi) = tail_range(
        g,
        reach,
        Counts { rho, vol, packing },
        images as f64,
        fog,
        floor,
    );
    // The integrals are Simpson's rule to about 1e-9 of their size: a millionth of it
    // keeps the bound a bound.
    let bound = (hi - tail).max(tail - lo).max(0.0) + 1e-6 * (lo.abs() + hi.abs());
    if !bound.is_finite() {
        return Err(overflow("error bound"));
    }
    Ok(Fluence {
        images,
        exact,
        tail,
        bound,
        reach,
    })
}

/// The fluence with the reach chosen so that the stated bound is at most `fraction` of the
/// total where the image limit allows: it starts where about 200 images lie (`V(R) = 200
/// vol(M)`, at most eight fog distances) and lengthens the reach by the fog distances the
/// bound still has to fall (it falls like `e^(−R/λ)`), no farther than the reach whose
/// images [`MAX_IMAGES`] can hold. The second value says whether the bound came within
/// `fraction`; where it did not, the longest reach within the limit is returned (in H³ the
/// count's uncertainty grows with the reach as fast as the images do, and a tight bound
/// would need far more of them).
pub fn fluence_within(
    space: &Space,
    lamp: DVec4,
    at: DVec4,
    fog: f64,
    radius: f64,
    fraction: f64,
) -> Result<(Fluence, bool), FluenceError> {
    if !(fog > 0.0 && fog.is_finite()) {
        return Err(FluenceError::Fog(fog));
    }
    let g = space.geometry;
    let vol = volume(space);
    let longest = (8.0 * fog).min(f64::MAX);
    let start = radius_holding(g, 200.0 * vol, 0.0).min(longest);
    // The walk to the images keeps the cells whose centres lie within the reach, the
    // point's distance from the centre and the circumradius: past the reach whose ball of
    // that size holds most of the limit's cells, it would give up.
    let pad = g.distance(DVec4::W, at) + circumradius(space);
    let cap = radius_holding(g, 0.8 * MAX_IMAGES as f64 * vol, pad).max(start);
    let mut best = fluence(space, lamp, at, fog, start.max(f64::MIN_POSITIVE), radius)?;
    for _ in 0..4 {
        let target = fraction * best.total();
        if best.bound <= target || best.reach >= cap {
            break;
        }
        let longer = (best.reach + fog * ((best.bound / target).ln() + 0.5)).min(cap);
        match fluence(space, lamp, at, fog, longer, radius) {
            Ok(f) => best = f,
            // More images than the estimate: the longest reach within the limit, by a few
            // bisections.
            Err(FluenceError::TooMany { .. }) => {
                let (mut ok, mut bad) = (best.reach, longer);
                for _ in 0..4 {
                    let mid = 0.5 * (ok + bad);
                    match fluence(space, lamp, at, fog, mid, radius) {
                        Ok(f) => {
                            ok = mid;
                            best = f;
                        }
                        Err(FluenceError::TooMany { .. }) => bad = mid,
                        Err(e) => return Err(e),
                    }
                }
                break;
            }
            Err(e) => return Err(e),
        }
    }
    let within = best.bound <= fraction * best.total();
    Ok((best, within))
}

/// The radius `R` whose ball of radius `R + pad` has volume `want` (0 if even the ball of
/// radius `pad` has more): bracketed by doubling, since a cell may be of any size, then
/// bisected.
fn radius_holding(g: Geometry, want: f64, pad: f64) -> f64 {
    if ball_volume(g, pad) >= want {
        return 0.0;
    }
    let mut hi = 1.0f64;
    while ball_volume(g, hi + pad) < want && hi < f64::MAX / 4.0 {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if ball_volume(g, mid + pad) < want {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// How far the lamp lies from the farthest point of the cell: the farthest vertex (the
/// distance from a point is convex along geodesics, so its largest value on the convex cell
/// is at a vertex), or, for a cell without vertices, the lamp's distance from the centre
/// plus the circumradius.
fn lamp_cell_reach(space: &Space, lamp: DVec4) -> f64 {
    let g = space.geometry;
    if space.vertices.is_empty() {
        return g.distance(lamp, DVec4::W) + circumradius(space);
    }
    (0..space.vertices.len())
        .map(|v| g.distance(lamp, space.vertex_point(v)))
        .fold(0.0, f64::max)
}

/// Half the distance from the lamp to its nearest other image: the balls of that radius
/// about the images are disjoint. Every image within `searched` of the centre is in
/// `images`, so one not found is farther than `searched − d(centre, lamp)` from the lamp,
/// and the radius never exceeds half of that.
fn packing_radius(g: Geometry, lamp: DVec4, images: &[(DVec4, f64)], searched: f64) -> f64 {
    let unseen = searched - g.distance(DVec4::W, lamp);
    images
        .iter()
        .map(|(q, _)| g.distance(lamp, *q))
        .filter(|&d| d > 1e-9)
        .fold(unseen, f64::min)
        .max(0.0)
        * 0.5
}

/// What bounds the count `N(r)` of images within `r` of the point: `ρ`, how far the lamp
/// lies from its cell's farthest point (`V(r−ρ)/vol ≤ N(r) ≤ V(r+ρ)/vol`), and the packing
/// radius `p` (disjoint balls of radius `p` about the images within `r` lie in the ball of
/// radius `r + p`: `N(r) ≤ V(r+p)/V(p)`, the tighter in H³, where `e^(2ρ)` is large).
#[derive(Clone, Copy, Debug)]
struct Counts {
    rho: f64,
    vol: f64,
    packing: f64,
}

impl Counts {
    /// `ln` of the lower and upper counts at `r`.
    fn ln_range(&self, g: Geometry, r: f64) -> (f64, f64) {
        let ln_vol = self.vol.ln();
        let lo = ln_ball_volume(g, r - self.rho) - ln_vol;
        let mut hi = ln_ball_volume(g, r + self.rho) - ln_vol;
        if self.packing > 0.0 {
            hi = hi.min(ln_ball_volume(g, r + self.packing) - ln_ball_volume(g, self.packing));
        }
        (lo, hi)
    }
}

/// `ln S(r)` for `r > 0` (E³: `ln r`, H³: `ln sinh r`), without overflow for large `r`.
fn ln_s(g: Geometry, r: f64) -> f64 {
    match g {
        Geometry::Euclidean => r.ln(),
        Geometry::Spherical => r.sin().ln(),
        Geometry::Hyperbolic if r > 20.0 => {
            r - std::f64::consts::LN_2 + (-(-2.0 * r).exp()).ln_1p()
        }
        Geometry::Hyperbolic => r.sinh().ln(),
    }
}

/// `ln V(r)`, the logarithm of a ball's volume ([`ball_volume`]), without overflow for large
/// `r`; `−∞` for `r ≤ 0`.
fn ln_ball_volume(g: Geometry, r: f64) -> f64 {
    if !(r > 0.0) {
        return f64::NEG_INFINITY;
    }
    match g {
        // π (sinh 2r − 2r) = (π/2) e^(2r) (1 − e^(−4r) − 4r e^(−2r)).
        Geometry::Hyperbolic if r > 20.0 => {
            (0.5 * std::f64::consts::PI).ln() + 2.0 * r + (-4.0 * r * (-2.0 * r).exp()).ln_1p()
        }
        _ => ball_volume(g, r).ln(),
    }
}

/// The range of the true tail beyond `reach`: `−f(R) N(R) + ∫_R^∞ N (−f′) dr` with `N`
/// between the [`Counts`] (`V(r − ρ)/vol` below, the smaller of `V(r + ρ)/vol` and
/// `V(r + p)/V(p)` above), `f` the falloff `e^(−r/λ) / max(S(r), s₀)²` (`s₀ = S(r₀)` the
/// lamp's floor, below which `f` falls only with the fog: `−f′ = f/λ` there).
///
/// The integrands are products of a count growing like `r³` or `e^(2r)` and a falloff
/// shrinking like `e^(−2r − r/λ)`: each is taken through its logarithm, so neither overflows
/// where the product does not. Simpson's rule, on panels that start at a fortieth of the
/// smaller of `λ` and `ρ` and grow by 5 % each, out to where the integrand has fallen by
/// e⁻⁶⁰ (sixty fog distances): fine near the reach, where the integrand changes on the
/// scale of `ρ`, and few far out, where it changes on the scale of `λ`.
fn tail_range(
    g: Geometry,
    reach: f64,
    counts: Counts,
    counted: f64,
    fog: f64,
    floor: f64,
) -> (f64, f64) {
    let ln_floor = floor.ln();
    // ln f and −f′/f.
    let ln_f = |r: f64| -r / fog - 2.0 * ln_s(g, r).max(ln_floor);
    let rate = |r: f64| {
        let above = ln_s(g, r) > ln_floor;
        let cot = match g {
            Geometry::Euclidean => 1.0 / r,
            _ => 1.0 / r.tanh(),
        };
        1.0 / fog + if above { 2.0 * cot } else { 0.0 }
    };
    let term = |ln_n: f64, r: f64| {
        if ln_n == f64::NEG_INFINITY {
            0.0
        } else {
            (ln_n + ln_f(r)).exp() * rate(r)
        }
    };
    let integrands = |r: f64| {
        let (lo, hi) = counts.ln_range(g, r);
        (term(lo, r), term(hi, r))
    };
    let end = reach + 60.0 * fog;
    let mut width = (fog.min(counts.rho.max(1e-3)) / 40.0).max(reach * f64::EPSILON);
    let (mut lo_sum, mut hi_sum) = (0.0, 0.0);
    let mut a = reach;
    // Each panel's end is the next one's start: evaluated once.
    let (mut la, mut ha) = integrands(a);
    while a < end {
        let b = (a + width).min(end);
        let ((lm, hm), (lb, hb)) = (integrands(0.5 * (a + b)), integrands(b));
        lo_sum += (b - a) / 6.0 * (la + 4.0 * lm + lb);
        hi_sum += (b - a) / 6.0 * (ha + 4.0 * hm + hb);
        (a, la, ha) = (b, lb, hb);
        width *= 1.05;
    }
    let start = -(ln_f(reach)).exp() * counted;
    (start + lo_sum, start + hi_sum)
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
