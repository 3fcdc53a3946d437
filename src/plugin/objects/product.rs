//! A game's entities in a product space (H²×R, S²×R): while a product space is shown,
//! [`CurvedObject`]s move along the product's geodesics and come back into the cell through
//! the sides, the top and the bottom (with their [`crate::space::Holonomy`] and an
//! [`super::ObjectCrossedFace`] each) by the family's generic systems
//! ([`super::move_objects`], [`super::wrap_objects`]), and are drawn as product objects
//! ([`collect_product_objects`] into [`ProductEntityObjects`]).
//!
//! A product scene has balls and horizontal discs among its shapes, so those are what an
//! entity can be here: a [`CurvedShape::Ball`] is a ball at the entity's position, a
//! [`CurvedShape::Disc`] whose normal (the entity's own `z`) is the fibre is a horizontal
//! disc. Other shapes are left out, each with one warning naming the entity. A ball within
//! its radius of a face is drawn with its image through that face too (the part past the
//! face seen from the partner side), so one flying through a face is never cut off; near a
//! corner the images through two faces are added, not their composition.

use super::{CurvedObject, CurvedShape, CurvedTransform, CurvedVelocity};
use crate::geometry::Geometry;
use crate::plugin::components::ActiveSpace;
use crate::space::product::ProductWalker;
use crate::trace::product::{ProductObject, ProductShape};
use bevy::prelude::*;
use glam::{DMat4, DVec4};
use std::collections::HashSet;

/// The entities' objects in the product space shown, gathered when they change (read by
/// the product scene's upload). `generation` counts the changes.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct ProductEntityObjects {
    /// The objects, images through the faces included.
    pub objects: Vec<ProductObject>,
    /// Bumped whenever `objects` changes.
    pub generation: u64,
}

pub use crate::space::product::motion::step_product_velocity as step_product_object;

/// The objects whose shape or frame changed since the last run.
type Changed<'w, 's> = Query<
    'w,
    's,
    (),
    Or<(
        bevy::prelude::Changed<CurvedObject>,
        bevy::prelude::Changed<CurvedTransform>,
    )>,
>;

/// The product object of an entity's shape at `frame`, or why it has none.
fn product_object(
    g: Geometry,
    object: &CurvedObject,
    frame: DMat4,
) -> Result<ProductObject, String> {
    let colour = object.colour.unwrap_or(glam::DVec3::ONE) + object.emission;
    let positive = |x: f64| {
        if x > 0.0 && x.is_finite() {
            Ok(x)
        } else {
            Err(format!("its radius must be a positive number, got {x}"))
        }
    };
    if !frame.is_finite() {
        return Err("its frame is not finite".into());
    }
    let p = frame.w_axis;
    match &object.shape {
        CurvedShape::Ball { radius } => Ok(ProductObject {
            shape: ProductShape::Point(p),
            radius: positive(*radius)?,
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
                radius: positive(*radius)?,
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

/// Gathers the entities' objects (and the images of balls reaching through faces) into
/// [`ProductEntityObjects`] when any of them or the space changed.
pub fn collect_product_objects(
    active: Res<ActiveSpace>,
    objects: Query<(Entity, &CurvedObject, &CurvedTransform)>,
    changed: Changed,
    mut removed: RemovedComponents<CurvedObject>,
    mut warned: Local<HashSet<Entity>>,
    mut walker: Local<Option<(usize, ProductWalker<DVec4>)>>,
    mut out: ResMut<ProductEntityObjects>,
) {
    let Some(space) = active.product() else {
        return;
    };
    let removed_any = removed.read().count() > 0;
    if !(active.is_changed() || removed_any || !changed.is_empty()) {
        return;
    }
    let g = space.base();
    // The walker of the space shown, built once per space, not on every frame an object moves.
    let key = std::sync::Arc::as_ptr(space) as usize;
    if walker.as_ref().is_none_or(|(k, _)| *k != key) {
        *walker = Some((key, ProductWalker::<DVec4>::new(space)));
    }
    let Some((_, walker)) = walker.as_ref() else {
        return;
    };
    let mut sorted: Vec<_> = objects.iter().collect();
    sorted.sort_by_key(|(e, _, _)| *e);
    let mut gathered = Vec::with_capacity(sorted.len());
    for (entity, object, transform) in sorted {
        match product_object(g, object, transform.0) {
            Ok(o) => {
                gathered.extend(images_through_faces(space, walker, &o));
                gathered.push(o);
            }
            Err(why) => {
                if warned.insert(entity) {
                    warn!("{entity} is not drawn in {}: {why}", active.id);
                }
            }
        }
    }
    if gathered != out.objects {
        out.objects = gathered;
        out.generation += 1;
    }
}

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
