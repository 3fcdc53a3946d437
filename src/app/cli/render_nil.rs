//! `render` of a Nil space: its default scene (the box's edges, the centrepiece, two balls,
//! a lamp) with the f64 CPU reference, mono or stereo.

use super::RenderArgs;
use super::render::{saved, stereo_words};
use bevy_curved_spaces::space::nil::NilSpace;
use bevy_curved_spaces::space::{Family, Feature, FrameSpace};
use bevy_curved_spaces::trace::nil::{NilCamera, default_camera, default_scene, render_nil_view};
use bevy_curved_spaces::view::ViewLayout;
use glam::{DMat4, DVec3};
use std::time::Instant;

/// The camera at the chart point `eye` (brought into the box by the lattice) looking along
/// the shortest geodesic to `target`, `E₃` up as far as the view allows.
fn camera_between(
    space: &NilSpace,
    eye: DVec3,
    target: DVec3,
    fov: f64,
) -> Result<NilCamera, String> {
    for (what, p) in [("camera position", eye), ("point looked at", target)] {
        if !p.is_finite() || p.abs().max_element() > 1e6 {
            return Err(format!(
                "{what} {:?} is not a chart point of Nil within 10⁶",
                p.to_array()
            ));
        }
    }
    let (length, forward) =
        bevy_curved_spaces::space::nil::shortest(eye.to_array(), target.to_array());
    if !(length > 0.0) {
        return Err("the camera looks at its own position".into());
    }
    let forward = DVec3::from_array(forward);
    let right = forward.cross(DVec3::Z);
    let right = if right.length() > 1e-9 {
        right.normalize()
    } else {
        DVec3::X
    };
    let up = right.cross(forward);
    let at = space.into_box(eye.to_array());
    Ok(NilCamera {
        frame: DMat4::from_cols(
            right.extend(0.0),
            up.extend(0.0),
            (-forward).extend(0.0),
            DVec3::from_array(at).extend(1.0),
        ),
        fov_y_degrees: fov,
    })
}

/// `render nil-K`: on the GPU, or with the f64 CPU reference (`--cpu`).
pub(super) fn render_nil_command(args: &RenderArgs, space: &NilSpace) -> Result<(), String> {
    let refuse = |feature| {
        Family::Nil
            .supports(feature)
            .map_err(|e| format!("{}: {e}", space.name()))
    };
    if args.time != 0.0 {
        refuse(Feature::MovingObjects)?;
    }
    if args.view.changes_parts() {
        refuse(Feature::SceneParts)?;
    }
    if args.view.walls.walls.is_some() {
        refuse(Feature::Walls)?;
    }
    if args.view.colour_by != super::ColourByArg::Shading {
        refuse(Feature::TeachingViews)?;
    }
    let mut scene = default_scene(space);
    let mut camera = default_camera(space);
    if let (Some(eye), Some(target)) = (args.eye, args.look_at) {
        camera = camera_between(space, eye, target, camera.fov_y_degrees)?;
    }
    if args.view.light.any() {
        let lighting = args.view.light.lighting(scene.lighting);
        let light = scene.light;
        scene.set_lighting(space, light, lighting)?;
    }
    if let Some(fog) = args.fog {
        scene.fog_distance = fog;
    }
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
    let eyes = if stereo.mode.is_stereo() {
        space.eye_frames(camera.frame, stereo.ipd_for(space.scale()))
    } else {
        [camera.frame; 2]
    };
    let layout = ViewLayout::new(
        stereo.mode,
        stereo.swap_eyes,
        eyes,
        camera.fov_y_degrees,
        args.size.0,
        args.size.1,
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
