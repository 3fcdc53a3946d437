//! How a lamp's light reaches a surface point of the manifold: along the geodesics to its
//! images in the universal cover, the nearest few walked for shadows, the far ones by their
//! mean (`docs/light.md`). The shader mirrors it (`shaders/lighting.wgsl`).
//!
//! A surface point `x` with normal `n` gets from a lamp of colour × power `P`
//!
//! ```text
//! E(x) = P · Σ_paths  max(0, ⟨n, l⟩) · e^(−d/λ) / max(S(d), S(r₀))²   +   P · T / 4
//! ```
//!
//! the sum over the geodesics from `x` to the images `g·L` within the reach `R` (`l` the
//! unit tangent at `x` along it, `d` its length, `λ` the fog distance: the medium that fogs
//! the view absorbs the light too), each left out where a shadow ray walked along it
//! through the faces meets an object first (the [`Lighting::shadows`] images nearest the
//! cell's centre; the rest are not walked). `T` is the mean fluence of the images beyond `R`
//! ([`tail_fluence`]): they come from every direction alike, and the mean of `max(0, cos θ)`
//! over the sphere of directions is `1/4`.
//!
//! In a spherical space an image is reached along the short arc (length `d`, direction `l`)
//! and the long one (`2π − d`, direction `−l`), and each again after whole turns round the
//! great circle; a turn passes both arcs, so it is dark where either arc is shadowed, and
//! the turns sum to a factor `t / (1 − t)`, `t = e^(−2π/λ)`.
//!
//! [`LightPaths::Nearest`] is the older model: the nearest of the lamp and its images
//! through the faces only, with no absorption on the way.

use crate::geometry::Geometry;
use crate::space::Space;
use crate::space::invariants::{circumradius, inradius, volume};
use glam::{DVec3, DVec4};
use std::f64::consts::{PI, TAU};

/// How far a shadow ray starts from the surface it leaves (a geodesic distance): it keeps
/// the surface itself from shadowing the point where f32 rounding puts the start a little
/// inside it.
pub const SHADOW_OFFSET: f64 = 1e-3;

/// In a spherical space, images farther than this (within 1e-3 of the point's antipode) are
/// left out: the geodesics to them have no one direction.
pub const ANTIPODE: f64 = PI - 1e-3;

/// The most images of one lamp summed exactly: past them the reach is shortened to what
/// they cover, and the rest joins the tail. The shader holds them in its uniform, 16 bytes
/// each.
pub const MAX_LAMP_IMAGES: usize = 256;

/// Which geodesics from a point to a lamp carry its light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LightPaths {
    /// Only the nearest of the lamp and its images through the cell's faces, unabsorbed:
    /// the older model, cheap, and wrong by the other images.
    Nearest,
    /// Every image within the reach, absorbed by the fog, and the rest by its mean.
    #[default]
    Images,
}

impl LightPaths {
    /// Its name on the command line and in scene files.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            LightPaths::Nearest => "nearest",
            LightPaths::Images => "images",
        }
    }

    /// The paths of a name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        [LightPaths::Nearest, LightPaths::Images]
            .into_iter()
            .find(|m| m.name() == name)
    }
}

/// How the lamps' light is gathered ([the module's description](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Which geodesics carry light.
    pub paths: LightPaths,
    /// How far, in inradii of the cell, the images are summed exactly ([`LightPaths::Images`];
    /// a spherical space sums all of them, up to [`MAX_LAMP_IMAGES`]).
    pub reach_inradii: f64,
    /// Whether the images beyond the reach add their mean.
    pub tail: bool,
    /// How many images of each lamp (those nearest the cell's centre) are walked for
    /// shadows; 0: none.
    pub shadows: u32,
}

impl Default for Lighting {
    fn default() -> Self {
        Self {
            paths: LightPaths::Images,
            reach_inradii: Self::DEFAULT_REACH_INRADII,
            tail: true,
            shadows: Self::DEFAULT_SHADOWS,
        }
    }
}

impl Lighting {
    /// The default reach in inradii: `bench --lighting` found 2 as close to its reference as
    /// 4 or 8 once the tail is added, and cheaper (docs/light.md).
    pub const DEFAULT_REACH_INRADII: f64 = 2.0;
    /// The default number of shadowed images per lamp: none. In the default scenes 4
    /// shadows cost 6–26 times the frame on lavapipe and take off at most 0.4/255 of mean
    /// error (docs/light.md); scenes that need them ask (`[lighting] shadows`).
    pub const DEFAULT_SHADOWS: u32 = 0;
    /// The most shadowed images per lamp.
    pub const MAX_SHADOWS: u32 = 64;

    /// The older model: the nearest copy, no tail, no shadows.
    pub const NEAREST: Self = Self {
        paths: LightPaths::Nearest,
        reach_inradii: Self::DEFAULT_REACH_INRADII,
        tail: false,
        shadows: 0,
    };

    /// The reach as a distance in `space`.
    #[must_use]
    pub fn reach(&self, space: &Space) -> f64 {
        self.reach_inradii * inradius(space)
    }

