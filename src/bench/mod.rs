//! `curved-spaces bench`: speed against error, measured in one run.
//!
//! For every space it times the GPU tracer (the plugin's shader and uniform, in a plain wgpu
//! harness) against a trivial fullscreen material of the same size, over resolutions,
//! crossing budgets and fog distances; it measures in the same run what each setting costs
//! in accuracy against the f64 CPU reference (pixels whose hit differs, colour error), the
//! f32 drift of long rays, and the error of the fog cut-off against its stated bound. The
//! figures go to JSON and CSV files and charts (PNG and SVG) in one folder.

pub mod entities;
pub mod harness;

mod accuracy;
mod edge_work;
mod plot;
mod report;
mod timing;

use crate::components::Quality;
use crate::render::gpu::GpuScene;
use crate::scene::CurvedScene;
use crate::space::{Space, invariants, seed_space};
use crate::trace::{BudgetChoice, auto_budget};
use crate::view::TraceCamera;
pub use accuracy::growth;
use accuracy::*;
use indicatif::{ProgressBar, ProgressStyle};
pub use report::{
    charts, read_report, summary_markdown, write_edges_report, write_report, write_scene_report,
};
use serde::{Deserialize, Serialize};
pub use timing::bench_mesh;
use timing::*;

pub use harness::{BASELINE_WGSL, DeviceInfo, Frame, Harness, HarnessError, Output, Program};

pub use plot::{Chart, Corner, PlotError, Series, write_chart};

/// The crossing budget of the "exact" reference: far more than any ray of the default
/// scenes needs before the fog cut-off.
pub const EXACT_BUDGET: usize = 4096;

/// The constant of the drift bound `C ε n G(d)`.
pub const DRIFT_BOUND_FACTOR: f64 = 4.0;

/// Machine epsilon of f32 (the GPU's precision).
pub const F32_EPSILON: f64 = f32::EPSILON as f64;

/// What to measure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BenchConfig {
    /// Seed space ids.
    pub spaces: Vec<String>,
    /// Resolutions the GPU frame time is measured at.
    pub sizes: Vec<(u32, u32)>,
    /// Resolution of the accuracy comparisons against the CPU reference.
    pub error_size: (u32, u32),
    /// Crossing budgets of the sweep (at the default fog).
    pub budgets: Vec<u32>,
    /// Fog distances of the sweep, in inradii (at the automatic budget).
    pub fog_factors: Vec<f64>,
    /// At least this many timed frames per setting…
    pub min_frames: usize,
    /// …and until this many seconds were spent on it (at most `max_frames`).
    pub min_seconds: f64,
    /// Most frames timed per setting.
    pub max_frames: usize,
    /// Random rays per space for the f32 drift.
    pub drift_rays: usize,
    /// Crossing counts the drift is reported at.
    pub drift_crossings: Vec<usize>,
    /// Rays per space walked against the double-double reference (100 crossings each).
    #[serde(default)]
    pub conditioning_rays: usize,
    /// Rays sampled for each automatic budget.
    pub budget_samples: usize,
    /// Skip the GPU part (CPU accuracy only).
    pub cpu_only: bool,
    /// Triangle counts of the mesh scenes (a cube for 12, torus knots otherwise).
    #[serde(default)]
    pub mesh_triangles: Vec<usize>,
}

impl BenchConfig {
    /// The middle of the timed resolutions (by width): where the specialisation and stereo
    /// comparisons are timed.
    fn middle_size(&self) -> (u32, u32) {
        let mut sizes = self.sizes.clone();
        sizes.sort_unstable();
        sizes[sizes.len() / 2]
    }

    /// The full benchmark (minutes on a software rasteriser, seconds on a GPU).
    #[must_use]
    pub fn full() -> Self {
        Self {
            spaces: crate::space::SEED_SPACES
                .iter()
                .map(|s| s.id.to_string())
                .collect(),
            sizes: vec![(320, 180), (640, 360), (1280, 720)],
            error_size: (320, 180),
            budgets: vec![2, 4, 8, 16, 32, 64],
            fog_factors: vec![1.0, 2.0, 3.0, 4.0],
            min_frames: 5,
            min_seconds: 0.3,
            max_frames: 200,
            drift_rays: 64,
            drift_crossings: vec![10, 30, 100, 1000],
            conditioning_rays: 32,
            budget_samples: 4096,
            cpu_only: false,
            mesh_triangles: vec![12, 960, 4608, 19_200, 76_800, 307_200],
        }
    }

