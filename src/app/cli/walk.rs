//! `walk`: the app in a window (or a headset), or an offscreen picture where there is no
//! display.

use super::render::Chosen;
use super::render::{Choice, choose, render_command};
use super::*;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::plugin::flight::FlightReplay;
use bevy_curved_spaces::plugin::offscreen::gpu_available;
use bevy_curved_spaces::plugin::render::FramesTraced;
use bevy_curved_spaces::scene::flight::{Flight, load_flight_file};
use bevy_curved_spaces::space::motion::CoverFlight;
use bevy_curved_spaces::view::StereoMode;
use bevy_curved_spaces::{ActiveSpace, CurvedSpaceCamera, CurvedSpacesPlugin};
use std::path::{Path, PathBuf};

/// `walk --screenshot`: where to save, and whether it was requested.
#[derive(Resource)]
pub(super) struct ScreenshotThenExit {
    pub(super) path: PathBuf,
    pub(super) requested: bool,
}

/// Frames the tracer draws before `--screenshot` captures (the window has settled).
pub(super) const SCREENSHOT_AFTER_FRAMES: u64 = 10;

pub(super) fn screenshot_then_exit(
    frames: Res<FramesTraced>,
    mut shot: ResMut<ScreenshotThenExit>,
    mut commands: Commands,
) {
    if shot.requested || frames.get() < SCREENSHOT_AFTER_FRAMES {
        return;
    }
    shot.requested = true;
    let path = shot.path.clone();
    commands.spawn(Screenshot::primary_window()).observe(
        move |captured: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
            match bevy_curved_spaces::plugin::screenshot::save_screenshot(&captured.image, &path) {
                Ok(()) => {
                    let shown = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
                    say!("wrote {}", shown.display());
                    exit.write(AppExit::Success);
                }
                Err(e) => {
                    eprintln!("error: cannot write {}: {e}", path.display());
                    exit.write(AppExit::error());
                }
            }
        },
    );
}

/// Whether a window can be opened (an X11 or Wayland display is named).
pub(super) fn display_available() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|x| !x.is_empty()))
}

/// The stereo mode shown instead of a headset: the one asked for, side by side if none.
pub(super) fn desktop_stereo(asked: StereoMode) -> StereoMode {
    if asked.is_stereo() {
        asked
    } else {
        StereoMode::SideBySide
    }
}

/// Whether a headset can be used: an OpenXR loader and runtime, in a build with `xr`.
pub(super) fn xr_runtime() -> Result<(), String> {
    #[cfg(feature = "xr")]
    {
        bevy_curved_spaces::plugin::xr::probe_runtime().map_err(|e| e.to_string())
    }
    #[cfg(not(feature = "xr"))]
    {
        Err("this build has no OpenXR support (build it with `cargo build --release --features xr`)".into())
    }
}

/// `walk --xr`'s start: where a runtime and a display are there (in a build with the `xr`
/// feature), the headset `session` runs and its result is returned; else this says which is
/// missing, switches `stereo` to the desktop fallback and returns `None`.
#[cfg_attr(not(feature = "xr"), allow(unused_variables))]
pub(super) fn headset_or_desktop(
    stereo: &mut StereoArgs,
    session: impl FnOnce() -> Result<(), String>,
) -> Option<Result<(), String>> {
    match xr_runtime() {
        #[cfg(feature = "xr")]
        Ok(()) if display_available() => return Some(session()),
        Ok(()) => {
            eprintln!("an OpenXR runtime was found, but no display to open the app's window on")
        }
        Err(e) => eprintln!("{e}"),
    }
    stereo.stereo = desktop_stereo(stereo.stereo);
    eprintln!(
        "falling back to desktop stereo: {} (choose another with --stereo)",
        stereo.stereo.label()
    );
    None
}

