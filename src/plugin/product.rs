//! Product spaces (H²×R, S²×R) in the plugin: while the [`ActiveSpace`] is a product
//! space, the scene is packed for the tracer's `PRODUCT` variant when the space or the
//! settings change. Players and entities move and wrap by the systems written once over the
//! geometry contract ([`crate::plugin::family::FamilyPlugin`]): with the fibre up unless
//! [`crate::plugin::components::PlayerSettings::fibre_up`] is off, through the sides, the
//! top and the bottom ([`crate::space::product::motion::wrap_product_frame`]).

use crate::plugin::components::{
    AUTO_BUDGET_SAMPLES, ActiveSpace, BaseProductScene, TracerSettings, TracerStatus,
};
use crate::plugin::render::PreparedScene;
use crate::plugin::render::gpu::{GpuScene, MAX_GPU_BUDGET};
use crate::space::product::ProductSpace;
use crate::trace::product::{ProductScene, default_scene, product_auto_budget};
use bevy::prelude::*;
use std::sync::Arc;

/// What the packed product scene was made from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ProductKey {
    space: usize,
    fog: Option<f64>,
    walls: Option<crate::scene::WallStyle>,
    colour_by: crate::scene::ColourBy,
    max_crossings: Option<u32>,
    quality: crate::plugin::components::Quality,
    lighting: Option<crate::scene::lighting::Lighting>,
    /// Whether a base scene is shown (its changes are caught by change detection).
    base: bool,
}

/// What the last automatic budget was chosen for (the entities' objects do not choose it:
/// they move every frame).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct BudgetFor {
    key: ProductKey,
    budget: u32,
    choice: Option<crate::trace::BudgetChoice>,
}

/// The scene shown in a product space: the base product scene or the default one, with
/// the fog set in the settings.
#[must_use]
pub fn product_scene(
    space: &ProductSpace,
    settings: &TracerSettings,
    base: Option<&BaseProductScene>,
) -> ProductScene {
    let mut scene = base.map_or_else(|| default_scene(space), |b| b.scene.clone());
    if let Some(fog) = settings.fog_distance.filter(|f| f.is_finite() && *f > 0.0) {
        scene.fog_distance = fog;
    }
    // The walls set here, else the base scene's own; an opening of 1 turns them off.
    scene.walls = settings.walls.or(scene.walls).filter(|w| w.opening < 1.0);
    scene.colour_by = settings.colour_by;
    // The lighting set here, else the base scene's own, its shadows capped by the quality.
    let mut lighting = settings.lighting.unwrap_or(scene.lighting);
    lighting.shadows = lighting.shadows.min(settings.quality.max_shadows());
    // The product spaces' lamp is a point (a radius set for the other spaces is left there).
    lighting.lamp_radius_inradii = 0.0;
    let same_images = lighting.paths == scene.lighting.paths
        && lighting.reach_inradii == scene.lighting.reach_inradii;
    if same_images {
        // The images stay: only the tail or the shadows change.
        scene.lighting = lighting;
    } else {
        let light = scene.light;
        if let Err(e) = scene.set_lighting(space, light, lighting) {
            bevy::log::warn!("lighting: {e}");
        }
    }
    scene
}

/// Packs the product scene for the GPU when the space, the scene, the fog, the budget or
/// the quality changed, with the automatic crossing budget sampled from the start view.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload_product_scene(
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    base: Option<Res<BaseProductScene>>,
    entities: Res<crate::plugin::objects::product::ProductEntityObjects>,
    prepared: Option<Res<PreparedScene>>,
    mut status: ResMut<TracerStatus>,
    mut last: Local<Option<(ProductKey, u64)>>,
    mut budget_for: Local<Option<BudgetFor>>,
    mut commands: Commands,
) {
    let Some(space) = active.product() else {
        return;
    };
    let key = ProductKey {
        space: Arc::as_ptr(space) as usize,
        fog: settings.fog_distance,
        walls: settings.walls,
        colour_by: settings.colour_by,
        max_crossings: settings.max_crossings,
        quality: settings.quality,
        lighting: settings.lighting,
        base: base.is_some(),
    };
    let base_changed = base.as_ref().is_some_and(|b| b.is_changed());
    let now = (key.clone(), entities.generation);
    if prepared.is_some() && !active.is_changed() && !base_changed && last.as_ref() == Some(&now) {
        return;
    }
    let mut scene = product_scene(space, &settings, base.as_deref());
    // The budget is chosen for the scene without the entities, and kept while only they
    // change.
    let fresh = active.is_changed() || base_changed;
    let (budget, choice) = match (settings.max_crossings, budget_for.as_ref()) {
        (Some(b), _) => (b.clamp(1, MAX_GPU_BUDGET), None),
        (None, Some(b)) if !fresh && b.key == key => (b.budget, b.choice),
        (None, _) => {
            let eye = BaseProductScene::start_frame(base.as_deref(), space).w_axis;
            let choice = product_auto_budget(
                space,
                &scene,
                eye,
                settings.quality.miss_fraction(),
                AUTO_BUDGET_SAMPLES,
            );
            let budget = choice.budget.clamp(1, MAX_GPU_BUDGET);
            *budget_for = Some(BudgetFor {
                key: key.clone(),
                budget,
                choice: Some(choice),
            });
            (budget, Some(choice))
        }
    };
    scene.objects.extend(entities.objects.iter().copied());
    *last = Some(now);
    let packed = GpuScene::product(space, &scene, budget);
    install_scene(packed, &active.id, &mut status, &mut commands);
    status.budget = budget;
    status.fog_distance = scene.fog_distance;
    status.auto_budget = choice;
}

/// Shows a packed scene (the render node takes it up), or says in the status and the log
/// why the scene of `id` could not be packed.
pub(crate) fn install_scene(
    packed: Result<GpuScene, crate::plugin::render::gpu::GpuSceneError>,
    id: &str,
    status: &mut TracerStatus,
    commands: &mut Commands,
) {
    match packed {
        Ok(gpu) => {
            commands.insert_resource(PreparedScene(Arc::new(gpu)));
            status.error = None;
        }
        Err(e) => {
            let message = format!("{id}: {e}");
            error!("{message}");
            status.error = Some(message);
        }
    }
}
