//! Balls of a Nil scene that move: a scene file's balls with a `velocity`.
//!
//! A moving ball flies along the Nil geodesic of its velocity (given in the frame
//! `E₁, E₂, E₃` at its centre: the body velocity, which the lattice's left translations
//! keep) and comes back into the box through the faces it passes
//! ([`crate::space::FrameSpace`]'s `step_velocity` and `wrap_frame`, in the steps of
//! [`crate::space::motion::fly`]); at a time it is drawn with every lattice image of it that
//! reaches into the box ([`super::NilScene::add_with_images`]). A still picture at a time
//! places it there ([`NilMover::object_at`]); the plugin places it at the app's clock each
//! frame.

use super::{NilObject, NilScene, NilShape};
use crate::space::motion::{MotionError, Mover};
use crate::space::nil::NilSpace;

/// A ball of a Nil scene that moves: the ball at time 0, its frame then in the box (the
/// axes `E₁, E₂, E₃`, its centre) and its velocity in those axes. Its frame at a time is
/// flown in the steps every family's moving objects take ([`Mover::frame_at`]).
pub type NilMover = Mover<NilObject>;

impl NilMover {
    /// The ball where it is at `time` seconds.
    ///
    /// # Errors
    /// Its motion cannot be followed ([`crate::space::motion::fly`]'s errors).
    pub fn object_at(&self, space: &NilSpace, time: f64) -> Result<NilObject, MotionError> {
        let frame = self.frame_at(space, time)?.0;
        Ok(NilObject {
            shape: NilShape::Ball(frame.w_axis.truncate().to_array()),
            ..self.object
        })
    }
}

/// `scene` with each mover where it is at `time` seconds, with its lattice images in the
/// box; an error says why a time cannot be flown (negative, not finite, too fast).
pub fn scene_at(
    space: &NilSpace,
    scene: &NilScene,
    movers: &[NilMover],
    time: f64,
) -> Result<NilScene, MotionError> {
    let mut at = scene.clone();
    for m in movers {
        at.add_with_images(space, m.object_at(space, time)?);
    }
    Ok(at)
}
