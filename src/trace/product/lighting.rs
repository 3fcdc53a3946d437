//! The lamp of a product scene (H²×R, S²×R) lit along every geodesic to each of its images
//! in the universal cover, as in the constant-curvature spaces ([`crate::scene::lighting`],
//! `docs/light.md`).
//!
//! The deck group is the surface group `Γ` (the polygon's side pairings, 4×4 matrices fixing
//! `z`) and the circle's translation `T: (p, z) ↦ (R p, z + L)`, `R` the turn; every element
//! is `(p, z) ↦ (M p, z + kL)` with `M` in the group `Γ` and `R` generate. The images of a
//! lamp at `(b, z₀)` are the points `(M b, z₀ + kL)`, found by walking the cells outwards
//! from the cell (nearest first, [`lamp_images`]).
//!
//! A point `x` gets from an image `q` a surface distance `ρ` away and `Δz` above along each
//! geodesic joining them: one in H²×R (`h = ρ`), and in S²×R one per way round the great
//! circle, `h = ρ + 2πn` towards the image's base point and `h = 2π(n+1) − ρ` away from it
//! (`n ≥ 0`). Each has length `r = √(h² + Δz²)` and leaves `x` along `(h·u + Δz·ẑ)/r` (`u`
//! the unit surface tangent towards or away), and brings
//!
//! ```text
//! max(0, ⟨n, l⟩) · e^(−r/λ) / max(A(h, Δz), 1),    A = r² |S(h)| / h,
//! ```
//!
//! `A` the area per solid angle of the geodesic sphere ([`super::light_spread`]), never
//! less than at distance 1 as the nearest-copy shading holds it. `A` vanishes where the
//! geodesics from the lamp meet again (`h = π, 2π, …` on S²): there the floor stands for a
//! lamp of finite size, and points within 10⁻³ of the fibre over the image's base point or
//! its antipode skip the windings that have no one direction. The images beyond the reach
//! add their mean: the sphere's area cancels the falloff, so each shell `dr` adds
//! `4π e^(−r/λ) dr / vol(M)` over every direction, `4πλ e^(−R/λ)/vol(M)` in all, and a
//! quarter of it lights a surface (the mean of Lambert's cosine over the sphere).

use super::{ProductScene, away_from, dot};
use crate::geometry::{Geometry, Real};
use crate::scene::lighting::{
    LampImages, LightPaths, Lighting, MAX_LAMP_IMAGES, Occluded, SHADOW_OFFSET,
};
use crate::space::product::{ProductSpace, ProductWalker};
use glam::{DMat4, DVec4};
use std::collections::{HashSet, VecDeque};
use std::f64::consts::{PI, TAU};

/// The most cells walked when gathering a lamp's images.
const MAX_CELLS: usize = 64 * MAX_LAMP_IMAGES;

/// Within this surface distance of the fibre over an image's base point (or its antipode on
/// S²) the geodesics that wind round have no one direction and are left out.
const FOCUS: f64 = 1e-3;

/// The lamp's images in the cover (their points), within `reach + ρ` of the cell's centre
/// (`ρ` the cell's circumradius).
pub type ProductLamp = LampImages<DVec4>;

impl ProductLamp {
    /// The images of the lamp at `light` within `lighting`'s reach (none for
    /// [`LightPaths::Nearest`]).
    #[must_use]
    pub fn new(space: &ProductSpace, light: DVec4, lighting: &Lighting) -> Self {
        Self::searched(lighting, reach(space, lighting), space.volume(), |r| {
            lamp_images(space, light, r)
        })
    }
}

/// The reach of `lighting` in a product space: its inradii times the cell's size
/// ([`ProductSpace::scale`]: the smaller of the polygon's inradius and half the circle).
#[must_use]
pub fn reach(space: &ProductSpace, lighting: &Lighting) -> f64 {
    lighting.reach_inradii * space.scale()
}

/// The distance from the cell's centre to its farthest point: the polygon's circumradius
/// (π for the sphere, π/2 for the hemisphere) with half the circle.
#[must_use]
pub fn cell_circumradius(space: &ProductSpace) -> f64 {
    let base = if space.polygon().sides.is_empty() {
        PI
    } else if space.hemisphere() {
        0.5 * PI
    } else {
        space.polygon().circumradius.to_f64()
    };
    base.hypot(0.5 * space.length())
}

/// The product distance between two points.
fn distance(g: Geometry, p: DVec4, q: DVec4) -> f64 {
    super::surface_distance(g, p, q).hypot(p.z - q.z)
}

