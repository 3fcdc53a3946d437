//! The lamp of a Nil scene, lit along the shortest geodesic to each of its images.
//!
//! A point `x` gets light from an image `q` of the lamp along the shortest geodesic from `x`
//! to `q` ([`crate::space::nil::shortest`], the inverse of the exponential map): it leaves
//! `x` along its start velocity `l`, has length `r`, and brings
//!
//! ```text
//! max(0, ⟨n, l⟩) · e^(−r/λ) / max(A(r, c), ε²)
//! ```
//!
//! where `A` is the area, per unit solid angle at the lamp, of the geodesic sphere of
//! radius `r` about it ([`area_density`]): the exponential map's Jacobian in polar
//! coordinates, held from below at its flat value `ε²` at the lamp's size `ε`
//! ([`NilScene::near_light`]); the scene's power scales the sum. A geodesic's vertical velocity `c` is constant along it (and its reverse
//! has `−c`, which `A` does not see), so `A` is read from the geodesic at `x`. The images
//! beyond the reach add their mean, `¼ · 4πλ e^(−R/λ)/vol(M)` (the sphere's area cancels
//! the falloff, so each shell adds the same, as in the other families).

use super::NilScene;
use crate::scene::lighting::{LampImages, LightPaths, Lighting, SHADOW_OFFSET, open_tail_fluence};
use crate::space::nil::{NilRay, NilSpace, distance, flow, group_product, shortest};
use glam::DVec3;

/// Below this `|ct|` the density's `(2(1 − cos s) − s sin s)/s⁴` is summed as a series.
const DENSITY_SERIES_BELOW: f64 = 0.05;

/// The area per unit solid angle of Nil's geodesic sphere of radius `r`, at the end of a
/// geodesic of vertical velocity `c` (`|c| ≤ 1`): with `s = c r`,
///
/// ```text
/// A(r, c) = r² · sin(s)/s + r⁴ · (2(1 − cos s) − s sin s)/s⁴,
/// ```
///
/// the absolute value of the determinant of the exponential map's derivative in polar
/// coordinates (`(r, θ, φ) ↦ exp(r·u(θ, φ))`, divided by `sin θ`). It is `r²` near the
/// centre and up the fibre (`c = ±1` gives `r² sin r / r` plus a term of order `r⁴`), `r² +
/// r⁴/12` along horizontal geodesics, and it vanishes where the geodesics from the centre
/// first meet again (`tan(s/2) = (1 − c²)s/2`, past `s = 2π`): callers bound it from below.
#[must_use]
pub fn area_density(r: f64, c: f64) -> f64 {
    let s = c * r;
    let sinc = if s.abs() < 1e-4 {
        1.0 - s * s / 6.0
    } else {
        s.sin() / s
    };
    let p = if s.abs() < DENSITY_SERIES_BELOW {
        let s2 = s * s;
        1.0 / 12.0 - s2 / 180.0 + s2 * s2 / 6720.0
    } else {
        let s2 = s * s;
        (2.0 * (1.0 - s.cos()) - s * s.sin()) / (s2 * s2)
    };
    (r * r * sinc + r.powi(4) * p).abs()
}

/// The lamp's images (chart points) within `reach + ρ` of the box's centre (`ρ` bounds the
/// distance from the centre to any point of the box).
pub type NilLamp = LampImages<[f64; 3]>;

/// A bound on the distance from the box's centre to its points: the horizontal straight
/// line to `(x, y, 0)` (a geodesic of length `√(x² + y²)`) then the fibre, `√½ + h`.
#[must_use]
pub fn box_radius(space: &NilSpace) -> f64 {
    0.5f64.sqrt() + space.half_height()
}

/// The reach of `lighting` in a Nil space: its inradii times the box's inradius (the
/// smaller of ½ and the half height).
#[must_use]
pub fn reach(space: &NilSpace, lighting: &Lighting) -> f64 {
    lighting.reach_inradii * space.half_height().min(0.5)
}

impl NilLamp {
    /// The images of the lamp at `light` within `lighting`'s reach (none for
    /// [`LightPaths::Nearest`]).
    #[must_use]
    pub fn new(space: &NilSpace, light: [f64; 3], lighting: &Lighting) -> Self {
        Self::searched(lighting, reach(space, lighting), space.volume(), |r| {
            lamp_images(space, light, r)
        })
    }
}

/// The most lattice points [`lamp_images`] looks at.
const MAX_CANDIDATES: f64 = 2e6;

