//! `curved-spaces`: walk, list, inspect, trace and render closed 3-manifolds and orbifolds.
//!
//! Run with no command to walk the default space in a window (or, with no display, to render
//! it to `curved-spaces.png`).

use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy_curved_spaces::bench::BenchConfig;
use bevy_curved_spaces::geometry::Vector4;
use bevy_curved_spaces::plugin::AUTO_BUDGET_SAMPLES;
use bevy_curved_spaces::plugin::BaseScene;
use bevy_curved_spaces::render::FramesTraced;
use bevy_curved_spaces::render::gpu::MAX_GPU_BUDGET;
use bevy_curved_spaces::render::offscreen::{OffscreenRender, gpu_available, render_offscreen};
use bevy_curved_spaces::scene::file::load_scene_file;
use bevy_curved_spaces::space::file::{SpaceRecord, load_space_file};
use bevy_curved_spaces::space::invariants::Invariants;
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{SEED_SPACES, Space, SpaceError, seed_space};
use bevy_curved_spaces::stereo::{
    StereoMode, StereoSettings, UnknownStereoMode, ViewLayout, check_ipd, eye_frames,
};
use bevy_curved_spaces::trace::SceneParts;
use bevy_curved_spaces::trace::auto_budget;
use bevy_curved_spaces::trace::{
    Camera, CellWalker, Limit, RenderSettings, Scene, Shading, Trace, chart_ray, render_view,
};
use bevy_curved_spaces::{ActiveSpace, CurvedSpaceCamera, CurvedSpacesPlugin, Quality};
use clap::{Args, Parser, Subcommand, ValueEnum};
use glam::{DVec3, DVec4, Vec4};
use serde_json::json;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Prints a line to standard output; a closed pipe (`curved-spaces list | head -3`) ends
/// the program quietly instead of panicking.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if let Err(e) = writeln!(std::io::stdout().lock(), $($arg)*) {
            if e.kind() == std::io::ErrorKind::BrokenPipe {
                std::process::exit(0);
            }
            eprintln!("error: cannot write to standard output: {e}");
            std::process::exit(1);
        }
    }};
}

/// The space shown when none is named.
const DEFAULT_SPACE: &str = "seifert-weber";

#[derive(Parser)]
#[command(
    name = "curved-spaces",
    version,
    about = "Ray tracing inside closed 3-manifolds and orbifolds of constant curvature",
    long_about = "Ray tracing inside closed 3-manifolds and orbifolds of constant curvature.\n\n\
                  With no command, walks the default space (seifert-weber) in a window; with no \
                  display, renders it to curved-spaces.png instead.\n\
                  SPACE is a seed space id (see `curved-spaces list`) or a path to a space file \
                  (JSON; `curved-spaces export` writes examples)."
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Walk inside a space in a window (first-person controls, F1 panel).
    Walk(WalkArgs),
    /// List the seed spaces.
    List,
    /// Show a space's invariants.
    Info {
        /// Seed space id or space file.
        space: String,
        /// Print JSON.
        #[arg(long)]
        json: bool,
    },
    /// Trace one geodesic through the cell and list its face crossings.
    Trace(TraceArgs),
    /// Render a picture of a space's default scene.
    Render(RenderArgs),
    /// Measure speed against error: GPU frame times against a trivial material, accuracy
    /// against the f64 reference, f32 drift, the fog cut-off; writes JSON, CSV and charts.
    Bench(BenchArgs),
    /// Write a space as a space file (JSON), a template for your own spaces.
    Export {
        /// Seed space id or space file.
        space: String,
        /// Output file (standard output if omitted).
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum Precision {
    F64,
    F32,
}

#[derive(Args)]
#[command(group = clap::ArgGroup::new("limit").required(true).args(["crossings", "distance"]))]
struct TraceArgs {
    /// Seed space id or space file.
    space: String,
    /// Chart direction of the ray (normalized to a unit tangent).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    dir: DVec3,
    /// Chart start point (inside the cell).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    from: DVec3,
    /// Stop after this many face crossings (at most 10⁶).
    #[arg(long, value_parser = parse_crossings)]
    crossings: Option<usize>,
    /// Stop at this geodesic distance (at most 10⁶).
    #[arg(long, value_parser = parse_distance, allow_hyphen_values = true)]
    distance: Option<f64>,
    /// Arithmetic of the walk (f32 is what the GPU uses).
    #[arg(long, value_enum, default_value = "f64")]
    precision: Precision,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Args)]
