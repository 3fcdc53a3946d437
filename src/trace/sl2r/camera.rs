//! The SL̃(2,R) camera: its frame (the viewer's axes as body vectors with `e` in their
//! fourth entries, the base point as the position), placed by a chart point or looking at
//! one along the shortest geodesic; the default view; the rays through the lens.

use crate::space::FrameSpace;
use crate::space::sl2r::UnitTangentSpace;
use crate::space::sl2r::flow::Sl2rRay;
use glam::{DMat4, DVec3, DVec4};

/// A camera: its frame (the contract's: the viewer's axes as body vectors with `e` in their
/// fourth entries, the base point as the position) and vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rCamera {
    /// The frame.
    pub frame: DMat4,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

/// The viewer's axes looking along `e` (the body direction `X`) with the fibre `V` up:
/// right `−Y`, up `V`, back `−X` (right × up = back), at the point of `frame`.
fn looking_along_e(frame: DMat4) -> DMat4 {
    let e = [frame.x_axis.w, frame.y_axis.w, frame.z_axis.w];
    DMat4::from_cols(
        DVec4::new(0.0, -1.0, 0.0, e[0]),
        DVec4::new(0.0, 0.0, 1.0, e[1]),
        DVec4::new(-1.0, 0.0, 0.0, e[2]),
        frame.w_axis,
    )
}

impl Sl2rCamera {
    /// The camera at the chart point `(x, y, θ)` (base point `(x, y, √(1 + x² + y²))`, `e` at
    /// angle `θ` in the frame boosted from the origin's; first brought into the cell by the
    /// pairings), looking along `e` with the fibre up; an error names a point the chart or
    /// the cell cannot take.
    pub fn at(space: &UnitTangentSpace, point: DVec3, fov_y_degrees: f64) -> Result<Self, String> {
        if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) {
            return Err(format!(
                "the field of view must be between 0 and 180 degrees, got {fov_y_degrees}"
            ));
        }
        let ([e, _, p], sheet) = space.frame_at_chart_point(point)?;
        let frame = DMat4::from_cols(
            DVec4::new(1.0, 0.0, 0.0, e[0]),
            DVec4::new(0.0, 1.0, 0.0, e[1]),
            DVec4::new(0.0, 0.0, 1.0, e[2]),
            DVec3::from_array(p).extend(1.0 + f64::from(sheet)),
        );
        Ok(Self {
            frame: looking_along_e(frame),
            fov_y_degrees,
        })
    }
}

impl Sl2rCamera {
    /// The camera at the chart point `eye` (`[x, y, θ]`, as [`Sl2rCamera::at`]) looking along
    /// the shortest geodesic to the chart point `target`, with the fibre as near up as the
    /// view allows; an error names a point the chart cannot take, a target on the eye, or one
    /// farther than the inverse exponential map is solved
    /// ([`crate::space::sl2r::distance::TRUSTED_LENGTH`]).
    pub fn looking_at(
        space: &UnitTangentSpace,
        eye: DVec3,
        target: DVec3,
        fov_y_degrees: f64,
    ) -> Result<Self, String> {
        use crate::space::sl2r::distance::{TRUSTED_LENGTH, shortest};
        if !(eye.is_finite() && target.is_finite()) {
            return Err(format!(
                "the eye {eye} and the point looked at {target} must be chart points"
            ));
        }
        let from = crate::space::sl2r::chart_frame(eye.x, eye.y, eye.z);
        let to = crate::space::sl2r::chart_frame(target.x, target.y, target.z);
        let (length, v) = shortest(&from, &to).ok_or_else(|| {
            format!(
                "the point looked at {target} is {} or more from the eye {eye}: the direction is \
                 solved only within the injectivity radius of UT H² (pick a nearer point)",
                TRUSTED_LENGTH
            )
        })?;
        if length == 0.0 {
            return Err("the camera looks at its own position: nothing to look towards".into());
        }
        let camera = Self::at(space, eye, fov_y_degrees)?;
        Ok(Self {
            frame: looking_along(camera.frame, v),
            fov_y_degrees,
        })
    }
}

/// The camera frame at `frame`'s point looking along the body direction `forward` (unit),
/// with the fibre `V` as near up as the view allows (`X` where it looks straight along the
/// fibre).
#[must_use]
pub fn looking_along(frame: DMat4, forward: [f64; 3]) -> DMat4 {
    let forward = DVec3::from_array(forward);
    let up = DVec3::Z - forward * forward.z;
    let up = if up.length() > 1e-9 {
        up.normalize()
    } else {
        DVec3::X
    };
    let back = -forward;
    let right = up.cross(back);
    DMat4::from_cols(
        right.extend(frame.x_axis.w),
        up.extend(frame.y_axis.w),
        back.extend(frame.z_axis.w),
        frame.w_axis,
    )
}

/// The camera frame (viewer's axes as body vectors with `e` in their fourth entries, the
/// base point as the position) at the point `(e, e⊥, p)`, looking along `e` with the fibre
/// up.
#[must_use]
pub fn frame_at(point: &[[f64; 3]; 3]) -> DMat4 {
    let [e, _, p] = *point;
    looking_along_e(DMat4::from_cols(
        DVec4::new(1.0, 0.0, 0.0, e[0]),
        DVec4::new(0.0, 1.0, 0.0, e[1]),
        DVec4::new(0.0, 0.0, 1.0, e[2]),
        DVec3::from_array(p).extend(1.0),
    ))
}

/// The default camera: seven tenths of the inradius behind the polygon's centre, `e`
/// pointing at the centre, looking along `X` (at the centre's pillar) with the fibre `V` up.
#[must_use]
pub fn default_camera(space: &UnitTangentSpace) -> Sl2rCamera {
    let frame = looking_along_e(space.frame_from_centre(DVec3::ZERO));
    // Backwards along the horizontal geodesic (e stays parallel, pointing at the centre).
    let frame = space.step_frame(
        frame,
        &crate::space::FrameMotion {
            translation: DVec3::new(0.0, 0.0, 0.7 * space.inradius()),
            rotation: DVec3::ZERO,
            level: false,
        },
    );
    Sl2rCamera {
        frame,
        fov_y_degrees: 70.0,
    }
}

/// The fibre cover's sheet of a frame: its last column's fourth entry is `1 + sheet` (1 in
/// `UT Σ`).
#[must_use]
pub fn camera_sheet(frame: &DMat4) -> u32 {
    crate::space::sl2r::frame_sheet(frame)
}

/// The camera ray of a frame through the lens point `(x, y)`: its point, and the body
/// direction `x·right + y·up − back`, normalised.
#[must_use]
pub fn camera_ray(frame: &DMat4, x: f64, y: f64) -> Sl2rRay<f64> {
    let axis = |c: DVec4| c.truncate();
    let d = (x * axis(frame.x_axis) + y * axis(frame.y_axis) - axis(frame.z_axis)).normalize();
    let p = frame.w_axis.truncate().to_array();
    let e = [frame.x_axis.w, frame.y_axis.w, frame.z_axis.w];
    Sl2rRay {
        frame: [e, crate::space::sl2r::flow::perp(p, e), p],
        velocity: d.to_array(),
    }
}
