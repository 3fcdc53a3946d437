//! A game's entities in a product space (H²×R, S²×R): while a product space is shown,
//! [`CurvedObject`]s move along the product's geodesics and come back into the cell through
//! the sides, the top and the bottom (with their [`crate::space::Holonomy`] and an
//! [`super::ObjectCrossedFace`] each) by the family's generic systems
//! ([`super::move_objects`], [`super::wrap_objects`]), and are drawn as product objects
//! ([`super::gather::collect_entity_objects`] into [`ProductEntityObjects`]).
//!
//! A product scene has balls and horizontal discs among its shapes, so those are what an
//! entity can be here: a [`CurvedShape::Ball`] is a ball at the entity's position, a
//! [`CurvedShape::Disc`] whose normal (the entity's own `z`) is the fibre is a horizontal
//! disc. Other shapes are left out, each with one warning naming the entity. A ball within
//! its radius of a face is drawn with its image through that face too (the part past the
//! face seen from the partner side), so one flying through a face is never cut off; near a
//! corner the images through two faces are added, not their composition.

use super::gather::{EntityObjectsOf, EntityShapes, entity_colour, entity_radius};
use super::{CurvedObject, CurvedShape, CurvedTransform, CurvedVelocity};
use crate::geometry::Geometry;
use crate::plugin::components::ActiveSpace;
use crate::space::product::{ProductSpace, ProductWalker};
use crate::trace::product::{ProductObject, ProductShape};
use bevy::prelude::*;
use glam::{DMat4, DVec4};

/// The entities' objects in the product space shown, gathered when they change (read by
/// the product scene's upload) by [`super::gather::collect_entity_objects`].
pub type ProductEntityObjects = EntityObjectsOf<ProductSpace>;

pub use crate::space::product::motion::step_product_velocity as step_product_object;

/// The product spaces draw balls and horizontal discs of a game's entities.
impl EntityShapes for ProductSpace {
    type Object = ProductObject;
    // The walker of the space shown, built once per space, not on every frame an object moves.
    type Context = ProductWalker<DVec4>;

    fn entity_context(&self) -> Self::Context {
        ProductWalker::<DVec4>::new(self)
    }

    fn entity_objects(
        &self,
        walker: &Self::Context,
        object: &CurvedObject,
        frame: DMat4,
        out: &mut Vec<ProductObject>,
    ) -> Result<(), String> {
        let o = product_object(self.base(), object, frame)?;
        out.extend(images_through_faces(self, walker, &o));
        out.push(o);
        Ok(())
    }
}

/// The product object of an entity's shape at `frame`, or why it has none.
fn product_object(
    g: Geometry,
    object: &CurvedObject,
    frame: DMat4,
) -> Result<ProductObject, String> {
    let colour = entity_colour(object);
    if !frame.is_finite() {
        return Err("its frame is not finite".into());
    }
    let p = frame.w_axis;
    match &object.shape {
        CurvedShape::Ball { radius } => Ok(ProductObject {
            shape: ProductShape::Point(p),
            radius: entity_radius(*radius, f64::INFINITY)?,
            colour,
        }),
        CurvedShape::Disc { radius } => {
            let n = frame.z_axis;
            let len = crate::space::product::motion::product_dot(g, n, n).sqrt();
            if !(n.z.abs() >= (1.0 - 1e-9) * len) {
                return Err(
                    "a disc in a product space lies in a slice: its normal (the entity's own z) \
                     must be the fibre"
                        .into(),
                );
            }
            Ok(ProductObject {
                shape: ProductShape::Disc(p),
                radius: entity_radius(*radius, f64::INFINITY)?,
                colour,
            })
        }
        _ => Err(
            "product spaces draw balls and horizontal discs of a game's entities; other shapes \
             are left out"
                .into(),
        ),
    }
}

use crate::trace::product::moving::images_through_faces;

/// Spawns an entity (a ball flying with its velocity) for each moving ball of the base
/// product scene while a product space is shown; on a change of the scene or the space the
/// ones spawned before go.
pub fn spawn_product_movers(
    base: Option<Res<crate::plugin::components::BaseProductScene>>,
    active: Res<ActiveSpace>,
    movers: Query<Entity, With<super::SceneMover>>,
    mut commands: Commands,
) {
    if !(active.is_changed() || base.as_ref().is_some_and(|b| b.is_changed())) {
        return;
    }
    for e in &movers {
        commands.entity(e).despawn();
    }
    let (Some(base), Some(_)) = (base, active.product()) else {
        return;
    };
    for (i, m) in base.moving.iter().enumerate() {
        commands.spawn((
            super::SceneMover(i),
            CurvedObject::ball(m.object.radius, m.object.colour),
            CurvedTransform(m.frame),
            CurvedVelocity(m.velocity),
        ));
    }
}