struct RenderArgs {
    /// Seed space id or space file.
    #[arg(default_value = DEFAULT_SPACE)]
    space: String,
    /// Use the f64 CPU reference renderer instead of the GPU tracer.
    #[arg(long)]
    cpu: bool,
    /// Image size, WIDTHxHEIGHT.
    #[arg(long, value_parser = parse_size, default_value = "640x360")]
    size: (u32, u32),
    /// Output PNG file.
    #[arg(long, default_value = "curved-spaces.png")]
    out: PathBuf,
    /// Fog distance scale λ (default: three times the inradius). Rays stop at λ·ln 510.
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    fog: Option<f64>,
    /// Crossing budget per ray (at most 10⁶; default: the smallest that reaches the fog
    /// cut-off for every sampled ray, chosen automatically).
    #[arg(long, value_parser = parse_crossings)]
    crossings: Option<usize>,
    /// Vertical field of view in degrees.
    #[arg(long, default_value_t = 70.0, value_parser = parse_fov)]
    fov: f64,
    /// Camera position in the chart (default: a view past the centre ball).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, requires = "look_at")]
    eye: Option<DVec3>,
    /// Chart point the camera looks at.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, requires = "eye")]
    look_at: Option<DVec3>,
    #[command(flatten)]
    stereo: StereoArgs,
    /// A scene file (TOML; see docs/scenes.md and assets/scenes/): its space, objects,
    /// lights, fog and start view instead of the default scene.
    #[arg(long, conflicts_with = "space")]
    scene: Option<PathBuf>,
    /// The scene's clock in seconds (turns spinning globes).
    #[arg(long, default_value_t = 0.0, value_parser = parse_time)]
    time: f64,
}

/// Stereo options shared by `walk` and `render`.
#[derive(Args, Clone, Copy, Default)]
struct StereoArgs {
    /// Stereo mode: mono, side-by-side, side-by-side-half, top-bottom, top-bottom-half,
    /// anaglyph (red–cyan, Dubois), anaglyph-optimized, anaglyph-red-cyan.
    #[arg(long, default_value = "mono", value_parser = parse_stereo)]
    stereo: StereoMode,
    /// Distance between the eyes in the space's units (default: 0.043 × the cell's
    /// inradius, so that the inradius feels like 1.5 m).
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    ipd: Option<f64>,
    /// Put the right eye's picture where the left one's goes (cross-eyed viewing).
    #[arg(long)]
    swap_eyes: bool,
}

impl StereoArgs {
    /// The settings, with the eye distance checked against the cell.
    fn settings(&self, space: &Space) -> Result<StereoSettings, String> {
        if let Some(ipd) = self.ipd {
            check_ipd(ipd, inradius(space)).map_err(|e| e.to_string())?;
        }
        Ok(StereoSettings {
            mode: self.stereo,
            ipd: self.ipd,
            swap_eyes: self.swap_eyes,
        })
    }
}

fn parse_stereo(s: &str) -> Result<StereoMode, String> {
    s.parse().map_err(|e: UnknownStereoMode| e.to_string())
}

#[derive(Args)]
struct BenchArgs {
    /// A smoke run of every part, in seconds (one space per geometry, 160×90).
    #[arg(long)]
    quick: bool,
    /// Folder for bench.json, the CSV tables and the charts (PNG and SVG).
    #[arg(long, default_value = "results")]
    out: PathBuf,
    /// Only these seed spaces (comma-separated ids; default: all).
    #[arg(long, value_delimiter = ',')]
    spaces: Option<Vec<String>>,
    /// Crossing budgets of the sweep (comma-separated; default 2,4,8,16,32,64).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=4096))]
    budgets: Option<Vec<u32>>,
    /// Timed resolutions (comma-separated WIDTHxHEIGHT; default 320x180,640x360,1280x720).
    #[arg(long, value_delimiter = ',', value_parser = parse_size)]
    sizes: Option<Vec<(u32, u32)>>,
    /// Skip the GPU: only the CPU measurements (f32 drift, fog cut-off, automatic budgets).
    #[arg(long)]
    cpu_only: bool,
    /// Measure nothing: redraw the tables, charts and summary of an earlier bench.json.
    #[arg(long, conflicts_with_all = ["quick", "spaces", "budgets", "sizes", "cpu_only"])]
    from: Option<PathBuf>,
}