pub(super) fn walk(args: &WalkArgs) -> Result<(), String> {
    // A replayed flight names its own space or scene.
    let replay = match &args.replay {
        Some(path) => Some(load_flight_file(path)?),
        None => None,
    };
    let mut args_for_flight;
    let args = match &replay {
        Some(file) => {
            args_for_flight = args.clone();
            let base = args
                .replay
                .as_deref()
                .and_then(Path::parent)
                .unwrap_or(Path::new(""));
            args_for_flight.scene = file.scene.as_ref().map(|s| base.join(s));
            if let Some(space) = &file.space {
                args_for_flight.space = space.clone();
            }
            &args_for_flight
        }
        None => args,
    };
    let chosen = match choose(&args.space, args.scene.as_deref(), args.fog)? {
        Choice::Constant(chosen) => chosen,
        Choice::Sl2r(chosen) => {
            let flight = match &replay {
                Some(file) => Some(
                    bevy_curved_spaces::trace::sl2r::flight::Sl2rFlight::new(file)?
                        .in_space(&chosen.space),
                ),
                None => None,
            };
            return super::walk_sl2r::walk_sl2r(args, chosen, flight);
        }
        Choice::Nil(chosen) => {
            let flight = match &replay {
                Some(file) => Some(bevy_curved_spaces::trace::nil::flight::NilFlight::new(
                    &chosen.space,
                    file,
                )?),
                None => None,
            };
            return walk_nil(args, chosen, flight);
        }
        Choice::Product(product) => {
            let flight = match &replay {
                Some(file) => Some(
                    bevy_curved_spaces::trace::product::flight::ProductFlight::new(
                        &product.space,
                        file,
                    )?,
                ),
                None => None,
            };
            return walk_product(args, product, flight);
        }
    };
    let flight = match &replay {
        Some(file) => Some(Flight::new(&chosen.space, file)?),
        None => None,
    };
    let space = chosen.space.clone();
    let mut stereo_args = args.stereo;
    if args.xr
        && let Some(done) = headset_or_desktop(&mut stereo_args, || walk_xr(args, &chosen))
    {
        return done;
    }
    if !display_available() {
        say_no_display(args);
        let mut render = RenderArgs::of(&args.space);
        render.fog = args.fog;
        render.crossings = args.crossings.map(|c| c as usize);
        render.scene = args.scene.clone();
        render.stereo = stereo_args;
        render.view = args.view;
        if !gpu_available() {
            eprintln!("no GPU adapter found: using the CPU reference renderer");
            render.cpu = true;
        }
        return render_command(&render);
    }
    let stereo = stereo_args.settings(&space)?;
    let walls = args.view.walls.style(chosen.scene.shading.walls)?;
    let lighting = walk_lighting(args, &chosen)?;
    let active = ActiveSpace::new(&chosen.id, space);
    eprintln!(
        "walking in {}: click to look around, WASD to move, Esc releases the mouse, F1 the panel",
        active.space.name()
    );
    let mut app = App::new();
    app.add_plugins(window_plugins(format!(
        "curved spaces: {}",
        active.space.name()
    )));
    app.insert_resource(chosen.base.clone())
        .insert_resource(active);
    add_walk_plugins(&mut app, args, stereo, walls, lighting).add_systems(
        Startup,
        |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        },
    );
    if let Some(flight) = flight {
        eprintln!("replaying the flight ({:.1} s, looping)", flight.duration());
        app.insert_resource(FlightReplay::new(flight, true));
    }
    {
        let mut settings = app
            .world_mut()
            .resource_mut::<bevy_curved_spaces::plugin::components::TracerSettings>();
        settings.parts = args.view.parts(settings.parts);
    }
    record_to(&mut app, args)?;
    if let Some(path) = &args.screenshot {
        app.insert_resource(ScreenshotThenExit {
            path: path.clone(),
            requested: false,
        })
        .add_systems(Update, screenshot_then_exit);
    }
    exit_result(app.run())
}

