//! `UT Σ` under the geometry contract: its chart, its cell and the motion of frames.
//!
//! A frame of the contract (`DMat4`) holds, for SL̃(2,R), the point `(p, e)` and the
//! viewer's axes: the columns' first three entries are the right, up and back axes as body
//! vectors in `(X, Y, V)`, their fourth entries are `e = (e_x, e_y, e_w)`, and the last
//! column is `(p_x, p_y, p_w, 1 + k)` (so `w_axis` is the base point, as the other families'
//! positions are; `k` is a fibre cover's sheet, 0 in `UT Σ`). A frame moves along the geodesic of its motion with its axes' body
//! components kept: the motion is the left translation carrying the start to the end, an
//! isometry, as the gluings are. The chart of `trace --from x,y,θ` is the reference's:
//! `p = (x, y, √(1 + x² + y²))`, `e = cos θ E₁ + sin θ E₂` with `(E₁, E₂)` the boost of the
//! origin's `(∂x, ∂y)` to `p`.

use super::flow::{Sl2rRay, flow, moved_by, on_model};
use super::space::UnitTangentSpace;
use super::walk::Sl2rWalker;
use crate::geometry::{Ray, Vector4};
use crate::space::Family;
use crate::space::contract::{FamilySpace, FrameCrossing, FrameMotion, FrameSpace};
use crate::space::motion::Velocity;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// The most pairings one wrap applies (a frame far outside is refused by the chart).
const MAX_WRAPS: usize = 64;

/// The point `(p, e)` of a frame, with the velocity `v`.
fn point_of(frame: &DMat4, v: [f64; 3]) -> Sl2rRay<f64> {
    let p = frame.w_axis.truncate().to_array();
    let e = [frame.x_axis.w, frame.y_axis.w, frame.z_axis.w];
    Sl2rRay {
        frame: [e, super::flow::perp(p, e), p],
        velocity: v,
    }
}

/// The viewer's axes (right, up, back as body vectors, columns).
fn axes_of(frame: &DMat4) -> DMat3 {
    DMat3::from_cols(
        frame.x_axis.truncate(),
        frame.y_axis.truncate(),
        frame.z_axis.truncate(),
    )
}

/// The fibre cover's sheet of a frame (its last column's fourth entry less 1).
#[must_use]
pub fn frame_sheet(frame: &DMat4) -> u32 {
    let k = (frame.w_axis.w - 1.0).round();
    if k >= 0.0 && k < f64::from(u32::MAX) {
        k as u32
    } else {
        0
    }
}

/// The frame of the point `r` on `sheet` with the viewer's `axes`.
fn frame_of(r: &Sl2rRay<f64>, axes: DMat3, sheet: u32) -> DMat4 {
    let [e, _, p] = r.frame;
    DMat4::from_cols(
        axes.x_axis.extend(e[0]),
        axes.y_axis.extend(e[1]),
        axes.z_axis.extend(e[2]),
        DVec3::from_array(p).extend(1.0 + f64::from(sheet)),
    )
}

/// Axes made orthonormal again (Gram–Schmidt, right-handed).
fn orthonormal(axes: DMat3) -> DMat3 {
    let x = axes.x_axis.normalize();
    let y = (axes.y_axis - x * x.dot(axes.y_axis)).normalize();
    DMat3::from_cols(x, y, x.cross(y))
}

/// The point `r` on `sheet` moved along the body direction `u` (any length) by its length,
/// with the sheet it reaches in a cover of `sheets`.
fn moved_along(r: &Sl2rRay<f64>, sheet: u32, sheets: u32, u: DVec3) -> (Sl2rRay<f64>, u32) {
    let length = u.length();
    if !(length > 0.0) || !length.is_finite() {
        return (*r, sheet);
    }
    let ray = Sl2rRay {
        frame: r.frame,
        velocity: (u / length).to_array(),
    };
    let end = on_model(&flow(&ray, length));
    if sheets <= 1 {
        return (end, sheet);
    }
    let climbed = super::cover::sheets_climbed(&ray, length, &end.frame).unwrap_or(0);
    (end, super::cover::sheet_plus(sheet, climbed, sheets))
}

/// A 3×3 pairing of `H²` (rows, on `(x, y, w)`) as the 4×4 the holonomy composes, the
/// fibre's coordinate (the third) fixed, as the product spaces write theirs.
fn pairing_matrix(m: &[[f64; 3]; 3]) -> DMat4 {
    let idx = [0, 1, 3];
    let mut out = DMat4::IDENTITY;
    for (r, &i) in idx.iter().enumerate() {
        for (c, &j) in idx.iter().enumerate() {
            out.col_mut(j)[i] = m[r][c];
        }
    }
    out
}