    /// A smoke run of every part (seconds): one space per geometry, small images.
    #[must_use]
    pub fn quick() -> Self {
        Self {
            spaces: vec!["torus".into(), "poincare".into(), "seifert-weber".into()],
            sizes: vec![(160, 90)],
            error_size: (160, 90),
            budgets: vec![4, 16],
            fog_factors: vec![1.0, 3.0],
            min_frames: 2,
            min_seconds: 0.0,
            max_frames: 2,
            drift_rays: 8,
            drift_crossings: vec![10, 30, 100],
            conditioning_rays: 4,
            budget_samples: 512,
            cpu_only: false,
            mesh_triangles: vec![12, 960],
        }
    }
}

/// Why the benchmark stopped.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// An error from below, passed on as it is.
    #[error(transparent)]
    Space(#[from] crate::space::SpaceError),
    /// An error from below, passed on as it is.
    #[error(transparent)]
    Gpu(#[from] HarnessError),
    /// The scene of `space` cannot be packed for the GPU: `error`.
    #[error("the scene of {space} cannot be packed for the GPU: {error}")]
    Scene {
        space: String,
        error: crate::render::gpu::GpuSceneError,
    },
    /// An error from below, passed on as it is.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// Writing `path` failed: `error`.
    #[error("writing {path} failed: {error}")]
    Write { path: String, error: String },
    /// Nothing to measure (the reason is attached).
    #[error("nothing to measure: {0}")]
    Empty(&'static str),
    /// The scene file could not be loaded (its error attached).
    #[error("{0}")]
    SceneFile(String),
}

/// GPU frame time of one setting.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TimingRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// How the budget was chosen: "fixed", or the quality preset of the automatic budget.
    pub budget_from: String,
    /// Fog distance in inradii.
    pub fog_factor: f64,
    /// Frames timed.
    pub frames: usize,
    /// Median frame time, ms.
    pub median_ms: f64,
    /// 10th percentile frame time, ms.
    pub p10_ms: f64,
    /// 90th percentile frame time, ms.
    pub p90_ms: f64,
    /// Median frame time of the trivial material, measured interleaved with the tracer.
    pub baseline_ms: f64,
    /// `median_ms / baseline_ms`.
    pub ratio: f64,
}

/// Accuracy of one setting against the f64 reference at the same camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrorRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Crossing budget per ray.
    pub budget: u32,
    /// How the budget was chosen (`fixed`, `auto-low`, `auto-medium`, `auto-high`).
    pub budget_from: String,
    /// Fog distance in inradii.
    pub fog_factor: f64,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Pixels whose hit (object and exit-face sequence) differs from the exact reference
    /// (f64, budget [`EXACT_BUDGET`]): the budget's error and f32's together.
    pub hit_differs: f64,
    /// Pixels whose hit differs from the f64 reference with the same budget: f32's share.
    pub hit_differs_same_budget: f64,
    /// The floor under that share: pixels whose f64 hit changes when only the camera ray is
    /// rounded to f32 (what any f32 tracer gets wrong at best, docs/design.md §3). Far away in H³
    /// a pixel covers many cells, so the hit there is decided below the pixel's size.
    pub hit_floor_f32: f64,
    /// Colour error against the exact reference, in 8-bit levels.
    pub mean_levels: f64,
    /// Largest colour error, in levels of 255.
    pub max_levels: u32,
    /// GPU rays that used up the whole budget (shown as fog).
    pub budget_exhausted: f64,
    /// Pixels more than 2 and more than 10 levels off the exact reference.
    pub over_2_levels: f64,
    /// Fraction of pixels off by more than 10 levels.
    pub over_10_levels: f64,
    /// Mean face crossings per pixel on the GPU (from the `HIT_ID` pass): the work done.
    #[serde(default)]
    pub mean_crossings: f64,
    /// 90th percentile of the face crossings per pixel.
    #[serde(default)]
    pub p90_crossings: f64,
}

