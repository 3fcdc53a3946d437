//! A head-mounted display's poses mapped to frames in the curved space, without any XR
//! runtime (the `xr` feature's glue feeds it; tests drive it with pose sequences).
//!
//! The headset reports rigid poses in the room (metres, right-handed, y up, looking along
//! −z: the same axes as our frames' right, up, back). The head's motion since the last pose,
//! `Δ = P_last⁻¹ · P_now` (a translation `t` and a rotation `R` in the head's own axes), is
//! applied as *local* motion of the head's frame in the space, `F ← F · T(s·t) · R` with `s`
//! the world scale in space units per metre. So walking in the room walks along geodesics,
//! through faces (wrapping with holonomy, as the desktop player does), and a closed walk in
//! the room comes back rotated and displaced by the space's curvature, as it must.
//!
//! Each eye is the head's frame moved by the eye's own pose relative to the head
//! (`P_head⁻¹ · P_eye`, which holds the IPD and any canting of the displays), scaled the
//! same way, and wrapped into the cell with its own pairing ([`crate::view::stereo::wrap_eye`]).

use crate::geometry::Geometry;
use crate::geometry::translate_local;
use crate::space::{FamilySpace, FrameMotion, Holonomy};
use crate::view::stereo::{Eye, wrap_eye};
use glam::{DMat4, DQuat, DVec3};

/// A rigid pose in the room: metres and a unit quaternion (OpenXR's `Posef`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RoomPose {
    /// Position in the room, metres.
    pub position: DVec3,
    /// Orientation in the room.
    pub orientation: DQuat,
}

impl Default for RoomPose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl RoomPose {
    /// The room's origin, looking along −z.
    pub const IDENTITY: RoomPose = RoomPose {
        position: DVec3::ZERO,
        orientation: DQuat::IDENTITY,
    };

    /// A pose from its position and orientation.
    #[must_use]
    pub fn new(position: DVec3, orientation: DQuat) -> Self {
        Self {
            position,
            orientation: orientation.normalize(),
        }
    }

    /// `other` seen from this pose: its translation and rotation in this pose's axes.
    #[must_use]
    pub fn relative(&self, other: &RoomPose) -> (DVec3, DQuat) {
        let inverse = self.orientation.conjugate();
        (
            inverse * (other.position - self.position),
            (inverse * other.orientation).normalize(),
        )
    }

    /// The head between two eye poses: the mean position and the halfway orientation.
    #[must_use]
    pub fn between(a: &RoomPose, b: &RoomPose) -> RoomPose {
        RoomPose::new(
            (a.position + b.position) / 2.0,
            a.orientation.slerp(b.orientation, 0.5),
        )
    }
}

/// A frame moved by a local translation `t` (space units, in the frame's axes) along the
/// geodesic, then turned by `rotation` about its new position.
#[must_use]
pub fn local_motion(geometry: Geometry, frame: DMat4, t: DVec3, rotation: DQuat) -> DMat4 {
    let mut f = translate_local(geometry, frame, t);
    if rotation != DQuat::IDENTITY && rotation.is_finite() {
        f *= DMat4::from_quat(rotation.normalize());
    }
    f
}

/// [`local_motion`] in a space of any family: the translation along the family's geodesic
/// with the frame carried along ([`crate::space::FrameSpace::step_frame`]), then the turn of the frame's
/// own axes. Bit for bit [`local_motion`] in constant curvature.
#[must_use]
pub fn local_motion_in<S: FamilySpace>(
    space: &S,
    frame: DMat4,
    t: DVec3,
    rotation: DQuat,
) -> DMat4 {
    let mut f = space.step_frame(
        frame,
        &FrameMotion {
            translation: t,
            rotation: DVec3::ZERO,
            level: false,
        },
    );
    if rotation != DQuat::IDENTITY && rotation.is_finite() {
        f = space.turn_axes(f, glam::DMat3::from_quat(rotation.normalize()));
    }
    f
}

/// The head of a headset wearer in the curved space (any family: the product spaces' head
/// moves along the product's geodesics and wraps through the sides, the top and the bottom).
#[derive(Clone, Debug, PartialEq)]
pub struct HeadTracker {
    /// The head's frame (columns right, up, back, position), inside the cell.
    pub frame: DMat4,
    /// The face crossings of the head since it entered the space.
    pub holonomy: Holonomy,
    /// Space units per metre of the room.
    pub units_per_metre: f64,
    /// How far past a face the head may go before it wraps (as the desktop player).
    pub wrap_margin: f64,
    last: Option<RoomPose>,
}

