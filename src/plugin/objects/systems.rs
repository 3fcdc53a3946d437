//! The systems that move, wrap and gather the entities' objects.

use super::meshes::MeshKey;
use super::*;
use crate::space::FamilySpace;

pub(super) fn update_sightlines(
    active: Res<ActiveSpace>,
    mut sightlines: ResMut<ActiveSightlines>,
) {
    let Some(space) = active.constant() else {
        return;
    };
    if active.is_changed() || sightlines.0.is_none() {
        sightlines.0 = Some(Arc::new(Sightlines::new(space)));
    }
}

/// The objects whose shape or frame changed since the last run.
type ChangedObjects<'w, 's> =
    Query<'w, 's, (), Or<(Changed<CurvedObject>, Changed<CurvedTransform>)>>;

/// The scale of a size as a key (sizes are compared exactly).
fn size_key(size: f64) -> u64 {
    size.to_bits()
}

/// Moves every object with a velocity by one fixed step (`FixedUpdate`), in the family `F` of
/// the space shown. An object too fast to follow (a step past
/// [`crate::space::motion::MAX_CELLS_PER_STEP`] cell sizes) stays where it is, with a warning
/// once.
pub fn move_objects<F: FamilySpace>(
    time: Res<Time>,
    active: Res<ActiveSpace>,
    mut objects: Query<(Entity, &mut CurvedTransform, &CurvedVelocity)>,
    mut too_fast: Local<std::collections::HashSet<Entity>>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    let dt = time.delta_secs_f64();
    for (entity, mut transform, velocity) in &mut objects {
        if velocity.0.is_zero() {
            continue;
        }
        // A step past a few cells is more than the wrap follows (and in H³ leaves f64):
        // such an entity stays where it is, and the game is told once.
        if let Err(e) = crate::space::motion::check_speed(space.as_ref(), &velocity.0, dt) {
            if too_fast.insert(entity) {
                warn!("entity {entity} does not move: {e}");
            }
            continue;
        }
        too_fast.remove(&entity);
        transform.0 = space.step_velocity(transform.0, &velocity.0, dt);
    }
}

/// Brings objects that left the cell of the family `F`'s space back in through the faces
/// (the player's rule and margin), recording each crossing in their [`Holonomy`] and as an
/// [`ObjectCrossedFace`]. Runs after the fixed-step motion and again after `Update`'s
/// motion (objects the game moved itself); on a change of space every object is checked.
pub fn wrap_objects<F: FamilySpace>(
    active: Res<ActiveSpace>,
    settings: Res<PlayerSettings>,
    mut objects: Query<(Entity, &mut CurvedTransform, &mut Holonomy), With<CurvedObject>>,
    mut crossed_faces: MessageWriter<ObjectCrossedFace>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    for (entity, mut transform, mut holonomy) in &mut objects {
        if !(transform.is_changed() || active.is_changed()) {
            continue;
        }
        let (wrapped, crossed) = space.wrap_frame(transform.0, settings.wrap_margin);
        if crossed.is_empty() {
            continue;
        }
        for c in crossed {
            holonomy.record_crossing(&c);
            crossed_faces.write(ObjectCrossedFace {
                entity,
                face: c.face,
                pairing: c.pairing,
                crossings: holonomy.crossings,
            });
        }
        transform.0 = wrapped;
    }
}