impl UnitTangentSpace {
    /// The sides' covectors and pairings in `f64`.
    fn sides_f64(&self) -> Vec<([f64; 3], [[f64; 3]; 3])> {
        self.sides()
            .iter()
            .map(|s| (s.normal.map(|x| x.hi), s.pairing.map(|r| r.map(|x| x.hi))))
            .collect()
    }

    /// The side the base point `p` lies farthest outside of, and by how far (the distance
    /// in `H²` to the side's geodesic, negative inside).
    fn farthest_past(&self, p: [f64; 3]) -> (usize, f64) {
        let cosh_rho = self.inradius().cosh();
        let mut best = (0, f64::NEG_INFINITY);
        for (i, (n, _)) in self.sides_f64().iter().enumerate() {
            let d = (cosh_rho * (n[0] * p[0] + n[1] * p[1] + n[2] * p[2])).asinh();
            if !(d <= best.1) {
                best = (i, d);
            }
        }
        best
    }

    /// The ray `r` brought into the cell by the sides' pairings (its base point into the
    /// polygon, up to rounding), its body velocity kept.
    #[must_use]
    pub fn into_cell(&self, r: &Sl2rRay<f64>) -> Sl2rRay<f64> {
        self.wrap_point(r, 0, 0.0).0
    }

    /// The point of the space at the chart point `[x, y, θ]` (`θ` lifted: its whole turns
    /// name the sheet of a fibre cover), brought into the cell: its frame (columns `e`, `e⊥`,
    /// `p`) and its sheet. The message says why a point is refused (as [`FrameSpace::chart_ray`]).
    pub fn frame_at_chart_point(&self, point: DVec3) -> Result<([[f64; 3]; 3], u32), String> {
        let ray = self.chart_ray(point, DVec3::X)?;
        Ok((
            Sl2rWalker::<DVec4>::sl2r_ray(&ray).frame,
            Sl2rWalker::<DVec4>::sheet_of(&ray),
        ))
    }

    /// The sheets a point of `UT H²` climbs as the sides' pairings bring it into the cell
    /// (modulo the cover's `N`): a frame of `UT H²` on sheet `k` is on sheet `k` plus this once
    /// in the cell, whichever sides bring it there (the lifted pairings compose consistently,
    /// [`UnitTangentSpace::euler_turns`]).
    #[must_use]
    pub fn sheets_into_cell(&self, frame: &[[f64; 3]; 3]) -> u32 {
        let r = Sl2rRay {
            frame: *frame,
            velocity: [0.0; 3],
        };
        self.wrap_point(&r, 0, 0.0).1
    }

    /// The point `r` on `sheet` brought into the cell by the sides' pairings once it is past
    /// a side by more than `margin`, with the sheet it is then on and the sides crossed.
    fn wrap_point(
        &self,
        r: &Sl2rRay<f64>,
        sheet: u32,
        margin: f64,
    ) -> (Sl2rRay<f64>, u32, Vec<usize>) {
        let sides = self.sides_f64();
        let (mut r, mut sheet) = (*r, sheet);
        let mut crossed = Vec::new();
        for _ in 0..MAX_WRAPS {
            let (face, past) = self.farthest_past(r.frame[2]);
            if !(past > margin) {
                break;
            }
            let moved = on_model(&moved_by(&sides[face].1, &r));
            if self.sheets() > 1 {
                let climbed = self.sheets_through(face, &r.frame, &moved.frame);
                sheet = super::cover::sheet_plus(sheet, climbed, self.sheets());
            }
            r = moved;
            crossed.push(face);
        }
        (r, sheet, crossed)
    }
}

impl FamilySpace for UnitTangentSpace {
    const FAMILY: Family = Family::Sl2r;
    type Walker<V: Vector4> = Sl2rWalker<V>;

    fn walker<V: Vector4>(&self) -> Sl2rWalker<V> {
        Sl2rWalker::new(self)
    }
}

impl FrameSpace for UnitTangentSpace {
    /// The ray from the chart point `from = (x, y, θ)` (see the module), first brought into
    /// the cell by the pairings, along the body direction `dir` (in `X, Y, V`).
    fn chart_ray(&self, from: DVec3, dir: DVec3) -> Result<Ray<DVec4>, String> {
        if !from.is_finite() {
            return Err(format!(
                "the start point {from} is not a point of the chart"
            ));
        }
        if !(dir.is_finite() && dir.length() > 0.0 && dir.length().is_finite()) {
            return Err(format!("the direction {dir} has no length"));
        }
        let start = on_model(&Sl2rRay {
            frame: super::chart_frame(from.x, from.y, from.z),
            velocity: dir.normalize().to_array(),
        });
        // The chart's angle is the lifted fibre angle: its whole turns are sheets.
        let turns = ((from.z - super::cover::wrap_angle(from.z)) / std::f64::consts::TAU).round();
        let sheet = super::cover::sheet_plus(0, turns as i64, self.sheets());
        let (inside, sheet, _) = self.wrap_point(&start, sheet, 0.0);
        if !(self.farthest_past(inside.frame[2]).1 <= 1e-9) {
            return Err(format!(
                "the start point {from} is too far to bring into the cell (more than \
                 {MAX_WRAPS} side crossings): start nearer the origin"
            ));
        }
        Ok(Sl2rWalker::<DVec4>::ray_on_sheet(&inside, sheet))
    }