impl HeadTracker {
    /// A head at `frame`; the first pose it is given only sets the room's reference.
    #[must_use]
    pub fn new(frame: DMat4, units_per_metre: f64, wrap_margin: f64) -> Self {
        Self {
            frame,
            holonomy: Holonomy::default(),
            units_per_metre,
            wrap_margin,
            last: None,
        }
    }

    /// Moves the head by its motion in the room since the last pose and wraps it into the
    /// cell. Returns the faces crossed.
    pub fn track<S: FamilySpace>(&mut self, space: &S, head: RoomPose) -> Vec<usize> {
        let Some(last) = self.last.replace(head) else {
            return Vec::new();
        };
        let (t, r) = last.relative(&head);
        let moved = local_motion_in(space, self.frame, t * self.units_per_metre, r);
        self.wrap(space, moved)
    }

    /// Forgets the room's reference (after the runtime recentred it): the head stays where it
    /// is in the space, and the next pose only sets the new reference.
    pub fn reanchor(&mut self) {
        self.last = None;
    }

    /// Controller locomotion: a local translation (space units, head axes) and a turn about
    /// the head's up axis (radians, counter-clockwise seen from above). The room reference
    /// is kept, so the next pose continues from here.
    pub fn locomote<S: FamilySpace>(
        &mut self,
        space: &S,
        translation: DVec3,
        yaw: f64,
    ) -> Vec<usize> {
        let turn = DQuat::from_rotation_y(yaw);
        let moved = local_motion_in(space, self.frame, translation, turn);
        self.wrap(space, moved)
    }

    fn wrap<S: FamilySpace>(&mut self, space: &S, frame: DMat4) -> Vec<usize> {
        let (wrapped, crossed) = space.wrap_frame(frame, self.wrap_margin);
        for c in &crossed {
            self.holonomy.record_crossing(c);
        }
        self.frame = wrapped;
        crossed.iter().map(|c| c.face).collect()
    }

    /// An eye's frame from its room pose and the head's: the head's frame moved by the
    /// eye's pose relative to the head, wrapped into the cell with its own pairing.
    #[must_use]
    pub fn eye<S: FamilySpace>(&self, space: &S, head: &RoomPose, eye: &RoomPose) -> Eye {
        let (t, r) = head.relative(eye);
        wrap_eye(
            space,
            local_motion_in(space, self.frame, t * self.units_per_metre, r),
        )
    }
}

/// How the right thumbstick turns the head.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TurnStyle {
    /// A steady turn while the stick is held, at the plugin's turning speed.
    Smooth,
    /// One turn of `degrees` each time the stick is pushed past 70 % to a side (it must come
    /// back under 30 % before the next): what most wearers prone to motion sickness prefer.
    Snap {
        /// The angle of one snap, in degrees.
        degrees: f64,
    },
}

impl Default for TurnStyle {
    fn default() -> Self {
        TurnStyle::Snap { degrees: 30.0 }
    }
}

/// Stick values under this are resting drift.
pub const DEAD_ZONE: f64 = 0.15;
/// A snap turn fires past this push…
const SNAP_PUSH: f64 = 0.7;
/// …and re-arms once the stick is back under this.
const SNAP_RELEASE: f64 = 0.3;

/// The yaw (radians, counter-clockwise seen from above) the turning stick's `x` (right
/// positive) asks for in a frame of `dt` seconds, and whether a snap is held after it
/// (`snapped`: whether one was held before).
#[must_use]
pub fn turn_yaw(style: TurnStyle, x: f64, turn_speed: f64, dt: f64, snapped: bool) -> (f64, bool) {
    match style {
        TurnStyle::Smooth => {
            let x = if x.abs() < DEAD_ZONE { 0.0 } else { x };
            (-x * turn_speed * dt, false)
        }
        TurnStyle::Snap { degrees } => {
            if snapped {
                (0.0, x.abs() >= SNAP_RELEASE)
            } else if x.abs() > SNAP_PUSH {
                (-x.signum() * degrees.to_radians(), true)
            } else {
                (0.0, false)
            }
        }
    }
}
