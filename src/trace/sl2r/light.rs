//! The lamp of an SL̃(2,R) scene, lit along the shortest geodesic to each of its images.
//!
//! A lamp is a point of the space: a frame `(q, f)` of `UT H²` (and, in a fibre cover, the
//! sheet it sits on). A point `x` gets light from an image of the lamp along the shortest
//! geodesic from `x` to it ([`crate::space::sl2r::distance::shortest_within`], the inverse of
//! the exponential map): it leaves `x` along the unit body velocity `l = (a, b, c)`, has
//! length `r`, and brings
//!
//! ```text
//! max(0, ⟨n, l⟩) · e^(−r/λ) / max(A(r, c), ε²)
//! ```
//!
//! where `A` is the area, per unit solid angle at the lamp, of the geodesic sphere of radius
//! `r` about it ([`area_density`], from the exponential map; `c` is constant along a
//! geodesic, and the reverse geodesic's `−c` gives the same `A`), held from below at its
//! flat value `ε²` at the lamp's size `ε` ([`Sl2rScene::near_light`]).
//!
//! **Which images.** `UT Σ = PSL(2,R)/Γ`; its universal cover unwinds the fibre, so the
//! lamp's images there are `Γ`'s images of it together with their lifts `2π` apart along
//! the fibre. Two lifts of one point are at least `2π` apart (every geodesic loop of
//! `PSL(2,R)` is that long), so within a reach below the injectivity radius `π` each image
//! of `Γ` has at most one lift, which the inverse exponential map of `PSL(2,R)` finds: the
//! reach is held below [`MAX_LIGHT_REACH`]. In a fibre cover an image sits on a sheet, and a
//! path to it counts where it ends on that sheet (the sheets climbed along it,
//! [`crate::space::sl2r::cover::sheets_climbed`]). The images beyond the reach add their
//! mean, `¼ · 4πλ e^(−R/λ)/vol(M)`, as in the other families.

use super::{Sl2rScene, apply};
use crate::scene::lighting::{LampImages, LightPaths, Lighting, SHADOW_OFFSET, open_tail_fluence};
use crate::space::sl2r::UnitTangentSpace;
use crate::space::sl2r::cover::{fibre_angle, sheet_plus, sheets_climbed};
use crate::space::sl2r::distance::{
    Frame, TRUSTED_LENGTH, base_distance, distance_floor, shortest_within,
};
use crate::space::sl2r::flow::{Sl2rRay, flow};
use glam::DVec3;

/// The longest reach of a lamp's images: below the injectivity radius `π` of `UT H²`, where
/// the inverse exponential map's geodesic is the shortest and each image has one lift.
pub const MAX_LIGHT_REACH: f64 = TRUSTED_LENGTH;

/// Below this `|ω²r²|` the density is summed as a series.
const DENSITY_SERIES_BELOW: f64 = 0.5;

/// The area per unit solid angle of SL̃(2,R)'s geodesic sphere of radius `r`, at the end of
/// a geodesic of vertical body velocity `c` (`|c| ≤ 1`): with `ω² = 1 − 2c²`,
/// `S = sinh(ωr)/ω` and `K = (cosh(ωr) − 1)/ω²` (their trigonometric twins where `ω² < 0`),
///
/// ```text
/// A(r, c) = r·S + (r·S − 2K)/ω²,
/// ```
///
/// the absolute value of the determinant of the exponential map's derivative in polar
/// coordinates (`(r, θ, φ) ↦ exp(r·u(θ, φ))`, divided by `sin θ`). It is `r²` near the
/// centre, `2(r sinh r − cosh r + 1)` along horizontal geodesics and `2(1 − cos r)` up the
/// fibre, where it vanishes at `2π` (the fibre's geodesics from the centre meet again there):
/// callers bound it from below. Near `ω²r² = 0` it is the series
/// `r² Σ xᵏ/(2k+1)! + r⁴ Σ_{k≥1} 2k·xᵏ⁻¹/(2k+2)!` in `x = ω²r²`, the same on both sides.
#[must_use]
pub fn area_density(r: f64, c: f64) -> f64 {
    let w2 = 1.0 - 2.0 * c * c;
    let x = w2 * r * r;
    let a = if x.abs() < DENSITY_SERIES_BELOW {
        // Σ xᵏ/(2k+1)! and Σ 2(k+1)·xᵏ/(2k+4)!, each to below 1e-17 of its first term.
        let (mut s, mut p) = (0.0, 0.0);
        let (mut term_s, mut term_p) = (1.0, 2.0 / 24.0);
        for k in 0..12 {
            s += term_s;
            p += term_p;
            let kf = f64::from(k);
            term_s *= x / ((2.0 * kf + 2.0) * (2.0 * kf + 3.0));
            term_p *= x * (kf + 2.0) / ((kf + 1.0) * (2.0 * kf + 5.0) * (2.0 * kf + 6.0));
        }
        r * r * s + r.powi(4) * p
    } else if w2 > 0.0 {
        let w = w2.sqrt();
        let s = (w * r).sinh() / w;
        let k = ((w * r).cosh() - 1.0) / w2;
        r * s + (r * s - 2.0 * k) / w2
    } else {
        let w = (-w2).sqrt();
        let s = (w * r).sin() / w;
        let k = (1.0 - (w * r).cos()) / -w2;
        r * s + (r * s - 2.0 * k) / w2
    };
    a.abs()
}

