//! A camera flight in an SL̃(2,R) space: a flight file's keys as chart points `[x, y, θ]` of
//! `UT H²` (the base point `(x, y, √(1 + x² + y²))` and `e` at angle `θ`, as `render --eye`
//! and the scene files name them), the camera between two keys on the shortest geodesic
//! between them (the inverse exponential map, [`shortest`], then the flow), looking along
//! the shortest geodesic to the point between their targets with the fibre as near up as the
//! view allows, and brought back into the cell through the sides it passed (the frame's axes
//! are body vectors, which the surface group keeps).
//!
//! The inverse exponential map is solved within [`TRUSTED_LENGTH`] (below the injectivity
//! radius `π` of `UT H²`), so consecutive keys, and each key's position and target, must lie
//! within that of each other (add keys between farther ones); between keys, where the target
//! passes farther than that from the eye, the camera looks along its `e`. The keys' `up` is
//! not used (the fibre is up). In a fibre cover a key's `θ` is the lifted angle (its whole
//! turns are sheets), and the camera's sheet between keys follows the geodesic from the key
//! before ([`crate::space::sl2r::cover`]).

use crate::scene::flight::FlightFile;
use crate::space::motion::{CoverFlight, keyed};
use crate::space::sl2r::distance::{Frame, TRUSTED_LENGTH, shortest};
use crate::space::sl2r::{Sl2rRay, UnitTangentSpace, chart_frame, chart_point, flow};
use glam::{DMat4, DVec3};

/// The farthest a key's base point may lie from the origin in the chart: `√(x² + y²)` at most
/// 100, about 5.3 in `H²` (the frames are brought into the cell crossing by crossing, in f64).
pub const MAX_KEY_CHART: f64 = 100.0;

/// A flight through an SL̃(2,R) space: its keys as frames of `UT H²`.
#[derive(Clone, Debug)]
pub struct Sl2rFlight {
    /// Time, position and target of each key.
    keys: Vec<(f64, Frame, Frame)>,
    /// The whole turns of each key position's lifted angle.
    turns: Vec<i64>,
    /// The sheets of the space flown (1 until [`Sl2rFlight::in_space`]).
    sheets: u32,
    /// Vertical field of view in degrees.
    pub fov: f64,
}

/// The frame a fraction `s` of the way along the shortest geodesic from `a` to `b` (`a`
/// where they are farther apart than the solver reaches: refused when the flight is read).
fn between(a: Frame, b: Frame, s: f64) -> Frame {
    match shortest(&a, &b) {
        Some((length, velocity)) if length > 0.0 => {
            flow(&Sl2rRay { frame: a, velocity }, s * length).frame
        }
        _ => a,
    }
}

/// A key's chart point as a frame, refused where it is not finite.
fn key_frame(p: DVec3, what: &str) -> Result<Frame, String> {
    if !p.is_finite() || p.truncate().length() > MAX_KEY_CHART || p.z.abs() > 1e6 {
        return Err(format!(
            "{what} {:?} is not a chart point [x, y, θ] with x² + y² ≤ {MAX_KEY_CHART}² (a base point at most about 5.3 from the origin) and |θ| ≤ 10⁶",
            p.to_array()
        ));
    }
    Ok(chart_frame(p.x, p.y, p.z))
}

/// Refuses two frames farther apart than the inverse exponential map is solved.
fn within_reach(a: &Frame, b: &Frame, what: &str) -> Result<(), String> {
    if shortest(a, b).is_some() {
        Ok(())
    } else {
        Err(format!(
            "{what} lie {TRUSTED_LENGTH} or more apart: the shortest geodesic between points of \
             SL̃(2,R) is solved only within the injectivity radius (add keys between)"
        ))
    }
}

impl Sl2rFlight {
    /// The flight of a file's keys.
    pub fn new(file: &FlightFile) -> Result<Self, String> {
        let mut keys: Vec<(f64, Frame, Frame)> = Vec::with_capacity(file.keys.len());
        let turns = file
            .keys
            .iter()
            .map(|k| {
                let lifted = k.1.z - crate::space::sl2r::cover::wrap_angle(k.1.z);
                (lifted / std::f64::consts::TAU).round() as i64
            })
            .collect();
        for (i, &(time, position, target)) in file.keys.iter().enumerate() {
            let n = i + 1;
            let p = key_frame(position, &format!("key {n}: position"))?;
            let t = key_frame(target, &format!("key {n}: look_at"))?;
            within_reach(&p, &t, &format!("key {n}'s position and look_at"))?;
            if let Some(last) = keys.last() {
                within_reach(&last.1, &p, &format!("keys {} and {n}'s positions", n - 1))?;
                within_reach(&last.2, &t, &format!("keys {} and {n}'s look_at", n - 1))?;
            }
            keys.push((time, p, t));
        }
        Ok(Self {
            keys,
            turns,
            sheets: 1,
            fov: file.fov,
        })
    }

