//! A game's entities in a Nil space: while a Nil space is shown, [`CurvedObject`]s move along
//! Nil's geodesics (in closed form) and come back into the box through its faces by the
//! family's generic systems ([`super::move_objects`], [`super::wrap_objects`]), and are drawn
//! as metric balls ([`super::gather::collect_entity_objects`] into [`NilEntityObjects`]).
//!
//! A Nil scene meets metric balls and fibre tubes exactly; a game's entity is a point with a
//! frame, so a [`CurvedShape::Ball`] is drawn: a metric ball of its radius about the entity's
//! position (at most [`MAX_NIL_RADIUS`], half the box's side), with each of its lattice
//! images that reaches into the box, so a ball flying through a face is never cut off. Other
//! shapes are left out, each with one warning naming the entity. The entities make at most
//! [`MAX_NIL_OBJECTS`] objects with their images (each is tested along every segment): an
//! entity past it is left out with a warning.

use super::gather::{EntityObjectsOf, EntityShapes, entity_colour, entity_radius};
use super::{CurvedObject, CurvedShape};
use crate::space::nil::NilSpace;
use crate::trace::nil::{MAX_NIL_OBJECTS, MAX_NIL_RADIUS, NilObject, NilShape, push_with_images};
use glam::DMat4;

/// The entities' objects in the Nil space shown, gathered when they change (read by the Nil
/// scene's upload).
pub type NilEntityObjects = EntityObjectsOf<NilSpace>;

/// Nil spaces draw the balls of a game's entities as metric balls.
impl EntityShapes for NilSpace {
    type Object = NilObject;
    type Context = ();

    fn entity_context(&self) -> Self::Context {}

    fn entity_objects(
        &self,
        (): &(),
        object: &CurvedObject,
        frame: DMat4,
        out: &mut Vec<NilObject>,
    ) -> Result<(), String> {
        let CurvedShape::Ball { radius } = object.shape else {
            return Err(
                "Nil spaces draw the balls of a game's entities (metric balls); other shapes \
                 are left out"
                    .into(),
            );
        };
        if !frame.is_finite() {
            return Err("its frame is not finite".into());
        }
        let centre = self.into_box(frame.w_axis.truncate().to_array());
        let ball = NilObject {
            shape: NilShape::Ball(centre),
            radius: entity_radius(radius, MAX_NIL_RADIUS)?,
            colour: entity_colour(object),
        };
        let before = out.len();
        push_with_images(self, ball, out);
        if out.len() > MAX_NIL_OBJECTS {
            return Err(format!(
                "with its {} lattice images in the box the entities would make more than \
                 {MAX_NIL_OBJECTS} objects: spawn fewer or smaller balls",
                out.len() - before
            ));
        }
        Ok(())
    }
}
