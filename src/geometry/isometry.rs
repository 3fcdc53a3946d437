//! Isometries of the model as 4×4 matrices acting on column vectors, and frames.

use super::{Geometry, ORIGIN};
use glam::{DMat3, DMat4, DVec3, DVec4};

/// The largest absolute entry of a matrix (given as its array of entries); NaN if any entry
/// is NaN (`f64::max` would pass over it, and a check `defect < tol` would accept it).
#[must_use]
pub(crate) fn max_abs_entry(entries: &[f64]) -> f64 {
    entries.iter().fold(0.0_f64, |acc, x| {
        if acc.is_nan() || x.is_nan() {
            f64::NAN
        } else {
            acc.max(x.abs())
        }
    })
}

impl Geometry {
    /// Translation by distance `t` along the geodesic through the origin with unit chart
    /// direction `u`: `M = I + (C−1)(o oᵀ + u uᵀ) + S(u oᵀ − κ o uᵀ)`, so that
    /// `M o = C o + S u` (the geodesic) and `M u = −κ S o + C u` (its tangent).
    #[must_use]
    pub fn translation(self, u: DVec3, t: f64) -> DMat4 {
        let u = u.normalize();
        let (c, s) = self.cs(t);
        let k = self.kappa();
        let col = |j: usize| {
            let mut e = DVec4::ZERO;
            e[j] = 1.0;
            e + (c - 1.0) * u[j] * u.extend(0.0) - k * s * u[j] * ORIGIN
        };
        DMat4::from_cols(col(0), col(1), col(2), c * ORIGIN + s * u.extend(0.0))
    }

    /// Translation by distance `t` along the geodesic through the point `p` with tangent `v`
    /// (moves `p` to `γ(t)` and carries the geodesic into itself).
    #[must_use]
    pub fn translation_along(self, p: DVec4, v: DVec4, t: f64) -> DMat4 {
        let a = self.translation_to(p);
        let a_inv = self.inverse(a);
        a * self.translation((a_inv * v).truncate(), t) * a_inv
    }

    /// The translation along the geodesic from the origin to `p` that carries the origin
    /// to `p` (identity when `p` is the origin).
    #[must_use]
    pub fn translation_to(self, p: DVec4) -> DMat4 {
        let x = self.to_chart(p);
        if x.length_squared() == 0.0 {
            return DMat4::IDENTITY;
        }
        self.translation(x, self.distance(ORIGIN, p))
    }

    /// Rotation by `angle` (right-hand rule) about the geodesic through the origin with
    /// chart direction `axis`.
    #[must_use]
    pub fn rotation(self, axis: DVec3, angle: f64) -> DMat4 {
        DMat4::from_axis_angle(axis.normalize(), angle)
    }

    /// Rotation by `angle` about the geodesic through the point `p` with chart direction
    /// `axis_dir` at `p` (right-hand rule about the tangent).
    #[must_use]
    pub fn rotation_about(self, p: DVec4, axis_dir: DVec3, angle: f64) -> DMat4 {
        let a = self.translation_to(p);
        let a_inv = self.inverse(a);
        let v = self.unit_tangent(p, axis_dir.extend(0.0));
        let at_origin = (a_inv * v).truncate();
        a * self.rotation(at_origin, angle) * a_inv
    }

    /// Reflection in the totally geodesic plane `N·X = 0` of the covector `N = (n, −r)`:
    /// `X ↦ X − 2 (N·X) m / (N·m)` with `m = (n, −κ r)` the vector dual to `N` under ⟨,⟩
    /// (for E³, where the form is degenerate, `m = (n, 0)`: the Euclidean reflection).
    #[must_use]
    pub fn reflection(self, covector: DVec4) -> DMat4 {
        let m = DVec4::new(
            covector.x,
            covector.y,
            covector.z,
            self.kappa() * covector.w,
        );
        let scale = 2.0 / covector.dot(m);
        DMat4::from_cols(
            DVec4::X - scale * covector.x * m,
            DVec4::Y - scale * covector.y * m,
            DVec4::Z - scale * covector.z * m,
            DVec4::W - scale * covector.w * m,
        )
    }

    /// Inverse of an isometry: `G gᵀ G` (S³, H³, `G = diag(1,1,1,κ)`), `(Aᵀ, −Aᵀ b)` (E³).
    #[must_use]
    pub fn inverse(self, g: DMat4) -> DMat4 {
        match self {
            Self::Euclidean => {
                let a = DMat3::from_mat4(g).transpose();
                let b = g.w_axis.truncate();
                let mut m = DMat4::from_mat3(a);
                m.w_axis = (-(a * b)).extend(1.0);
                m
            }
            _ => {
                let gm = DMat4::from_diagonal(DVec4::new(1.0, 1.0, 1.0, self.kappa()));
                gm * g.transpose() * gm
            }
        }
    }