    /// The flight in `space` (a fibre cover's keys name sheets).
    #[must_use]
    pub fn in_space(mut self, space: &UnitTangentSpace) -> Self {
        self.sheets = space.sheets();
        self
    }

    /// The camera's sheet at time `t`: the key before's, climbed along the geodesic from it.
    fn sheet_at(&self, t: f64, position: &Frame) -> u32 {
        use crate::space::sl2r::cover::{sheet_plus, sheets_climbed};
        if self.sheets <= 1 || self.keys.is_empty() {
            return 0;
        }
        let i = self.keys.partition_point(|k| k.0 <= t).max(1) - 1;
        let from = self.keys[i].1;
        let climbed = match shortest(&from, position) {
            Some((length, velocity)) if length > 0.0 => sheets_climbed(
                &Sl2rRay {
                    frame: from,
                    velocity,
                },
                length,
                position,
            )
            .unwrap_or(0),
            _ => 0,
        };
        let start = sheet_plus(0, self.turns[i], self.sheets);
        sheet_plus(start, climbed, self.sheets)
    }

    /// The camera frame at time `t` in `UT H²` (before wrapping).
    #[must_use]
    pub fn cover_frame(&self, t: f64) -> DMat4 {
        let (p, target) = keyed(&self.keys, t, between);
        let mut eye = super::frame_at(&p);
        eye.w_axis.w = 1.0 + f64::from(self.sheet_at(t, &p));
        match shortest(&p, &target) {
            Some((length, v)) if length > 0.0 => super::looking_along(eye, v),
            _ => eye,
        }
    }

    /// The camera at time `t` in the cell.
    #[must_use]
    pub fn camera(&self, space: &UnitTangentSpace, t: f64) -> super::Sl2rCamera {
        super::Sl2rCamera {
            frame: self.frame_in_cell(space, t).0,
            fov_y_degrees: self.fov,
        }
    }
}

impl CoverFlight for Sl2rFlight {
    type Space = UnitTangentSpace;

    fn duration(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.0)
    }

    fn cover_frame(&self, t: f64) -> DMat4 {
        Sl2rFlight::cover_frame(self, t)
    }
}

/// The key of a camera at `frame` in the cell that reached it through `holonomy` (`walk
/// --record`): its chart point, the point a quarter ahead along its view and the point a
/// quarter above it (the replay keeps the fibre up), carried back into `UT H²` by the inverse
/// of the surface group's element the crossings applied. `None` where a key cannot hold them
/// (a base point beyond [`MAX_KEY_CHART`]).
#[must_use]
pub fn recorded_sl2r_key(
    space: &UnitTangentSpace,
    frame: DMat4,
    holonomy: &crate::space::Holonomy,
) -> Option<(DVec3, DVec3, DVec3)> {
    // The 3×3 element (rows and columns 0, 1, 3 of the holonomy's matrix, as the crossings
    // recorded it) and its inverse J Mᵀ J.
    let idx = [0, 1, 3];
    let m = holonomy.matrix;
    let sign = [1.0, 1.0, -1.0];
    let inverse: [[f64; 3]; 3] =
        [0, 1, 2].map(|r| [0, 1, 2].map(|c| sign[r] * sign[c] * m.col(idx[r])[idx[c]]));
    let apply = |v: [f64; 3]| {
        [0, 1, 2].map(|r| inverse[r][0] * v[0] + inverse[r][1] * v[1] + inverse[r][2] * v[2])
    };
    let p = frame.w_axis.truncate().to_array();
    let e = [frame.x_axis.w, frame.y_axis.w, frame.z_axis.w];
    let (p, e) = (apply(p), apply(e));
    let cover = [e, crate::space::sl2r::flow::perp(p, e), p];
    let moved = |axis: glam::DVec4| {
        let v = axis.truncate().normalize().to_array();
        chart_point(
            &flow(
                &Sl2rRay {
                    frame: cover,
                    velocity: v,
                },
                0.25,
            )
            .frame,
        )
    };
    // In a fibre cover the chart's angle is lifted: the sheet of `UT H²` whose frame the
    // sides' pairings bring to the walker's frame on its sheet (as the replay brings it in).
    let mut at = chart_point(&cover);
    if space.sheets() > 1 {
        let climbed = space.sheets_into_cell(&cover);
        let sheet = i64::from(super::camera_sheet(&frame)) - i64::from(climbed);
        let sheet = sheet.rem_euclid(i64::from(space.sheets()));
        at.z += std::f64::consts::TAU * sheet as f64;
    }
    let follow = |k: DVec3| {
        let d = crate::space::sl2r::cover::wrap_angle(k.z - at.z);
        DVec3::new(k.x, k.y, at.z + d)
    };
    let ahead = follow(moved(-frame.z_axis));
    let above = follow(moved(frame.y_axis));
    [at, ahead, above]
        .iter()
        .all(|k| k.is_finite() && k.truncate().length() <= MAX_KEY_CHART)
        .then_some((at, ahead, above))
}