#[derive(Args)]
struct WalkArgs {
    /// Seed space id or space file.
    #[arg(default_value = DEFAULT_SPACE)]
    space: String,
    /// Speed against accuracy: the automatic crossing budget's target and the traced
    /// resolution.
    #[arg(long, value_enum, default_value = "medium")]
    quality: QualityArg,
    /// Fog distance scale λ (default: three times the inradius).
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    fog: Option<f64>,
    /// Crossing budget per ray, 1 to 1024 (default: automatic, from the fog and the quality).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    crossings: Option<u32>,
    /// Start without the panel (F1 shows it).
    #[arg(long)]
    no_ui: bool,
    /// Save a screenshot of the window to this PNG once the view has settled, then quit.
    #[arg(long)]
    screenshot: Option<PathBuf>,
    #[command(flatten)]
    stereo: StereoArgs,
    /// Walk with an OpenXR headset (SteamVR, Monado, a Meta runtime; needs a build with
    /// `--features xr`). Without a runtime, falls back to desktop stereo.
    #[arg(long)]
    xr: bool,
    /// A scene file (TOML; see docs/scenes.md and assets/scenes/): its space, objects,
    /// lights, fog and start view instead of the default scene.
    #[arg(long, conflicts_with = "space")]
    scene: Option<PathBuf>,
    /// Hide your ship (otherwise seen where rays come back round the space; the panel
    /// toggles it too).
    #[arg(long)]
    no_avatar: bool,
}

/// `walk --screenshot`: where to save, and whether it was requested.
#[derive(Resource)]
struct ScreenshotThenExit {
    path: PathBuf,
    requested: bool,
}

/// Frames the tracer draws before `--screenshot` captures (the window has settled).
const SCREENSHOT_AFTER_FRAMES: u64 = 10;

fn screenshot_then_exit(
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
            let saved = captured
                .image
                .clone()
                .try_into_dynamic()
                .map_err(|e| e.to_string())
                .and_then(|img| img.to_rgb8().save(&path).map_err(|e| e.to_string()));
            match saved {
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

#[derive(Clone, Copy, ValueEnum)]
enum QualityArg {
    Low,
    Medium,
    High,
}

impl From<QualityArg> for Quality {
    fn from(q: QualityArg) -> Self {
        match q {
            QualityArg::Low => Quality::Low,
            QualityArg::Medium => Quality::Medium,
            QualityArg::High => Quality::High,
        }
    }
}

fn parse_vec3(s: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!(
            "expected three comma-separated numbers like 1,0,0.5, got `{s}`"
        ));
    }
    let mut v = [0.0; 3];
    for (x, p) in v.iter_mut().zip(&parts) {
        *x = p
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("`{p}` is not a finite number"))?;
    }
    Ok(DVec3::from_array(v))
}

fn parse_time(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|t| t.is_finite())
        .ok_or_else(|| format!("expected a time in seconds, got {s:?}"))
}

fn parse_positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("expected a positive number, got `{s}`")),
    }
}

/// Longer walks than this take minutes and say nothing new.
const MAX_WALK: usize = 1_000_000;

fn parse_crossings(s: &str) -> Result<usize, String> {
    match s.parse::<usize>() {
        Ok(n) if n <= MAX_WALK => Ok(n),
        _ => Err(format!(
            "expected a whole number from 0 to {MAX_WALK}, got `{s}`"
        )),
    }
}

fn parse_distance(s: &str) -> Result<f64, String> {
    match parse_positive(s)? {
        d if d <= MAX_WALK as f64 => Ok(d),
        _ => Err(format!("expected a distance up to {MAX_WALK}, got `{s}`")),
    }
}

fn parse_fov(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x > 0.0 && x < 180.0 => Ok(x),
        _ => Err(format!(
            "expected an angle between 0 and 180 degrees, got `{s}`"
        )),
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let err = || format!("expected WIDTHxHEIGHT like 640x360 (1 to 16384 each), got `{s}`");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
    let w: u32 = w.trim().parse().map_err(|_| err())?;
    let h: u32 = h.trim().parse().map_err(|_| err())?;
    if !(1..=16384).contains(&w) || !(1..=16384).contains(&h) {
        return Err(err());
    }
    Ok((w, h))
}

