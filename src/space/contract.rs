//! The geometry contract: what a family's space provides so that the walk, the player, the
//! entities and the plugin's systems are written once for every family.
//!
//! A family implements [`FamilySpace`] on its validated space type (the constant-curvature
//! [`Space`] here, the product spaces' in their folder): its walker in each precision (the
//! [`CellWalk`] contract: exits, crossings and steps, with the walk loop written once over
//! it), and the motion of frames (a player's step, an entity's velocity, and the wrap back
//! into the cell through the faces, each crossing with its pairing for the holonomy). The
//! plugin registers one generic set of systems per family (`plugin::family`), and the
//! registry ([`super::AnySpace`]) hands each the space of its own type.

use super::motion::Velocity;
use super::walk::{CellWalk, CellWalker};
use super::wrap::{frame_on_model, wrap_into_cell};
use super::{Family, Space};
use crate::geometry::{Geometry, Ray, Vector4, translate_local};
use glam::{DMat4, DVec3, DVec4};

/// How a frame is asked to move in one step, in its own axes (a player's controls).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameMotion {
    /// Distance along right, up and back (geodesic units).
    pub translation: DVec3,
    /// Angles (radians) to turn about right (pitch), up (yaw) and back (roll).
    pub rotation: DVec3,
    /// Keep the family's "up" (the fibre of a product space) where it is: walking stays
    /// level and yaw turns about it. Families without a preferred up ignore it.
    pub level: bool,
}

/// A face a frame crossed on its way back into the cell, with the pairing applied to it
/// (its linear part where the pairing also shifts along a fibre), for the [`super::Holonomy`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameCrossing {
    /// The face left through (numbered as the family's walk numbers its exits).
    pub face: usize,
    /// The pairing applied (its linear part where it also shifts along a fibre).
    pub pairing: DMat4,
    /// How far the pairing shifted the point along a product's fibre (the top and the
    /// bottom: a circle down or up, several at once past a far height); 0 elsewhere.
    pub fibre_shift: f64,
}

/// A geometry family's validated space: the contract every family implements. Its walker
/// is here (generic over precision); the rest, which needs no type of its own, is
/// [`FrameSpace`], which a caller may hold as `&dyn FrameSpace` whatever the family
/// ([`crate::space::AnySpace::frames`]).
pub trait FamilySpace: FrameSpace + Sized + 'static {
    /// The family.
    const FAMILY: Family;

    /// The walker of this family in the precision of `V` (`DVec4` f64, `Vec4` f32,
    /// `DdVec4` double-double).
    type Walker<V: Vector4>: CellWalk<V>;

    /// The walker of this space in the precision of `V`.
    #[must_use]
    fn walker<V: Vector4>(&self) -> Self::Walker<V>;
}

/// The part of the geometry contract that is the same for every precision: the chart, the
/// cell, and the motion of frames (players, entities, stereo and headset eyes).
pub trait FrameSpace: Send + Sync + std::fmt::Debug {
    /// The unit ray from the chart point `from` along the chart direction `dir` (the
    /// family's chart: the gnomonic chart in E³, S³ and H³; the surface's chart and the
    /// height in a product); an error names a point or direction the chart cannot take.
    fn chart_ray(&self, from: DVec3, dir: DVec3) -> Result<Ray<DVec4>, String>;

    /// How far the model point `p` lies outside the cell (at most 0 inside; NaN, a point the
    /// model cannot hold, counts as outside).
    #[must_use]
    fn outside_by(&self, p: DVec4) -> f64;

    /// How many faces the cell has (a walk's face indices are below it).
    #[must_use]
    fn face_count(&self) -> usize;

    /// A length of the cell's size: walking speeds, eye distances and the default fog are
    /// measured in it.
    #[must_use]
    fn scale(&self) -> f64;

    /// How far `frame`'s first three columns are from orthonormal in the metric at its
    /// position (the largest entry of `FᵀGF − I`).
    #[must_use]
    fn frame_defect(&self, frame: DMat4) -> f64;

    /// The frame after one step of `motion` in its own axes, exactly along the geodesic,
    /// not yet wrapped back into the cell.
    #[must_use]
    fn step_frame(&self, frame: DMat4, motion: &FrameMotion) -> DMat4;

    /// The frame after `dt` seconds of `velocity` (linear and angular, in the frame's own
    /// axes), back on the model; a non-finite velocity or time leaves it where it is.
    #[must_use]
    fn step_velocity(&self, frame: DMat4, velocity: &Velocity, dt: f64) -> DMat4;

