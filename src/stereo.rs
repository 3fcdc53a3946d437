//! Stereo views that stay correct in curved space (`DESIGN.md` §4).
//!
//! Each eye is the head's frame moved by ∓IPD/2 along the head's own `right` tangent: a
//! geodesic translation of the space (`F·T(right, ±b/2)`), not an offset in the chart, so the
//! parallax is the one the geometry gives and the eye axis follows head roll. An eye that
//! ends up past a face is wrapped into the cell with its own pairing, so both eyes always
//! see from inside the cell even when the head is on a face.
//!
//! The pixel mapping of every layout (mono, side-by-side, top-bottom, anaglyph) is defined
//! here once, in [`ViewLayout`]; the CPU reference renders through it and the GPU packer
//! writes it into the shader's uniform, where `shaders/curved_space.wgsl` mirrors it.

use crate::geometry::Geometry;
use crate::player::translate_local;
use crate::space::Space;
use crate::trace::Ray;
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::fmt;
use std::str::FromStr;

/// How the two eyes' pictures share the output image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum StereoMode {
    /// One eye at the head's position.
    #[default]
    Mono,
    /// Left eye on the left half, right eye on the right; each half keeps its own aspect
    /// ratio (for cross-eyed or parallel free viewing and cardboard viewers).
    SideBySide,
    /// Each eye sees the whole image's field of view squeezed into half the width, as 3D
    /// TVs and projectors expect (they stretch it back).
    SideBySideHalf,
    /// Left eye on the top half, right eye on the bottom; each half keeps its aspect.
    TopBottom,
    /// Each eye sees the whole image's field of view squeezed into half the height.
    TopBottomHalf,
    /// Red–cyan anaglyph with Dubois' least-squares matrices: the colours are kept as well
    /// as red–cyan glasses allow, with little ghosting.
    AnaglyphDubois,
    /// Red–cyan "optimized" anaglyph: the left eye's red is made from its green and blue,
    /// which removes retinal rivalry on red objects at the cost of their red.
    AnaglyphOptimized,
    /// Plain red–cyan colour anaglyph: red from the left eye, green and blue from the right.
    AnaglyphRedCyan,
}

impl StereoMode {
    /// Every mode, in the order the UI lists them.
    pub const ALL: [StereoMode; 8] = [
        StereoMode::Mono,
        StereoMode::SideBySide,
        StereoMode::SideBySideHalf,
        StereoMode::TopBottom,
        StereoMode::TopBottomHalf,
        StereoMode::AnaglyphDubois,
        StereoMode::AnaglyphOptimized,
        StereoMode::AnaglyphRedCyan,
    ];