    /// Whether the settings are usable: a reach that is a positive number, shadows within
    /// [`Lighting::MAX_SHADOWS`]. The message names what is wrong.
    pub fn check(&self) -> Result<(), String> {
        if !(self.reach_inradii > 0.0 && self.reach_inradii <= 64.0) {
            return Err(format!(
                "the light reach must be more than 0 and at most 64 inradii, got {}",
                self.reach_inradii
            ));
        }
        if self.shadows > Self::MAX_SHADOWS {
            return Err(format!(
                "at most {} shadowed images per light, got {}",
                Self::MAX_SHADOWS,
                self.shadows
            ));
        }
        Ok(())
    }
}

/// A lamp's images in the cover for [`LightPaths::Images`]: those within `reach + ρ` of the
/// origin (`ρ` the circumradius, so that every image within `reach` of a point of the cell
/// is there), nearest the origin first, and the reach they cover. Past
/// [`MAX_LAMP_IMAGES`] the reach is shortened to what the nearest ones cover.
#[must_use]
pub fn cover_images(space: &Space, lamp: DVec4, reach: f64) -> (Vec<DVec4>, f64) {
    let g = space.geometry;
    let rho = if g == Geometry::Spherical {
        PI
    } else {
        circumradius(space)
    };
    // The images within `radius` of the origin and the reach they cover from every point
    // of the cell, or `None` where the walk to them visits too many cells.
    let fit = |radius: f64| -> Option<(Vec<DVec4>, f64)> {
        let images = super::light_images::lamp_images(space, lamp, radius, 64 * MAX_LAMP_IMAGES)?;
        if images.len() <= MAX_LAMP_IMAGES {
            let covered = if g == Geometry::Spherical {
                PI
            } else {
                radius - rho
            };
            return Some((images.into_iter().map(|(q, _)| q).collect(), covered));
        }
        // Every image nearer the origin than the first one left out is kept.
        let edge = images[MAX_LAMP_IMAGES].1;
        let kept = images[..MAX_LAMP_IMAGES]
            .iter()
            .take_while(|(_, d)| *d < edge)
            .map(|(q, _)| *q)
            .collect();
        Some((kept, (edge - rho).max(0.0)))
    };
    if let Some(found) = fit(reach + rho) {
        return found;
    }
    // Too many cells to walk that far: the farthest radius that can be walked, by
    // bisection (the cell alone, reach 0, always can).
    let (mut lo, mut hi) = (rho, reach + rho);
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
    best.or_else(|| fit(rho)).unwrap_or((vec![lamp], 0.0))
}

/// The mean fluence of a unit lamp's images beyond `reach` from a point, in fog of distance
/// `fog` (`docs/light.md`): images spread with density `1/vol(M)`, and a sphere's area
/// `4π S(r)²` cancels the falloff, so the shells add `4π e^(−r/λ) dr / vol(M)`:
/// `4πλ e^(−R/λ) / vol(M)` in E³ and H³; in S³ from `R` to `π`, both arcs and the turns,
/// `4πλ (e^(−R/λ) − e^(−(2π−R)/λ)) / (vol(M) (1 − e^(−2π/λ)))`.
#[must_use]
pub fn tail_fluence(geometry: Geometry, reach: f64, fog: f64, volume: f64) -> f64 {
    if !(volume > 0.0 && fog > 0.0) {
        return 0.0;
    }
    let near = (-reach / fog).exp();
    match geometry {
        Geometry::Spherical => {
            let reach = reach.min(PI);
            4.0 * PI * fog * (near - (-(TAU - reach) / fog).exp())
                / (volume * (1.0 - (-TAU / fog).exp()))
        }
        _ => 4.0 * PI * fog * near / volume,
    }
}

/// The volume of the space, for the tail (0 where it cannot be computed: no tail then).
#[must_use]
pub fn cell_volume(space: &Space) -> f64 {
    let v = volume(space);
    if v.is_finite() && v > 0.0 { v } else { 0.0 }
}

/// Asks whether anything lies on the geodesic from a point along a unit tangent within a
/// length: `occluded(point, tangent, length)`.
pub type Occluded<'a> = dyn FnMut(DVec4, DVec4, f64) -> bool + 'a;

/// A point light, with its copies in the cells around the fundamental cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Where the light is, inside the cell.
    pub position: DVec4,
    /// Colour, linear RGB.
    pub colour: DVec3,
    /// Brightness at distance `d` is `power / S(d)²` (`sin²`, `d²`, `sinh²`).
    pub power: f64,
    /// The light and its images under the face pairings, in the cell's coordinates: a
    /// surface point is lit by the nearest of them ([`LightPaths::Nearest`]).
    pub images: Vec<DVec4>,
    /// Its images in the universal cover within `reach + ρ` of the origin, nearest the
    /// origin first ([`LightPaths::Images`], [`crate::scene::lighting::cover_images`]).
    pub cover: Vec<DVec4>,
    /// The distance from a lit point within which the images are summed exactly.
    pub reach: f64,
    /// The space's volume, the images' density in the cover (the tail beyond the reach).
    pub volume: f64,
}