/// A walk's error against the double-double reference in units of the conditioning limit
/// (`space::accuracy`): 1 is the limit, 10 a digit lost beyond it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConditioningRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// `f64` or `f32`.
    pub precision: String,
    /// `compensated` (the walk) or `plain` (the plain product, as before compensation).
    pub pairing: String,
    /// Crossings of the rays (statistics over crossings 1 to this).
    pub crossings: usize,
    /// Median error / conditioning over the crossings counted.
    pub median: f64,
    /// Largest error / conditioning.
    pub worst: f64,
    /// Crossings counted.
    pub counted: usize,
    /// Crossings left out: split or saturated (`space::accuracy::SATURATED`).
    pub left_out: usize,
}

/// Digits lost beyond the conditioning limit against distance: the median over the rays'
/// crossings in one distance bin of `log10(error / conditioning)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ConditioningPoint {
    /// Seed space id.
    pub space: String,
    /// `f64` or `f32`.
    pub precision: String,
    /// `compensated` or `plain`.
    pub pairing: String,
    /// Middle of the distance bin.
    pub distance: f64,
    /// Median `log10(error / conditioning)` in the bin (below 0: under the limit).
    pub median_digits: f64,
    /// Crossings in the bin.
    pub count: usize,
}

/// f32 against f64 along long rays.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DriftRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Crossings walked.
    pub crossings: usize,
    /// Rays walked.
    pub rays: usize,
    /// Rays whose f32 face sequence still equals the f64 one.
    pub same_faces: f64,
    /// Median geodesic distance travelled by then (f64).
    pub median_distance: f64,
    /// Geodesic distance between the f32 and the f64 point (median and max over the rays
    /// that still agree; `None` when none does).
    pub median_position_error: Option<f64>,
    /// Largest chart distance between the f32 and f64 walks (`None` where they left through different faces).
    pub max_position_error: Option<f64>,
    /// Angle between the f32 and the f64 direction (radians), median over agreeing rays.
    pub median_direction_error: Option<f64>,
    /// The conditioning bound `4 ε₃₂ · n · G(d)` at the median distance: `G = e^d` (H³),
    /// `1 + d` (E³), `1` (S³), with `n` the crossings (each adds rounding); the factor 4
    /// is our formulas' constant (measured: the worst ray stays under it in every space).
    /// (`None` where it overflows: e^d past d ≈ 700.)
    pub bound: Option<f64>,
    /// The largest ratio of a ray's position error to the same bound at that ray's own
    /// distance (≤ 1: every agreeing ray is within the bound).
    pub worst_bound_ratio: Option<f64>,
}

/// The fog cut-off's error against tracing without it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CutoffRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Fog distance in inradii.
    pub fog_factor: f64,
    /// Fog distance λ.
    pub fog_distance: f64,
    /// Where rays stop, λ ln 510.
    pub cutoff_distance: f64,
    /// The stated bound: the fog weight at the cut-off, per channel in [0, 1].
    pub bound: f64,
    /// Largest colour error of the cut-off against a far longer ray.
    pub max_error: f64,
    /// Mean colour error of the cut-off.
    pub mean_error: f64,
    /// Whether the largest error is within the stated bound.
    pub within_bound: bool,
    /// Reference rays (no cut-off) that used up [`EXACT_BUDGET`].
    pub reference_budget_exhausted: f64,
}

/// The automatic budget of a quality preset and what it costs and buys.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AutoBudgetRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// The quality preset.
    pub quality: String,
    /// Fog distance in inradii.
    pub fog_factor: f64,
    /// Share of sampled rays the budget may leave short.
    pub miss_fraction_allowed: f64,
    /// The budget chosen and how.
    #[serde(flatten)]
    pub choice: BudgetChoice,
}