    /// The name used on the command line and in files.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            StereoMode::Mono => "mono",
            StereoMode::SideBySide => "side-by-side",
            StereoMode::SideBySideHalf => "side-by-side-half",
            StereoMode::TopBottom => "top-bottom",
            StereoMode::TopBottomHalf => "top-bottom-half",
            StereoMode::AnaglyphDubois => "anaglyph",
            StereoMode::AnaglyphOptimized => "anaglyph-optimized",
            StereoMode::AnaglyphRedCyan => "anaglyph-red-cyan",
        }
    }

    /// A short description for menus.
    #[must_use]
    pub const fn label(self) -> &'static str {
        match self {
            StereoMode::Mono => "mono",
            StereoMode::SideBySide => "side by side",
            StereoMode::SideBySideHalf => "side by side, half width (3D TV)",
            StereoMode::TopBottom => "top and bottom",
            StereoMode::TopBottomHalf => "top and bottom, half height (3D TV)",
            StereoMode::AnaglyphDubois => "anaglyph red–cyan (Dubois)",
            StereoMode::AnaglyphOptimized => "anaglyph red–cyan (optimized)",
            StereoMode::AnaglyphRedCyan => "anaglyph red–cyan (plain)",
        }
    }

    /// How the shader must be specialised for this mode.
    #[must_use]
    pub const fn kind(self) -> ViewKind {
        match self {
            StereoMode::Mono => ViewKind::Mono,
            StereoMode::SideBySide
            | StereoMode::SideBySideHalf
            | StereoMode::TopBottom
            | StereoMode::TopBottomHalf => ViewKind::Split,
            StereoMode::AnaglyphDubois
            | StereoMode::AnaglyphOptimized
            | StereoMode::AnaglyphRedCyan => ViewKind::Anaglyph,
        }
    }

    /// Whether the eyes share the picture side by side (x) or on top of each other (y).
    #[must_use]
    pub const fn split_axes(self) -> [bool; 2] {
        match self {
            StereoMode::SideBySide | StereoMode::SideBySideHalf => [true, false],
            StereoMode::TopBottom | StereoMode::TopBottomHalf => [false, true],
            _ => [false, false],
        }
    }

    /// Whether two eyes are drawn.
    #[must_use]
    pub const fn is_stereo(self) -> bool {
        !matches!(self, StereoMode::Mono)
    }

    /// The anaglyph's matrices `(M_left, M_right)`: the output's linear RGB is
    /// `M_left·left + M_right·right` (clamped), both eyes' colours in linear RGB.
    #[must_use]
    pub fn anaglyph_matrices(self) -> Option<(DMat3, DMat3)> {
        // Rows as written in the sources; glam matrices are built from columns.
        let rows = |r: [[f64; 3]; 3]| {
            DMat3::from_cols_array_2d(&r).transpose() // rows → columns
        };
        match self {
            // E. Dubois, "A projection method to generate anaglyph stereo images", ICASSP
            // 2001; the red–cyan matrices from his published table.
            StereoMode::AnaglyphDubois => Some((
                rows([
                    [0.456100, 0.500484, 0.176381],
                    [-0.0400822, -0.0378246, -0.0157589],
                    [-0.0152161, -0.0205971, -0.00546856],
                ]),
                rows([
                    [-0.0434706, -0.0879388, -0.00155529],
                    [0.378476, 0.73364, -0.0184503],
                    [-0.0721527, -0.112961, 1.2264],
                ]),
            )),
            StereoMode::AnaglyphOptimized => Some((
                rows([[0.0, 0.7, 0.3], [0.0; 3], [0.0; 3]]),
                rows([[0.0; 3], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
            )),
            StereoMode::AnaglyphRedCyan => Some((
                rows([[1.0, 0.0, 0.0], [0.0; 3], [0.0; 3]]),
                rows([[0.0; 3], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
            )),
            _ => None,
        }
    }
}

impl fmt::Display for StereoMode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(self.name())
    }
}

/// A stereo mode name that is not one of [`StereoMode::ALL`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown stereo mode {0:?}; the modes are: {modes}", modes = StereoMode::ALL.map(StereoMode::name).join(", "))]
pub struct UnknownStereoMode(pub String);

impl FromStr for StereoMode {
    type Err = UnknownStereoMode;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let wanted = s.trim().to_ascii_lowercase().replace('_', "-");
        StereoMode::ALL
            .into_iter()
            .find(|m| m.name() == wanted)
            .or(match wanted.as_str() {
                "sbs" => Some(StereoMode::SideBySide),
                "tb" | "over-under" => Some(StereoMode::TopBottom),
                "anaglyph-dubois" => Some(StereoMode::AnaglyphDubois),
                _ => None,
            })
            .ok_or_else(|| UnknownStereoMode(s.to_string()))
    }
}

/// What the shader is specialised on for a view: one eye, two eyes in two parts of the
/// image, or two eyes traced per pixel and mixed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ViewKind {
    #[default]
    Mono,
    Split,
    Anaglyph,
}

/// A typical adult's interpupillary distance, in metres.
pub const HUMAN_IPD_METRES: f64 = 0.064;

/// How tall the cell's inradius feels by default, in metres: a room-sized cell.
pub const DEFAULT_INRADIUS_METRES: f64 = 1.5;

