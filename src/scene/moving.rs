//! Objects of a scene that move: a scene file's objects with a `velocity` start at their
//! place and fly through the faces ([`crate::space::motion`]); at a time `T` each is where
//! its motion has taken it, turned by every pairing it crossed.

use super::{CurvedScene, Object, PlaceError};
use crate::space::Space;
pub use crate::space::motion::MOVING_WRAP_MARGIN;
use crate::space::motion::{MotionError, Mover};
use glam::DMat4;

/// An object of a constant-curvature scene that moves: as it is at time 0, its frame then,
/// and its velocity in that frame's axes (its texture, mesh and material indices are its
/// scene's).
pub type MovingObject = Mover<Object>;

impl MovingObject {
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