/// Gathers the entities' objects into [`EntityObjects`] when any of them, the space or a
/// mesh they use changed, or while a mesh is loading or being built.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
pub fn collect_objects(
    active: Res<ActiveSpace>,
    objects: Query<(Entity, &CurvedObject, &CurvedTransform)>,
    changed: ChangedObjects,
    mut removed: RemovedComponents<CurvedObject>,
    meshes: Option<Res<Assets<Mesh>>>,
    images: Option<Res<Assets<Image>>>,
    mut traced: ResMut<TracedMeshes>,
    mut out: ResMut<EntityObjects>,
) {
    let Some(space) = active.constant() else {
        return;
    };
    let removed_any = removed.read().count() > 0;
    if !(active.is_changed()
        || removed_any
        || !changed.is_empty()
        || traced.changed
        || out.pending > 0)
    {
        return;
    }
    traced.changed = false;
    let g = space.geometry;
    let mut ready = Vec::with_capacity(objects.iter().len());
    let mut pending = 0;
    let mut problems = Vec::new();
    let mut used = std::collections::HashSet::new();
    let mut sorted: Vec<_> = objects.iter().collect();
    sorted.sort_by_key(|(e, _, _)| *e);
    for (entity, object, transform) in sorted {
        let positive = |name: &str, x: f64| -> Result<f64, String> {
            if x > 0.0 && x.is_finite() {
                Ok(x)
            } else {
                Err(format!("its {name} must be a positive number, got {x}"))
            }
        };
        let shape: Result<Option<ReadyShape>, String> = match &object.shape {
            CurvedShape::Ball { radius } => {
                positive("radius", *radius).map(|r| Some(ReadyShape::Ball(r)))
            }
            CurvedShape::Globe {
                radius,
                texture,
                spin,
            } => positive("radius", *radius).and_then(|r| {
                if spin.is_finite() {
                    Ok(Some(ReadyShape::Globe(r, texture.clone(), *spin)))
                } else {
                    Err(format!("its spin must be finite, got {spin}"))
                }
            }),
            CurvedShape::Tube { length, radius } => positive("length", *length)
                .and_then(|l| positive("radius", *radius).map(|r| Some(ReadyShape::Tube(l, r)))),
            CurvedShape::Disc { radius } => {
                positive("radius", *radius).map(|r| Some(ReadyShape::Disc(r)))
            }
            CurvedShape::Model { model, size } => positive("size", *size).and_then(|size| {
                let ptr = Arc::as_ptr(model) as usize;
                traced.models.entry(ptr).or_insert_with(|| model.clone());
                let key = MeshKey::Model(ptr, g, size_key(size));
                used.insert(key.clone());
                let model = model.clone();
                traced
                    .get(key, g, size, move || Ok((*model).clone()))
                    .map(|m| m.map(ReadyShape::Mesh))
            }),
            CurvedShape::Carried { object, start } => {
                Ok(Some(ReadyShape::Carried(*object, *start)))
            }
            CurvedShape::Traced(model) => {
                if model.geometry == g {
                    Ok(Some(ReadyShape::Mesh(model.clone())))
                } else {
                    Err(format!(
                        "its mesh was traced for {} space, not {}",
                        model.geometry.name(),
                        g.name()
                    ))
                }
            }
            CurvedShape::Mesh {
                mesh,
                texture,
                size,
            } => positive("size", *size).and_then(|size| {
                let key = MeshKey::Asset(
                    mesh.id(),
                    texture.as_ref().map(Handle::id),
                    g,
                    size_key(size),
                );
                let Some(meshes) = meshes.as_deref() else {
                    return Err("the app has no mesh assets (add Bevy's MeshPlugin)".into());
                };
                let Some(m) = meshes.get(mesh) else {
                    return Ok(None);
                };
                let image = match texture {
                    None => None,
                    Some(t) => match images.as_deref().and_then(|i| i.get(t)) {
                        Some(i) => Some(i),
                        None => return Ok(None),
                    },
                };
                used.insert(key.clone());
                traced
                    .get(key, g, size, || {
                        model_from_bevy_mesh(m, image).map_err(|e| e.to_string())
                    })
                    .map(|m| m.map(ReadyShape::Mesh))
            }),
        };
        match shape {
            Ok(Some(shape)) => {
                if transform.0.is_finite() {
                    // A frame the game set past a face this frame (wrapped in the next
                    // update) is drawn where it is: at its image in the cell.
                    let frame = if space.outside_by(g.project_point(transform.0.w_axis)) > 0.0 {
                        wrap_into_cell(space, transform.0, 0.0).0
                    } else {
                        transform.0
                    };
                    ready.push(ReadyObject {
                        entity,
                        shape,
                        frame,
                        colour: object.colour,
                        emission: object.emission,
                        reflectance: object.reflectance,
                    });
                } else {
                    problems.push(format!("object {entity}: its frame is not finite"));
                }
            }
            Ok(None) => pending += 1,
            Err(e) => problems.push(format!("object {entity}: {e}")),
        }
    }
    traced.keep_only(&used);
    for p in &problems {
        if !out.problems.contains(p) {
            warn!("{p}");
        }
    }
    *out = EntityObjects {
        objects: ready,
        pending,
        problems,
    };
}

/// Forgets traced meshes whose assets changed or went away (hot reloading).
pub fn forget_changed_assets(
    mut mesh_events: MessageReader<AssetEvent<Mesh>>,
    mut image_events: MessageReader<AssetEvent<Image>>,
    mut traced: ResMut<TracedMeshes>,
) {
    for e in mesh_events.read() {
        match e {
            AssetEvent::Modified { id }
            | AssetEvent::Removed { id }
            | AssetEvent::Unused { id } => {
                traced.forget_mesh(*id);
            }
            AssetEvent::LoadedWithDependencies { .. } | AssetEvent::Added { .. } => {
                traced.changed = true;
            }
        }
    }
    for e in image_events.read() {
        match e {
            AssetEvent::Modified { id }
            | AssetEvent::Removed { id }
            | AssetEvent::Unused { id } => {
                traced.forget_image(*id);
            }
            AssetEvent::LoadedWithDependencies { .. } | AssetEvent::Added { .. } => {
                traced.changed = true;
            }
        }
    }
}

/// Marks the entities the plugin spawned for the base scene's moving objects (the index in
/// [`crate::plugin::components::BaseScene::moving`]): despawned when the base scene or the space
/// changes.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneMover(pub usize);

/// Spawns an entity for each moving object of the base scene while it is in use.
pub fn spawn_scene_movers(
    base: Res<crate::plugin::components::BaseScene>,
    active: Res<ActiveSpace>,
    movers: Query<Entity, With<SceneMover>>,
    mut commands: Commands,
) {
    if !(base.is_changed() || active.is_changed()) {
        return;
    }
    for e in &movers {
        commands.entity(e).despawn();
    }
    if base.for_space(&active).is_none() {
        return;
    }
    for (i, m) in base.moving.iter().enumerate() {
        commands.spawn((
            SceneMover(i),
            CurvedObject::of(
                CurvedShape::Carried {
                    object: m.object,
                    start: m.frame,
                },
                None,
            ),
            CurvedTransform(m.frame),
            CurvedVelocity(m.velocity),
        ));
    }
}
