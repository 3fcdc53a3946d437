//! The `curved-spaces` command line: its arguments and one module per command, each a thin
//! layer over library calls.

mod bench;
mod flight;
mod info;
mod light;
mod parse;
mod render;
mod render_nil;
mod render_sl2r;
mod spaces;
mod trace;
mod walk;
mod walk_sl2r;

use bevy::prelude::*;
use bevy_curved_spaces::plugin::components::Quality;
use bevy_curved_spaces::plugin::components::StereoSettings;
use bevy_curved_spaces::scene::walls::DEFAULT_WALL_OPACITY;
use bevy_curved_spaces::scene::{Centrepiece, LightPaths, Lighting, SceneParts, WallStyle};
use bevy_curved_spaces::space::DEFAULT_SPACE;
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{AnySpace, Feature, Space};
use bevy_curved_spaces::view::StereoMode;
use bevy_curved_spaces::view::stereo::check_ipd;
use clap::{Args, Parser, Subcommand, ValueEnum};
use glam::DVec3;
use parse::*;
use spaces::*;
use std::path::PathBuf;

#[derive(Parser)]
#[command(
    name = "curved-spaces",
    version,
    about = "Ray tracing inside closed 3-manifolds and orbifolds: flat, spherical, hyperbolic, \
             H²×R and S²×R",
    long_about = "Ray tracing inside closed 3-manifolds and orbifolds: flat, spherical, \
                  hyperbolic, H²×R and S²×R.\n\n\
                  With no command, walks the default space (seifert-weber) in a window; with no \
                  display, renders it to curved-spaces.png instead.\n\
                  SPACE is a seed space id (see `curved-spaces list`), a member of a family of \
                  the library (lens-7-2, surface-abAB-circle-1, …), or a path to a space file \
                  (JSON; `curved-spaces export` writes examples) or a generator file (`.gen`)."
)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
    /// The centre of the Dirichlet domain of a space given by a generator file (`.gen`), as
    /// a chart point `X,Y,Z` (default: the origin).
    #[arg(long, global = true, value_parser = parse_vec3, allow_hyphen_values = true)]
    basepoint: Option<DVec3>,
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
    /// The fluence at a point from a unit lamp: the sum over every image of the lamp in
    /// the universal cover of e^(−d/λ)/S(d)² (the near ones exactly, the rest by its
    /// mean, with the error bound of that).
    Light(LightArgs),
    /// Render a picture of a space's default scene.
    Render(RenderArgs),
    /// Measure speed against error: GPU frame times against a trivial material, accuracy
    /// against the f64 reference, f32 drift, the fog cut-off; writes JSON, CSV and charts.
    Bench(BenchArgs),
    /// Render a flight file (keyframes through a space) to PNG frames, and to
    /// FLIGHT_DIR/flight.mp4 where ffmpeg is installed; resumable, and sliceable with
    /// --frames A..B for several machines.
    Flight(FlightArgs),
    /// Write a space as a space file (JSON, a template for your own spaces) or as a
    /// generator file (`.gen`).
    Export {
        /// Seed space id or space file.
        space: String,
        /// Output file (standard output if omitted); a `.gen` name writes a generator file.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write Curved Spaces' generator format (`.gen`: one matrix per face pairing)
        /// instead of JSON.
        #[arg(long)]
        gen_format: bool,
    },
}

/// Where a headset wearer is (`walk --xr --play-area`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum PlayAreaArg {
    /// Standing, room scale.
    Standing,
    /// Seated.
    Seated,
}

#[derive(Clone, Copy, ValueEnum)]
enum Precision {
    F64,
    F32,
}