impl Light {
    /// A light at `position` (inside the cell) with its images under the pairings and in
    /// the cover within the default reach ([`Lighting::DEFAULT_REACH_INRADII`]).
    #[must_use]
    pub fn new(space: &Space, position: DVec4, colour: DVec3, power: f64) -> Self {
        Self::reaching(
            space,
            position,
            colour,
            power,
            Lighting::default().reach(space),
        )
    }

    /// [`Light::new`] with the images in the cover within `reach` of each lit point.
    #[must_use]
    pub fn reaching(space: &Space, position: DVec4, colour: DVec3, power: f64, reach: f64) -> Self {
        let g = space.geometry;
        let mut images = vec![position];
        for face in &space.faces {
            let image = g.project_point(face.pairing * position);
            if images.iter().all(|q| g.distance(*q, image) > 1e-9) {
                images.push(image);
            }
        }
        let (cover, reach) = cover_images(space, position, reach);
        Self {
            position,
            colour,
            power,
            images,
            cover,
            reach,
            volume: cell_volume(space),
        }
    }

    /// The same light with its images in the cover within `reach`.
    #[must_use]
    pub fn with_reach(&self, space: &Space, reach: f64) -> Self {
        Self::reaching(space, self.position, self.colour, self.power, reach)
    }

    /// The image nearest to `x` and its distance.
    #[must_use]
    pub fn nearest(&self, geometry: Geometry, x: DVec4) -> (DVec4, f64) {
        self.images
            .iter()
            .map(|q| (*q, geometry.distance(x, *q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((self.position, geometry.distance(x, self.position)))
    }
}

/// The light a surface point (`point`, unit normal `normal`) gets from `light`, per unit of
/// its colour × power ([the module's description](self)), in fog of distance `fog`, the
/// falloff held at `S(near_light)` within `near_light`; `occluded` walks the shadow rays
/// (answer `false` for none).
#[must_use]
pub fn gather(
    lighting: &Lighting,
    (fog, near_light): (f64, f64),
    g: Geometry,
    light: &Light,
    point: DVec4,
    normal: DVec4,
    occluded: &mut Occluded<'_>,
) -> f64 {
    let s2 = |d: f64| {
        let s = g.s(d).abs().max(g.s(near_light));
        s * s
    };
    let lambert = |l: DVec4| g.form(normal, l).max(0.0);
    let shadows = lighting.shadows as usize;
    if lighting.paths == LightPaths::Nearest {
        let (at, dl) = light.nearest(g, point);
        if !(dl > 0.0) {
            return 0.0;
        }
        let l = g.tangent_towards(point, at);
        let cos = lambert(l);
        if cos > 0.0 && shadows > 0 && shadowed(g, occluded, point, l, dl) {
            return 0.0;
        }
        return cos / s2(dl);
    }
    let absorbed = |d: f64| (-d / fog).exp();
    let mut sum = 0.0;
    for (k, q) in light.cover.iter().enumerate() {
        let d = g.distance(point, *q);
        if !(d > 0.0) || d > light.reach {
            continue;
        }
        let walk = k < shadows;
        if g == Geometry::Spherical && d > ANTIPODE {
            continue;
        }
        let l = g.tangent_towards(point, *q);
        if g == Geometry::Spherical {
            let (short, long) = (lambert(l), lambert(-l));
            if short == 0.0 && long == 0.0 {
                continue;
            }
            let t = (-TAU / fog).exp();
            let a = !walk || !shadowed(g, occluded, point, l, d);
            let b = !walk || !shadowed(g, occluded, point, -l, TAU - d);
            let fs = short * absorbed(d);
            let fl = long * absorbed(TAU - d);
            let mut paths = 0.0;
            if a {
                paths += fs;
            }
            if b {
                paths += fl;
            }
            if a && b {
                paths += (fs + fl) * t / (1.0 - t);
            }
            sum += paths / s2(d);
        } else {
            let cos = lambert(l);
            if cos > 0.0 && !(walk && shadowed(g, occluded, point, l, d)) {
                sum += cos * absorbed(d) / s2(d);
            }
        }
    }
    if lighting.tail {
        sum += 0.25 * tail_fluence(g, light.reach, fog, light.volume);
    }
    sum
}

/// Whether the shadow ray from `point` along `l` for `length` meets something: it starts
/// [`SHADOW_OFFSET`] along the geodesic.
fn shadowed(g: Geometry, occluded: &mut Occluded<'_>, point: DVec4, l: DVec4, length: f64) -> bool {
    if length <= SHADOW_OFFSET {
        return false;
    }
    let (from, along) = g.geodesic(point, l, SHADOW_OFFSET);
    let from = g.project_point(from);
    occluded(from, g.unit_tangent(from, along), length - SHADOW_OFFSET)
}