/// The images `γ·lamp` (`γ ∈ Γ_K`) within `reach + ρ` of the centre ([`box_radius`]),
/// nearest first, and the reach they cover from every point of the box: shortened to what
/// the nearest [`crate::scene::lighting::MAX_LAMP_IMAGES`] cover where more lie within it,
/// and where the reach asks to look at more than two million lattice points.
///
/// An element is `A^p B^q C^m = (p, q, pq/2 + m/K)`. A point at distance `R` from the
/// origin has `|x|, |y| ≤ R` and `|z| ≤ R + R²/4` (the chart's vertical speed is at most
/// `1 + t/2` at time `t`), which bounds `p`, `q` and `m`.
#[must_use]
pub fn lamp_images(space: &NilSpace, lamp: [f64; 3], reach: f64) -> (Vec<[f64; 3]>, f64) {
    let rho = box_radius(space);
    let k = f64::from(space.k());
    let offset = 0.5 + lamp[0].abs().max(lamp[1].abs());
    // The lattice points a reach makes us look at: the horizontal square times the heights.
    let candidates = |reach: f64| {
        let within = reach + rho;
        let side = 2.0 * (within + offset).ceil() + 1.0;
        side * side * (2.0 * (within + within * within / 4.0) * k + 3.0)
    };
    // A reach whose candidates are too many to look at is shortened (the reach returned
    // says what is covered): a long reach of a thin box would otherwise take ages.
    let mut reach = if reach.is_finite() {
        reach.max(0.0)
    } else {
        0.0
    };
    while reach > 0.0 && candidates(reach) > MAX_CANDIDATES {
        reach *= 0.8;
    }
    let within = reach + rho;
    let horizontal = (within + offset).ceil() as i64;
    let mut found: Vec<([f64; 3], f64)> = Vec::new();
    for p in -horizontal..=horizontal {
        for q in -horizontal..=horizontal {
            let (pf, qf) = (p as f64, q as f64);
            let moved = group_product(space.element(pf, qf, 0), lamp);
            if moved[0].hypot(moved[1]) > within {
                continue;
            }
            // The heights within reach: |z| ≤ R + R²/4.
            let top = within + within * within / 4.0;
            let lo = ((-top - moved[2]) * k).floor() as i64;
            let hi = ((top - moved[2]) * k).ceil() as i64;
            for m in lo..=hi {
                let image = [moved[0], moved[1], moved[2] + m as f64 / k];
                let d = distance([0.0; 3], image);
                if d <= within {
                    found.push((image, d));
                }
            }
        }
    }
    found.sort_by(|a, b| a.1.total_cmp(&b.1));
    crate::scene::lighting::nearest_images(found, reach, rho)
}

/// The light reaching the point `x` of a surface with outward normal `normal` (both in the
/// left-invariant frame at `x`): Lambert's cosine, the fog along the way and the sphere's
/// area ([`area_density`]), summed over the lamp's images (or from the nearest copy, for
/// [`LightPaths::Nearest`]). `occluded(ray, length)` walks a shadow ray for the
/// `lighting.shadows` images nearest the centre.
pub fn gather(
    scene: &NilScene,
    x: [f64; 3],
    normal: DVec3,
    occluded: &mut dyn FnMut(NilRay<f64>, f64) -> bool,
) -> f64 {
    let lighting = &scene.lighting;
    let fog = scene.fog_distance;
    let floor = scene.near_light * scene.near_light;
    // Light along the shortest geodesic (length r, start l) to an image, shadowed or not.
    let mut light_along = |(r, l): (f64, [f64; 3]), shadowed: bool| -> f64 {
        let cos = normal.dot(DVec3::from_array(l));
        if !(cos > 0.0 && r > 0.0) {
            return 0.0;
        }
        if shadowed && r > SHADOW_OFFSET {
            let start = flow(
                &NilRay {
                    point: x,
                    velocity: l,
                },
                SHADOW_OFFSET,
            );
            if occluded(start, r - SHADOW_OFFSET) {
                return 0.0;
            }
        }
        cos * (-r / fog).exp() / area_density(r, l[2]).max(floor)
    };
    if lighting.paths == LightPaths::Nearest {
        return light_along(shortest(x, scene.light), false);
    }
    let lamp = &scene.lamp;
    let shadows = lighting.shadows as usize;
    let mut sum = 0.0;
    for (k, path) in paths_within(&lamp.images, x, lamp.reach) {
        sum += light_along(path, k < shadows);
    }
    if lighting.tail {
        sum += 0.25 * open_tail_fluence(lamp.reach, fog, lamp.volume);
    }
    sum
}

/// The shortest geodesics from `x` to the `images` within `reach` (their index, length and
/// start velocity): the images past it by the root-free floor of the distance are skipped
/// without a root to find ([`crate::space::nil::distance_floor`]).
fn paths_within<'a>(
    images: &'a [[f64; 3]],
    x: [f64; 3],
    reach: f64,
) -> impl Iterator<Item = (usize, (f64, [f64; 3]))> + 'a {
    images
        .iter()
        .enumerate()
        .filter(move |(_, q)| crate::space::nil::distance_floor(**q, x) <= reach)
        .map(move |(k, q)| (k, shortest(x, *q)))
        .filter(move |(_, path)| path.0 <= reach)
}

/// The fluence at the point `x` of the box from a unit lamp at `lamp` (a point of the box),
/// as `light` reports it: `e^(−r/λ) / max(A(r, c), ε²)` along the shortest geodesic to every
/// image within `reach` of `x` (`ε` the default lamp's size [`super::NEAR_LIGHT`], as the tracer holds it),
/// and the images beyond by their mean `4πλ e^(−R/λ)/vol`. Returns the images summed, the
/// exact sum, the tail and the reach they cover (shortened where more images lie within it
/// than the tracer gathers).
#[must_use]
pub fn nil_fluence(
    space: &NilSpace,
    lamp: [f64; 3],
    x: [f64; 3],
    fog: f64,
    reach: f64,
) -> (usize, f64, f64, f64) {
    let floor = super::NEAR_LIGHT * super::NEAR_LIGHT;
    let (images, covered) = lamp_images(space, lamp, reach);
    let mut exact = 0.0;
    let mut paths = 0;
    for (_, (r, l)) in paths_within(&images, x, covered) {
        paths += 1;
        exact += (-r / fog).exp() / area_density(r, l[2]).max(floor);
    }
    (
        paths,
        exact,
        open_tail_fluence(covered, fog, space.volume()),
        covered,
    )
}