/// The default eye distance for a cell of inradius `inradius`: a human IPD at the scale at
/// which the inradius feels like [`DEFAULT_INRADIUS_METRES`].
#[must_use]
pub fn default_ipd(inradius: f64) -> f64 {
    inradius * HUMAN_IPD_METRES / DEFAULT_INRADIUS_METRES
}

/// The stereo options of the curved-space cameras (a resource; changeable at run time).
#[derive(bevy::prelude::Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct StereoSettings {
    pub mode: StereoMode,
    /// Distance between the eyes in the space's units (geodesic); `None` for
    /// [`default_ipd`] of the cell. It sets the world scale: how big the cell feels.
    pub ipd: Option<f64>,
    /// Show the right eye where the left one belongs and vice versa (cross-eyed viewing of
    /// side-by-side pictures).
    pub swap_eyes: bool,
}

impl StereoSettings {
    /// The eye distance in use for a cell of this inradius: the chosen one, or the default
    /// where none is chosen or the chosen one fails [`check_ipd`].
    #[must_use]
    pub fn ipd_for(&self, inradius: f64) -> f64 {
        self.ipd
            .filter(|&ipd| check_ipd(ipd, inradius).is_ok())
            .unwrap_or_else(|| default_ipd(inradius))
    }

    /// Space units per metre at this eye distance (the "world scale").
    #[must_use]
    pub fn units_per_metre(&self, inradius: f64) -> f64 {
        self.ipd_for(inradius) / HUMAN_IPD_METRES
    }
}

/// A bad stereo setting.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StereoError {
    #[error("the eye distance (IPD) must be a positive finite number of space units, got {0}")]
    BadIpd(f64),
    #[error(
        "an eye distance of {ipd} is more than the cell's inradius {inradius}: the eyes would see different cells' worth of space; use a smaller IPD"
    )]
    IpdTooLarge { ipd: f64, inradius: f64 },
}

/// Checks an eye distance against the cell.
pub fn check_ipd(ipd: f64, inradius: f64) -> Result<(), StereoError> {
    if !(ipd.is_finite() && ipd > 0.0) {
        return Err(StereoError::BadIpd(ipd));
    }
    if ipd > inradius {
        return Err(StereoError::IpdTooLarge { ipd, inradius });
    }
    Ok(())
}

/// One eye: its frame inside the cell and the faces it was wrapped through.
#[derive(Clone, Debug, PartialEq)]
pub struct Eye {
    /// Columns right, up, back, position, inside the cell.
    pub frame: DMat4,
    /// Faces crossed to bring the eye into the cell, in order (empty when it was inside).
    pub crossed: Vec<usize>,
    /// The product of those pairings: `frame = pairing · (head · T(right, offset))`.
    pub pairing: DMat4,
}

/// The frame moved by `offset` along its own `right` tangent (a geodesic translation) and
/// then wrapped into the cell through the faces it is past.
#[must_use]
pub fn offset_eye(space: &Space, head: DMat4, offset: f64) -> Eye {
    wrap_eye(
        space,
        translate_local(space.geometry, head, DVec3::X * offset),
    )
}

/// A frame wrapped into the cell (no margin: an eye past a face by any amount is moved).
#[must_use]
pub fn wrap_eye(space: &Space, frame: DMat4) -> Eye {
    let (frame, crossed) = crate::player::wrap_into_cell(space, frame, 0.0);
    let pairing = crossed
        .iter()
        .fold(DMat4::IDENTITY, |m, &f| space.faces[f].pairing * m);
    Eye {
        frame,
        crossed,
        pairing,
    }
}

/// The two eyes of a head frame `[left, right]`, `ipd` apart along the head's `right`.
#[must_use]
pub fn eye_frames(space: &Space, head: DMat4, ipd: f64) -> [Eye; 2] {
    [
        offset_eye(space, head, -ipd / 2.0),
        offset_eye(space, head, ipd / 2.0),
    ]
}

