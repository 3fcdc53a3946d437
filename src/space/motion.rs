//! Things that move through the faces: a frame with a constant velocity in its own axes,
//! stepped along geodesics and wrapped into the cell like the player ([`fly`]), and the
//! shortest geodesic between two points of the manifold, through any faces ([`Sightlines`]).
//!
//! One step moves the frame by `F ← F · T(v dt) · R(ω dt)`: a translation along its own
//! direction `v` (a geodesic: steps along the same local direction compose exactly), then
//! a turn about its own axis `ω`. After every step the frame is wrapped into the cell by
//! its family's wrap ([`super::FrameSpace::wrap_frame`]), so its numbers stay those of a
//! point in the cell however long it flies (a frame carried along in the cover would lose
//! digits as `cosh d` grows in H³).
//! The plugin's fixed-step systems and a scene file's `velocity` at a time `T` use the same
//! steps of [`MOTION_STEP`], so they agree.

use super::invariants::circumradius;
use super::orbit::OrbitPoints;
use super::{Holonomy, Space};
use crate::geometry::{Geometry, translate_local};
use glam::{DMat4, DVec3, DVec4};

/// The length of one motion step in seconds: Bevy's default fixed time step (64 Hz).
pub const MOTION_STEP: f64 = 1.0 / 64.0;

/// How many cell sizes ([`super::FrameSpace::scale`]) one step of [`fly`] may go at most.
pub const MAX_CELLS_PER_STEP: f64 = 4.0;

/// The most steps [`fly`] takes (about 43 hours of motion at [`MOTION_STEP`]).
pub const MAX_MOTION_STEPS: u64 = 10_000_000;

/// A velocity in a frame's own axes (right, up, back).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Velocity {
    /// Distance per second along the frame's own axes (geodesic units).
    pub linear: DVec3,
    /// Radians per second about the frame's own axes (the turn's axis times its rate).
    pub angular: DVec3,
}

impl Velocity {
    /// Whether it moves or turns at all.
    #[must_use]
    pub fn is_zero(&self) -> bool {
        self.linear == DVec3::ZERO && self.angular == DVec3::ZERO
    }

    /// Whether every component is a finite number.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.linear.is_finite() && self.angular.is_finite()
    }

    /// The frame after `dt` seconds of this velocity: translated along its own direction,
    /// then turned about its own axis. A non-finite velocity leaves the frame where it is.
    #[must_use]
    pub fn step(&self, geometry: Geometry, frame: DMat4, dt: f64) -> DMat4 {
        if !self.is_finite() || !dt.is_finite() {
            return frame;
        }
        let mut f = translate_local(geometry, frame, self.linear * dt);
        let rate = self.angular.length();
        if rate > 0.0 {
            f *= geometry.rotation(self.angular / rate, rate * dt);
        }
        f
    }
}

/// Why a motion cannot be followed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// The time or a velocity component is not a finite number.
    #[error("the time and the velocity must be finite numbers")]
    NotFinite,
    /// The time is negative.
    #[error("the time must be 0 or more, got {0}")]
    NegativeTime(f64),
    /// Following the motion would take more than [`MAX_MOTION_STEPS`] steps.
    #[error(
        "{steps} motion steps of {MOTION_STEP} s are needed for that time; at most {MAX_MOTION_STEPS} are taken"
    )]
    TooLong {
        /// The steps that would be needed.
        steps: u64,
    },
    /// One step of [`MOTION_STEP`] would go farther than [`MAX_CELLS_PER_STEP`] cell sizes
    /// (the wrap brings a frame back through a few faces a step, and in H³ or H²×R a step
    /// of thousands of units leaves f64).
    #[error(
        "a speed of {speed} is too fast: one motion step would cross more than {MAX_CELLS_PER_STEP} cells (at most {limit} in this space's units a second)"
    )]
    TooFast {
        /// The linear speed asked for (space units a second).
        speed: f64,
        /// The largest speed followed.
        limit: f64,
    },
}

/// Whether one step of `dt` seconds at `velocity` stays within [`MAX_CELLS_PER_STEP`] cell
/// sizes of `space` (the most the wrap after it follows; in H³ or H²×R a step of thousands of
/// units leaves f64): [`fly`]'s bound on its steps, and the plugin's on an entity's fixed
/// step. A velocity that is not finite is too fast.
///
/// # Errors
/// [`MotionError::TooFast`] with the speed and the largest speed followed at this step.
pub fn check_speed<S: super::FrameSpace + ?Sized>(
    space: &S,
    velocity: &Velocity,
    dt: f64,
) -> Result<(), MotionError> {
    let (speed, limit) = (
        velocity.linear.length(),
        MAX_CELLS_PER_STEP * space.scale() / dt,
    );
    if speed <= limit {
        Ok(())
    } else {
        Err(MotionError::TooFast { speed, limit })
    }
}

