//! `render` of an SL̃(2,R) space: its default scene (the cell's edges and five pillars,
//! fibre tubes met exactly, and a stack of metric balls along a fibre) or a scene file's, on
//! the GPU or with the f64 CPU reference, mono or stereo, from the default view or a placed
//! eye (`--eye x,y,θ --look-at x,y,θ`). The options that need a lamp or walls are not
//! written for the family yet, and each is refused by name.

use super::RenderArgs;
use super::render::Sl2rChoice;
use super::render::{saved, stereo_words};
use bevy_curved_spaces::space::sl2r::UnitTangentSpace;
use bevy_curved_spaces::space::{Family, Feature, FrameSpace};
use bevy_curved_spaces::trace::sl2r::render_sl2r_view;
use std::time::Instant;

/// The crossing budget where none is given: the fog's cut-off is a few cells away.
const DEFAULT_BUDGET: usize = bevy_curved_spaces::plugin::sl2r::DEFAULT_SL2R_BUDGET as usize;

/// `render unit-tangent-WORD`: on the GPU, or with the f64 CPU reference (`--cpu`).
pub(super) fn render_sl2r_command(args: &RenderArgs, chosen: Sl2rChoice) -> Result<(), String> {
    let space: &UnitTangentSpace = &chosen.space;
    let name = space.name();
    let refuse = |feature| super::spaces::require(Family::Sl2r, name, feature);
    if args.time != 0.0 {
        refuse(Feature::MovingObjects)?;
    }
    if args.view.changes_parts() {
        refuse(Feature::SceneParts)?;
    }
    if args.view.colour_by == super::ColourByArg::Holonomy {
        refuse(Feature::HolonomyView)?;
    }
    let mut scene = chosen.scene;
    if args.view.light.any() {
        let lighting = args.view.light.lighting(scene.lighting);
        let light = (scene.light, scene.light_sheet);
        scene
            .set_lighting(space, light, lighting)
            .map_err(|e| format!("{name}: {e}"))?;
    }
    let mut camera = chosen.camera;
    if let (Some(eye), Some(target)) = (args.eye, args.look_at) {
        camera = bevy_curved_spaces::trace::sl2r::Sl2rCamera::looking_at(
            space,
            eye,
            target,
            camera.fov_y_degrees,
        )
        .map_err(|e| format!("{name}: {e}"))?;
    }
    if let Some(fog) = args.fog {
        scene.fog_distance = fog;
    }
    if let Some(fov) = args.fov {
        camera.fov_y_degrees = fov;
    }
    scene.colour_by = args.view.colour_by.into();
    scene.walls = args
        .view
        .walls
        .style(scene.walls)?
        .filter(|w| w.opening < 1.0);
    let budget = args.crossings.unwrap_or(DEFAULT_BUDGET);
    let stereo = args.stereo.settings_for(space.scale())?;
    say!(
        "rendering {name} (SL̃(2,R)) at {}×{} with the {} (fog λ = {:.3}, ≤ {budget} \
         crossings{})…",
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
        render_sl2r_view(space, &scene, &layout, budget)
    } else {
        let gpu_budget = super::render::gpu_budget(budget)?;
        bevy_curved_spaces::plugin::offscreen::OffscreenRenderer::new()
            .and_then(|mut r| r.render_sl2r(space, &scene, &camera, args.size, gpu_budget, stereo))
            .map_err(|e| e.to_string())?
    };
    saved(&image, args, started)
}