/// The images of a lamp at `lamp` (a point of the cell) within `reach + ρ` of the cell's
/// centre (`ρ` = [`cell_circumradius`]), nearest the centre first, and the reach they cover
/// from every point of the cell. Past [`MAX_LAMP_IMAGES`], or where the walk would visit
/// more than a limit of cells, the reach is shortened to what the nearest images cover.
#[must_use]
pub fn lamp_images(space: &ProductSpace, lamp: DVec4, reach: f64) -> (Vec<DVec4>, f64) {
    let rho = cell_circumradius(space);
    let fit = |reach: f64| -> Option<(Vec<DVec4>, f64)> {
        let found = images_within(space, lamp, reach + rho)?;
        Some(crate::scene::lighting::nearest_images(found, reach, rho))
    };
    if let Some(found) = fit(reach) {
        return found;
    }
    // Too many cells to walk that far: the farthest reach that can be walked, by bisection.
    let (mut lo, mut hi) = (0.0, reach);
    let mut best = None;
    for _ in 0..12 {
        let mid = 0.5 * (lo + hi);
        match fit(mid) {
            Some(found) => {
                best = Some(found);
                lo = mid;
            }
            None => hi = mid,
        }
    }
    best.or_else(|| fit(0.0)).unwrap_or((vec![lamp], 0.0))
}

/// The images of `lamp` within `within` of the cell's centre with their distances, nearest
/// first, or `None` where the walk to them visits more than [`MAX_CELLS`] cells.
fn images_within(space: &ProductSpace, lamp: DVec4, within: f64) -> Option<Vec<(DVec4, f64)>> {
    let g = space.base();
    let walker = ProductWalker::<DVec4>::new(space);
    let rho = cell_circumradius(space);
    let centre = space.centre();
    let length = space.length();
    // The generators: each side's pairing (fixing z), the top's (R⁻¹, −L), the bottom's.
    let mut generators: Vec<(DMat4, i64)> = walker.pairings.iter().map(|m| (*m, 0)).collect();
    generators.push((walker.up.0, -1));
    generators.push((walker.down.0, 1));
    let apply = |(m, k): (DMat4, i64), p: DVec4| {
        let q = m * DVec4::new(p.x, p.y, 0.0, p.w);
        DVec4::new(q.x, q.y, p.z + k as f64 * length, q.w)
    };
    let key = |element: (DMat4, i64)| {
        let c = apply(element, centre);
        // Γ acts freely, so an element is known by where it takes the centre and its k.
        let r = |x: f64| (x * 1e6).round() as i64;
        (r(c.x), r(c.y), r(c.w), element.1)
    };
    // An image within `within` of the centre: its segment to the centre crosses cells
    // whose centres lie within `within + ρ`, each next to the one before: the walk visits
    // them all.
    let mut seen = HashSet::new();
    let mut queue = VecDeque::new();
    let start = (DMat4::IDENTITY, 0);
    seen.insert(key(start));
    queue.push_back(start);
    let mut found: Vec<(DVec4, f64)> = Vec::new();
    while let Some(element) = queue.pop_front() {
        let image = apply(element, lamp);
        let d = distance(g, centre, image);
        if d <= within {
            found.push((image, d));
        }
        for generator in &generators {
            // The cell across a face of this one (the face's pairing on the right).
            let next = (element.0 * generator.0, element.1 + generator.1);
            if distance(g, centre, apply(next, centre)) > within + rho || !seen.insert(key(next)) {
                continue;
            }
            if seen.len() > MAX_CELLS {
                return None;
            }
            queue.push_back(next);
        }
    }
    found.sort_by(|a, b| a.1.total_cmp(&b.1));
    Some(found)
}

/// The mean fluence of a unit lamp's images beyond `reach`, in fog of distance `fog`:
/// `4πλ e^(−R/λ)/vol(M)` ([the module's description](self)).
#[must_use]
pub fn product_tail_fluence(reach: f64, fog: f64, volume: f64) -> f64 {
    crate::scene::lighting::open_tail_fluence(reach, fog, volume)
}

/// One geodesic from a point to an image: its unit tangent at the point and its length,
/// and its falloff `max(A, 1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LampPath {
    /// The unit tangent at the lit point.
    pub tangent: DVec4,
    /// The geodesic's length.
    pub length: f64,
    /// The area per solid angle of the geodesic sphere there, at least 1.
    pub spread: f64,
}

