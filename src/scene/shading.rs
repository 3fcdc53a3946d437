//! Lights, materials and the shading model, defined once for the CPU reference and mirrored
//! by the shader.

pub use super::lighting::Light;
use super::lighting::Lighting;
use super::object::Hit;
use crate::geometry::Geometry;
use crate::space::Space;
use glam::{DVec3, DVec4};

/// Half a colour step of an 8-bit image.
pub const DEFAULT_CUTOFF_WEIGHT: f64 = 1.0 / 510.0;

/// The shading model, in one place (`docs/design.md` §4):
///
/// ```text
/// lit     = albedo · (ambient + (1 − ambient) · Σ_lights light · power · E_light)
/// surface = min(lit + emission, 1)                        per channel
/// colour  = e^(−d/λ) · surface + (1 − e^(−d/λ)) · fog     d = distance along the ray
/// ```
///
/// `E_light` is what [`Shading::light_from`] gathers as [`Shading::lighting`] says: every
/// image of the lamp in the cover within a reach, each by Lambert's cosine, the falloff
/// `1/max(S(d)², S(r₀)²)` (`r₀` a small radius that keeps it finite) and the fog's
/// absorption `e^(−d/λ)`, the nearest few walked for shadows, and the rest by its mean
/// ([`crate::scene::lighting`]); or, in the older model, the nearest copy only.
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
    /// What surfaces are coloured by over their shading (the teaching views).
    pub colour_by: ColourBy,
    /// The cell's walls with windows ([`crate::scene::walls`]); `None`: no walls.
    pub walls: Option<crate::scene::WallStyle>,
    /// How the lamps' light reaches surfaces: which images, the tail, shadows
    /// ([`crate::scene::lighting`]).
    pub lighting: Lighting,
}

/// What a teaching view colours each surface by, over its shading: the surface's lit
/// brightness times a tint ([`ColourBy::tint`]), then the fog as usual.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ColourBy {
    /// The plain picture.
    #[default]
    Shading,
    /// How many faces the ray crossed before it met the surface: tint `palette(k)`.
    Crossings,
    /// The last face the ray crossed: tint `palette(face)`, white where it crossed none.
    Face,
    /// The rotation of the copy of the cell the surface was seen in (its deck
    /// transformation, with the translation from the centre taken off), in bins of 30°:
    /// white for none, a colour per bin, other colours where the copy is mirrored.
    Holonomy,
}

impl ColourBy {
    /// Every mode, the plain picture first.
    pub const ALL: [ColourBy; 4] = [
        ColourBy::Shading,
        ColourBy::Crossings,
        ColourBy::Face,
        ColourBy::Holonomy,
    ];

    /// Its name on the command line and in the panel.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            ColourBy::Shading => "shading",
            ColourBy::Crossings => "crossings",
            ColourBy::Face => "face",
            ColourBy::Holonomy => "holonomy",
        }
    }

    /// The mode of a name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The shader's number for it (0 for the plain picture).
    #[must_use]
    pub fn index(self) -> u32 {
        self as u32
    }

    /// The tint of a surface seen after `crossings` crossings, the last through
    /// `last_face`, in the copy `h·D` of the cell (`h` the product of the pairings
    /// applied to the ray, [`holonomy_bin`]).
    #[must_use]
    pub fn tint(
        self,
        geometry: Geometry,
        crossings: usize,
        last_face: Option<usize>,
        h: glam::DMat4,
    ) -> DVec3 {
        match self {
            ColourBy::Shading => DVec3::ONE,
            ColourBy::Crossings => crate::scene::palette(crossings),
            ColourBy::Face => last_face.map_or(DVec3::ONE, crate::scene::palette),
            ColourBy::Holonomy => match holonomy_bin(geometry, h) {
                0 => DVec3::ONE,
                k => crate::scene::palette(k),
            },
        }
    }

    /// A surface's lit colour recoloured: its brightness times the tint.
    #[must_use]
    pub fn recolour(tint: DVec3, surface: DVec3) -> DVec3 {
        let lum = surface.dot(DVec3::new(0.2126, 0.7152, 0.0722)).min(1.0);
        tint * (0.25 + 0.75 * lum)
    }
}

