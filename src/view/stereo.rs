//! Stereo views that stay correct in curved space (`docs/design.md` §7).
//!
//! Each eye is the head's frame moved by ∓IPD/2 along the head's own `right` tangent: a
//! geodesic translation of the space (`F·T(right, ±b/2)`), not an offset in the chart, so the
//! parallax is the one the geometry gives and the eye axis follows head roll. An eye that
//! ends up past a face is wrapped into the cell with its own pairing, so both eyes always
//! see from inside the cell even when the head is on a face.

use super::ViewKind;
use crate::geometry::translate_local;
use crate::space::Space;
use glam::{DMat3, DMat4, DVec3};
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

/// A bad stereo setting.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StereoError {
    /// The eye distance (IPD, attached) is not a positive finite number of space units.
    #[error("the eye distance (IPD) must be a positive finite number of space units, got {0}")]
    BadIpd(f64),
    /// An eye distance of `ipd` is more than the cell's inradius `inradius`: the eyes would see different cells' worth of space.
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

/// A frame wrapped into the cell of a space of any family (no margin: an eye past a face by
/// any amount is moved).
#[must_use]
pub fn wrap_eye<S: crate::space::FamilySpace>(space: &S, frame: DMat4) -> Eye {
    let (frame, crossed) = space.wrap_frame(frame, 0.0);
    let pairing = crossed.iter().fold(DMat4::IDENTITY, |m, c| c.pairing * m);
    Eye {
        frame,
        crossed: crossed.iter().map(|c| c.face).collect(),
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