#[derive(Args)]
struct LightArgs {
    /// Seed space id or space file.
    space: String,
    /// The lamp's chart point (inside the cell).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true, default_value = "0,0,0")]
    light: DVec3,
    /// The chart point lit (inside the cell).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    at: DVec3,
    /// Fog distance λ (default: the space's, 3 inradii); the light is absorbed as the
    /// view is fogged.
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    fog: Option<f64>,
    /// Sum the images within this distance exactly (default: where about 2000 lie, at
    /// most 8λ; every image in a spherical space).
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    reach: Option<f64>,
    /// The lamp's radius, within which its falloff stops growing (default 0.05).
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    radius: Option<f64>,
    /// Also sum the images out to this longer reach and say how far the shortcut is off.
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    check: Option<f64>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
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
    #[arg(long, value_parser = parse_crossings, allow_negative_numbers = true)]
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
    #[arg(long, value_parser = parse_size, default_value = DEFAULT_SIZE, allow_hyphen_values = true)]
    size: (u32, u32),
    /// Output PNG file.
    #[arg(long, default_value = DEFAULT_OUT)]
    out: PathBuf,
    /// Fog distance scale λ (default: three times the inradius). Rays stop at λ·ln 510.
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    fog: Option<f64>,
    /// Crossing budget per ray (at most 10⁶; default: the smallest that reaches the fog
    /// cut-off for every sampled ray, chosen automatically).
    #[arg(long, value_parser = parse_crossings, allow_negative_numbers = true)]
    crossings: Option<usize>,
    /// Vertical field of view in degrees (default: the scene file's `fov`, else 70).
    #[arg(long, value_parser = parse_fov, allow_negative_numbers = true)]
    fov: Option<f64>,
    /// Camera position in the chart (default: a view past the centre ball); in a product
    /// space (H²×R, S²×R) the surface's chart point and a height, as `trace --from`.
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
    #[arg(long, default_value_t = 0.0, value_parser = parse_time, allow_negative_numbers = true)]
    time: f64,
    #[command(flatten)]
    view: ViewArgs,
}

/// The teaching view and the extra scene parts `walk` and `render` share (in `walk` the
/// panel changes them).
#[derive(Args, Clone, Copy, Default)]
struct ViewArgs {
    /// A teaching view: colour surfaces by the faces crossed to see them, by the last face
    /// crossed, or by the rotation of the copy of the cell they are in.
    #[arg(long, value_enum, default_value_t = ColourByArg::Shading)]
    colour_by: ColourByArg,
    /// In spherical spaces, show Clifford parallels (great circles of a Hopf fibration).
    #[arg(long)]
    clifford: bool,
    /// What sits at the cell's centre (default: the scene's, a ball in the default scene).
    #[arg(long, value_enum)]
    centrepiece: Option<CentrepieceArg>,
    /// The same as `--centrepiece gyroscope`.
    #[arg(long, conflicts_with = "centrepiece")]
    gyroscope: bool,
    #[command(flatten)]
    walls: WallArgs,
    #[command(flatten)]
    light: LightingArgs,
}

/// How the lamps' light is gathered (`render`, `walk`, `flight`; see docs/light.md).
#[derive(Args, Clone, Copy, Default)]
struct LightingArgs {
    /// Which geodesics carry a lamp's light: every image of it in the cover within the
    /// reach, absorbed by the fog (images), or the nearest copy only, unabsorbed, the older
    /// model (nearest).
    #[arg(long, value_enum)]
    light_paths: Option<LightPathsArg>,
    /// How far the images are summed exactly, in inradii of the cell (above 0, at most 64;
    /// default 2; at most 256 images per lamp). A spherical space sums them all.
    #[arg(long, value_name = "INRADII", value_parser = parse_reach, allow_negative_numbers = true)]
    light_reach: Option<f64>,
    /// Leave out the mean of the images beyond the reach.
    #[arg(long)]
    no_light_tail: bool,
    /// How many images of each lamp, nearest the cell's centre first, are walked for
    /// shadows (0 to 64; default 0: each costs about a walk per lit pixel).
    #[arg(long, value_name = "IMAGES", value_parser = clap::value_parser!(u32).range(0..=64))]
    shadows: Option<u32>,
    /// The lamps' radius in inradii (0 to 1; default 0, points): the shadows' penumbra.
    /// Soft shadows need `--shadows` too.
    #[arg(long, value_name = "INRADII", value_parser = parse_lamp_radius, allow_negative_numbers = true)]
    lamp_radius: Option<f64>,
    /// Shadow rays per shadowed image of a lamp with a radius (1 to 64; default 8; 1: hard
    /// shadows from its centre).
    #[arg(long, value_name = "RAYS", value_parser = clap::value_parser!(u32).range(1..=64))]
    soft_samples: Option<u32>,
}