/// The bin of a deck transformation's rotation: its rotation about the centre after the
/// translation taking the origin to `h·origin` is taken off, its angle in bins of 30° (0 to
/// 6), plus 7 for a mirrored (orientation-reversing) copy. The origin is the model's (the
/// cell's centre for spaces centred there, as the seeds and the library are).
#[must_use]
pub fn holonomy_bin(geometry: Geometry, h: glam::DMat4) -> usize {
    let q = h.w_axis;
    let k = geometry.kappa();
    let qs = q.truncate();
    // T_q⁻¹ h, upper-left block: (I − κ qs qsᵀ/(1 + q.w)) A₃ − qs bᵀ.
    let a3 = glam::DMat3::from_cols(
        h.x_axis.truncate(),
        h.y_axis.truncate(),
        h.z_axis.truncate(),
    );
    let b = DVec3::new(h.x_axis.w, h.y_axis.w, h.z_axis.w);
    let outer = |u: DVec3, v: DVec3| glam::DMat3::from_cols(u * v.x, u * v.y, u * v.z);
    let m = if k == 0.0 {
        a3
    } else {
        (glam::DMat3::IDENTITY - outer(qs, qs) * (k / (1.0 + q.w))) * a3 - outer(qs, b)
    };
    let mirrored = m.determinant() < 0.0;
    let r = if mirrored { -m } else { m };
    let trace = r.x_axis.x + r.y_axis.y + r.z_axis.z;
    let angle = ((trace - 1.0) / 2.0).clamp(-1.0, 1.0).acos();
    let bin = (angle / (std::f64::consts::PI / 6.0)).round() as usize;
    bin.min(6) + if mirrored { 7 } else { 0 }
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
            colour_by: ColourBy::Shading,
            walls: None,
            lighting: Lighting::default(),
        }
    }
}

impl Shading {
    /// The light a surface point (`point`, unit normal `normal`) gets from `light`, per unit
    /// of its colour × power, as [`Shading::lighting`] says
    /// ([`crate::scene::lighting::gather`]); `occluded` walks the shadow rays.
    #[must_use]
    pub fn light_from(
        &self,
        g: Geometry,
        light: &Light,
        point: DVec4,
        normal: DVec4,
        occluded: &mut crate::scene::lighting::Occluded<'_>,
    ) -> f64 {
        super::lighting::gather(
            &self.lighting,
            (self.fog_distance, self.near_light),
            g,
            light,
            point,
            normal,
            occluded,
        )
    }

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
        self.shade_tinted(geometry, lights, hit, d, None)
    }

    /// [`Shading::shade`] with the surface recoloured by `tint` ([`ColourBy::recolour`])
    /// before the fog, where given.
    #[must_use]
    pub fn shade_tinted(
        &self,
        geometry: Geometry,
        lights: &[Light],
        hit: &Hit,
        d: f64,
        tint: Option<DVec3>,
    ) -> DVec3 {
        self.shade_with(geometry, lights, hit, d, tint, &mut |_, _, _| false)
    }

    /// [`Shading::shade_tinted`] with the shadow rays walked by `occluded` (`shade` and
    /// `shade_tinted` walk none: they have no cell to walk).
    #[must_use]
    pub fn shade_with(
        &self,
        geometry: Geometry,
        lights: &[Light],
        hit: &Hit,
        d: f64,
        tint: Option<DVec3>,
        occluded: &mut crate::scene::lighting::Occluded<'_>,
    ) -> DVec3 {
        let mut lit = DVec3::splat(self.ambient);
        for light in lights {
            let e = self.light_from(geometry, light, hit.point, hit.normal, occluded);
            lit += (1.0 - self.ambient) * light.colour * (light.power * e);
        }
        let mut surface = (hit.colour * lit + hit.emission).min(DVec3::ONE);
        if let Some(t) = tint {
            surface = ColourBy::recolour(t, surface);
        }
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
    /// The share of light the surface reflects as a mirror, 0 to 1 (the rest is lit as
    /// usual): [`crate::trace::render`] follows the reflected ray.
    pub reflectance: f64,
}

impl Default for SurfaceMaterial {
    fn default() -> Self {
        Self {
            colour: DVec3::splat(0.8),
            texture: None,
            emission: DVec3::ZERO,
            reflectance: 0.0,
        }
    }
}