/// A seed space by id, or a space file by path.
fn resolve_space(arg: &str) -> Result<Space, String> {
    if SEED_SPACES.iter().any(|s| s.id == arg) {
        return seed_space(arg).map_err(|e| e.to_string());
    }
    let path = Path::new(arg);
    if path.exists() || arg.ends_with(".json") {
        return load_space_file(path).map_err(|e| e.to_string());
    }
    Err(SpaceError::UnknownSpace(arg.to_string()).to_string())
}

fn list() {
    say!(
        "{:<22} {:<11} {:>5} {:>14}  description",
        "id",
        "geometry",
        "faces",
        "volume"
    );
    for seed in SEED_SPACES {
        match seed.build() {
            Ok(space) => say!(
                "{:<22} {:<11} {:>5} {:>14.10}  {}",
                seed.id,
                space.geometry.name(),
                space.faces.len(),
                bevy_curved_spaces::space::invariants::volume(&space),
                seed.summary
            ),
            Err(e) => say!("{:<22} invalid: {e}", seed.id),
        }
    }
}

fn info(space: &Space, as_json: bool) -> Result<(), String> {
    let inv = Invariants::compute(space);
    if as_json {
        say!(
            "{}",
            serde_json::to_string_pretty(&inv).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    let opt = |x: Option<f64>| x.map_or("–".to_string(), |x| format!("{x:.10}"));
    let opt_n = |x: Option<usize>| x.map_or("–".to_string(), |x| x.to_string());
    say!("{} ({})", inv.name, inv.geometry.name());
    say!("  {}", space.description);
    say!("  faces               {}", inv.faces.len());
    say!("  volume              {:.12}", inv.volume);
    say!("  inradius            {:.10}", inv.inradius);
    say!("  circumradius        {:.10}", inv.circumradius);
    say!("  edge length         {}", opt(inv.edge_length));
    let cycles: Vec<String> = inv
        .edge_cycles
        .iter()
        .map(|c| format!("{}×{:.1}°", c.edges, c.angle_sum.to_degrees()))
        .collect();
    say!(
        "  edge cycles         {} ({})",
        cycles.len(),
        cycles.join(", ")
    );
    say!("  vertex cycles       {}", inv.vertex_cycles);
    say!("  orientable          {}", inv.orientable);
    say!("  manifold            {}", inv.manifold);
    say!("  holonomy order      {}", opt_n(inv.holonomy_order));
    say!("  group order         {}", opt_n(inv.group_order));
    say!("  injectivity radius  {}", opt(inv.injectivity_radius));
    match &inv.closed_geodesics {
        None => say!("  closed geodesics    too many group elements to enumerate"),
        Some(list) if !list.is_empty() => {
            say!("  closed geodesics    length × count");
            for g in list {
                say!("                      {:.10} × {}", g.length, g.count);
            }
        }
        Some(_) => {}
    }
    Ok(())
}

/// The trace in f64 whatever precision it ran in.
fn trace_f64<V: Vector4>(space: &Space, start: DVec4, dir: DVec4, limit: Limit) -> Trace<DVec4> {
    let walker = CellWalker::<V>::new(space);
    let start = bevy_curved_spaces::trace::Ray {
        point: V::from_f64(start),
        tangent: V::from_f64(dir),
    };
    let t = walker.trace(start, limit);
    let ray = |r: bevy_curved_spaces::trace::Ray<V>| bevy_curved_spaces::trace::Ray {
        point: r.point.to_f64(),
        tangent: r.tangent.to_f64(),
    };
    Trace {
        crossings: t
            .crossings
            .iter()
            .map(|c| bevy_curved_spaces::trace::Crossing {
                face: c.face,
                distance: c.distance,
                ray: ray(c.ray),
            })
            .collect(),
        end: ray(t.end),
        distance: t.distance,
    }
}

fn trace(args: &TraceArgs) -> Result<(), String> {
    let space = resolve_space(&args.space)?;
    let g = space.geometry;
    let start = chart_ray(g, args.from, args.dir).map_err(|e| e.to_string())?;
    if space.outside_by(start.point) > 1e-12 {
        return Err(format!(
            "start point {:?} is outside the cell of {}",
            args.from.to_array(),
            space.name
        ));
    }
    let limit = match (args.crossings, args.distance) {
        (Some(n), _) => Limit::Crossings(n),
        (None, Some(d)) => Limit::Distance(d),
        (None, None) => return Err("give --crossings N or --distance D".into()),
    };
    let result = match args.precision {
        Precision::F64 => trace_f64::<DVec4>(&space, start.point, start.tangent, limit),
        Precision::F32 => trace_f64::<Vec4>(&space, start.point, start.tangent, limit),
    };
    let chart = |p: DVec4| g.to_chart(p).to_array();
    if args.json {
        let crossings: Vec<_> = result
            .crossings
            .iter()
            .map(|c| {
                json!({
                    "face_normal": space.faces[c.face].normal.to_array(),
                    "distance": c.distance,
                    "point": chart(c.ray.point),
                })
            })
            .collect();
        let out = json!({
            "crossings": crossings,
            "end": {
                "point": chart(result.end.point),
                "direction": g.chart_direction(result.end.point, result.end.tangent).to_array(),
                "distance": result.distance,
            }
        });
        say!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
    } else {
        say!(
            "{:>5} {:>5} {:>20}  entry point (chart)",
            "#",
            "face",
            "distance"
        );
        for (i, c) in result.crossings.iter().enumerate() {
            let p = chart(c.ray.point);
            say!(
                "{:>5} {:>5} {:>20.15}  ({:+.15}, {:+.15}, {:+.15})",
                i + 1,
                c.face,
                c.distance,
                p[0],
                p[1],
                p[2]
            );
        }
        let p = chart(result.end.point);
        say!(
            "end at distance {:.15}: ({:+.15}, {:+.15}, {:+.15})",
            result.distance,
            p[0],
            p[1],
            p[2]
        );
    }
    Ok(())
}

/// A scene file's space, scene and start view, or the named space's default scene.
struct Chosen {
    id: String,
    space: Space,
    /// The whole scene (the CPU renders it).
    scene: Scene,
    /// What the plugin is given: a scene file's base scene, parts and start view (empty for
    /// the default scene).
    base: BaseScene,
    parts: SceneParts,
}

fn choose_scene(space_arg: &str, scene: Option<&Path>, fog: Option<f64>) -> Result<Chosen, String> {
    match scene {
        Some(path) => {
            let mut file = load_scene_file(path).map_err(|e| e.to_string())?;
            if let Some(fog) = fog {
                file.base.shading.fog_distance = fog;
            }
            Ok(Chosen {
                id: file.space_id.clone(),
                scene: file.scene(),
                base: BaseScene::from_file(&file),
                parts: file.parts,
                space: file.space,
            })
        }
        None => {
            let space = resolve_space(space_arg)?;
            let fog = fog.unwrap_or_else(|| Shading::default_fog_distance(&space));
            Ok(Chosen {
                id: space_arg.to_string(),
                scene: Scene::default_for(&space, fog),
                space,
                base: BaseScene::default(),
                parts: SceneParts::default(),
            })
        }
    }
}

fn render_command(args: &RenderArgs) -> Result<(), String> {
    let chosen = choose_scene(&args.space, args.scene.as_deref(), args.fog)?;
    let space = chosen.space.clone();
    let mut scene = chosen.scene.clone();
    scene.time = args.time;
    let fog = scene.shading.fog_distance;
    let camera = match (args.eye, args.look_at) {
        (Some(eye), Some(target)) => {
            let probe = space.geometry.from_chart(eye).map_err(|e| e.to_string())?;
            if space.outside_by(probe) > 1e-12 {
                return Err(format!(
                    "camera position {:?} is outside the cell of {}",
                    eye.to_array(),
                    space.name
                ));
            }
            Camera::looking_at(space.geometry, eye, target, args.fov).map_err(|e| e.to_string())?
        }
        _ => Camera {
            fov_y_degrees: args.fov,
            frame: chosen
                .base
                .start
                .unwrap_or_else(|| Camera::default_for(&space).frame),
        },
    };
    scene.set_avatar_frame(&space, camera.frame);
    let max_crossings = match args.crossings {
        Some(n) => n,
        None => {
            let choice = auto_budget(
                &space,
                &scene,
                Quality::High.miss_fraction(),
                AUTO_BUDGET_SAMPLES,
            );
            eprintln!(
                "automatic crossing budget: {} (the most any of {} sampled rays needs to reach an object before the fog cut-off)",
                choice.budget, choice.samples
            );
            choice.budget as usize
        }
    };
    let settings = RenderSettings {
        width: args.size.0,
        height: args.size.1,
        max_crossings,
    };
    let stereo = args.stereo.settings(&space)?;
    let eyes = if stereo.mode.is_stereo() {
        let inradius = inradius(&space);
        let ipd = stereo.ipd_for(inradius);
        let eyes = eye_frames(&space, camera.frame, ipd);
        let wrapped: Vec<String> = eyes
            .iter()
            .zip(["left", "right"])
            .filter(|(e, _)| !e.crossed.is_empty())
            .map(|(e, name)| format!("the {name} eye is wrapped through face(s) {:?}", e.crossed))
            .collect();
        eprintln!(
            "stereo {}: eyes {ipd:.4} apart (the inradius feels like {:.2} m){}",
            stereo.mode,
            inradius / stereo.units_per_metre(inradius),
            if wrapped.is_empty() {
                String::new()
            } else {
                format!("; {}", wrapped.join(", "))
            }
        );
        eyes.map(|e| e.frame)
    } else {
        [camera.frame; 2]
    };
    let started = Instant::now();
    let image = if args.cpu {
        eprintln!(
            "rendering {} ({}) at {}×{} with the f64 CPU reference on {} threads (fog λ = {fog:.3}, ≤ {} crossings)…",
            space.name,
            space.geometry.name(),
            settings.width,
            settings.height,
            rayon::current_num_threads(),
            settings.max_crossings
        );
        // A percentage on a terminal, updated every 5 %; nothing in logs.
        let tty = std::io::stderr().is_terminal();
        let layout = ViewLayout::new(
            stereo.mode,
            stereo.swap_eyes,
            eyes,
            camera.fov_y_degrees,
            settings.width,
            settings.height,
        );
        render_view(&space, &scene, &layout, &settings, |done, rows| {
            if tty && (done * 20 / rows != (done - 1) * 20 / rows || done == rows) {
                eprint!("\r{:>3} %", done * 100 / rows);
                if done == rows {
                    eprintln!();
                }
            }
        })
    } else {
        eprintln!(
            "rendering {} ({}) at {}×{} with the GPU tracer (fog λ = {fog:.3}, ≤ {} crossings)…",
            space.name,
            space.geometry.name(),
            settings.width,
            settings.height,
            settings.max_crossings
        );
        let max_crossings = u32::try_from(max_crossings)
            .ok()
            .filter(|&n| (1..=MAX_GPU_BUDGET).contains(&n))
            .ok_or_else(|| {
                format!(
                    "the GPU tracer takes a crossing budget from 1 to {MAX_GPU_BUDGET}, got {max_crossings} (use --cpu for more)"
                )
            })?;
        render_offscreen(&OffscreenRender {
            space: ActiveSpace::new(&chosen.id, space.clone()),
            width: settings.width,
            height: settings.height,
            frame: camera.frame,
            fov_y_degrees: camera.fov_y_degrees,
            fog_distance: Some(fog),
            max_crossings,
            parts: chosen.parts,
            objects: Vec::new(),
            resolution_scale: 1.0,
            base: chosen.base.clone(),
            time: args.time,
            stereo,
        })
        .map_err(|e| e.to_string())?
    };
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create folder {}: {e}", dir.display()))?;
    }
    image
        .save(&args.out)
        .map_err(|e| format!("cannot write {}: {e}", args.out.display()))?;
    let shown = std::fs::canonicalize(&args.out).unwrap_or_else(|_| args.out.clone());
    say!(
        "wrote {} ({}×{}, {:.2} s)",
        shown.display(),
        settings.width,
        settings.height,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Whether a window can be opened (an X11 or Wayland display is named).
fn display_available() -> bool {
    ["DISPLAY", "WAYLAND_DISPLAY"]
        .iter()
        .any(|v| std::env::var_os(v).is_some_and(|x| !x.is_empty()))
}

/// The stereo mode shown instead of a headset: the one asked for, side by side if none.
fn desktop_stereo(asked: StereoMode) -> StereoMode {
    if asked.is_stereo() {
        asked
    } else {
        StereoMode::SideBySide
    }
}

/// Whether a headset can be used: an OpenXR loader and runtime, in a build with `xr`.
fn xr_runtime() -> Result<(), String> {
    #[cfg(feature = "xr")]
    {
        bevy_curved_spaces::xr::probe_runtime().map_err(|e| e.to_string())
    }
    #[cfg(not(feature = "xr"))]
    {
        Err("this build has no OpenXR support (build it with `cargo build --release --features xr`)".into())
    }
}

fn walk(args: &WalkArgs) -> Result<(), String> {
    let chosen = choose_scene(&args.space, args.scene.as_deref(), args.fog)?;
    let space = chosen.space.clone();
    let mut stereo_args = args.stereo;
    if args.xr {
        match xr_runtime() {
            #[cfg(feature = "xr")]
            Ok(()) if display_available() => return walk_xr(args, &chosen),
            Ok(()) => {
                eprintln!("an OpenXR runtime was found, but no display to open the app's window on")
            }
            Err(e) => eprintln!("{e}"),
        }
        stereo_args.stereo = desktop_stereo(stereo_args.stereo);
        eprintln!(
            "falling back to desktop stereo: {} (choose another with --stereo)",
            stereo_args.stereo.label()
        );
    }
    if !display_available() {
        eprintln!(
            "no display found (DISPLAY and WAYLAND_DISPLAY are unset): rendering {} offscreen to curved-spaces.png instead",
            args.space
        );
        let render = Cli::parse_from(["curved-spaces", "render", args.space.as_str()]);
        let Some(Command::Render(mut render)) = render.command else {
            unreachable!("`render SPACE` parses as the render command")
        };
        render.fog = args.fog;
        render.scene = args.scene.clone();
        render.stereo = stereo_args;
        if !gpu_available() {
            eprintln!("no GPU adapter found: using the CPU reference renderer");
            render.cpu = true;
        }
        return render_command(&render);
    }
    let stereo = stereo_args.settings(&space)?;
    let active = ActiveSpace::new(&chosen.id, space);
    eprintln!(
        "walking in {}: click to look around, WASD to move, Esc releases the mouse, F1 the panel",
        active.space.name
    );
    let mut app = App::new();
    app.add_plugins(DefaultPlugins.set(window_titled(format!(
        "curved spaces: {}",
        active.space.name
    ))));
    app.insert_resource(chosen.base.clone());
    add_walk_plugins(&mut app, args, active, stereo).add_systems(
        Startup,
        |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        },
    );
    if let Some(path) = &args.screenshot {
        app.insert_resource(ScreenshotThenExit {
            path: path.clone(),
            requested: false,
        })
        .add_systems(Update, screenshot_then_exit);
    }
    exit_result(app.run())
}

/// The window of `walk`.
fn window_titled(title: String) -> WindowPlugin {
    WindowPlugin {
        primary_window: Some(Window { title, ..default() }),
        ..default()
    }
}

/// The space, the plugin with `walk`'s options and the panel's visibility.
fn add_walk_plugins<'a>(
    app: &'a mut App,
    args: &WalkArgs,
    active: ActiveSpace,
    stereo: StereoSettings,
) -> &'a mut App {
    app.insert_resource(active)
        .add_plugins(CurvedSpacesPlugin {
            fog_distance: args.fog,
            max_crossings: args.crossings,
            quality: args.quality.into(),
            ui: true,
            stereo,
            avatar: !args.no_avatar,
            ..default()
        })
        .insert_resource(bevy_curved_spaces::ui::PanelVisible(!args.no_ui))
}