#[derive(Clone, Copy, ValueEnum)]
enum LightPathsArg {
    Images,
    Nearest,
}

impl LightingArgs {
    /// `base` with the settings asked for.
    fn lighting(&self, base: Lighting) -> Lighting {
        Lighting {
            paths: match self.light_paths {
                Some(LightPathsArg::Images) => LightPaths::Images,
                Some(LightPathsArg::Nearest) => LightPaths::Nearest,
                None => base.paths,
            },
            reach_inradii: self.light_reach.unwrap_or(base.reach_inradii),
            tail: base.tail && !self.no_light_tail,
            shadows: self.shadows.unwrap_or(base.shadows),
            lamp_radius_inradii: self.lamp_radius.unwrap_or(base.lamp_radius_inradii),
            soft_samples: self.soft_samples.unwrap_or(base.soft_samples),
        }
    }

    /// Whether any setting is asked for.
    fn any(&self) -> bool {
        self.light_paths.is_some()
            || self.light_reach.is_some()
            || self.no_light_tail
            || self.shadows.is_some()
            || self.lamp_radius.is_some()
            || self.soft_samples.is_some()
    }
}

fn parse_reach(s: &str) -> Result<f64, String> {
    let r: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("not a number: {s:?}"))?;
    if r > 0.0 && r <= 64.0 {
        Ok(r)
    } else {
        Err(format!(
            "the reach must be above 0 and at most 64 inradii, got {s}"
        ))
    }
}

fn parse_lamp_radius(s: &str) -> Result<f64, String> {
    let r: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("not a number: {s:?}"))?;
    if (0.0..=Lighting::MAX_LAMP_RADIUS_INRADII).contains(&r) {
        Ok(r)
    } else {
        Err(format!(
            "a lamp's radius must be 0 to {} inradii, got {s}",
            Lighting::MAX_LAMP_RADIUS_INRADII
        ))
    }
}

/// The cell's walls with windows (`render`, `walk`, `flight`).
#[derive(Args, Clone, Copy, Default)]
struct WallArgs {
    /// Draw the cell's walls as see-through panels with windows, glued faces in one colour
    /// and mirrors in silver: OPENING 0 gives solid walls, 1 no walls (a scene file's
    /// `walls` otherwise).
    #[arg(long, value_name = "OPENING", value_parser = parse_opening, allow_negative_numbers = true)]
    walls: Option<f64>,
    /// The share of light a wall stops, above 0 and at most 1 (default 0.45).
    #[arg(long, value_parser = parse_opacity, allow_negative_numbers = true, requires = "walls")]
    wall_opacity: Option<f64>,
}

impl ViewArgs {
    /// The centrepiece asked for, if any.
    fn centrepiece(&self) -> Option<Centrepiece> {
        match (self.centrepiece, self.gyroscope) {
            (Some(c), _) => Some(c.into()),
            (None, true) => Some(Centrepiece::Gyroscope),
            (None, false) => None,
        }
    }

    /// Whether the arguments change the scene's parts.
    fn changes_parts(&self) -> bool {
        self.clifford || self.centrepiece().is_some()
    }

    /// `parts` with the parallels and the centrepiece asked for.
    fn parts(&self, parts: SceneParts) -> SceneParts {
        SceneParts {
            clifford: parts.clifford || self.clifford,
            centrepiece: self.centrepiece().unwrap_or(parts.centrepiece),
            ..parts
        }
    }
}