/// The specialised shader against the unspecialised one (same view, same scene).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpecialisationRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Median frame time of the specialised shader, ms.
    pub specialised_ms: f64,
    /// Median frame time of the unspecialised shader, ms.
    pub general_ms: f64,
    /// `general_ms / specialised_ms`: how much faster specialising makes the frame.
    pub gain: f64,
    /// Uniform size of the specialised variant.
    pub specialised_uniform_bytes: usize,
    /// Uniform size of the unspecialised variant.
    pub general_uniform_bytes: usize,
    /// Pixels that differ between the two pictures (they compute the same formulas).
    pub differing_pixels: f64,
}

/// Stereo against mono: the same head, the same scene, the same size, the eyes traced by the
/// same shader (each timed interleaved with mono).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StereoRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Median frame time in mono, ms.
    pub mono_ms: f64,
    /// Side by side: one ray per pixel, each half its own eye.
    pub side_by_side_ms: f64,
    /// `side_by_side_ms / mono_ms` (measured in the same loop).
    pub side_by_side_ratio: f64,
    /// Anaglyph: two rays per pixel.
    pub anaglyph_ms: f64,
    /// `anaglyph_ms / mono_ms` (measured in the same loop).
    pub anaglyph_ratio: f64,
}

/// Everything one run measured.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct BenchReport {
    /// The GPU measured (`None` for CPU-only runs).
    pub device: Option<DeviceInfo>,
    /// "release" or "debug".
    pub build: String,
    /// CPU threads of the reference renderer.
    pub cpu_threads: usize,
    /// Frame times.
    pub timings: Vec<TimingRow>,
    /// Errors against the reference.
    pub errors: Vec<ErrorRow>,
    /// f32 drift of long rays.
    pub drift: Vec<DriftRow>,
    /// Walks against the double-double reference (absent from older reports).
    #[serde(default)]
    pub conditioning: Vec<ConditioningRow>,
    /// Digits lost beyond conditioning against distance, per space.
    #[serde(default)]
    pub conditioning_curve: Vec<ConditioningPoint>,
    /// Errors of the fog cut-off.
    pub cutoff: Vec<CutoffRow>,
    /// Automatic budgets.
    pub auto_budgets: Vec<AutoBudgetRow>,
    /// The specialised shader against the general one.
    pub specialisation: Vec<SpecialisationRow>,
    /// Absent from reports written before stereo existed.
    #[serde(default)]
    pub stereo: Vec<StereoRow>,
    /// Absent from reports written before meshes existed.
    #[serde(default)]
    pub meshes: Vec<MeshRow>,
    /// The cell's edges, culled and not (absent from reports written before culling).
    #[serde(default)]
    pub edges: Vec<EdgesRow>,
    /// The tracer against a straightforward one on the plainest view.
    #[serde(default)]
    pub straightforward: Vec<StraightforwardRow>,
}

/// The tracer against a straightforward tracer of the same walk (the shader variant
/// [`GpuScene::straightforward`]: arc length and trigonometric functions, a division a
/// face, plain f32 pairings) on the plainest view: the camera at the cell's centre looking
/// along −z with a 90° horizontal field of view, one ball of radius 0.3 inradii at the
/// centre, fog at 2 inradii, no edges; the two timed in turn.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StraightforwardRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Median frame time of the tracer, ms.
    pub tracer_ms: f64,
    /// Median frame time of the straightforward tracer, ms.
    pub straightforward_ms: f64,
    /// The tracer's time as a share of the straightforward one's (the median over rounds of
    /// each round's ratio): below 1 is faster.
    pub ratio: f64,
    /// Share of pixels whose colour differs between the two pictures (the same walk and
    /// shading, computed by other formulas in f32).
    pub differing_pixels: f64,
}