/// Starts recording the walk to `--record`'s file, if given (a key every
/// `--record-interval` seconds, in the flight format of the space's family).
pub(super) fn record_to(app: &mut App, args: &WalkArgs) -> Result<(), String> {
    let Some(path) = &args.record else {
        return Ok(());
    };
    use bevy_curved_spaces::plugin::flight::FlightRecorder;
    use bevy_curved_spaces::scene::flight::FlightSource;
    let source = match &args.scene {
        Some(scene) => FlightSource::Scene(
            std::fs::canonicalize(scene)
                .unwrap_or_else(|_| scene.clone())
                .display()
                .to_string(),
        ),
        None => FlightSource::Space(args.space.clone()),
    };
    // Fail now, not after the walk, where the file cannot be written.
    bevy_curved_spaces::files::write_atomic(path, b"")
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    eprintln!(
        "recording the walk to {} (a key every {} s; replay it with walk --replay)",
        path.display(),
        args.record_interval
    );
    app.insert_resource(FlightRecorder::new(
        path.clone(),
        source,
        args.record_interval,
    ));
    Ok(())
}

/// Says that there is no display and what `walk` does instead: one picture of the start
/// view, offscreen, and none of the options that need a walk in a window.
pub(super) fn say_no_display(args: &WalkArgs) {
    eprintln!(
        "no display found (DISPLAY and WAYLAND_DISPLAY are unset): rendering {} offscreen to curved-spaces.png instead",
        args.space
    );
    let skipped: Vec<&str> = [
        (args.record.is_some(), "--record"),
        (args.replay.is_some(), "--replay"),
        (args.screenshot.is_some(), "--screenshot"),
    ]
    .into_iter()
    .filter_map(|(given, name)| given.then_some(name))
    .collect();
    if !skipped.is_empty() {
        eprintln!(
            "without a window there is no walk: {} {} nothing",
            skipped.join(", "),
            if skipped.len() == 1 { "does" } else { "do" }
        );
    }
}

/// The window of `walk`.
pub(super) fn window_titled(title: String) -> WindowPlugin {
    WindowPlugin {
        primary_window: Some(Window { title, ..default() }),
        ..default()
    }
}

/// Bevy's default plugins for a walk in a window with this title, on the GPU APIs the
/// tracer is tested on ([`render_plugin`](bevy_curved_spaces::plugin::offscreen::render_plugin)).
pub(super) fn window_plugins(title: String) -> bevy::app::PluginGroupBuilder {
    DefaultPlugins
        .set(window_titled(title))
        .set(bevy_curved_spaces::plugin::offscreen::render_plugin())
}

/// The plugin with `walk`'s options and the panel's visibility (the space is inserted
/// before).
pub(super) fn add_walk_plugins<'a>(
    app: &'a mut App,
    args: &WalkArgs,
    stereo: StereoSettings,
    walls: Option<bevy_curved_spaces::scene::WallStyle>,
    lighting: Option<bevy_curved_spaces::scene::lighting::Lighting>,
) -> &'a mut App {
    app.add_plugins(CurvedSpacesPlugin {
        fog_distance: args.fog,
        max_crossings: args.crossings,
        quality: args.quality.into(),
        ui: true,
        stereo,
        avatar: !args.no_avatar,
        // A screenshot shows the quality's resolution, not one chosen by timing.
        target_fps: (args.screenshot.is_none() && args.fps > 0.0).then_some(args.fps),
        colour_by: args.view.colour_by.into(),
        walls,
        lighting,
        ..default()
    })
    .insert_resource(bevy_curved_spaces::plugin::ui::PanelVisible(!args.no_ui));
    if args.log_fps {
        app.add_systems(Update, log_frame_rate);
    }
    app
}