fn exit_result(exit: AppExit) -> Result<(), String> {
    match exit {
        AppExit::Success => Ok(()),
        AppExit::Error(code) => Err(format!("the app stopped with error code {code}")),
    }
}

/// `walk --xr` with a runtime: the headset's views are traced, the window mirrors the head.
#[cfg(feature = "xr")]
fn walk_xr(args: &WalkArgs, chosen: &Chosen) -> Result<(), String> {
    use bevy_curved_spaces::xr::{CurvedSpacesXrPlugin, add_xr_plugins, xr_available};
    let stereo = args.stereo.settings(&chosen.space)?;
    let active = ActiveSpace::new(&chosen.id, chosen.space.clone());
    eprintln!(
        "walking in {} with a headset: left thumbstick walks, right thumbstick turns; the window mirrors the head",
        active.space.name
    );
    let mut app = App::new();
    app.add_plugins(add_xr_plugins(DefaultPlugins).set(window_titled(format!(
        "curved spaces (XR mirror): {}",
        active.space.name
    ))));
    add_walk_plugins(&mut app, args, active, stereo);
    if xr_available(app.world()) {
        app.add_plugins(CurvedSpacesXrPlugin::default());
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

fn bench(args: &BenchArgs) -> Result<(), String> {
    if let Some(from) = &args.from {
        let (config, report) =
            bevy_curved_spaces::bench::read_report(from).map_err(|e| e.to_string())?;
        let written = bevy_curved_spaces::bench::write_report(&report, &config, &args.out)
            .map_err(|e| e.to_string())?;
        say!("wrote {} files to {}", written.len(), args.out.display());
        return Ok(());
    }
    let mut config = if args.quick {
        BenchConfig::quick()
    } else {
        BenchConfig::full()
    };
    if let Some(spaces) = &args.spaces {
        for id in spaces {
            seed_space(id).map_err(|e| e.to_string())?;
        }
        config.spaces.clone_from(spaces);
    }
    if let Some(budgets) = &args.budgets {
        config.budgets.clone_from(budgets);
    }
    if let Some(sizes) = &args.sizes {
        config.sizes.clone_from(sizes);
    }
    config.cpu_only = args.cpu_only;
    if !config.cpu_only && !gpu_available() {
        return Err("no GPU adapter was found: install one (on Debian `apt-get install mesa-vulkan-drivers libvulkan1`) or pass --cpu-only".into());
    }
    if cfg!(debug_assertions) {
        eprintln!(
            "note: this is a debug build; for representative timings run `cargo run --release -- bench`"
        );
    }
    eprintln!(
        "benchmarking {} space(s) at {} size(s), budgets {:?}, fog {:?} inradii…",
        config.spaces.len(),
        config.sizes.len(),
        config.budgets,
        config.fog_factors
    );
    let started = Instant::now();
    let progress = indicatif::ProgressBar::new(0);
    let report = bevy_curved_spaces::bench::run(&config, &progress).map_err(|e| e.to_string())?;
    if let Some(device) = &report.device {
        say!(
            "device: {} ({}, {}, {}); frame times from {}",
            device.name,
            device.device_type,
            device.backend,
            device.driver,
            if device.timestamps {
                "GPU timestamps"
            } else {
                "wall time around each submission"
            }
        );
    }
    for t in report
        .timings
        .iter()
        .filter(|t| t.budget_from == "auto-high")
    {
        if t.fog_factor != bevy_curved_spaces::bench::DEFAULT_FOG_FACTOR
            || Some((t.width, t.height)) != config.sizes.iter().copied().max()
        {
            continue;
        }
        let error = report.errors.iter().find(|e| {
            e.space == t.space && e.budget_from == t.budget_from && e.fog_factor == t.fog_factor
        });
        say!(
            "{:<22} {:>4}×{:<4} budget {:>4}: {:>9.3} ms ({:>6.1}× the trivial material), hits differing from f64 {:.3} %",
            t.space,
            t.width,
            t.height,
            t.budget,
            t.median_ms,
            t.ratio,
            error.map_or(f64::NAN, |e| 100.0 * e.hit_differs)
        );
    }
    for c in &report.cutoff {
        if !c.within_bound {
            eprintln!(
                "warning: {} fog {} inradii: cut-off error {:.2e} exceeds its bound {:.2e}",
                c.space, c.fog_factor, c.max_error, c.bound
            );
        }
    }
    let written = bevy_curved_spaces::bench::write_report(&report, &config, &args.out)
        .map_err(|e| e.to_string())?;
    say!(
        "wrote {} files to {} in {:.1} s",
        written.len(),
        std::fs::canonicalize(&args.out)
            .unwrap_or_else(|_| args.out.clone())
            .display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

fn export(space: &Space, out: Option<&Path>) -> Result<(), String> {
    let text =
        serde_json::to_string_pretty(&SpaceRecord::from_space(space)).map_err(|e| e.to_string())?;
    match out {
        Some(path) => {
            std::fs::write(path, text + "\n")
                .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
            say!("wrote {}", path.display());
        }
        None => say!("{text}"),
    }
    Ok(())
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        None => match Cli::parse_from(["curved-spaces", "walk"]).command {
            // The `walk` subcommand with its own defaults.
            Some(Command::Walk(args)) => walk(&args),
            _ => unreachable!("`walk` parses as the walk command"),
        },
        Some(Command::Walk(args)) => walk(&args),
        Some(Command::List) => {
            list();
            Ok(())
        }
        Some(Command::Info { space, json }) => info(&resolve_space(&space)?, json),
        Some(Command::Trace(args)) => trace(&args),
        Some(Command::Render(args)) => render_command(&args),
        Some(Command::Bench(args)) => bench(&args),
        Some(Command::Export { space, out }) => export(&resolve_space(&space)?, out.as_deref()),
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
