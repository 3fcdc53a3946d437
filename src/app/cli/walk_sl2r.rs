//! `walk` in an SL̃(2,R) space: the plugin draws the unit tangent bundle on the GPU and the
//! player walks with the fibre up (moving along it turns `e`, which the picture shows as the
//! world turning round the fibre). Without a display it renders one picture instead, as
//! `walk` does in every family. `--replay FILE` flies a flight file's path instead of the
//! player, `--record FILE` writes the walk as one, `--xr` walks in a headset. What is not
//! written for the family yet (lamps, walls) is refused by the one table.

use super::render::{Sl2rChoice, render_command};
use super::walk::{
    ScreenshotThenExit, add_walk_plugins, display_available, exit_result, say_no_display,
    screenshot_then_exit, window_plugins,
};
use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::plugin::offscreen::gpu_available;
use bevy_curved_spaces::space::{AnySpace, Family, Feature};
use bevy_curved_spaces::{ActiveSpace, CurvedSpaceCamera};

pub(super) fn walk_sl2r(
    args: &WalkArgs,
    chosen: Sl2rChoice,
    flight: Option<bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight>,
) -> Result<(), String> {
    let space = &chosen.space;
    let refuse = |feature| super::spaces::require(Family::Sl2r, space.name(), feature);
    for (asked, feature) in [
        (
            args.view.colour_by == super::ColourByArg::Holonomy,
            Feature::HolonomyView,
        ),
        (args.view.changes_parts(), Feature::SceneParts),
    ] {
        if asked {
            refuse(feature)?;
        }
    }
    // The light switches over the scene's own lighting, checked before anything starts.
    let lighting = if args.view.light.any() {
        let lighting = args.view.light.lighting(chosen.scene.lighting);
        let mut lit = chosen.scene.clone();
        lit.set_lighting(space, (lit.light, lit.light_sheet), lighting)
            .map_err(|e| format!("{}: {e}", space.name()))?;
        Some(lighting)
    } else {
        None
    };
    let mut stereo_args = args.stereo;
    if args.xr
        && let Some(done) = super::walk::headset_or_desktop(&mut stereo_args, || {
            let active = ActiveSpace::new(space.name(), AnySpace::Sl2r(space.clone()));
            let stereo = args.stereo.settings_for(active.inradius)?;
            let base = bevy_curved_spaces::plugin::sl2r::BaseSl2rScene {
                scene: chosen.scene.clone(),
                start: Some(chosen.camera),
            };
            let walls = args.view.walls.style(chosen.scene.walls)?;
            super::walk::run_xr(args, active, (stereo, walls, lighting), move |app| {
                app.insert_resource(base);
            })
        })
    {
        return done;
    }
    if !display_available() {
        say_no_display(args);
        let mut render = RenderArgs::of(&args.space);
        render.fog = args.fog;
        render.crossings = args.crossings.map(|c| c as usize);
        render.view.colour_by = args.view.colour_by;
        render.view.walls = args.view.walls;
        render.view.light = args.view.light;
        render.scene = args.scene.clone();
        render.stereo = stereo_args;
        if !gpu_available() {
            eprintln!("no GPU adapter found: using the CPU reference renderer");
            render.cpu = true;
        }
        return render_command(&render);
    }
    let active = ActiveSpace::new(space.name(), AnySpace::Sl2r(space.clone()));
    let stereo = stereo_args.settings_for(active.inradius)?;
    eprintln!(
        "walking in {} (SL̃(2,R)): click to look around, WASD to walk on the surface, \
         Space/Shift along the fibre (which turns e: the world turns round you), Esc releases \
         the mouse, F1 the panel",
        space.name()
    );
    let mut app = App::new();
    app.add_plugins(window_plugins(format!("curved spaces: {}", space.name())));
    app.insert_resource(active)
        .insert_resource(bevy_curved_spaces::plugin::sl2r::BaseSl2rScene {
            scene: chosen.scene.clone(),
            start: Some(chosen.camera),
        });
    let walls = args.view.walls.style(chosen.scene.walls)?;
    add_walk_plugins(&mut app, args, stereo, walls, lighting).add_systems(
        Startup,
        |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        },
    );
    if let Some(flight) = flight {
        use bevy_curved_spaces::space::motion::CoverFlight as _;
        eprintln!("replaying the flight ({:.1} s, looping)", flight.duration());
        app.insert_resource(bevy_curved_spaces::plugin::flight::Sl2rFlightReplay::new(
            flight, true,
        ));
    }
    super::walk::record_to(&mut app, args)?;
    if let Some(path) = &args.screenshot {
        app.insert_resource(ScreenshotThenExit {
            path: path.clone(),
            requested: false,
        })
        .add_systems(Update, screenshot_then_exit);
    }
    exit_result(app.run())
}