/// The frame `frame` (in the cell of a space of any family) after `time` seconds at
/// `velocity`: stepped by [`MOTION_STEP`] (the last step shorter) and wrapped into the cell
/// after each step with margin `margin`, every crossing recorded in `holonomy` (the
/// plugin's entities move by the same steps and the same rule).
pub fn fly<S: super::FrameSpace + ?Sized>(
    space: &S,
    frame: DMat4,
    velocity: &Velocity,
    time: f64,
    margin: f64,
    holonomy: &mut Holonomy,
) -> Result<DMat4, MotionError> {
    if !(time.is_finite() && velocity.is_finite()) {
        return Err(MotionError::NotFinite);
    }
    if time < 0.0 {
        return Err(MotionError::NegativeTime(time));
    }
    if velocity.is_zero() || time == 0.0 {
        return Ok(frame);
    }
    check_speed(space, velocity, MOTION_STEP)?;
    let steps = (time / MOTION_STEP).ceil();
    if steps > MAX_MOTION_STEPS as f64 {
        return Err(MotionError::TooLong {
            steps: steps as u64,
        });
    }
    let whole = (time / MOTION_STEP).floor() as u64;
    let rest = time - whole as f64 * MOTION_STEP;
    let mut f = frame;
    let mut advance = |f: DMat4, dt: f64| {
        let (wrapped, crossed) = space.wrap_frame(space.step_velocity(f, velocity, dt), margin);
        for c in &crossed {
            holonomy.record_crossing(c);
        }
        wrapped
    };
    for _ in 0..whole {
        f = advance(f, MOTION_STEP);
    }
    if rest > 0.0 {
        f = advance(f, rest);
    }
    Ok(f)
}

/// The shortest geodesic from one point of the manifold to another, through any faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sightline {
    /// Its length.
    pub distance: f64,
    /// The unit direction it leaves in, in the axes of the frame it starts from (right,
    /// up, back); zero where the two points are the same.
    pub direction: DVec3,
    /// The deck transformation `h` with the target seen at `h · target`: the copy of the
    /// target the geodesic runs to.
    pub element: DMat4,
}

/// The shortest geodesics between points of a space's manifold: a best-first search over
/// the copies of the cell near the starting point.
///
/// The geodesic from `a` to the nearest copy `h·b` of `b` crosses a chain of face-adjacent
/// copies of the cell, each within `d(a, h·b) + R` of `a` (`R` the cell's circumradius about
/// its centre). The search visits copies `g·D` (neighbours by the face pairings) in order of
/// `d(a, g·c)` and stops once that exceeds the best distance found plus `R`: every copy the
/// chain needs is visited. In H³ that is a few hundred copies for a cell like
/// Seifert–Weber's, in microseconds.
#[derive(Clone, Debug)]
pub struct Sightlines {
    geometry: Geometry,
    centre: DVec4,
    radius: f64,
    pairings: Vec<DMat4>,
}

/// The most copies of the cell one [`Sightlines::between`] visits (a guard: far more than
/// any seed space or census manifold needs).
pub const MAX_SIGHTLINE_COPIES: usize = 200_000;

/// Two copies of the cell are one when their centres are closer than this.
const SAME_COPY: f64 = 1e-7;

impl Sightlines {
    /// The search for `space`.
    #[must_use]
    pub fn new(space: &Space) -> Self {
        Self {
            geometry: space.geometry,
            centre: space.centre(),
            radius: circumradius(space),
            pairings: space.faces.iter().map(|f| f.pairing).collect(),
        }
    }

    /// The shortest geodesic from the origin of `from` (a frame in the cell) to `to` (a
    /// point in the cell).
    #[must_use]
    pub fn between(&self, from: DMat4, to: DVec4) -> Sightline {
        use std::cmp::Reverse;
        use std::collections::BinaryHeap;
        let g = self.geometry;
        let a = g.project_point(from.w_axis);
        let to = g.project_point(to);
        // Ordered by the distance from `a` to the copy's centre (f64 bits order like the
        // numbers for non-negative values).
        let mut queue = BinaryHeap::new();
        let mut seen = OrbitPoints::new(g, SAME_COPY);
        seen.push(self.centre);
        queue.push((Reverse(g.distance(a, self.centre).to_bits()), 0usize));
        let mut elements = vec![DMat4::IDENTITY];
        let (mut best, mut element) = (g.distance(a, to), DMat4::IDENTITY);
        while let Some((Reverse(bits), i)) = queue.pop() {
            if f64::from_bits(bits) > best + self.radius + 1e-9 {
                break;
            }
            let h = elements[i];
            let d = g.distance(a, g.project_point(h * to));
            if d < best {
                (best, element) = (d, h);
            }
            if elements.len() >= MAX_SIGHTLINE_COPIES {
                continue;
            }
            for pairing in &self.pairings {
                let next = h * *pairing;
                let c = g.project_point(next * self.centre);
                if seen.insert(c) {
                    elements.push(next);
                    queue.push((Reverse(g.distance(a, c).to_bits()), elements.len() - 1));
                }
            }
        }
        let direction = if best > 1e-12 {
            let v = g.tangent_towards(a, g.project_point(element * to));
            // The frame's columns are orthonormal in the form: a tangent's coordinates in
            // them are its forms with the columns.
            DVec3::new(
                g.form(v, from.x_axis),
                g.form(v, from.y_axis),
                g.form(v, from.z_axis),
            )
            .normalize_or_zero()
        } else {
            DVec3::ZERO
        };
        Sightline {
            distance: best,
            direction,
            element,
        }
    }
}

