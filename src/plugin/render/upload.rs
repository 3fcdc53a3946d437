//! Packing the scene for the GPU when the space, the settings or the objects change, with the
//! automatic crossing budget chosen for it.

use super::PreparedScene;
use super::gpu::GpuScene;
use crate::plugin::components::{
    AUTO_BUDGET_SAMPLES, ActiveSpace, BaseScene, Quality, SceneObjects, TracerSettings,
    TracerStatus,
};
use crate::plugin::objects::{EntityObjects, add_entity_objects};
use crate::scene::{CurvedScene, Object};
use crate::space::Space;
use crate::trace::{BudgetChoice, auto_budget_with_floor};
use bevy::prelude::*;
use std::sync::Arc;

/// The scene the tracer shows: the base scene (or the default parts) and the user's objects
/// with their images; the avatar as [`SceneParts::avatar`](crate::scene::SceneParts::avatar) says. Objects that cannot be
/// placed are left out and described in the returned message.
#[must_use]
pub fn build_scene(
    space: &Space,
    settings: &TracerSettings,
    objects: &[Object],
    base: Option<&CurvedScene>,
) -> (CurvedScene, Option<String>) {
    let fog = settings.fog_for(space, base);
    let mut scene = match base {
        Some(b) => b.adding_parts(space, settings.parts),
        None => CurvedScene::with_parts(space, fog, settings.parts),
    };
    scene.shading.fog_distance = fog;
    scene.shading.colour_by = settings.colour_by;
    // The walls set here, else the base scene's own (a scene file's `walls`); an opening of
    // 1 turns a base scene's walls off.
    scene.shading.walls = settings
        .walls
        .or(scene.shading.walls)
        .filter(|w| w.opening < 1.0);
    let mut problems: Vec<String> = Vec::new();
    if let Some(lighting) = settings.lighting
        && lighting != scene.shading.lighting
        && let Err(e) = scene.set_lighting(space, lighting)
    {
        problems.push(format!("lighting: {e}"));
    }
    // The quality's shadow cap: shadows are a shading choice only (no images to find again).
    let lighting = &mut scene.shading.lighting;
    lighting.shadows = lighting.shadows.min(settings.quality.max_shadows());
    problems.extend(objects.iter().enumerate().filter_map(|(i, o)| {
        scene
            .place(space, *o)
            .err()
            .map(|e| format!("scene object {i}: {e}"))
    }));
    for p in &problems {
        warn!("{p}");
    }
    (scene, (!problems.is_empty()).then(|| problems.join("; ")))
}

/// Packs the scene for the GPU when the space, the settings, the objects or the entities'
/// objects changed. The part without the entities is kept between frames, and while only
/// entities move the automatic budget and the scene data (meshes, textures) are kept too:
/// a moved object costs its images' placing and the uniform's words.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload_scene(
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    objects: Res<SceneObjects>,
    entities: Res<EntityObjects>,
    base: Res<BaseScene>,
    mut status: ResMut<TracerStatus>,
    prepared: Option<Res<PreparedScene>>,
    share: Option<Res<crate::plugin::frame_rate::BudgetShare>>,
    mut cache: Local<UploadCache>,
    mut commands: Commands,
) {
    let Some(space) = active.constant() else {
        return;
    };
    let static_changed = prepared.is_none()
        || active.is_changed()
        || settings.is_changed()
        || objects.is_changed()
        || base.is_changed()
        || share.as_ref().is_some_and(|s| s.is_changed())
        || cache.fixed.is_none();
    if !static_changed && !entities.is_changed() {
        return;
    }
    if static_changed {
        cache.fixed = Some(build_scene(
            space,
            &settings,
            &objects.0,
            base.for_space(&active),
        ));
    }
    let cache = &mut *cache;
    let Some((fixed, fixed_problems)) = cache.fixed.as_ref() else {
        return;
    };
    let mut scene = fixed.clone();
    let mut problems: Vec<String> = fixed_problems.iter().cloned().collect();
    problems.extend(entities.problems.iter().cloned());
    problems.extend(add_entity_objects(&mut scene, space, &entities.objects));
    let problems = (!problems.is_empty()).then(|| problems.join("; "));
    // The automatic budget depends on the space, the scene and the quality only: a change
    // of the resolution scale or a fixed budget's toggling does not sample rays again, and
    // neither do entities that only moved.
    let auto = settings.max_crossings.is_none().then(|| {
        let quality = settings.quality;
        let count = entities.objects.len();
        let last = &mut cache.budget;
        // An unchanged fixed scene is the one the last upload checked the cache against:
        // compare it (meshes and all) only when it was built anew.
        match last.as_ref() {
            Some(c)
                if Arc::ptr_eq(&c.space, space)
                    && (!static_changed || c.scene == *fixed)
                    && c.entities == count
                    && c.quality == quality =>
            {
                c.choice
            }
            _ => {
                let choice = auto_budget_with_floor(
                    space,
                    &scene,
                    quality.miss_fraction(),
                    quality.floor_miss_fraction(),
                    AUTO_BUDGET_SAMPLES,
                );
                *last = Some(BudgetCache {
                    space: space.clone(),
                    scene: fixed.clone(),
                    entities: count,
                    quality,
                    choice,
                });
                choice
            }
        }
    });
    // A frame-rate target may trace a share of the automatic budget (never below its floor).
    let share = share.map_or(1.0, |s| s.0);
    let budget = settings
        .max_crossings
        .or(auto.map(|a| a.shared(share)))
        .unwrap_or(1);
    let gpu = if entities.objects.is_empty() {
        GpuScene::new(space, &scene, budget)
    } else {
        GpuScene::reusing(space, &scene, budget, prepared.as_deref().map(|p| &*p.0))
    };
    match gpu {
        Ok(gpu) => {
            commands.insert_resource(PreparedScene(Arc::new(gpu)));
            status.error = problems;
            status.budget = budget;
            status.fog_distance = scene.shading.fog_distance;
            commands.insert_resource(ShownScene(Arc::new(scene)));
            status.auto_budget = auto;
        }
        Err(e) => {
            error!("{e}");
            status.error = Some(e.to_string());
        }
    }
}

/// The scene the tracer shows now (with the entities' objects and every image), for the
/// CPU side: the panel's ray inspector traces it.
#[derive(Resource, Clone, Debug)]
pub struct ShownScene(pub Arc<CurvedScene>);

/// What [`upload_scene`] keeps between frames.
#[derive(Default)]
pub(crate) struct UploadCache {
    /// The scene without the entities, and its problems.
    fixed: Option<(CurvedScene, Option<String>)>,
    /// The automatic budget last chosen and what for.
    budget: Option<BudgetCache>,
}

/// The automatic budget last chosen and what it was chosen for.
pub(crate) struct BudgetCache {
    space: Arc<Space>,
    scene: CurvedScene,
    entities: usize,
    quality: Quality,
    choice: BudgetChoice,
}
