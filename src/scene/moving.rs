//! Objects of a scene that move: a scene file's objects with a `velocity` start at their
//! place and fly through the faces ([`crate::space::motion`]); at a time `T` each is where
//! its motion has taken it, turned by every pairing it crossed.

use super::{CurvedScene, Object, PlaceError};
use crate::space::motion::{MotionError, Velocity, fly};
use crate::space::{Holonomy, Space};
use glam::DMat4;

/// The wrap margin of moving objects (the player's default).
pub const MOVING_WRAP_MARGIN: f64 = 1e-4;

/// An object that moves: as it is at time 0, its frame then, and its velocity in that
/// frame's axes.
#[derive(Clone, Debug, PartialEq)]
pub struct MovingObject {
    /// The object at time 0 (its texture, mesh and material indices are its scene's).
    pub object: Object,
    /// Its frame at time 0, in the cell.
    pub frame: DMat4,
    /// Its velocity in its own axes.
    pub velocity: Velocity,
}

impl MovingObject {
    /// Its frame at `time` (in the cell) and the crossings on the way.
    pub fn frame_at(&self, space: &Space, time: f64) -> Result<(DMat4, Holonomy), MotionError> {
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

    /// The object carried from its start frame to `frame`.
    #[must_use]
    pub fn carried_to(&self, space: &Space, frame: DMat4) -> Object {
        let g = space.geometry();
        self.object.transformed(g, frame * g.inverse(self.frame))
    }
}

/// Why a moving object could not be shown at a time.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MovingError {
    /// Its motion could not be followed.
    #[error("moving object {0}: {1}")]
    Motion(usize, MotionError),
    /// It could not be placed where its motion took it.
    #[error("moving object {0}: {1}")]
    Place(usize, PlaceError),
}

impl CurvedScene {
    /// This scene with `moving` added where their motion has taken them at `time`, with
    /// their images through the faces.
    pub fn with_moving_at(
        &self,
        space: &Space,
        moving: &[MovingObject],
        time: f64,
    ) -> Result<CurvedScene, MovingError> {
        let mut scene = self.clone();
        for (i, m) in moving.iter().enumerate() {
            let (frame, _) = m
                .frame_at(space, time)
                .map_err(|e| MovingError::Motion(i, e))?;
            scene
                .place(space, m.carried_to(space, frame))
                .map_err(|e| MovingError::Place(i, e))?;
        }
        Ok(scene)
    }
}