    /// How far `g` is from an isometry of the model: the largest entry of `gᵀ G g − G`
    /// (S³, H³), or of `AᵀA − I` and the last row's deviation from `(0,0,0,1)` (E³).
    #[must_use]
    pub fn isometry_defect(self, g: DMat4) -> f64 {
        // A translation part is not checked by the form: a non-finite entry anywhere is no
        // isometry.
        if !g.is_finite() {
            return f64::INFINITY;
        }
        match self {
            Self::Euclidean => {
                let a = DMat3::from_mat4(g);
                let ortho = a.transpose() * a - DMat3::IDENTITY;
                let ortho = max_abs_entry(&ortho.to_cols_array());
                let row = g.row(3) - DVec4::W;
                max_abs_entry(&[ortho, row.x, row.y, row.z, row.w])
            }
            _ => {
                let gm = DMat4::from_diagonal(DVec4::new(1.0, 1.0, 1.0, self.kappa()));
                max_abs_entry(&(g.transpose() * gm * g - gm).to_cols_array())
            }
        }
    }

    /// Gram–Schmidt of a frame in ⟨,⟩: the position (column 3) is projected onto the model,
    /// then columns 0, 1, 2 (right, up, back) are made tangent there and orthonormal,
    /// in that order. The handedness of the input is kept.
    #[must_use]
    pub fn orthonormalize_frame(self, frame: DMat4) -> DMat4 {
        self.orthonormalize_frame_at(frame, self.project_point(frame.w_axis))
    }

    /// [`Geometry::orthonormalize_frame`] about the model point `p` already chosen for the
    /// frame's position. In S³, `project_point` turns a point past the equator to its
    /// antipode; a frame in a cell that reaches the equator keeps its point, only scaled to
    /// unit length.
    #[must_use]
    pub fn orthonormalize_frame_at(self, frame: DMat4, p: DVec4) -> DMat4 {
        let mut cols = [frame.x_axis, frame.y_axis, frame.z_axis];
        for i in 0..3 {
            let mut v = self.project_tangent(p, cols[i]);
            for done in &cols[..i] {
                v -= self.form(v, *done) * *done;
            }
            cols[i] = v / self.form(v, v).sqrt();
        }
        DMat4::from_cols(cols[0], cols[1], cols[2], p)
    }

    /// The largest deviation of a frame from orthonormality in ⟨,⟩ (0 for a perfect frame).
    #[must_use]
    pub fn frame_defect(self, frame: DMat4) -> f64 {
        let p = frame.w_axis;
        let mut worst = match self {
            Self::Euclidean => (p.w - 1.0).abs(),
            _ => (self.form(p, p) - self.kappa()).abs(),
        };
        let cols = [frame.x_axis, frame.y_axis, frame.z_axis];
        for i in 0..3 {
            let tangency = match self {
                Self::Euclidean => cols[i].w.abs(),
                _ => self.form(cols[i], p).abs(),
            };
            worst = worst.max(tangency);
            for j in 0..3 {
                let target = if i == j { 1.0 } else { 0.0 };
                worst = worst.max((self.form(cols[i], cols[j]) - target).abs());
            }
        }
        worst
    }

    /// A frame at chart point `eye` whose `back` column points away from `target`
    /// (so the camera looks at it), with `up` as close as possible to the chart `up`.
    pub fn look_at(
        self,
        eye: DVec3,
        target: DVec3,
        up: DVec3,
    ) -> Result<DMat4, super::GeometryError> {
        let p = self.from_chart(eye)?;
        let q = self.from_chart(target)?;
        let gap = target - eye;
        if gap == DVec3::ZERO {
            return Err(super::GeometryError::ZeroDirection(gap.x, gap.y, gap.z));
        }
        let back = -self.tangent_towards(p, q);
        // Pick the chart up vector, or another axis when it is parallel to the view.
        let up = [up, DVec3::Z, DVec3::X]
            .into_iter()
            .map(|u| {
                let u = self.project_tangent(p, u.extend(0.0));
                u - self.form(u, back) * back
            })
            .find(|u| self.form(*u, *u) > 1e-12)
            .ok_or(super::GeometryError::ZeroDirection(up.x, up.y, up.z))?;
        let up = up / self.form(up, up).sqrt();
        Ok(self.frame_from(p, up, back))
    }

    /// The right-handed frame at `p` with unit tangents `up` and `back` (orthogonal):
    /// right = up × back in the tangent space (transported to the origin, crossed, and
    /// transported back), re-orthonormalized.
    #[must_use]
    pub fn frame_from(self, p: DVec4, up: DVec4, back: DVec4) -> DMat4 {
        let a = self.translation_to(p);
        let a_inv = self.inverse(a);
        let r0 = (a_inv * up).truncate().cross((a_inv * back).truncate());
        let right = a * r0.extend(0.0);
        self.orthonormalize_frame(DMat4::from_cols(right, up, back, p))
    }
}

/// The frame moved by `t` in its own axes (right, up, back): along the geodesic in that
/// direction by `|t|`. A zero or non-finite `t` leaves it where it is.
#[must_use]
pub fn translate_local(geometry: Geometry, frame: DMat4, t: DVec3) -> DMat4 {
    let distance = t.length();
    if distance > 0.0 && distance.is_finite() {
        frame * geometry.translation(t / distance, distance)
    } else {
        frame
    }
}
