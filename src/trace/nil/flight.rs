//! A camera flight in a Nil space: a flight file's keys as chart points of the Heisenberg
//! group (the universal cover), the camera between two keys on the Nil geodesic between
//! them ([`crate::space::nil::shortest`], then the flow), looking along the shortest
//! geodesic to the point between their targets with `E₃` up as far as the view allows, and
//! brought back into the box through the faces it passed (the frame's axes are body
//! vectors, which a left translation keeps).
//!
//! A key's `position` and `look_at` are chart points `(x, y, z)`; the keys' `up` is not
//! used (`E₃` is up). A key may lie in another box than the first: the camera flies there,
//! and arrives wherever the lattice's twist takes it.

use super::look_frame;
use crate::scene::flight::FlightFile;
use crate::space::FrameSpace;
use crate::space::motion::{CoverFlight, keyed};
use crate::space::nil::{NilRay, NilSpace, flow, shortest};
use glam::{DMat4, DVec3, DVec4};

/// The most face crossings from the origin's box to a key: the flight's frames are brought
/// back into the box crossing by crossing ([`CoverFlight::frame_in_cell`]).
pub const MAX_KEY_CROSSINGS: usize = 1000;

/// A flight through a Nil space: its keys as chart points of the universal cover.
#[derive(Clone, Debug)]
pub struct NilFlight {
    /// Time, position and target of each key.
    keys: Vec<(f64, DVec3, DVec3)>,
    /// Vertical field of view in degrees.
    pub fov: f64,
}

/// How many face crossings bring the chart point `p` into the box (counted up to
/// `MAX_KEY_CROSSINGS + 1`).
fn crossings_to_box(space: &NilSpace, p: DVec3) -> usize {
    let mut frame = DMat4::IDENTITY;
    frame.w_axis = p.extend(1.0);
    let mut count = 0;
    while count <= MAX_KEY_CROSSINGS {
        let (wrapped, crossed) = space.wrap_frame(frame, 0.0);
        if crossed.is_empty() {
            break;
        }
        count += crossed.len();
        frame = wrapped;
    }
    count
}

/// A key's chart point, refused where it is not finite or more than
/// [`MAX_KEY_CROSSINGS`] crossings from the box.
fn key_point(space: &NilSpace, p: DVec3, what: &str) -> Result<DVec3, String> {
    super::chart_point(p.to_array(), what)?;
    let n = crossings_to_box(space, p);
    if n > MAX_KEY_CROSSINGS {
        return Err(format!(
            "{what} {:?} is more than {MAX_KEY_CROSSINGS} face crossings from the box of {} \
             (each frame is brought back crossing by crossing): keep keys nearer the origin",
            p.to_array(),
            space.name()
        ));
    }
    Ok(p)
}

/// The point a fraction `s` of the way along the shortest geodesic from `a` to `b`.
fn between(a: DVec3, b: DVec3, s: f64) -> DVec3 {
    let (length, direction) = shortest(a.to_array(), b.to_array());
    if !(length > 0.0) {
        return a;
    }
    let at = flow(
        &NilRay {
            point: a.to_array(),
            velocity: direction,
        },
        s * length,
    );
    DVec3::from_array(at.point)
}

impl NilFlight {
    /// The flight of a file's keys in `space`.
    pub fn new(space: &NilSpace, file: &FlightFile) -> Result<Self, String> {
        let mut keys = Vec::with_capacity(file.keys.len());
        for (i, &(time, position, target)) in file.keys.iter().enumerate() {
            let p = key_point(space, position, &format!("key {}: position", i + 1))?;
            let t = key_point(space, target, &format!("key {}: look_at", i + 1))?;
            keys.push((time, p, t));
        }
        Ok(Self {
            keys,
            fov: file.fov,
        })
    }

    /// The camera frame at time `t` in the universal cover (before wrapping).
    #[must_use]
    pub fn cover_frame(&self, t: f64) -> DMat4 {
        let (p, target) = keyed(&self.keys, t, between);
        // Between two keys the target may pass through the eye: look along E₂ there.
        look_frame(p, target)
            .unwrap_or_else(|| DMat4::from_cols(DVec4::X, DVec4::Z, -DVec4::Y, p.extend(1.0)))
    }

    /// The camera at time `t` in the box.
    #[must_use]
    pub fn camera(&self, space: &NilSpace, t: f64) -> super::NilCamera {
        super::NilCamera {
            frame: self.frame_in_cell(space, t).0,
            fov_y_degrees: self.fov,
        }
    }
}

impl CoverFlight for NilFlight {
    type Space = NilSpace;

    fn duration(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.0)
    }

    fn cover_frame(&self, t: f64) -> DMat4 {
        NilFlight::cover_frame(self, t)
    }
}

/// The key of a camera at `frame` in the box that reached it through `holonomy` (`walk
/// --record`): its chart point, a point a quarter ahead that it looks at, and a quarter above
/// it (the replay keeps `E₃` up), carried back into the universal cover by the inverse of
/// the lattice element the crossings applied. `None` where a key cannot hold them (more than
/// [`MAX_KEY_CROSSINGS`] crossings from the box).
#[must_use]
pub fn recorded_nil_key(
    space: &NilSpace,
    frame: DMat4,
    holonomy: &crate::space::Holonomy,
) -> Option<(DVec3, DVec3, DVec3)> {
    use crate::space::nil::transport;
    let mut cover = frame;
    cover.w_axis = holonomy.matrix.inverse() * frame.w_axis;
    let ahead = transport(cover, DVec3::NEG_Z, 0.25).w_axis.truncate();
    let above = transport(cover, DVec3::Y, 0.25).w_axis.truncate();
    let at = cover.w_axis.truncate();
    [at, ahead, above]
        .iter()
        .all(|p| key_point(space, *p, "").is_ok())
        .then_some((at, ahead, above))
}