/// A flight through a space of some family: keys in the universal cover, the camera at any
/// time a frame of the cover, brought back into the cell through the faces it passed. The
/// frame in the cell and the plugin's replay (`plugin::flight::FlightReplay`) are written
/// once over it; each family's flight type says how its keys are joined.
pub trait CoverFlight: Clone + std::fmt::Debug + Send + Sync + 'static {
    /// The family's space.
    type Space: super::FamilySpace;

    /// Seconds from the first key to the last.
    #[must_use]
    fn duration(&self) -> f64;

    /// The camera's frame at time `t` in the universal cover (before wrapping).
    #[must_use]
    fn cover_frame(&self, t: f64) -> DMat4;

    /// How many frames the flight has at `fps`: one every `1/fps` seconds from 0, up to but
    /// not including the end (one at least).
    #[must_use]
    fn frame_count(&self, fps: f64) -> usize {
        ((self.duration() * fps).round() as usize).max(1)
    }

    /// The camera frame at time `t` in the cell, with the crossings of the way there from
    /// the first key's cell, in order (the camera's holonomy).
    #[must_use]
    fn frame_in_cell(&self, space: &Self::Space, t: f64) -> (DMat4, Vec<super::FrameCrossing>) {
        use super::FrameSpace;
        let mut frame = self.cover_frame(t);
        let mut crossings = Vec::new();
        for _ in 0..64 {
            let (wrapped, crossed) = space.wrap_frame(frame, 0.0);
            frame = wrapped;
            if crossed.is_empty() {
                break;
            }
            crossings.extend(crossed);
        }
        (frame, crossings)
    }
}

/// The position and target at time `t` of a flight's keys (time, position, target, in
/// order of time): the first key's before it, the last's after it, and between two keys each
/// moved the share of the way `between(from, to, share)` says.
pub fn keyed<P: Copy>(keys: &[(f64, P, P)], t: f64, between: impl Fn(P, P, f64) -> P) -> (P, P) {
    let i = keys.partition_point(|k| k.0 <= t);
    if i == 0 {
        (keys[0].1, keys[0].2)
    } else if i == keys.len() {
        (keys[i - 1].1, keys[i - 1].2)
    } else {
        let (a, b) = (keys[i - 1], keys[i]);
        let s = (t - a.0) / (b.0 - a.0);
        (between(a.1, b.1, s), between(a.2, b.2, s))
    }
}

/// How far past a face a moving object is let go before it is wrapped back into the cell
/// (a scene's moving objects and the plugin's entities use the same margin, so a still
/// picture shows an object where a walk does).
pub const MOVING_WRAP_MARGIN: f64 = 1e-4;

/// An object of any family's scene that moves: the object as it is at time 0, its frame
/// then (in the cell) and its velocity in that frame's axes. Where it is at a time is
/// written once ([`Mover::frame_at`], in the steps of [`fly`]); what an object carried to a
/// frame is, is its family's (`scene::MovingObject`, `trace::product::moving::ProductMover`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mover<O> {
    /// The object at time 0.
    pub object: O,
    /// Its frame at time 0, in the cell.
    pub frame: DMat4,
    /// Its velocity in its own axes (space units a second).
    pub velocity: Velocity,
}

impl<O> Mover<O> {
    /// Its frame at `time` seconds (in the cell of `space`) and the crossings on the way.
    ///
    /// # Errors
    /// Its motion cannot be followed ([`fly`]'s errors).
    pub fn frame_at<S: super::FrameSpace + ?Sized>(
        &self,
        space: &S,
        time: f64,
    ) -> Result<(DMat4, Holonomy), MotionError> {
        let mut holonomy = Holonomy::default();
        let frame = fly(
            space,
            self.frame,
            &self.velocity,
            time,
            MOVING_WRAP_MARGIN,
            &mut holonomy,
        )?;
        Ok((frame, holonomy))
    }
}