impl WallArgs {
    /// The walls asked for, else those of the scene (file).
    fn style(&self, scene: Option<WallStyle>) -> Result<Option<WallStyle>, String> {
        match self.walls {
            Some(opening) => {
                WallStyle::with_opacity(opening, self.wall_opacity.unwrap_or(DEFAULT_WALL_OPACITY))
                    .map(Some)
                    .map_err(|e| e.to_string())
            }
            None => Ok(scene),
        }
    }
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
        self.settings_for(inradius(space))
    }

    /// The settings, with the eye distance checked against a cell of this inradius.
    fn settings_for(&self, inradius: f64) -> Result<StereoSettings, String> {
        if let Some(ipd) = self.ipd {
            check_ipd(ipd, inradius).map_err(|e| e.to_string())?;
        }
        Ok(StereoSettings {
            mode: self.stereo,
            ipd: self.ipd,
            swap_eyes: self.swap_eyes,
        })
    }
}

#[derive(Args)]
struct BenchArgs {
    /// A smoke run of every part, in seconds (one space per geometry, 160×90).
    #[arg(long)]
    quick: bool,
    /// Folder for bench.json, the CSV tables and the charts (PNG and SVG).
    #[arg(long, default_value = "results")]
    out: PathBuf,
    /// Only these spaces (comma-separated ids: seed spaces, or library members such as `weeks`; default: all seed spaces).
    #[arg(long, value_delimiter = ',')]
    spaces: Option<Vec<String>>,
    /// Crossing budgets of the sweep (comma-separated; default 2,4,8,16,32,64).
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=4096), allow_negative_numbers = true)]
    budgets: Option<Vec<u32>>,
    /// Timed resolutions (comma-separated WIDTHxHEIGHT; default 320x180,640x360,1280x720).
    #[arg(long, value_delimiter = ',', value_parser = parse_size, allow_hyphen_values = true)]
    sizes: Option<Vec<(u32, u32)>>,
    /// Skip the GPU: only the CPU measurements (f32 drift, fog cut-off, automatic budgets).
    #[arg(long)]
    cpu_only: bool,
    /// Measure nothing: redraw the tables, charts and summary of an earlier bench.json.
    #[arg(long, conflicts_with_all = ["quick", "spaces", "budgets", "sizes", "cpu_only"])]
    from: Option<PathBuf>,
    /// Time a scene file's start view instead (its space, objects, fog and `fov`), at each
    /// budget and size; writes timings.csv and the summary.
    #[arg(long, conflicts_with_all = ["spaces", "cpu_only", "from"])]
    scene: Option<PathBuf>,
    /// Measure the CPU cost of moving objects as entities instead (per update and per
    /// object, and a new mesh's build); writes entities.csv, new_meshes.csv, entities.md.
    #[arg(long, conflicts_with_all = ["spaces", "budgets", "sizes", "cpu_only", "from", "scene"])]
    entities: bool,
    /// Time only the tracer against a straightforward tracer of the same walk (arc length,
    /// trigonometric functions, plain pairings, every lamp image summed) on the plainest view: the camera at the
    /// centre, 90° across, a ball of 0.3 inradii, no edges (at --budgets, default 16,32, and
    /// the middle of --sizes); writes straightforward.csv and summary.md.
    #[arg(long, conflicts_with_all = ["cpu_only", "from", "scene", "entities", "edges"])]
    straightforward: bool,
    /// Measure only the product spaces (H²×R, S²×R): each default view timed against
    /// Seifert–Weber's in the same rounds, crossings a pixel, the GPU against the CPU
    /// reference, the walks against double-double (comma-separated library ids; `all` for
    /// every named one); writes products.csv and summary.md. The full run measures them too.
    #[arg(long, value_delimiter = ',', conflicts_with_all = ["cpu_only", "from", "scene", "entities", "edges", "straightforward", "spaces"])]
    products: Option<Vec<String>>,
    /// Measure only the Nil spaces `nil-K` by their K (comma-separated, 1 to 1000): each
    /// default view timed against Seifert–Weber's in the same rounds, crossings a pixel,
    /// the GPU against the CPU reference, the f64 and f32 walks against the exact geodesic;
    /// writes nil.csv and summary.md. The full run measures nil-1, nil-3 and nil-50.
    #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..=1000), conflicts_with_all = ["cpu_only", "from", "scene", "entities", "edges", "straightforward", "spaces", "products"])]
    nil: Option<Vec<u32>>,
    /// Measure only the SL̃(2,R) spaces (comma-separated ids, such as
    /// unit-tangent-bitorus): each default view timed against Seifert–Weber's in the same
    /// rounds, crossings and root iterations a pixel, the GPU against the CPU reference, the
    /// f64 and f32 walks against double-double over the conditioning limit; writes sl2r.csv
    /// and summary.md. The full run measures the bitorus's and genus three's (the bundles of
    /// two surfaces tiled by the same polygon walk alike: their rays cross the same tiling).
    #[arg(long, value_delimiter = ',', conflicts_with_all = ["cpu_only", "from", "scene", "entities", "edges", "straightforward", "spaces", "products", "nil"])]
    sl2r: Option<Vec<String>>,
    /// Time only what the cell's edges cost: the default view with its edges culled,
    /// unculled and absent, in turn, per space (at the first of --budgets, default 32, and
    /// the middle of --sizes); writes edges.csv and summary.md.
    #[arg(long, conflicts_with_all = ["cpu_only", "from", "scene", "entities"])]
    edges: bool,
    /// Measure only the lighting: per space, the default view timed with the nearest copy
    /// of the lamp and with every image within a few reaches, with and without the tail
    /// and with shadows capped at a few counts, in the same rounds, each against a CPU
    /// reference with every image within 16 inradii and 64 shadows (at the first of
    /// --budgets, default 24, and the middle of --sizes); writes lighting.csv, a chart of
    /// error against time and summary.md.
    #[arg(long, conflicts_with_all = ["cpu_only", "from", "scene", "entities", "edges", "straightforward", "products"])]
    lighting: bool,
}

