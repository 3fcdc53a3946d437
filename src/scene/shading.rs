//! Lights, materials and the shading model, defined once for the CPU reference and mirrored
//! by the shader.

use super::object::Hit;
use crate::geometry::Geometry;
use crate::space::Space;
use glam::{DVec3, DVec4};

/// Half a colour step of an 8-bit image.
pub const DEFAULT_CUTOFF_WEIGHT: f64 = 1.0 / 510.0;

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
    /// surface point is lit by the nearest of them.
    pub images: Vec<DVec4>,
}

impl Light {
    /// A light at `position` (inside the cell) with its images under the pairings.
    #[must_use]
    pub fn new(space: &Space, position: DVec4, colour: DVec3, power: f64) -> Self {
        let g = space.geometry;
        let mut images = vec![position];
        for face in &space.faces {
            let image = g.project_point(face.pairing * position);
            if images.iter().all(|q| g.distance(*q, image) > 1e-9) {
                images.push(image);
            }
        }
        Self {
            position,
            colour,
            power,
            images,
        }
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

/// The shading model, in one place (`docs/design.md` §4):
///
/// ```text
/// lit     = albedo · (ambient + (1 − ambient) · Σ_lights light · power · max(0, ⟨n, l⟩) / max(S(d_L)², S(r₀)²))
/// surface = min(lit + emission, 1)                        per channel
/// colour  = e^(−d/λ) · surface + (1 − e^(−d/λ)) · fog     d = distance along the ray
/// ```
///
/// `l` is the unit tangent at the hit towards the light's nearest copy (among the light and
/// its images under the face pairings), `d_L` its distance, `r₀` a small radius that keeps
/// the falloff finite. No shadows.
/// A ray stops at the distance `λ ln(1/w)` where the fog weight `e^(−d/λ)` falls to
/// `w = cutoff_weight`. Surface and fog colours lie in [0, 1], so whatever lies beyond
/// changes the pixel by at most `w` per channel: with the default `w = 1/510` that is half a
/// colour step of an 8-bit image, the cut-off's error bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    /// Fraction of the albedo seen without light.
    pub ambient: f64,
    /// The fog's colour, linear RGB.
    pub fog_colour: DVec3,
    /// Fog distance scale λ.
    pub fog_distance: f64,
    /// The radius within which the falloff stops growing (keeps it finite).
    pub near_light: f64,
    /// Fog weight at which a ray stops (the cut-off's error bound per channel).
    pub cutoff_weight: f64,
}

impl Default for Shading {
    /// The default scene's shading with a fog distance of 1 (set it for the space:
    /// [`Shading::default_fog_distance`]).
    fn default() -> Self {
        Self {
            ambient: 0.3,
            fog_colour: DVec3::new(0.04, 0.05, 0.08),
            fog_distance: 1.0,
            near_light: 0.05,
            cutoff_weight: DEFAULT_CUTOFF_WEIGHT,
        }
    }
}

impl Shading {
    /// The default fog distance scale λ in inradii: several cells deep in every space.
    pub const DEFAULT_FOG_INRADII: f64 = 3.0;

    /// The default fog distance scale λ: [`Shading::DEFAULT_FOG_INRADII`] times the inradius.
    #[must_use]
    pub fn default_fog_distance(space: &Space) -> f64 {
        Self::DEFAULT_FOG_INRADII * crate::space::invariants::inradius(space)
    }

    /// The distance past which nothing changes the image by half a colour step or more.
    #[must_use]
    pub fn cutoff_distance(&self) -> f64 {
        self.fog_distance * (1.0 / self.cutoff_weight).ln()
    }

    /// The colour of a surface point seen at distance `d`.
    #[must_use]
    pub fn shade(&self, geometry: Geometry, lights: &[Light], hit: &Hit, d: f64) -> DVec3 {
        let mut lit = DVec3::splat(self.ambient);
        for light in lights {
            let (at, dl) = light.nearest(geometry, hit.point);
            if dl > 0.0 {
                let l = geometry.tangent_towards(hit.point, at);
                let lambert = geometry.form(hit.normal, l).max(0.0);
                let s = geometry.s(dl).abs().max(geometry.s(self.near_light));
                lit += (1.0 - self.ambient) * light.colour * (light.power * lambert / (s * s));
            }
        }
        let surface = (hit.colour * lit + hit.emission).min(DVec3::ONE);
        let w = (-d / self.fog_distance).exp();
        w * surface + (1.0 - w) * self.fog_colour
    }
}

/// A surface's look: albedo (times its texture, if any) and emission, linear RGB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceMaterial {
    /// Colour, linear RGB.
    pub colour: DVec3,
    /// Index into [`CurvedScene::textures`](crate::scene::CurvedScene::textures).
    pub texture: Option<u32>,
    /// Emitted colour, linear RGB.
    pub emission: DVec3,
}

impl Default for SurfaceMaterial {
    fn default() -> Self {
        Self {
            colour: DVec3::splat(0.8),
            texture: None,
            emission: DVec3::ZERO,
        }
    }
}
