//! A player in a product space: a frame (columns right, up, back, position) of the product
//! model, moved along exact geodesics with parallel transport, turned about the fibre or its
//! own axes, and wrapped through the cell's faces.
//!
//! The frame's columns are product tangents at the position (4-vectors `(x, y, z, w)`, base
//! part tangent to the surface, `z` along the fibre). Moving by `t` along a unit tangent
//! `u` follows the geodesic of [`super::ProductWalker`]; a tangent `e` is carried parallel along it:
//! its part along the geodesic's base direction turns with the base velocity, the rest
//! (the surface normal to the path, and the fibre) stays as it is.

use super::ProductSpace;
use crate::geometry::{Geometry, Ray, Vector4};
use crate::space::Family;
use crate::space::contract::{FamilySpace, FrameCrossing, FrameMotion, FrameSpace};
use crate::space::motion::Velocity;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// The surface model's form on the base parts of two vectors.
fn base_form(g: Geometry, a: DVec4, b: DVec4) -> f64 {
    a.x * b.x + a.y * b.y + g.kappa() * a.w * b.w
}

/// The product metric on two tangents.
#[must_use]
pub fn product_dot(g: Geometry, a: DVec4, b: DVec4) -> f64 {
    base_form(g, a, b) + a.z * b.z
}

fn base(v: DVec4) -> DVec4 {
    DVec4::new(v.x, v.y, 0.0, v.w)
}

/// The frame moved by `t` along the geodesic of its unit tangent `u` at the position, every
/// column parallel transported.
#[must_use]
pub fn transport(g: Geometry, frame: DMat4, u: DVec4, t: f64) -> DMat4 {
    let p = frame.w_axis;
    let ub = base(u);
    let lambda = base_form(g, ub, ub).max(0.0).sqrt();
    let mut out = frame;
    out.w_axis.z = p.z + u.z * t;
    if lambda <= 0.0 || t == 0.0 {
        return out;
    }
    let e = ub / lambda;
    let pb = base(p);
    let (c, s) = g.cs(lambda * t);
    let moved = pb * c + e * s;
    let turned = pb * (-g.kappa() * s) + e * c;
    out.w_axis = DVec4::new(moved.x, moved.y, p.z + u.z * t, moved.w);
    for k in 0..3 {
        let col = frame.col(k);
        let a = base_form(g, col, e);
        *out.col_mut(k) = col + (turned - e) * a;
    }
    out
}

/// The quarter turn `J` of the surface's tangent plane at `p`, counter-clockwise seen from
/// `+z` (the fibre's direction), applied to the base part of `v`; `z` is dropped.
fn quarter_turn(g: Geometry, p: DVec4, v: DVec4) -> DVec4 {
    let a = DVec3::new(p.x, p.y, p.w);
    let b = DVec3::new(v.x, v.y, v.w);
    let c = a.cross(b);
    // In H² the cross product's dual under the form x² + y² − w² flips w.
    let w = if g == Geometry::Hyperbolic { -c.z } else { c.z };
    DVec4::new(c.x, c.y, 0.0, w)
}

/// Every column turned by `angle` about the fibre through the position (counter-clockwise
/// seen from above): the base parts rotate in the surface's tangent plane, the fibre parts
/// stay. A turn of the view that keeps "up" where it was.
#[must_use]
pub fn turn_about_fibre(g: Geometry, frame: DMat4, angle: f64) -> DMat4 {
    let p = frame.w_axis;
    let (s, c) = angle.sin_cos();
    let mut out = frame;
    for k in 0..3 {
        let col = frame.col(k);
        let b = base(col);
        let r = b * c + quarter_turn(g, p, b) * s;
        *out.col_mut(k) = DVec4::new(r.x, r.y, col.z, r.w);
    }
    out
}

/// How a product player moves this step: in the frame's own axes (`x` right, `y` up, `z`
/// back), and by angles.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ProductMotion {
    /// Walking: right, up, back (in units of distance). With `level`, forward and sideways
    /// stay horizontal and up is the fibre.
    pub translation: DVec3,
    /// Pitch about right, yaw (about the fibre with `level`, else about up), roll about back.
    pub rotation: DVec3,
    /// The fibre stays "up": walking is horizontal, turning is about the fibre.
    pub level: bool,
}

/// A unit tangent's part along the frame's own axes.
fn along_frame(frame: DMat4, d: DVec3) -> DVec4 {
    frame.x_axis * d.x + frame.y_axis * d.y + frame.z_axis * d.z
}