    /// The frame brought back into the cell once it is past a face by more than `margin`,
    /// through the faces' pairings, with the faces it crossed in order.
    #[must_use]
    fn wrap_frame(&self, frame: DMat4, margin: f64) -> (DMat4, Vec<FrameCrossing>);

    /// The frame with the viewer's axes turned by `rotation` (a rotation of the axes' own
    /// coordinates: the new axes are the old ones times it), its point kept. By default the
    /// frame's first three columns are turned as 4-vectors, which serves every family whose
    /// axes are tangent vectors in the frame's columns; a family that keeps more of its point
    /// in those columns (SL̃(2,R)'s `e`, in their fourth entries) turns only the axes.
    #[must_use]
    fn turn_axes(&self, frame: DMat4, rotation: glam::DMat3) -> DMat4 {
        frame * DMat4::from_mat3(rotation)
    }

    /// The two eyes of a head `ipd` apart, left first: each half the distance along the
    /// head's right, its frame carried along the geodesic and wrapped into the cell on its
    /// own (no margin).
    #[must_use]
    fn eye_frames(&self, head: DMat4, ipd: f64) -> [DMat4; 2] {
        [-0.5 * ipd, 0.5 * ipd].map(|t| {
            let eye = self.step_frame(
                head,
                &FrameMotion {
                    translation: DVec3::X * t,
                    rotation: DVec3::ZERO,
                    level: false,
                },
            );
            self.wrap_frame(eye, 0.0).0
        })
    }
}

/// The body direction (its length the step's) of a *level* step in a family whose "up" is
/// the third body axis (Nil's `E₃`, SL̃(2,R)'s fibre `V`): forward and sideways along the
/// horizontal parts of the frame's back and right (their up parts removed), at the step's
/// horizontal length, and up along that axis by `d.y`.
#[must_use]
pub fn level_step(right: DVec3, back: DVec3, d: DVec3) -> DVec3 {
    let flat = |v: DVec3| DVec3::new(v.x, v.y, 0.0);
    let h = flat(right) * d.x + flat(back) * d.z;
    let scale = d.x.hypot(d.z);
    let horizontal = if h.length() > 1e-12 {
        h * (scale / h.length())
    } else {
        DVec3::ZERO
    };
    horizontal + DVec3::Z * d.y
}

/// The frame after a local motion in a constant-curvature geometry: translated along the
/// local direction, then turned about right, up and back in that order, each by its angle.
#[must_use]
pub fn step_constant_frame(
    geometry: Geometry,
    frame: DMat4,
    translation: DVec3,
    rotation: DVec3,
) -> DMat4 {
    let mut f = translate_local(geometry, frame, translation);
    for (axis, angle) in [
        (DVec3::X, rotation.x),
        (DVec3::Y, rotation.y),
        (DVec3::Z, rotation.z),
    ] {
        if angle != 0.0 && angle.is_finite() {
            f *= geometry.rotation(axis, angle);
        }
    }
    f
}

impl FamilySpace for Space {
    const FAMILY: Family = Family::Constant;
    type Walker<V: Vector4> = CellWalker<V>;

    fn walker<V: Vector4>(&self) -> CellWalker<V> {
        CellWalker::new(self)
    }
}

impl FrameSpace for Space {
    fn chart_ray(&self, from: DVec3, dir: DVec3) -> Result<Ray<DVec4>, String> {
        crate::geometry::chart_ray(self.geometry, from, dir).map_err(|e| e.to_string())
    }

    fn outside_by(&self, p: DVec4) -> f64 {
        Space::outside_by(self, p)
    }

    fn face_count(&self) -> usize {
        self.faces.len()
    }

    fn scale(&self) -> f64 {
        super::invariants::inradius(self)
    }

    fn frame_defect(&self, frame: DMat4) -> f64 {
        self.geometry.frame_defect(frame)
    }

    fn step_frame(&self, frame: DMat4, motion: &FrameMotion) -> DMat4 {
        step_constant_frame(self.geometry, frame, motion.translation, motion.rotation)
    }

    fn step_velocity(&self, frame: DMat4, velocity: &Velocity, dt: f64) -> DMat4 {
        if velocity.is_zero() {
            return frame;
        }
        frame_on_model(self, velocity.step(self.geometry, frame, dt))
    }

    fn wrap_frame(&self, frame: DMat4, margin: f64) -> (DMat4, Vec<FrameCrossing>) {
        let (wrapped, crossed) = wrap_into_cell(self, frame, margin);
        let crossed = crossed
            .into_iter()
            .map(|face| FrameCrossing {
                face,
                pairing: self.faces[face].pairing,
                fibre_shift: 0.0,
            })
            .collect();
        (wrapped, crossed)
    }
}