/// A view frustum as the tangents of its four half-angles: a camera ray through image point
/// `(u, v)` ∈ [0, 1]² (v down) has direction `x·right + y·up − back` with
/// `x = left·(1−u) + right·u` and `y = top·(1−v) + bottom·v`. `left` and `bottom` are
/// negative for a frustum around the view axis; XR views are asymmetric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    pub left: f64,
    pub right: f64,
    pub bottom: f64,
    pub top: f64,
}

impl Lens {
    /// A symmetric frustum of vertical field of view `fov_y_degrees` and aspect ratio
    /// (width / height) `aspect`.
    #[must_use]
    pub fn symmetric(fov_y_degrees: f64, aspect: f64) -> Self {
        let half = (fov_y_degrees.to_radians() / 2.0).tan();
        Self {
            left: -half * aspect,
            right: half * aspect,
            bottom: -half,
            top: half,
        }
    }

    /// From the four half-angles in radians (OpenXR's `Fovf`: left and down negative).
    #[must_use]
    pub fn from_angles(left: f64, right: f64, down: f64, up: f64) -> Self {
        Self {
            left: left.tan(),
            right: right.tan(),
            bottom: down.tan(),
            top: up.tan(),
        }
    }

    /// The direction coefficients `(x, y)` of image point `(u, v)`.
    #[must_use]
    pub fn at(&self, u: f64, v: f64) -> (f64, f64) {
        (
            self.left * (1.0 - u) + self.right * u,
            self.top * (1.0 - v) + self.bottom * v,
        )
    }
}

/// How a view's pixels map to eyes and camera rays: what the CPU reference renders and the
/// GPU packer writes into the shader's `View` (the shader mirrors [`ViewLayout::rays_at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewLayout {
    /// The eyes' frames `[left, right]` (both the head's frame in mono).
    pub frames: [DMat4; 2],
    /// The frustum of each eye's picture.
    pub lens: Lens,
    /// The view's size in pixels.
    pub size: [f64; 2],
    /// Where the second half of the image starts (pixels, in x for side-by-side, in y for
    /// top-bottom; 0 for none).
    pub split: [f64; 2],
    /// Whether the left half shows the right eye.
    pub swap_eyes: bool,
    pub kind: ViewKind,
    /// The anaglyph's matrices (identity and zero otherwise).
    pub anaglyph: (DMat3, DMat3),
}

/// The camera rays of one pixel: one, or two for an anaglyph (left eye first).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelRays {
    One(Ray<DVec4>),
    Two(Ray<DVec4>, Ray<DVec4>),
}

impl ViewLayout {
    /// A layout for a view of `width × height` pixels with vertical field of view
    /// `fov_y_degrees` (each eye's picture has it).
    #[must_use]
    pub fn new(
        stereo: StereoMode,
        swap_eyes: bool,
        eyes: [DMat4; 2],
        fov_y_degrees: f64,
        width: u32,
        height: u32,
    ) -> Self {
        let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
        let [split_x, split_y] = stereo.split_axes();
        let split = [
            if split_x { w / 2.0 } else { 0.0 },
            if split_y { h / 2.0 } else { 0.0 },
        ];
        // Each eye's picture keeps its own aspect, unless squeezed into its half (3D TVs).
        let aspect = match stereo {
            StereoMode::SideBySideHalf | StereoMode::TopBottomHalf => w / h,
            _ if split_x => (w / 2.0) / h,
            _ if split_y => w / (h / 2.0),
            _ => w / h,
        };
        Self {
            frames: eyes,
            lens: Lens::symmetric(fov_y_degrees, aspect),
            size: [w, h],
            split,
            swap_eyes,
            kind: stereo.kind(),
            anaglyph: stereo
                .anaglyph_matrices()
                .unwrap_or((DMat3::IDENTITY, DMat3::ZERO)),
        }
    }

