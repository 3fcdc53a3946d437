//! SL̃(2,R) spaces in the plugin: while the [`ActiveSpace`] is a unit tangent bundle, its
//! scene (the [`BaseSl2rScene`] or the default one) is packed for the tracer's `SL2R`
//! variant when the space or the settings change. Players move and wrap by the systems
//! written once over the geometry contract ([`crate::plugin::family::FamilyPlugin`]): along
//! geodesics in closed form, their axes' body components kept, wrapped into the cell by the
//! surface group.

pub use crate::plugin::components::BaseSl2rScene;
use crate::plugin::components::{ActiveSpace, TracerSettings, TracerStatus};
use crate::plugin::render::PreparedScene;
use crate::plugin::render::gpu::{GpuScene, MAX_GPU_BUDGET};
use crate::space::sl2r::UnitTangentSpace;
use crate::trace::sl2r::{Sl2rScene, default_scene};
use bevy::prelude::*;
use std::sync::Arc;

/// The crossing budget of an SL̃(2,R) view where none is set.
pub const DEFAULT_SL2R_BUDGET: u32 = 24;

/// The scene shown: the base scene or the default one, with the fog, the teaching view, the
/// walls and the lighting set in the settings.
#[must_use]
pub fn sl2r_scene(
    space: &UnitTangentSpace,
    settings: &TracerSettings,
    base: Option<&BaseSl2rScene>,
) -> Sl2rScene {
    let mut scene = base.map_or_else(|| default_scene(space), |b| b.scene.clone());
    if let Some(fog) = settings.fog_distance.filter(|f| f.is_finite() && *f > 0.0) {
        scene.fog_distance = fog;
    }
    if settings.colour_by != crate::scene::ColourBy::Holonomy {
        scene.colour_by = settings.colour_by;
    }
    // The walls set here, else the base scene's own; an opening of 1 turns them off.
    scene.walls = settings.walls.or(scene.walls).filter(|w| w.opening < 1.0);
    // The lighting set here (the lamp stays where the scene has it, a point).
    if let Some(mut lighting) = settings.lighting {
        lighting.shadows = lighting.shadows.min(settings.quality.max_shadows());
        lighting.lamp_radius_inradii = 0.0;
        let light = (scene.light, scene.light_sheet);
        if let Err(e) = scene.set_lighting(space, light, lighting) {
            bevy::log::warn!("lighting: {e}");
        }
    }
    scene
}

/// What the packed scene was made from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Sl2rKey {
    space: usize,
    fog: Option<f64>,
    max_crossings: Option<u32>,
    colour_by: crate::scene::ColourBy,
    walls: Option<crate::scene::WallStyle>,
    quality: crate::plugin::components::Quality,
    lighting: Option<crate::scene::lighting::Lighting>,
}

/// Packs the SL̃(2,R) scene for the GPU when the space, the base scene or the settings
/// changed.
pub(crate) fn upload_sl2r_scene(
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    base: Option<Res<BaseSl2rScene>>,
    prepared: Option<Res<PreparedScene>>,
    mut status: ResMut<TracerStatus>,
    mut last: Local<Option<Sl2rKey>>,
    mut commands: Commands,
) {
    let Some(space) = active.space.get::<UnitTangentSpace>() else {
        return;
    };
    let key = Sl2rKey {
        space: Arc::as_ptr(space) as usize,
        fog: settings.fog_distance,
        max_crossings: settings.max_crossings,
        colour_by: settings.colour_by,
        walls: settings.walls,
        quality: settings.quality,
        lighting: settings.lighting,
    };
    let base_changed = base.as_ref().is_some_and(|b| b.is_changed());
    if prepared.is_some() && !active.is_changed() && !base_changed && last.as_ref() == Some(&key) {
        return;
    }
    let scene = sl2r_scene(space, &settings, base.as_deref());
    let budget = settings
        .max_crossings
        .map_or(DEFAULT_SL2R_BUDGET, |b| b.clamp(1, MAX_GPU_BUDGET));
    *last = Some(key);
    let packed = GpuScene::sl2r(space, &scene, budget);
    crate::plugin::product::install_scene(packed, &active.id, &mut status, &mut commands);
    status.budget = budget;
    status.fog_distance = scene.fog_distance;
    status.auto_budget = None;
}