/// Every geodesic from `x` to the image `q` of length at most `reach` ([the module's
/// description](self)), handed to `each`.
pub fn paths_to(g: Geometry, x: DVec4, q: DVec4, reach: f64, mut each: impl FnMut(LampPath)) {
    let (away, rho) = away_from(g, x, q);
    let dz = q.z - x.z;
    let mut path = |h: f64, u: DVec4| {
        let r = h.hypot(dz);
        if !(r > 0.0) || r > reach {
            return;
        }
        let tangent = (u * h + DVec4::Z * dz) / r;
        let spread = if h < 1e-4 {
            r * r
        } else {
            r * r * g.s(h).abs() / h
        };
        each(LampPath {
            tangent,
            length: r,
            spread: spread.max(1.0),
        });
    };
    if g != Geometry::Spherical {
        path(rho, -away);
        return;
    }
    if rho > PI - FOCUS {
        // On the antipodal fibre: every way round has a whole cone of directions.
        return;
    }
    path(rho, -away);
    if rho < FOCUS {
        return;
    }
    let mut n = 0.0;
    loop {
        let (toward, back) = (rho + TAU * (n + 1.0), TAU * (n + 1.0) - rho);
        if back.hypot(dz) > reach {
            break;
        }
        path(back, away);
        path(toward, -away);
        n += 1.0;
    }
}

/// The light a surface point `x` with unit normal `normal` gets from the scene's lamp, per
/// unit of its power ([the module's description](self)); `occluded` walks the shadow rays
/// of the first [`Lighting::shadows`] images (answer `false` for none).
#[must_use]
pub fn product_gather(
    g: Geometry,
    scene: &ProductScene,
    x: DVec4,
    normal: DVec4,
    occluded: &mut Occluded<'_>,
) -> f64 {
    let lighting = &scene.lighting;
    let lambert = |l: DVec4| dot(g, normal, l).max(0.0);
    if lighting.paths == LightPaths::Nearest {
        // The older model: the lamp in the cell only, unabsorbed.
        let l = super::tangent_towards(g, x, scene.light);
        let spread = super::light_spread(
            g,
            super::surface_distance(g, x, scene.light),
            x.z - scene.light.z,
        );
        return lambert(l) / spread.max(1.0);
    }
    let lamp = &scene.lamp;
    let fog = scene.fog_distance;
    let shadows = lighting.shadows as usize;
    let mut sum = 0.0;
    for (k, q) in lamp.images.iter().enumerate() {
        paths_to(g, x, *q, lamp.reach, |p| {
            let cos = lambert(p.tangent);
            if cos > 0.0 && !(k < shadows && shadowed(g, occluded, x, p)) {
                sum += cos * (-p.length / fog).exp() / p.spread;
            }
        });
    }
    if lighting.tail {
        sum += 0.25 * product_tail_fluence(lamp.reach, fog, lamp.volume);
    }
    sum
}

/// Whether the shadow ray from `x` along a path meets something: it starts
/// [`SHADOW_OFFSET`] along the geodesic.
fn shadowed(g: Geometry, occluded: &mut Occluded<'_>, x: DVec4, path: LampPath) -> bool {
    if path.length <= SHADOW_OFFSET {
        return false;
    }
    let ray = crate::geometry::Ray {
        point: x,
        tangent: path.tangent,
    };
    let from = super::along(g, &ray, SHADOW_OFFSET);
    let along = super::along_tangent(g, &ray, SHADOW_OFFSET);
    occluded(from, along, path.length - SHADOW_OFFSET)
}

/// The fluence at `x` from a unit lamp at `lamp`, summed over every path to its images
/// within `reach` with the fog's absorption (no Lambert factor), and the tail's mean: the
/// check the tests and `curved-spaces light` make of the sums. Returns the paths summed,
/// their sum, the tail, and the reach the images gathered cover (shorter than `reach`
/// where more than [`MAX_LAMP_IMAGES`] lie within it).
#[must_use]
pub fn product_fluence(
    space: &ProductSpace,
    lamp: DVec4,
    x: DVec4,
    fog: f64,
    reach: f64,
) -> (usize, f64, f64, f64) {
    let g = space.base();
    let (images, covered) = lamp_images(space, lamp, reach);
    let mut exact = 0.0;
    let mut paths = 0;
    for q in &images {
        paths_to(g, x, *q, covered, |p| {
            paths += 1;
            exact += (-p.length / fog).exp() / p.spread;
        });
    }
    (
        paths,
        exact,
        product_tail_fluence(covered, fog, space.volume()),
        covered,
    )
}
