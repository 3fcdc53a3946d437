//! Nil spaces in the plugin: while the [`ActiveSpace`] is a Nil space, its scene (the
//! [`BaseNilScene`] or the default one) is packed for the tracer's `NIL` variant when the
//! space or the settings change. Players and entities move and wrap by the systems written
//! once over the geometry contract ([`crate::plugin::family::FamilyPlugin`]): along
//! geodesics in closed form, their axes carried by parallel transport, wrapped into the box
//! by the lattice. A game's entities' balls are drawn as metric balls
//! ([`crate::plugin::objects::nil`]).

pub use crate::plugin::components::BaseNilScene;
use crate::plugin::components::{ActiveSpace, TracerSettings, TracerStatus};
use crate::plugin::render::PreparedScene;
use crate::plugin::render::gpu::{GpuScene, MAX_GPU_BUDGET};
use crate::space::nil::NilSpace;
use crate::trace::nil::{NilScene, default_scene};
use bevy::prelude::*;
use std::sync::Arc;

/// The crossing budget of a Nil view where none is set: thin boxes (large K) are crossed
/// often, so the budget grows with K up to the GPU's limit.
#[must_use]
pub fn default_nil_budget(space: &NilSpace) -> u32 {
    (32 + 2 * space.k()).min(MAX_GPU_BUDGET)
}

/// The scene shown: the base scene or the default one, its moving balls where they are at
/// `time` seconds, with the fog and the lighting set in the settings (the lamp stays a point).
#[must_use]
pub fn nil_scene(
    space: &NilSpace,
    settings: &TracerSettings,
    base: Option<&BaseNilScene>,
    time: f64,
) -> NilScene {
    let mut scene = base.map_or_else(|| default_scene(space), |b| b.scene.clone());
    if let Some(b) = base.filter(|b| !b.moving.is_empty()) {
        match crate::trace::nil::moving::scene_at(space, &scene, &b.moving, time) {
            Ok(at) => scene = at,
            Err(e) => bevy::log::warn!("moving balls left out: {e}"),
        }
    }
    if let Some(fog) = settings.fog_distance.filter(|f| f.is_finite() && *f > 0.0) {
        scene.fog_distance = fog;
    }
    // The walls set here, else the base scene's own; an opening of 1 turns them off.
    scene.walls = settings.walls.or(scene.walls).filter(|w| w.opening < 1.0);
    scene.colour_by = settings.colour_by;
    if let Some(mut lighting) = settings.lighting {
        lighting.shadows = lighting.shadows.min(settings.quality.max_shadows());
        lighting.lamp_radius_inradii = 0.0;
        let light = scene.light;
        if let Err(e) = scene.set_lighting(space, light, lighting) {
            bevy::log::warn!("lighting: {e}");
        }
    }
    scene
}

/// What the packed Nil scene was made from.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct NilKey {
    space: usize,
    fog: Option<f64>,
    max_crossings: Option<u32>,
    quality: crate::plugin::components::Quality,
    lighting: Option<crate::scene::lighting::Lighting>,
    walls: Option<crate::scene::WallStyle>,
    colour_by: crate::scene::ColourBy,
}

/// Packs the Nil scene for the GPU, with a game's entities' balls
/// ([`crate::plugin::objects::nil::NilEntityObjects`]), when the space, the base scene, the
/// settings or the entities changed, and every frame while the scene's balls move.
#[allow(clippy::too_many_arguments)]
pub(crate) fn upload_nil_scene(
    time: Res<Time>,
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    base: Option<Res<BaseNilScene>>,
    entities: Res<crate::plugin::objects::nil::NilEntityObjects>,
    prepared: Option<Res<PreparedScene>>,
    mut status: ResMut<TracerStatus>,
    mut last: Local<Option<(NilKey, u64)>>,
    mut commands: Commands,
) {
    let Some(space) = active.space.get::<NilSpace>() else {
        return;
    };
    let key = NilKey {
        space: Arc::as_ptr(space) as usize,
        fog: settings.fog_distance,
        max_crossings: settings.max_crossings,
        quality: settings.quality,
        lighting: settings.lighting,
        walls: settings.walls,
        colour_by: settings.colour_by,
    };
    // Moving balls: packed again every frame.
    let base_changed = base
        .as_ref()
        .is_some_and(|b| b.is_changed() || !b.moving.is_empty());
    let now = (key, entities.generation);
    if prepared.is_some() && !active.is_changed() && !base_changed && last.as_ref() == Some(&now) {
        return;
    }
    let mut scene = nil_scene(space, &settings, base.as_deref(), time.elapsed_secs_f64());
    // A game's entities (their balls with the images in the box).
    scene.objects.extend(entities.objects.iter().copied());
    let budget = settings
        .max_crossings
        .map_or_else(|| default_nil_budget(space), |b| b.clamp(1, MAX_GPU_BUDGET));
    *last = Some(now);
    let packed = GpuScene::nil(space, &scene, budget);
    crate::plugin::product::install_scene(packed, &active.id, &mut status, &mut commands);
    status.budget = budget;
    status.fog_distance = scene.fog_distance;
    status.auto_budget = None;
}