/// An image of the lamp: its frame (columns `f`, `f⊥`, `q`) and the sheet of the fibre cover
/// it sits on (0 in `UT Σ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LampImage {
    /// The frame.
    pub frame: Frame,
    /// The sheet.
    pub sheet: u32,
}

/// The lamp's images (frames on their sheets) whose base point is within `reach + ρ` of the
/// polygon's centre (`ρ` its circumradius).
pub type Sl2rLamp = LampImages<LampImage>;

/// The reach of `lighting` in an SL̃(2,R) space: its inradii times the polygon's inradius,
/// at most [`MAX_LIGHT_REACH`].
#[must_use]
pub fn reach(space: &UnitTangentSpace, lighting: &Lighting) -> f64 {
    (lighting.reach_inradii * space.inradius()).min(MAX_LIGHT_REACH)
}

impl Sl2rLamp {
    /// The images of the lamp `light` (on its sheet) within `lighting`'s reach (none for
    /// [`LightPaths::Nearest`]).
    #[must_use]
    pub fn new(space: &UnitTangentSpace, light: LampImage, lighting: &Lighting) -> Self {
        Self::searched(lighting, reach(space, lighting), space.volume(), |r| {
            lamp_images(space, light, r)
        })
    }
}

/// The images `γ·lamp` (`γ` in the surface group) whose base point is within `reach + ρ` of
/// the polygon's centre (`ρ` the circumradius: every point of the cell lies over a point
/// within `ρ` of it, and the distance is at least the base distance), nearest first, each on
/// its sheet; and the reach they cover from every point of the cell (shortened where more
/// than [`crate::scene::lighting::MAX_LAMP_IMAGES`] lie within it). The reach is held below
/// [`MAX_LIGHT_REACH`].
#[must_use]
pub fn lamp_images(space: &UnitTangentSpace, lamp: LampImage, reach: f64) -> (Vec<LampImage>, f64) {
    let reach = if reach.is_finite() {
        reach.clamp(0.0, MAX_LIGHT_REACH)
    } else {
        0.0
    };
    let rho = space.circumradius();
    let q = lamp.frame[2];
    let angle = fibre_angle(&lamp.frame);
    let mut found: Vec<(LampImage, f64)> = Vec::new();
    for (m, turn) in super::elements_within(space, q, reach + rho) {
        let frame = lamp.frame.map(|c| apply(&m, c));
        let d = base_distance([0.0, 0.0, 1.0], frame[2]);
        if d > reach + rho {
            continue;
        }
        let climbed = ((angle + turn - fibre_angle(&frame)) / std::f64::consts::TAU).round();
        let sheet = sheet_plus(lamp.sheet, climbed as i64, space.sheets());
        found.push((LampImage { frame, sheet }, d));
    }
    found.sort_by(|a, b| a.1.total_cmp(&b.1));
    crate::scene::lighting::nearest_images(found, reach, rho)
}