/// Every 2 seconds, the frames shown since the last report (`walk --log-fps`).
fn log_frame_rate(
    time: Res<Time<Real>>,
    settings: Res<bevy_curved_spaces::plugin::components::TracerSettings>,
    share: Option<Res<bevy_curved_spaces::plugin::frame_rate::BudgetShare>>,
    mut since: Local<Option<(f64, u32)>>,
) {
    let now = time.elapsed_secs_f64();
    let (start, frames) = since.get_or_insert((now, 0));
    *frames += 1;
    let span = now - *start;
    if span >= 2.0 {
        let fps = f64::from(*frames) / span;
        let budget = match settings.max_crossings {
            Some(n) => format!("crossing budget {n}"),
            None => format!(
                "{:.0} % of the automatic crossing budget",
                100.0 * share.map_or(1.0, |s| s.0)
            ),
        };
        eprintln!(
            "{fps:.2} frames a second ({:.0} ms a frame), {:.0} % of the resolution traced, {budget}",
            1000.0 / fps,
            100.0 * settings.resolution_scale
        );
        *since = Some((now, 0));
    }
}

/// The lighting the walk starts with: the light switches over the chosen scene's own, or
/// `None` (the scene's own) where none is given.
fn walk_lighting(
    args: &WalkArgs,
    chosen: &Chosen,
) -> Result<Option<bevy_curved_spaces::scene::lighting::Lighting>, String> {
    if !args.view.light.any() {
        return Ok(None);
    }
    let lighting = args.view.light.lighting(chosen.scene.shading.lighting);
    lighting.check()?;
    Ok(Some(lighting))
}

pub(super) fn exit_result(exit: AppExit) -> Result<(), String> {
    match exit {
        AppExit::Success => Ok(()),
        AppExit::Error(code) => Err(format!("the app stopped with error code {code}")),
    }
}

/// `walk --xr` with a runtime: the headset's views are traced, the window mirrors the head.
pub(super) fn walk_xr(args: &WalkArgs, chosen: &Chosen) -> Result<(), String> {
    let stereo = args.stereo.settings(&chosen.space)?;
    let walls = args.view.walls.style(chosen.scene.shading.walls)?;
    let lighting = walk_lighting(args, chosen)?;
    let active = ActiveSpace::new(&chosen.id, chosen.space.clone());
    run_xr(args, active, (stereo, walls, lighting), |_| {})
}

/// The headset session of `walk --xr` in `active`, a space of any family: `add_scene` adds
/// the scene's resources (a product scene file's base scene).
#[cfg_attr(not(feature = "xr"), allow(unused_variables))]
pub(super) fn run_xr(
    args: &WalkArgs,
    active: ActiveSpace,
    settings: (
        StereoSettings,
        Option<bevy_curved_spaces::scene::WallStyle>,
        Option<bevy_curved_spaces::scene::lighting::Lighting>,
    ),
    add_scene: impl FnOnce(&mut App),
) -> Result<(), String> {
    #[cfg(feature = "xr")]
    {
        run_headset(args, active, settings, add_scene)
    }
    // Not reached (`walk --xr` finds no runtime in such a build), but says why if it were.
    #[cfg(not(feature = "xr"))]
    {
        xr_runtime()
    }
}