/// The frame after one step: translated (exactly, with transport), then turned.
#[must_use]
pub fn step_product_frame(g: Geometry, frame: DMat4, motion: &ProductMotion) -> DMat4 {
    let mut f = frame;
    let t = motion.translation;
    if t.is_finite() && t.length() > 0.0 {
        let u = if motion.level {
            // Horizontal walking: the frame's right and back with their fibre parts dropped,
            // and the fibre itself for up.
            let flat = |v: DVec4| base(v);
            let h = flat(f.x_axis) * t.x + flat(f.z_axis) * t.z;
            let hl = base_form(g, h, h).max(0.0).sqrt();
            let horizontal = if hl > 1e-12 {
                h * ((t.x * t.x + t.z * t.z).sqrt() / hl)
            } else {
                DVec4::ZERO
            };
            horizontal + DVec4::Z * t.y
        } else {
            along_frame(f, t)
        };
        let len = product_dot(g, u, u).max(0.0).sqrt();
        if len > 0.0 {
            f = transport(g, f, u / len, len);
        }
    }
    let r = motion.rotation;
    if motion.level && r.y != 0.0 && r.y.is_finite() {
        // A turn about the fibre is a turn of the world, counter-clockwise seen from above;
        // a frame that crossed an orientation-reversing side (left-handed, determinant −1)
        // sees it the other way round, so its yaw turns the world the other way and the
        // controls stay natural (as past a mirror in the constant-curvature spaces).
        let yaw = if f.determinant() < 0.0 { -r.y } else { r.y };
        f = turn_about_fibre(g, f, yaw);
    }
    for (k, (axis, angle)) in [(DVec3::X, r.x), (DVec3::Y, r.y), (DVec3::Z, r.z)]
        .into_iter()
        .enumerate()
    {
        if (motion.level && k == 1) || angle == 0.0 || !angle.is_finite() {
            continue;
        }
        f *= DMat4::from_axis_angle(axis, angle);
    }
    f
}

/// A face a frame crossed: the side index, or the top (`sides`) or the bottom (`sides + 1`),
/// and the linear part of its pairing (the top and bottom also shift the height, which the
/// holonomy does not hold).
pub type ProductCrossing = FrameCrossing;

/// The frame back inside the cell: while its position is past a face by more than `margin`
/// (side faces by the unit base point's `N·X`, the top and bottom by `|z| − L/2`), the
/// face's pairing is applied to every column (a side's maps the face onto its partner; the
/// top's is `R⁻¹` with `z − L`, the bottom's `R` with `z + L`; a height k circles past
/// is brought back at once, as one crossing with `R⁻ᵏ` or `Rᵏ`). A pairing that reverses
/// orientation leaves a left-handed frame, which the view follows as it is. Then the frame
/// is put back onto the model and made orthonormal. At most 16 wraps.
#[must_use]
pub fn wrap_product_frame(
    space: &ProductSpace,
    frame: DMat4,
    margin: f64,
) -> (DMat4, Vec<ProductCrossing>) {
    let g = space.base();
    let walker = super::ProductWalker::<DVec4>::new(space);
    let sides = walker.covectors.len();
    let half = 0.5 * space.length();
    let mut f = frame;
    let mut crossed = Vec::new();
    for _ in 0..16 {
        let p = f.w_axis;
        let pb = base(p);
        let norm = (g.kappa() * base_form(g, pb, pb))
            .abs()
            .sqrt()
            .max(f64::MIN_POSITIVE);
        let unit = pb / norm;
        let mut worst: Option<(usize, f64)> = None;
        for (k, n) in walker.covectors.iter().enumerate() {
            let past = n.dot(unit);
            if past > margin && worst.is_none_or(|(_, w)| past > w) {
                worst = Some((k, past));
            }
        }
        // Past the top or bottom by k circles at once (a far height): k crossings in one,
        // the turn's k-th power.
        let circles = |z: f64| {
            let k = ((z.abs() - half) / space.length()).ceil().max(1.0);
            let turns = (k % f64::from(space.turn().max(1))) as u32;
            (k, turns)
        };
        let power = |m: DMat4, n: u32| (0..n).fold(DMat4::IDENTITY, |acc, _| m * acc);
        let (face, pairing, shift) = match worst {
            Some((k, _)) => (k, walker.pairings[k], 0.0),
            None if p.z > half + margin => {
                let (k, n) = circles(p.z);
                (sides, power(walker.up.0, n), -k * space.length())
            }
            None if p.z < -half - margin => {
                let (k, n) = circles(p.z);
                (sides + 1, power(walker.down.0, n), k * space.length())
            }
            None => break,
        };
        f = pairing * f;
        f.w_axis.z += shift;
        crossed.push(ProductCrossing {
            face,
            pairing,
            fibre_shift: shift,
        });
    }
    (orthonormal(g, f), crossed)
}