/// The shortest geodesic from `x` (on `sheet` of a cover of `sheets`) to the lamp `image`
/// shorter than `reach`: its length and unit start velocity in `x`'s body frame, where it
/// ends on the image's sheet.
fn path_to(
    x: &Frame,
    (sheet, sheets): (u32, u32),
    image: &LampImage,
    reach: f64,
) -> Option<(f64, [f64; 3])> {
    // Past the reach by the base distance (one Lorentz product), then by the floor.
    if -crate::space::sl2r::flow::lorentz(image.frame[2], x[2]) > reach.cosh()
        || distance_floor(&image.frame, x) > reach
    {
        return None;
    }
    let (r, l) = shortest_within(x, &image.frame, reach)?;
    if sheets > 1 {
        let ray = Sl2rRay {
            frame: *x,
            velocity: l,
        };
        let climbed = sheets_climbed(&ray, r, &image.frame)?;
        if sheet_plus(sheet, climbed, sheets) != image.sheet {
            return None;
        }
    }
    Some((r, l))
}

/// The light reaching the point `x` (on `sheet`) of a surface with outward normal `normal`
/// (in `x`'s body frame `X, Y, V`): Lambert's cosine, the fog along the way and the
/// sphere's area ([`area_density`]), summed over the lamp's images within the reach, and the
/// tail beyond (or from the lamp itself, for [`LightPaths::Nearest`]).
/// `occluded(ray, sheet, length)` walks a shadow ray for the `lighting.shadows` images
/// nearest the cell's centre.
pub fn gather(
    scene: &Sl2rScene,
    (x, sheet, sheets): (&Frame, u32, u32),
    normal: DVec3,
    occluded: &mut dyn FnMut(Sl2rRay<f64>, u32, f64) -> bool,
) -> f64 {
    let lighting = &scene.lighting;
    let fog = scene.fog_distance;
    let floor = scene.near_light * scene.near_light;
    let mut light_along = |(r, l): (f64, [f64; 3]), shadowed: bool| -> f64 {
        let cos = normal.dot(DVec3::from_array(l));
        if !(cos > 0.0 && r > 0.0) {
            return 0.0;
        }
        if shadowed && r > SHADOW_OFFSET {
            let ray = Sl2rRay {
                frame: *x,
                velocity: l,
            };
            let start = flow(&ray, SHADOW_OFFSET);
            let climbed = if sheets > 1 {
                sheets_climbed(&ray, SHADOW_OFFSET, &start.frame).unwrap_or(0)
            } else {
                0
            };
            if occluded(start, sheet_plus(sheet, climbed, sheets), r - SHADOW_OFFSET) {
                return 0.0;
            }
        }
        cos * (-r / fog).exp() / area_density(r, l[2]).max(floor)
    };
    if lighting.paths == LightPaths::Nearest {
        let lamp = LampImage {
            frame: scene.light,
            sheet: scene.light_sheet,
        };
        return path_to(x, (sheet, sheets), &lamp, MAX_LIGHT_REACH)
            .map_or(0.0, |path| light_along(path, false));
    }
    let lamp = &scene.lamp;
    let shadows = lighting.shadows as usize;
    let mut sum = 0.0;
    for (k, image) in lamp.images.iter().enumerate() {
        if let Some(path) = path_to(x, (sheet, sheets), image, lamp.reach) {
            sum += light_along(path, k < shadows);
        }
    }
    if lighting.tail {
        sum += 0.25 * open_tail_fluence(lamp.reach, fog, lamp.volume);
    }
    sum
}

/// The fluence at the point `x` (on `sheet`) from a unit lamp `lamp`, as `light` reports it:
/// `e^(−r/λ) / max(A(r, c), ε²)` along the shortest geodesic to every image within `reach`
/// of `x` (`ε` the default lamp's size [`super::NEAR_LIGHT`]), and the images beyond by
/// their mean `4πλ e^(−R/λ)/vol`. Returns the images summed, the exact sum, the tail and the
/// reach they cover (at most [`MAX_LIGHT_REACH`]; shortened where more images lie within it
/// than the tracer gathers).
#[must_use]
pub fn sl2r_fluence(
    space: &UnitTangentSpace,
    lamp: LampImage,
    (x, sheet): (&Frame, u32),
    fog: f64,
    reach: f64,
) -> (usize, f64, f64, f64) {
    let floor = super::NEAR_LIGHT * super::NEAR_LIGHT;
    let (images, covered) = lamp_images(space, lamp, reach);
    let mut exact = 0.0;
    let mut paths = 0;
    for image in &images {
        if let Some((r, l)) = path_to(x, (sheet, space.sheets()), image, covered) {
            paths += 1;
            exact += (-r / fog).exp() / area_density(r, l[2]).max(floor);
        }
    }
    (
        paths,
        exact,
        open_tail_fluence(covered, fog, space.volume()),
        covered,
    )
}