#[derive(Args, Clone)]
struct WalkArgs {
    /// Seed space id or space file.
    #[arg(default_value = DEFAULT_SPACE)]
    space: String,
    /// Speed against accuracy: the automatic crossing budget's target and the traced
    /// resolution.
    #[arg(long, value_enum, default_value_t = QualityArg::Medium)]
    quality: QualityArg,
    /// Fog distance scale λ (default: three times the inradius).
    #[arg(long, value_parser = parse_positive, allow_hyphen_values = true)]
    fog: Option<f64>,
    /// Crossing budget per ray, 1 to 1024 (default: automatic, from the fog and the quality).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024), allow_negative_numbers = true)]
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
    /// With --xr: `standing` (room scale: the runtime's stage, its floor at the room's
    /// y = 0) or `seated` (the runtime's local space, centred where the head starts).
    #[arg(long, value_enum, default_value_t = PlayAreaArg::Standing, requires = "xr")]
    play_area: PlayAreaArg,
    /// With --xr: the right thumbstick turns in snaps of this many degrees; 0 turns smoothly.
    #[arg(long, default_value_t = 30.0, value_parser = parse::parse_snap_degrees, allow_hyphen_values = true, requires = "xr")]
    snap_turn: f64,
    /// A scene file (TOML; see docs/scenes.md and assets/scenes/): its space, objects,
    /// lights, fog and start view instead of the default scene.
    #[arg(long, conflicts_with = "space")]
    scene: Option<PathBuf>,
    /// Hide your ship (otherwise seen where rays come back round the space; the panel
    /// toggles it too).
    #[arg(long)]
    no_avatar: bool,
    /// Frames a second to hold by lowering or raising the traced resolution within the
    /// quality's range (0: keep the quality's resolution). Off for --screenshot.
    #[arg(long, default_value_t = DEFAULT_WALK_FPS, value_parser = parse_fps, allow_negative_numbers = true)]
    fps: f64,
    /// Print the frame rate every 2 seconds (frames a second, ms a frame, the traced share
    /// of the resolution and the crossing budget) to standard error.
    #[arg(long)]
    log_fps: bool,
    /// Replay a flight file in the window, looping (its space or scene replaces SPACE; the
    /// keys do not move you while it plays).
    #[arg(long, conflicts_with_all = ["space", "scene"])]
    replay: Option<PathBuf>,
    /// Record the walk as a flight file (TOML): replay it with --replay, render it with
    /// `flight`. Written every second and when the window closes.
    #[arg(long, conflicts_with = "replay")]
    record: Option<PathBuf>,
    /// Seconds between the recorded keys (0.01 to 10).
    #[arg(long, default_value_t = 0.1, value_parser = parse_record_interval)]
    record_interval: f64,
    #[command(flatten)]
    view: ViewArgs,
}

