//! A game's entities drawn in a family whose scenes have an object type of their own (the
//! product spaces, Nil): one gathering system written once ([`collect_entity_objects`]),
//! instantiated per family, turns each [`CurvedObject`] into the family's scene objects
//! (with the images that reach into the cell through its faces) when any of them or the
//! space changed; the family's upload adds them to its scene. The family says which shapes
//! it can meet exactly ([`EntityShapes`]); an entity of any other shape is left out with one
//! warning that names it and says why.

use super::{CurvedObject, CurvedTransform};
use crate::plugin::components::ActiveSpace;
use crate::space::FamilySpace;
use bevy::prelude::*;
use glam::{DMat4, DVec3};
use std::collections::HashSet;

/// What a family draws of a game's entities: its scene object type, and how an entity's
/// shape at a frame becomes objects of it.
pub trait EntityShapes: FamilySpace {
    /// The family's scene object.
    type Object: Clone + PartialEq + Send + Sync + std::fmt::Debug + 'static;
    /// What the gathering keeps per space shown (made once a space, not once a frame).
    type Context: Send + Sync + 'static;

    /// The per-space context.
    fn entity_context(&self) -> Self::Context;

    /// Pushes onto `out` the objects that draw `object` at `frame` (the frame already
    /// wrapped into the cell), its images through the faces included; `out` holds the
    /// objects gathered before it (a family with a limit counts them). An error says why
    /// the entity is not drawn.
    fn entity_objects(
        &self,
        context: &Self::Context,
        object: &CurvedObject,
        frame: DMat4,
        out: &mut Vec<Self::Object>,
    ) -> Result<(), String>;
}

/// The entities' objects in the space shown of the family `F`, gathered when they change
/// (read by the family's scene upload). `generation` counts the changes.
#[derive(Resource)]
pub struct EntityObjectsOf<F: EntityShapes> {
    /// The objects, images through the faces included.
    pub objects: Vec<F::Object>,
    /// Bumped whenever `objects` changes.
    pub generation: u64,
}

impl<F: EntityShapes> Default for EntityObjectsOf<F> {
    fn default() -> Self {
        Self {
            objects: Vec::new(),
            generation: 0,
        }
    }
}

impl<F: EntityShapes> Clone for EntityObjectsOf<F> {
    fn clone(&self) -> Self {
        Self {
            objects: self.objects.clone(),
            generation: self.generation,
        }
    }
}

impl<F: EntityShapes> std::fmt::Debug for EntityObjectsOf<F> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EntityObjectsOf")
            .field("objects", &self.objects)
            .field("generation", &self.generation)
            .finish()
    }
}

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

/// Gathers the entities' objects (with their images through faces) into
/// [`EntityObjectsOf<F>`] when any of them or the space changed, while a space of `F` is
/// shown. Entities are taken in their id's order, so the same entities give the same scene.
// A Bevy system takes its queries and resources as arguments.
#[allow(clippy::too_many_arguments)]
pub fn collect_entity_objects<F: EntityShapes>(
    active: Res<ActiveSpace>,
    objects: Query<(Entity, &CurvedObject, &CurvedTransform)>,
    changed: Changed,
    mut removed: RemovedComponents<CurvedObject>,
    mut warned: Local<HashSet<Entity>>,
    mut context: Local<Option<(usize, F::Context)>>,
    mut out: ResMut<EntityObjectsOf<F>>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    let removed_any = removed.read().count() > 0;
    if !(active.is_changed() || removed_any || !changed.is_empty()) {
        return;
    }
    let key = std::sync::Arc::as_ptr(space) as usize;
    if context.as_ref().is_none_or(|(k, _)| *k != key) {
        *context = Some((key, space.entity_context()));
    }
    let Some((_, context)) = context.as_ref() else {
        return;
    };
    let mut sorted: Vec<_> = objects.iter().collect();
    sorted.sort_by_key(|(e, _, _)| *e);
    let mut gathered = Vec::with_capacity(sorted.len());
    for (entity, object, transform) in sorted {
        let before = gathered.len();
        if let Err(why) = space.entity_objects(context, object, transform.0, &mut gathered) {
            gathered.truncate(before);
            if warned.insert(entity) {
                warn!("{entity} is not drawn in {}: {why}", active.id);
            }
        }
    }
    if gathered != out.objects {
        out.objects = gathered;
        out.generation += 1;
    }
}

/// An entity's colour in a family that has no emission of its own: its albedo (white where
/// it has none) plus what it gives off.
#[must_use]
pub fn entity_colour(object: &CurvedObject) -> DVec3 {
    object.colour.unwrap_or(DVec3::ONE) + object.emission
}

/// A radius that is a positive finite number at most `most` (infinite: no limit), or why not.
pub fn entity_radius(radius: f64, most: f64) -> Result<f64, String> {
    if radius > 0.0 && radius.is_finite() && radius <= most {
        Ok(radius)
    } else if most.is_finite() {
        Err(format!(
            "its radius must be a positive number of at most {most}, got {radius}"
        ))
    } else {
        Err(format!(
            "its radius must be a positive number, got {radius}"
        ))
    }
}