/// [`run_xr`] in a build with the `xr` feature.
#[cfg(feature = "xr")]
fn run_headset(
    args: &WalkArgs,
    active: ActiveSpace,
    (stereo, walls, lighting): (
        StereoSettings,
        Option<bevy_curved_spaces::scene::WallStyle>,
        Option<bevy_curved_spaces::scene::lighting::Lighting>,
    ),
    add_scene: impl FnOnce(&mut App),
) -> Result<(), String> {
    use bevy_curved_spaces::plugin::xr::{
        CurvedSpacesXrPlugin, PlayArea, TurnStyle, xr_available, xr_plugins,
    };
    let name = active.space.name().to_string();
    let play_area = match args.play_area {
        super::PlayAreaArg::Standing => PlayArea::Standing,
        super::PlayAreaArg::Seated => PlayArea::Seated,
    };
    let turn = if args.snap_turn > 0.0 {
        TurnStyle::Snap {
            degrees: args.snap_turn,
        }
    } else {
        TurnStyle::Smooth
    };
    eprintln!(
        "walking in {} with a headset ({}): left thumbstick walks, right thumbstick turns ({}); the window mirrors the head",
        active.space.name(),
        play_area.label(),
        match turn {
            TurnStyle::Smooth => "smoothly".to_string(),
            TurnStyle::Snap { degrees } => format!("in snaps of {degrees}°"),
        }
    );
    let mut app = App::new();
    app.add_plugins(
        xr_plugins(DefaultPlugins, play_area)
            .set(window_titled(format!("curved spaces (XR mirror): {name}"))),
    );
    app.insert_resource(active);
    add_scene(&mut app);
    add_walk_plugins(&mut app, args, stereo, walls, lighting);
    if xr_available(app.world()) {
        app.add_plugins(CurvedSpacesXrPlugin {
            turn,
            ..CurvedSpacesXrPlugin::default()
        });
    } else {
        eprintln!(
            "the OpenXR runtime did not start a session: falling back to desktop stereo in the window"
        );
        let mut settings = app.world_mut().resource_mut::<StereoSettings>();
        settings.mode = desktop_stereo(settings.mode);
        app.add_systems(Startup, |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        });
    }
    exit_result(app.run())
}

/// The light switches over a product scene file's lighting (or the default), or `None`
/// where none is given.
fn product_lighting(
    args: &WalkArgs,
    chosen: &super::render::ProductChoice,
) -> Result<Option<bevy_curved_spaces::scene::lighting::Lighting>, String> {
    if !args.view.light.any() {
        return Ok(None);
    }
    let lighting = args.view.light.lighting(
        chosen
            .base
            .as_ref()
            .map_or_else(Default::default, |b| b.scene.lighting),
    );
    lighting.check()?;
    Ok(Some(lighting))
}

/// `walk --xr` in a product space: the head walks H²×R or S²×R, its eyes carried along the
/// product's geodesics.
fn walk_product_xr(args: &WalkArgs, chosen: &super::render::ProductChoice) -> Result<(), String> {
    let lighting = product_lighting(args, chosen)?;
    let id = args
        .scene
        .as_ref()
        .map_or_else(|| args.space.clone(), |_| chosen.space.name().to_string());
    let active = ActiveSpace::new(id, chosen.space.clone());
    let stereo = args.stereo.settings_for(active.inradius)?;
    let base = chosen.base.clone();
    run_xr(args, active, (stereo, None, lighting), move |app| {
        if let Some(base) = base {
            app.insert_resource(base);
        }
    })
}

/// `walk` in a product space (H²×R, S²×R): its default scene, the fibre up; offscreen to a
/// picture where there is no display.
fn walk_product(
    args: &WalkArgs,
    chosen: super::render::ProductChoice,
    flight: Option<bevy_curved_spaces::trace::product::flight::ProductFlight>,
) -> Result<(), String> {
    let mut stereo_args = args.stereo;
    if args.xr
        && let Some(done) = headset_or_desktop(&mut stereo_args, || walk_product_xr(args, &chosen))
    {
        return done;
    }
    if !display_available() {
        say_no_display(args);
        let mut render = RenderArgs::of(&args.space);
        render.scene = args.scene.clone();
        render.fog = args.fog;
        render.crossings = args.crossings.map(|c| c as usize);
        render.view.light = args.view.light;
        render.stereo = stereo_args;
        if !gpu_available() {
            eprintln!("no GPU adapter found: using the CPU reference renderer");
            render.cpu = true;
        }
        return render_command(&render);
    }
    let id = args
        .scene
        .as_ref()
        .map_or_else(|| args.space.clone(), |_| chosen.space.name().to_string());
    let lighting = product_lighting(args, &chosen)?;
    let active = ActiveSpace::new(id, chosen.space);
    let stereo = stereo_args.settings_for(active.inradius)?;
    eprintln!(
        "walking in {} ({}): click to look around, WASD to walk, Space/Shift along the fibre, Esc releases the mouse, F1 the panel",
        active.space.name(),
        active.space.geometry_name()
    );
    let mut app = App::new();
    app.add_plugins(window_plugins(format!(
        "curved spaces: {}",
        active.space.name()
    )));
    app.insert_resource(active);
    if let Some(base) = chosen.base {
        app.insert_resource(base);
    }
    add_walk_plugins(&mut app, args, stereo, None, lighting).add_systems(
        Startup,
        |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        },
    );
    if let Some(flight) = flight {
        eprintln!("replaying the flight ({:.1} s, looping)", flight.duration());
        app.insert_resource(
            bevy_curved_spaces::plugin::flight::ProductFlightReplay::new(flight, true),
        );
    }
    record_to(&mut app, args)?;
    if let Some(path) = &args.screenshot {
        app.insert_resource(ScreenshotThenExit {
            path: path.clone(),
            requested: false,
        })
        .add_systems(Update, screenshot_then_exit);
    }
    exit_result(app.run())
}