/// What the default scene's cell edges (tubes and vertex balls) cost: the default view
/// timed with them (face culling on, as drawn), with them unculled (every object tested in
/// every cell), and without them, interleaved in one loop.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgesRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Edge tubes and vertex balls.
    pub edge_objects: usize,
    /// Median frame time with the edges, culled (as the plugin draws them), ms.
    pub with_edges_ms: f64,
    /// Median frame time with the edges, every one tested in every cell, ms.
    pub unculled_ms: f64,
    /// Median frame time of the same view without edges, ms.
    pub without_edges_ms: f64,
    /// `with_edges_ms / without_edges_ms`.
    pub ratio: f64,
    /// `unculled_ms / without_edges_ms`.
    pub unculled_ratio: f64,
    /// Pixels whose `HIT_ID` (what the ray met, its crossings and face path, how it ended)
    /// differs between the culled and the unculled tracer: culling must leave it alone, so
    /// anything but 0 is a bug.
    #[serde(default)]
    pub hit_ids_differing: usize,
    /// Cells a ray of the view passes, on average (the CPU reference's walk).
    #[serde(default)]
    pub segments_per_pixel: f64,
    /// The share of segments that come near two faces at one point: only those can meet
    /// an edge tube or a vertex ball, so only those test any.
    #[serde(default)]
    pub near_two_faces: f64,
    /// The share of 4 × 2 pixel blocks (a software rasteriser's SIMD lanes) in which, at
    /// the same segment count, at least one pixel's segment comes near two faces at one
    /// point: the lanes run in step, so these blocks pay for the edge tests.
    #[serde(default)]
    pub blocks_near_two_faces: f64,
    /// Edge objects tested per segment once culled (CPU), against `edge_objects` unculled.
    #[serde(default)]
    pub tests_per_segment: f64,
}

/// A mesh at the cell's centre: frame time against triangle count, timed interleaved with
/// the same scene without the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshRow {
    /// Seed space id.
    pub space: String,
    /// Its geometry.
    pub geometry: String,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray.
    pub budget: u32,
    /// Triangles of the mesh.
    pub triangles: usize,
    /// Nodes of its hierarchy.
    pub nodes: usize,
    /// Depth of its hierarchy.
    pub depth: usize,
    /// Building the hierarchy on the CPU.
    pub build_ms: f64,
    /// Median frame time with the mesh, ms.
    pub with_mesh_ms: f64,
    /// Median frame time of the same view without it, ms.
    pub without_mesh_ms: f64,
    /// `with_mesh_ms / without_mesh_ms` (measured in the same loop).
    pub ratio: f64,
}

/// One space with what the benchmark needs of it.
struct Subject {
    id: String,
    space: Space,
    inradius: f64,
    camera: TraceCamera,
}

impl Subject {
    fn new(id: &str) -> Result<Self, BenchError> {
        let space = seed_space(id)?;
        Ok(Self {
            id: id.to_string(),
            inradius: invariants::inradius(&space),
            camera: TraceCamera::default_for(&space),
            space,
        })
    }

    fn geometry(&self) -> String {
        self.space.geometry.name().to_string()
    }

    /// The scene packed for the GPU with a crossing budget.
    fn pack(&self, scene: &CurvedScene, budget: u32) -> Result<GpuScene, BenchError> {
        GpuScene::new(&self.space, scene, budget).map_err(|error| BenchError::Scene {
            space: self.id.clone(),
            error,
        })
    }

    fn scene(&self, fog_factor: f64) -> CurvedScene {
        CurvedScene::default_for(&self.space, fog_factor * self.inradius)
    }
}