/// `--colour-by`'s values.
#[derive(Clone, Copy, Default, PartialEq, Eq, ValueEnum)]
enum ColourByArg {
    /// The plain picture.
    #[default]
    Shading,
    /// Faces crossed before the surface.
    Crossings,
    /// The last face crossed.
    Face,
    /// The rotation of the copy of the cell (30° bins; mirrored copies apart).
    Holonomy,
}

impl From<ColourByArg> for bevy_curved_spaces::scene::ColourBy {
    fn from(c: ColourByArg) -> Self {
        use bevy_curved_spaces::scene::ColourBy;
        match c {
            ColourByArg::Shading => ColourBy::Shading,
            ColourByArg::Crossings => ColourBy::Crossings,
            ColourByArg::Face => ColourBy::Face,
            ColourByArg::Holonomy => ColourBy::Holonomy,
        }
    }
}

/// `--centrepiece`'s values.
#[derive(Clone, Copy, ValueEnum)]
enum CentrepieceArg {
    /// Nothing at the centre.
    None,
    /// A gold ball.
    Ball,
    /// The spinning Earth-like globe.
    Globe,
    /// A ring, its axis and two markers: shows how each copy is turned.
    Gyroscope,
    /// A spiral galaxy of small glowing stars.
    Galaxy,
}

impl From<CentrepieceArg> for Centrepiece {
    fn from(c: CentrepieceArg) -> Self {
        match c {
            CentrepieceArg::None => Centrepiece::None,
            CentrepieceArg::Ball => Centrepiece::Ball,
            CentrepieceArg::Globe => Centrepiece::Globe,
            CentrepieceArg::Gyroscope => Centrepiece::Gyroscope,
            CentrepieceArg::Galaxy => Centrepiece::Galaxy,
        }
    }
}

/// The frame rate `walk` holds unless told otherwise.
pub const DEFAULT_WALK_FPS: f64 = 30.0;

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

/// `flight`'s arguments.
#[derive(Args)]
pub struct FlightArgs {
    /// The flight file (TOML: `space` or `scene`, `fov`, and `[[key]]`s with `time`,
    /// `position` and `look_at`).
    file: PathBuf,
    /// Frame size WIDTHxHEIGHT.
    #[arg(long, default_value = "640x360", value_parser = parse_size)]
    size: (u32, u32),
    /// Frames per second.
    #[arg(long, default_value_t = 30.0, value_parser = parse_flight_fps)]
    fps: f64,
    /// Folder of the frames (frame-00001.png, …) and the video.
    #[arg(long, default_value = "flight")]
    out: PathBuf,
    /// Render with the f64 CPU reference instead of the GPU tracer.
    #[arg(long)]
    cpu: bool,
    /// Crossing budget per ray (default: chosen by sampling rays, as `render` does).
    #[arg(long, value_parser = parse_crossings)]
    crossings: Option<usize>,
    /// Render only frames A to B (1-based, inclusive): the same files and pixels as a whole
    /// run, for splitting a flight across machines.
    #[arg(long, value_parser = flight::parse_frames)]
    frames: Option<(usize, usize)>,
    /// A teaching view: colour surfaces by crossings, by the last face crossed, or by
    /// holonomy.
    #[arg(long, value_enum, default_value_t = ColourByArg::Shading)]
    colour_by: ColourByArg,
    #[command(flatten)]
    walls: WallArgs,
    #[command(flatten)]
    light: LightingArgs,
}