/// `walk` in a Nil space: its default scene or a scene file's, `E₃` up, a flight replayed or
/// the walk recorded, with walls, in a window or the headset (`--xr`); offscreen to a picture
/// where there is no display; the teaching views but the holonomy's.
fn walk_nil(
    args: &WalkArgs,
    chosen: super::render::NilChoice,
    flight: Option<bevy_curved_spaces::trace::nil::flight::NilFlight>,
) -> Result<(), String> {
    let space = &chosen.space;
    use bevy_curved_spaces::space::{Family, Feature};
    let refuse = |feature| super::spaces::require(Family::Nil, space.name(), feature);
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
    let lighting = if args.view.light.any() {
        let lighting = args.view.light.lighting(Default::default());
        lighting.check()?;
        Some(lighting)
    } else {
        None
    };
    let mut stereo_args = args.stereo;
    if args.xr
        && let Some(done) = headset_or_desktop(&mut stereo_args, || {
            let active = ActiveSpace::new(space.name(), AnySpace::Nil(space.clone()));
            let stereo = args.stereo.settings_for(active.inradius)?;
            let base = chosen.base.clone();
            let walls = args.view.walls.style(chosen.scene.walls)?;
            run_xr(args, active, (stereo, walls, lighting), move |app| {
                if let Some(base) = base {
                    app.insert_resource(base);
                }
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
        render.view.light = args.view.light;
        render.view.walls = args.view.walls;
        render.view.colour_by = args.view.colour_by;
        render.scene = args.scene.clone();
        render.stereo = args.stereo;
        if !gpu_available() {
            eprintln!("no GPU adapter found: using the CPU reference renderer");
            render.cpu = true;
        }
        return render_command(&render);
    }
    let active = ActiveSpace::new(space.name(), AnySpace::Nil(space.clone()));
    let stereo = stereo_args.settings_for(active.inradius)?;
    let walls = args.view.walls.style(chosen.scene.walls)?;
    eprintln!(
        "walking in {} (Nil): click to look around, WASD to walk, Space/Shift along E3, Esc releases the mouse, F1 the panel",
        space.name()
    );
    let mut app = App::new();
    app.add_plugins(window_plugins(format!("curved spaces: {}", space.name())));
    app.insert_resource(active);
    if let Some(base) = chosen.base.clone() {
        app.insert_resource(base);
    }
    add_walk_plugins(&mut app, args, stereo, walls, lighting).add_systems(
        Startup,
        |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        },
    );
    if let Some(flight) = flight {
        eprintln!("replaying the flight ({:.1} s, looping)", flight.duration());
        app.insert_resource(bevy_curved_spaces::plugin::flight::NilFlightReplay::new(
            flight, true,
        ));
    }
    record_to(&mut app, args)?;
    if let Some(path) = &args.screenshot {
        app.insert_resource(ScreenshotThenExit {
            path: path.clone(),
            requested: false,
        })
        .add_systems(Update, screenshot_then_exit);
    }
    exit_result(app.run())
}