    /// A mono view with its own frustum (an XR eye).
    #[must_use]
    pub fn mono(frame: DMat4, lens: Lens, width: u32, height: u32) -> Self {
        Self {
            frames: [frame; 2],
            lens,
            size: [f64::from(width.max(1)), f64::from(height.max(1))],
            split: [0.0, 0.0],
            swap_eyes: false,
            kind: ViewKind::Mono,
            anaglyph: (DMat3::IDENTITY, DMat3::ZERO),
        }
    }

    /// Which eye (0 left, 1 right) a pixel centre `(x, y)` shows, and its point `(u, v)`
    /// in that eye's picture. Anaglyph and mono views answer eye 0 over the whole view.
    #[must_use]
    pub fn eye_at(&self, x: f64, y: f64) -> (usize, [f64; 2]) {
        let [sx, sy] = self.split;
        let second = (sx > 0.0 && x >= sx) || (sy > 0.0 && y >= sy);
        let half = usize::from(self.kind == ViewKind::Split && second);
        let (x, y) = (x - half as f64 * sx, y - half as f64 * sy);
        let eye_w = if sx > 0.0 { sx } else { self.size[0] };
        let eye_h = if sy > 0.0 { sy } else { self.size[1] };
        let eye = if self.kind == ViewKind::Split {
            half ^ usize::from(self.swap_eyes)
        } else {
            0
        };
        (eye, [x / eye_w, y / eye_h])
    }

    /// The unit camera ray of eye `eye` through image point `(u, v)`.
    #[must_use]
    pub fn ray(&self, geometry: Geometry, eye: usize, u: f64, v: f64) -> Ray<DVec4> {
        let f = self.frames[eye];
        let (x, y) = self.lens.at(u, v);
        let point = f.w_axis;
        Ray {
            point,
            tangent: geometry.unit_tangent(point, x * f.x_axis + y * f.y_axis - f.z_axis),
        }
    }

    /// The camera ray through the centre of pixel `(i, j)`: the left eye's for an anaglyph.
    #[must_use]
    pub fn ray_at(&self, geometry: Geometry, i: u32, j: u32) -> Ray<DVec4> {
        match self.rays_at(geometry, i, j) {
            PixelRays::One(ray) | PixelRays::Two(ray, _) => ray,
        }
    }

    /// The camera rays through the centre of pixel `(i, j)`.
    #[must_use]
    pub fn rays_at(&self, geometry: Geometry, i: u32, j: u32) -> PixelRays {
        let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        let (eye, [u, v]) = self.eye_at(x, y);
        match self.kind {
            ViewKind::Anaglyph => {
                PixelRays::Two(self.ray(geometry, 0, u, v), self.ray(geometry, 1, u, v))
            }
            _ => PixelRays::One(self.ray(geometry, eye, u, v)),
        }
    }

    /// The anaglyph's colour (8-bit-encoded values in [0, 1], as the tracer's colours are)
    /// from the two eyes' colours: decoded to linear RGB, mixed, clamped and encoded again.
    #[must_use]
    pub fn mix_anaglyph(&self, left: DVec3, right: DVec3) -> DVec3 {
        let (ml, mr) = self.anaglyph;
        let linear = ml * srgb_to_linear(left) + mr * srgb_to_linear(right);
        linear_to_srgb(linear.clamp(DVec3::ZERO, DVec3::ONE))
    }
}

/// The sRGB transfer function's inverse (encoded → linear), per channel.
#[must_use]
pub fn srgb_to_linear(c: DVec3) -> DVec3 {
    let f = |c: f64| {
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    DVec3::new(f(c.x), f(c.y), f(c.z))
}

/// The sRGB transfer function (linear → encoded), per channel.
#[must_use]
pub fn linear_to_srgb(c: DVec3) -> DVec3 {
    let f = |c: f64| {
        if c <= 0.0031308 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
    };
    DVec3::new(f(c.x), f(c.y), f(c.z))
}
