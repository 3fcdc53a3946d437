//! Packing the scene for the GPU when the space, the settings or the objects change, with the
//! automatic crossing budget chosen for it.

use super::PreparedScene;
use super::gpu::GpuScene;
use crate::components::{
    AUTO_BUDGET_SAMPLES, ActiveSpace, BaseScene, Quality, SceneObjects, TracerSettings,
    TracerStatus,
};
use crate::scene::{CurvedScene, Object};
use crate::space::Space;
use crate::trace::{BudgetChoice, auto_budget};
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
    let problems: Vec<String> = objects
        .iter()
        .enumerate()
        .filter_map(|(i, o)| {
            scene
                .place(space, *o)
                .err()
                .map(|e| format!("scene object {i}: {e}"))
        })
        .collect();
    for p in &problems {
        warn!("{p}");
    }
    (scene, (!problems.is_empty()).then(|| problems.join("; ")))
}

/// Packs the scene for the GPU when the space, the settings or the objects changed.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload_scene(
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    objects: Res<SceneObjects>,
    base: Res<BaseScene>,
    mut status: ResMut<TracerStatus>,
    prepared: Option<Res<PreparedScene>>,
    mut last_choice: Local<Option<BudgetCache>>,
    mut commands: Commands,
) {
    if prepared.is_some()
        && !active.is_changed()
        && !settings.is_changed()
        && !objects.is_changed()
        && !base.is_changed()
    {
        return;
    }
    let space = &active.space;
    let (scene, problems) = build_scene(space, &settings, &objects.0, base.for_space(&active));
    // The automatic budget depends on the space, the scene and the quality only: a change
    // of the resolution scale or a fixed budget's toggling does not sample rays again.
    let auto = settings.max_crossings.is_none().then(|| {
        let quality = settings.quality;
        match last_choice.as_ref() {
            Some(c) if Arc::ptr_eq(&c.space, space) && c.scene == scene && c.quality == quality => {
                c.choice
            }
            _ => {
                let choice =
                    auto_budget(space, &scene, quality.miss_fraction(), AUTO_BUDGET_SAMPLES);
                *last_choice = Some(BudgetCache {
                    space: space.clone(),
                    scene: scene.clone(),
                    quality,
                    choice,
                });
                choice
            }
        }
    });
    let budget = settings
        .max_crossings
        .or(auto.map(|a| a.budget))
        .unwrap_or(1);
    match GpuScene::new(space, &scene, budget) {
        Ok(gpu) => {
            commands.insert_resource(PreparedScene(Arc::new(gpu)));
            status.error = problems;
            status.budget = budget;
            status.fog_distance = scene.shading.fog_distance;
            status.auto_budget = auto;
        }
        Err(e) => {
            error!("{e}");
            status.error = Some(e.to_string());
        }
    }
}

/// The automatic budget last chosen and what it was chosen for.
pub(crate) struct BudgetCache {
    space: Arc<Space>,
    scene: CurvedScene,
    quality: Quality,
    choice: BudgetChoice,
}