/// The frame put back onto the model (the position's base part scaled onto the surface)
/// with its columns made tangent there and orthonormal (Gram–Schmidt in the product metric,
/// keeping each column's handedness).
#[must_use]
pub fn orthonormal(g: Geometry, frame: DMat4) -> DMat4 {
    let p = frame.w_axis;
    let pb = base(p);
    let norm = (g.kappa() * base_form(g, pb, pb)).abs().sqrt();
    if !(norm > 0.0 && norm.is_finite()) {
        return frame;
    }
    let mut q = pb / norm;
    if g == Geometry::Hyperbolic && q.w < 0.0 {
        q = -q;
    }
    let point = DVec4::new(q.x, q.y, p.z, q.w);
    let mut cols: [DVec4; 3] = [frame.x_axis, frame.y_axis, frame.z_axis];
    for k in 0..3 {
        let mut v = cols[k];
        let vb = base(v);
        let along = base_form(g, q, vb) / base_form(g, q, q);
        v -= q * along;
        for c in &cols[..k] {
            v -= *c * product_dot(g, v, *c);
        }
        let len = product_dot(g, v, v).max(0.0).sqrt();
        if len > 0.0 {
            cols[k] = v / len;
        }
    }
    DMat4::from_cols(cols[0], cols[1], cols[2], point)
}

/// How far a frame's first three columns are from orthonormal in the product metric (the
/// largest entry of `FᵀGF − I`).
#[must_use]
pub fn product_frame_defect(g: Geometry, frame: DMat4) -> f64 {
    let cols = [frame.x_axis, frame.y_axis, frame.z_axis];
    let mut worst: f64 = 0.0;
    for (i, a) in cols.iter().enumerate() {
        for (j, b) in cols.iter().enumerate() {
            let want = if i == j { 1.0 } else { 0.0 };
            worst = worst.max((product_dot(g, *a, *b) - want).abs());
        }
    }
    worst
}

/// The frame of a product camera: columns right, up, back and the eye.
#[must_use]
pub fn camera_frame(point: DVec4, [right, up, back]: [DVec4; 3]) -> DMat4 {
    DMat4::from_cols(right, up, back, point)
}

/// The two eyes of a head in a product space: each half of `ipd` along the head's right
/// (left first), its frame carried there by [`transport`] and brought back into the cell
/// where it left it (the stereo views of the CLI and the plugin).
#[must_use]
pub fn product_eye_frames(space: &ProductSpace, head: DMat4, ipd: f64) -> [DMat4; 2] {
    space.eye_frames(head, ipd)
}

/// The frame after `dt` seconds of `velocity`: translated along the product geodesic of
/// its linear part (in the frame's own axes), then turned by its angular part about the
/// frame's own axes, exactly. A non-finite velocity or time leaves the frame where it is.
#[must_use]
pub fn step_product_velocity(g: Geometry, frame: DMat4, velocity: &Velocity, dt: f64) -> DMat4 {
    if !velocity.is_finite() || !dt.is_finite() {
        return frame;
    }
    let moved = step_product_frame(
        g,
        frame,
        &ProductMotion {
            translation: velocity.linear * dt,
            rotation: DVec3::ZERO,
            level: false,
        },
    );
    let rate = velocity.angular.length();
    if rate == 0.0 {
        return moved;
    }
    let r = DMat3::from_axis_angle(velocity.angular / rate, rate * dt);
    let cols = [moved.x_axis, moved.y_axis, moved.z_axis];
    let turned = |c: DVec3| cols[0] * c.x + cols[1] * c.y + cols[2] * c.z;
    orthonormal(
        g,
        DMat4::from_cols(
            turned(r.x_axis),
            turned(r.y_axis),
            turned(r.z_axis),
            moved.w_axis,
        ),
    )
}

impl FamilySpace for ProductSpace {
    const FAMILY: Family = Family::Product;
    type Walker<V: Vector4> = super::ProductWalker<V>;

    fn walker<V: Vector4>(&self) -> super::ProductWalker<V> {
        super::ProductWalker::new(self)
    }
}

impl FrameSpace for ProductSpace {
    fn chart_ray(&self, from: DVec3, dir: DVec3) -> Result<Ray<DVec4>, String> {
        super::chart_ray(self.base(), from, dir)
    }

    fn outside_by(&self, p: DVec4) -> f64 {
        ProductSpace::outside_by(self, p)
    }

    fn face_count(&self) -> usize {
        ProductSpace::face_count(self)
    }

    fn scale(&self) -> f64 {
        ProductSpace::scale(self)
    }

    fn frame_defect(&self, frame: DMat4) -> f64 {
        product_frame_defect(self.base(), frame)
    }

    fn step_frame(&self, frame: DMat4, motion: &FrameMotion) -> DMat4 {
        step_product_frame(
            self.base(),
            frame,
            &ProductMotion {
                translation: motion.translation,
                rotation: motion.rotation,
                level: motion.level,
            },
        )
    }

    fn step_velocity(&self, frame: DMat4, velocity: &Velocity, dt: f64) -> DMat4 {
        step_product_velocity(self.base(), frame, velocity, dt)
    }

    fn wrap_frame(&self, frame: DMat4, margin: f64) -> (DMat4, Vec<FrameCrossing>) {
        wrap_product_frame(self, frame, margin)
    }
}