    /// How far the base point over `(p.x, p.y)` lies outside the polygon, in `H²` (its `w`
    /// derived: a walk's ray keeps the sheet there, a frame the base point's `w`).
    fn outside_by(&self, p: DVec4) -> f64 {
        let w = (1.0 + p.x * p.x + p.y * p.y).sqrt();
        let past = self.farthest_past([p.x, p.y, w]).1;
        if past.is_nan() { f64::INFINITY } else { past }
    }

    fn face_count(&self) -> usize {
        self.sides().len()
    }

    fn scale(&self) -> f64 {
        self.inradius().min(std::f64::consts::PI)
    }

    fn frame_defect(&self, frame: DMat4) -> f64 {
        let axes = axes_of(&frame);
        let r = point_of(&frame, [0.0; 3]);
        let [e, _, p] = r.frame;
        let l = super::flow::lorentz;
        (axes.transpose() * axes - DMat3::IDENTITY)
            .to_cols_array()
            .iter()
            .chain(&[l(p, p) + 1.0, l(e, e) - 1.0, l(e, p)])
            .fold(0.0_f64, |m, x| m.max(x.abs()))
    }

    /// A step of a player: with `level` (the plugin's default) the fibre `V` stays up —
    /// walking forward and sideways is horizontal (the axes without their `V` parts), up and
    /// down is along the fibre, and yaw turns about `V`; without it the frame moves along
    /// its own axes and turns about them. The axes keep their body components.
    fn step_frame(&self, frame: DMat4, motion: &FrameMotion) -> DMat4 {
        let d = motion.translation;
        let mut axes = axes_of(&frame);
        let mut r = point_of(&frame, [0.0; 3]);
        let mut sheet = frame_sheet(&frame);
        if d.length() > 0.0 && d.is_finite() {
            let u = if motion.level {
                crate::space::contract::level_step(axes.x_axis, axes.z_axis, d)
            } else {
                axes * d
            };
            (r, sheet) = moved_along(&r, sheet, self.sheets(), u);
        }
        let turn = motion.rotation;
        if motion.level && turn.y != 0.0 && turn.y.is_finite() {
            axes = DMat3::from_rotation_z(turn.y) * axes;
        }
        for (k, (axis, angle)) in [(DVec3::X, turn.x), (DVec3::Y, turn.y), (DVec3::Z, turn.z)]
            .into_iter()
            .enumerate()
        {
            if (motion.level && k == 1) || angle == 0.0 || !angle.is_finite() {
                continue;
            }
            axes *= DMat3::from_axis_angle(axis, angle);
        }
        frame_of(&r, orthonormal(axes), sheet)
    }

    fn turn_axes(&self, frame: DMat4, rotation: DMat3) -> DMat4 {
        frame_of(
            &point_of(&frame, [0.0; 3]),
            orthonormal(axes_of(&frame) * rotation),
            frame_sheet(&frame),
        )
    }

    fn step_velocity(&self, frame: DMat4, velocity: &Velocity, dt: f64) -> DMat4 {
        if !velocity.is_finite() || !dt.is_finite() || velocity.is_zero() {
            return frame;
        }
        let axes = axes_of(&frame);
        let (r, sheet) = moved_along(
            &point_of(&frame, [0.0; 3]),
            frame_sheet(&frame),
            self.sheets(),
            axes * (velocity.linear * dt),
        );
        let rate = velocity.angular.length();
        let axes = if rate > 0.0 {
            axes * DMat3::from_axis_angle(velocity.angular / rate, rate * dt)
        } else {
            axes
        };
        frame_of(&r, orthonormal(axes), sheet)
    }

    fn wrap_frame(&self, frame: DMat4, margin: f64) -> (DMat4, Vec<FrameCrossing>) {
        let (r, sheet, crossed) =
            self.wrap_point(&point_of(&frame, [0.0; 3]), frame_sheet(&frame), margin);
        if crossed.is_empty() {
            return (frame, Vec::new());
        }
        let sides = self.sides_f64();
        let crossings = crossed
            .into_iter()
            .map(|face| FrameCrossing {
                face,
                pairing: pairing_matrix(&sides[face].1),
                fibre_shift: 0.0,
            })
            .collect();
        (frame_of(&r, axes_of(&frame), sheet), crossings)
    }
}