/// Times only the tracer against the straightforward one ([`StraightforwardRow`]), for
/// each of `config.spaces` and `config.budgets` at the middle of `config.sizes`.
pub fn run_straightforward(
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    if config.spaces.is_empty() || config.sizes.is_empty() || config.budgets.is_empty() {
        return Err(BenchError::Empty("no spaces, sizes or budgets were named"));
    }
    let mut harness = Harness::new()?;
    progress.set_length((config.spaces.len() * config.budgets.len()) as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for id in &config.spaces {
        let subject = Subject::new(id)?;
        for &budget in &config.budgets {
            announce(
                progress,
                format!(
                    "{} at {budget} crossings: against a straightforward tracer",
                    subject.id
                ),
            );
            report.straightforward.extend(straightforward_cost(
                &mut harness,
                &subject,
                budget,
                config,
            )?);
            progress.inc(1);
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// Times only what the cell's edges cost ([`EdgesRow`]): the default view with its edges
/// culled, unculled and absent, in turn, for each of `config.spaces` at the first of
/// `config.budgets` and the middle of `config.sizes`. Seconds per space where the full
/// benchmark takes minutes, for working on the edges' cost.
pub fn run_edges(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    let budget = *config
        .budgets
        .first()
        .ok_or(BenchError::Empty("no crossing budget was given"))?;
    if config.spaces.is_empty() || config.sizes.is_empty() {
        return Err(BenchError::Empty("no spaces or sizes were named"));
    }
    let mut harness = Harness::new()?;
    progress.set_length(config.spaces.len() as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for id in &config.spaces {
        let subject = Subject::new(id)?;
        announce(
            progress,
            format!("{}: edges culled, unculled and none", subject.id),
        );
        report
            .edges
            .push(edges_cost(&mut harness, &subject, budget, config)?);
        progress.inc(1);
    }
    progress.finish_and_clear();
    Ok(report)
}

/// Times a scene file's start view (its space, objects, lights, fog, parts, and its `fov`)
/// at each of `config.budgets` × `config.sizes`, against the trivial material in the same
/// loop: one [`TimingRow`] per budget and size, `space` being the file's name. Nothing else
/// of the benchmark is measured.
#[cfg(feature = "scene-files")]
pub fn run_scene(
    config: &BenchConfig,
    path: &std::path::Path,
    progress: &ProgressBar,
) -> Result<BenchReport, BenchError> {
    let file = crate::scene::file::load_scene_file(path)
        .map_err(|e| BenchError::SceneFile(e.to_string()))?;
    let space = file.space.clone();
    let default_view = TraceCamera::default_for(&space);
    let subject = Subject {
        id: path.file_stem().map_or_else(
            || path.display().to_string(),
            |s| s.to_string_lossy().into_owned(),
        ),
        inradius: invariants::inradius(&space),
        camera: TraceCamera {
            frame: file.start.unwrap_or(default_view.frame),
            fov_y_degrees: file.start_fov.unwrap_or(default_view.fov_y_degrees),
        },
        space,
    };
    let scene = file.base.adding_parts(&subject.space, file.parts);
    let mut harness = Harness::new()?;
    progress.set_length((config.budgets.len() * config.sizes.len()) as u64);
    let mut report = BenchReport::empty(Some(&harness));
    for &budget in &config.budgets {
        let gpu = subject.pack(&scene, budget)?;
        for &(w, h) in &config.sizes {
            announce(
                progress,
                format!("{}: budget {budget} at {w}×{h}", subject.id),
            );
            let (tracer, baseline) =
                timing::time_setting(&mut harness, &subject, &gpu, (w, h), config)?;
            report.timings.push(TimingRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                width: w,
                height: h,
                budget,
                budget_from: "fixed".into(),
                fog_factor: scene.shading.fog_distance / subject.inradius,
                frames: tracer.frames,
                median_ms: tracer.median,
                p10_ms: tracer.p10,
                p90_ms: tracer.p90,
                baseline_ms: baseline.median,
                ratio: tracer.median / baseline.median,
            });
            progress.inc(1);
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

impl BenchReport {
    /// A report with nothing measured yet: the device (if any), the build and the threads.
    fn empty(harness: Option<&Harness>) -> Self {
        Self {
            device: harness.map(|h| h.info().clone()),
            build: if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            }
            .to_string(),
            cpu_threads: rayon::current_num_threads(),
            ..Default::default()
        }
    }
}

/// Mean and 90th percentile of the face crossings per pixel of a `HIT_ID` picture.
fn crossings_per_pixel(ids: &[[u32; 4]]) -> (f64, f64) {
    if ids.is_empty() {
        return (0.0, 0.0);
    }
    let mut c: Vec<u32> = ids.iter().map(|id| id[1]).collect();
    c.sort_unstable();
    let mean = c.iter().map(|&x| f64::from(x)).sum::<f64>() / c.len() as f64;
    let p90 = f64::from(c[((c.len() - 1) as f64 * 0.9).round() as usize]);
    (mean, p90)
}

/// Shows what the benchmark is doing: on the bar, or (no terminal) as a log line.
fn announce(progress: &ProgressBar, message: String) {
    if progress.is_hidden() {
        eprintln!(
            "[{}/{}] {message}",
            progress.position(),
            progress.length().unwrap_or(0)
        );
    }
    progress.set_message(message);
}

/// The fog factor (λ / inradius) of the spaces' default fog.
pub const DEFAULT_FOG_FACTOR: f64 = crate::scene::Shading::DEFAULT_FOG_INRADII;

/// Runs the benchmark; `progress` draws a bar on a terminal (hidden otherwise).
pub fn run(config: &BenchConfig, progress: &ProgressBar) -> Result<BenchReport, BenchError> {
    if config.spaces.is_empty() {
        return Err(BenchError::Empty("no spaces were named"));
    }
    let subjects = config
        .spaces
        .iter()
        .map(|id| Subject::new(id))
        .collect::<Result<Vec<_>, _>>()?;
    let mut harness = if config.cpu_only {
        None
    } else {
        Some(Harness::new()?)
    };
    let gpu_steps = if harness.is_some() {
        (config.budgets.len() + config.fog_factors.len()) * (config.sizes.len() + 1)
            + 3
            + config.mesh_triangles.len()
    } else {
        0
    };
    let per_space = gpu_steps + 2 + config.fog_factors.len();
    progress.set_length((per_space * subjects.len()) as u64);
    progress.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} {msg} (eta {eta})",
        )
        .expect("a valid progress template"),
    );
    let mut report = BenchReport::empty(harness.as_ref());
    for subject in &subjects {
        let budgets = cpu_measurements(subject, config, progress, &mut report);
        if let Some(harness) = harness.as_mut() {
            gpu_measurements(harness, subject, &budgets, config, progress, &mut report)?;
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// The automatic budgets chosen for a space: (fog factor, quality, budget).
type ChosenBudgets = Vec<(f64, Quality, u32)>;

/// What needs no GPU: the f32 drift, the automatic budgets and the fog cut-off's error.
fn cpu_measurements(
    subject: &Subject,
    config: &BenchConfig,
    progress: &ProgressBar,
    report: &mut BenchReport,
) -> ChosenBudgets {
    announce(progress, format!("{}: f32 drift", subject.id));
    report.drift.extend(drift(subject, config));
    announce(
        progress,
        format!("{}: walks against the double-double reference", subject.id),
    );
    let (rows, curve) = conditioning(subject, config);
    report.conditioning.extend(rows);
    report.conditioning_curve.extend(curve);
    progress.inc(1);
    announce(progress, format!("{}: automatic budgets", subject.id));
    let mut budgets = Vec::new();
    for &fog in &config.fog_factors {
        let scene = subject.scene(fog);
        for quality in [Quality::Low, Quality::Medium, Quality::High] {
            let allowed = quality.miss_fraction();
            let choice = auto_budget(&subject.space, &scene, allowed, config.budget_samples);
            budgets.push((fog, quality, choice.budget));
            report.auto_budgets.push(AutoBudgetRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                quality: format!("{quality:?}").to_lowercase(),
                fog_factor: fog,
                miss_fraction_allowed: allowed,
                choice,
            });
        }
    }
    progress.inc(1);
    for &fog in &config.fog_factors {
        announce(
            progress,
            format!("{}: fog cut-off at λ = {fog} inradii", subject.id),
        );
        report.cutoff.push(cutoff(subject, fog, config.error_size));
        progress.inc(1);
    }
    budgets
}

/// Frame times and errors on the GPU: the specialised shader, stereo and meshes at the
/// automatic budget, then the budget sweep at the default fog and the fog sweep at the
/// automatic budget, each timed and compared with the f64 reference.
fn gpu_measurements(
    harness: &mut Harness,
    subject: &Subject,
    budgets: &ChosenBudgets,
    config: &BenchConfig,
    progress: &ProgressBar,
    report: &mut BenchReport,
) -> Result<(), BenchError> {
    // The budget sweep at the default fog, then the fog sweep at the automatic budget.
    let mut settings: Vec<(u32, String, f64)> = config
        .budgets
        .iter()
        .map(|&b| (b, "fixed".to_string(), DEFAULT_FOG_FACTOR))
        .collect();
    for &fog in &config.fog_factors {
        let budget = budgets
            .iter()
            .find(|(f, q, _)| *f == fog && *q == Quality::High)
            .map_or(64, |b| b.2);
        settings.push((budget, "auto-high".to_string(), fog));
    }
    announce(
        progress,
        format!("{}: specialised against general shader", subject.id),
    );
    let auto_default = budgets
        .iter()
        .find(|(f, q, _)| *f == DEFAULT_FOG_FACTOR && *q == Quality::High)
        .map_or(32, |b| b.2);
    report
        .specialisation
        .push(specialisation(harness, subject, auto_default, config)?);
    progress.inc(1);
    announce(progress, format!("{}: stereo against mono", subject.id));
    report
        .stereo
        .push(stereo_cost(harness, subject, auto_default, config)?);
    progress.inc(1);
    announce(
        progress,
        format!("{}: edges culled, unculled and none", subject.id),
    );
    report
        .edges
        .push(edges_cost(harness, subject, auto_default, config)?);
    progress.inc(1);
    for budget in [16, 32] {
        if config.budgets.contains(&budget) {
            announce(
                progress,
                format!(
                    "{} at {budget} crossings: against a straightforward tracer",
                    subject.id
                ),
            );
            report
                .straightforward
                .extend(straightforward_cost(harness, subject, budget, config)?);
        }
    }
    for &triangles in &config.mesh_triangles {
        announce(
            progress,
            format!("{}: a mesh of {triangles} triangles", subject.id),
        );
        report.meshes.push(mesh_cost(
            harness,
            subject,
            triangles,
            auto_default,
            config,
        )?);
        progress.inc(1);
    }
    let mut exact_cache: Vec<(f64, Reference)> = Vec::new();
    for (budget, from, fog) in settings {
        let scene = subject.scene(fog);
        let gpu = subject.pack(&scene, budget)?;
        for &(w, h) in &config.sizes {
            announce(
                progress,
                format!(
                    "{}: {w}×{h}, budget {budget}, λ = {fog} inradii",
                    subject.id
                ),
            );
            let (stats, baseline) = time_setting(harness, subject, &gpu, (w, h), config)?;
            report.timings.push(TimingRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                width: w,
                height: h,
                budget,
                budget_from: from.clone(),
                fog_factor: fog,
                frames: stats.frames,
                median_ms: stats.median,
                p10_ms: stats.p10,
                p90_ms: stats.p90,
                baseline_ms: baseline.median,
                ratio: stats.median / baseline.median,
            });
            progress.inc(1);
        }
        announce(
            progress,
            format!(
                "{}: accuracy, budget {budget}, λ = {fog} inradii",
                subject.id
            ),
        );
        let exact = match exact_cache.iter().find(|(f, _)| *f == fog) {
            Some((_, r)) => r.clone(),
            None => {
                let r = Reference::trace(subject, &scene, config.error_size, EXACT_BUDGET, false);
                exact_cache.push((fog, r.clone()));
                r
            }
        };
        let same = Reference::trace(subject, &scene, config.error_size, budget as usize, false);
        let rounded = Reference::trace(subject, &scene, config.error_size, budget as usize, true);
        let measured = gpu_pixels(harness, subject, &gpu, budget, config.error_size)?;
        let against_exact = measured.compare(&exact);
        let work = crossings_per_pixel(&measured.ids);
        let against_same = measured.compare(&same);
        report.errors.push(ErrorRow {
            space: subject.id.clone(),
            geometry: subject.geometry(),
            budget,
            budget_from: from,
            fog_factor: fog,
            width: config.error_size.0,
            height: config.error_size.1,
            hit_differs: against_exact.hit_differs,
            hit_differs_same_budget: against_same.hit_differs,
            hit_floor_f32: rounded.compare(&same).hit_differs,
            budget_exhausted: measured.exhausted as f64
                / f64::from(config.error_size.0 * config.error_size.1),
            mean_levels: against_exact.mean_levels,
            max_levels: against_exact.max_levels,
            over_2_levels: against_exact.over_2_levels,
            over_10_levels: against_exact.over_10_levels,
            mean_crossings: work.0,
            p90_crossings: work.1,
        });
        progress.inc(1);
    }
    Ok(())
}
