//! `render` of a Nil space: its default scene (the box's edges, the centrepiece, two balls,
//! a lamp) or a scene file's, on the GPU or with the f64 CPU reference, mono or stereo.

use super::RenderArgs;
use super::render::{NilChoice, saved, stereo_words};
use bevy_curved_spaces::space::{Family, Feature, FrameSpace};
use bevy_curved_spaces::trace::nil::{NilCamera, render_nil_view};
use std::time::Instant;

/// `render nil-K`: on the GPU, or with the f64 CPU reference (`--cpu`).
pub(super) fn render_nil_command(args: &RenderArgs, chosen: NilChoice) -> Result<(), String> {
    let mut scene = chosen.scene_at(args.time)?;
    let mut camera = chosen.camera;
    let space = &*chosen.space;
    let refuse = |feature| super::spaces::require(Family::Nil, space.name(), feature);
    if args.view.changes_parts() {
        refuse(Feature::SceneParts)?;
    }
    if args.view.colour_by == super::ColourByArg::Holonomy {
        refuse(Feature::HolonomyView)?;
    }
    if let (Some(eye), Some(target)) = (args.eye, args.look_at) {
        camera = NilCamera::looking_at(space, eye, target, camera.fov_y_degrees)?;
    }
    if args.view.light.any() {
        let lighting = args.view.light.lighting(scene.lighting);
        let light = scene.light;
        scene.set_lighting(space, light, lighting)?;
    }
    if let Some(fog) = args.fog {
        scene.fog_distance = fog;
    }
    scene.colour_by = args.view.colour_by.into();
    scene.walls = args
        .view
        .walls
        .style(scene.walls)?
        .filter(|w| w.opening < 1.0);
    if let Some(fov) = args.fov {
        camera.fov_y_degrees = fov;
    }
    let budget = args
        .crossings
        .unwrap_or_else(|| bevy_curved_spaces::plugin::nil::default_nil_budget(space) as usize);
    let stereo = args.stereo.settings_for(space.scale())?;
    say!(
        "rendering {} (Nil) at {}×{} with the {} (fog λ = {:.3}, ≤ {budget} crossings{})…",
        space.name(),
        args.size.0,
        args.size.1,
        if args.cpu {
            "f64 CPU reference"
        } else {
            "GPU tracer"
        },
        scene.fog_distance,
        stereo_words(&stereo, space.scale())
    );
    let started = Instant::now();
    let layout = super::render::head_layout(
        space,
        camera.frame,
        camera.fov_y_degrees,
        &stereo,
        args.size,
    );
    let image = if args.cpu {
        render_nil_view(space, &scene, &layout, budget)
    } else {
        let gpu_budget = super::render::gpu_budget(budget)?;
        bevy_curved_spaces::plugin::offscreen::OffscreenRenderer::new()
            .and_then(|mut r| r.render_nil(space, &scene, &camera, args.size, gpu_budget, stereo))
            .map_err(|e| e.to_string())?
    };
    saved(&image, args, started)
}