/// A number in `range`, described as `what` in the error.
fn parse_in_range(
    s: &str,
    what: &str,
    range: std::ops::RangeInclusive<f64>,
) -> Result<f64, String> {
    let (lo, hi) = (range.start(), range.end());
    let x: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("expected {what} ({lo} to {hi}), got `{s}`"))?;
    if !range.contains(&x) {
        return Err(format!("expected {what} from {lo} to {hi}, got {x}"));
    }
    Ok(x)
}

/// Seconds between recorded keys: 0.01 to 10.
fn parse_record_interval(s: &str) -> Result<f64, String> {
    parse_in_range(s, "seconds between keys", 0.01..=10.0)
}

/// A flight's frame rate: 1 to 240 frames per second.
fn parse_flight_fps(s: &str) -> Result<f64, String> {
    parse_in_range(s, "frames per second", 1.0..=240.0)
}

/// `render`'s picture size when none is given.
const DEFAULT_SIZE: &str = "640x360";
/// `render`'s output file when none is given (also where `walk` renders without a display).
const DEFAULT_OUT: &str = "curved-spaces.png";
/// The vertical field of view in degrees when none is given.
pub(super) const DEFAULT_FOV: f64 = 70.0;

impl RenderArgs {
    /// `render SPACE` with every other option at its default.
    fn of(space: &str) -> Self {
        Self {
            space: space.to_string(),
            cpu: false,
            size: parse_size(DEFAULT_SIZE).expect("the default size parses"),
            out: DEFAULT_OUT.into(),
            fog: None,
            crossings: None,
            fov: None,
            eye: None,
            look_at: None,
            stereo: StereoArgs::default(),
            scene: None,
            time: 0.0,
            view: ViewArgs::default(),
        }
    }
}

impl Default for WalkArgs {
    /// `walk` with no options: the default space at medium quality.
    fn default() -> Self {
        Self {
            space: DEFAULT_SPACE.to_string(),
            quality: QualityArg::Medium,
            fog: None,
            crossings: None,
            no_ui: false,
            screenshot: None,
            stereo: StereoArgs::default(),
            xr: false,
            play_area: PlayAreaArg::Standing,
            snap_turn: 30.0,
            scene: None,
            no_avatar: false,
            fps: DEFAULT_WALK_FPS,
            log_fps: false,
            replay: None,
            record: None,
            record_interval: 0.1,
            view: ViewArgs::default(),
        }
    }
}

/// Runs a parsed command line.
pub fn run(cli: Cli) -> Result<(), String> {
    let _ = BASEPOINT.set(cli.basepoint);
    match cli.command {
        None => walk::walk(&WalkArgs::default()),
        Some(Command::Walk(args)) => walk::walk(&args),
        Some(Command::List) => {
            info::list();
            Ok(())
        }
        Some(Command::Info { space, json }) => match space_named(&space)? {
            AnySpace::Product(p) => info::product_info(&p, json),
            AnySpace::Constant(s) => info::info(&s, json),
            AnySpace::Nil(n) => info::nil_info(&n, json),
            AnySpace::Sl2r(s) => info::sl2r_info(&s, json),
        },
        Some(Command::Trace(args)) => trace::trace(&args),
        Some(Command::Light(args)) => light::light(&args),
        Some(Command::Render(args)) => render::render_command(&args),
        Some(Command::Bench(args)) => bench::bench(&args),
        Some(Command::Flight(args)) => flight::flight(&args),
        Some(Command::Export {
            space,
            out,
            gen_format,
        }) => info::export(
            constant_for(&space_named(&space)?, Feature::Export)?,
            out.as_deref(),
            gen_format,
        ),
    }
}
