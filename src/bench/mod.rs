//! `curved-spaces bench`: speed against error, measured in one run.
//!
//! For every space it times the GPU tracer (the plugin's shader and uniform, in a plain wgpu
//! harness) against a trivial fullscreen material of the same size, over resolutions,
//! crossing budgets and fog distances; it measures in the same run what each setting costs
//! in accuracy against the f64 CPU reference (pixels whose hit differs, colour error), the
//! f32 drift of long rays, and the error of the fog cut-off against its stated bound. The
//! figures go to JSON and CSV files and charts (PNG and SVG) in one folder.

pub mod harness;
mod plot;

pub use harness::{BASELINE_WGSL, DeviceInfo, Frame, Harness, HarnessError, Output, Program};
pub use plot::{Chart, Corner, PlotError, Series, write_chart};

use crate::geometry::{Geometry, Vector4};
use crate::plugin::Quality;
use crate::render::gpu::{GpuScene, gpu_object_indices, view_words};
use crate::space::{Space, invariants, seed_space};
use crate::stereo::{StereoMode, ViewKind, ViewLayout, default_ipd, eye_frames};
use crate::trace::{
    BudgetChoice, Camera, CellWalker, Limit, RayEnd, Scene, auto_budget, colour_of,
    first_hit_traced, sample_rays, to_byte,
};
use glam::{DVec4, Vec4};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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
    pub max_frames: usize,
    /// Random rays per space for the f32 drift.
    pub drift_rays: usize,
    /// Crossing counts the drift is reported at.
    pub drift_crossings: Vec<usize>,
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
            budget_samples: 512,
            cpu_only: false,
            mesh_triangles: vec![12, 960],
        }
    }
}

/// Why the benchmark stopped.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    #[error(transparent)]
    Space(#[from] crate::space::SpaceError),
    #[error(transparent)]
    Gpu(#[from] HarnessError),
    #[error("the scene of {space} cannot be packed for the GPU: {error}")]
    Scene {
        space: String,
        error: crate::render::gpu::GpuSceneError,
    },
    #[error(transparent)]
    Plot(#[from] PlotError),
    #[error("writing {path} failed: {error}")]
    Write { path: String, error: String },
    #[error("nothing to measure: {0}")]
    Empty(&'static str),
}

/// GPU frame time of one setting.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TimingRow {
    pub space: String,
    pub geometry: String,
    pub width: u32,
    pub height: u32,
    pub budget: u32,
    /// How the budget was chosen: "fixed", or the quality preset of the automatic budget.
    pub budget_from: String,
    pub fog_factor: f64,
    pub frames: usize,
    pub median_ms: f64,
    pub p10_ms: f64,
    pub p90_ms: f64,
    /// Median frame time of the trivial material, measured interleaved with the tracer.
    pub baseline_ms: f64,
    /// `median_ms / baseline_ms`.
    pub ratio: f64,
}

/// Accuracy of one setting against the f64 reference at the same camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrorRow {
    pub space: String,
    pub geometry: String,
    pub budget: u32,
    pub budget_from: String,
    pub fog_factor: f64,
    pub width: u32,
    pub height: u32,
    /// Pixels whose hit (object and exit-face sequence) differs from the exact reference
    /// (f64, budget [`EXACT_BUDGET`]): the budget's error and f32's together.
    pub hit_differs: f64,
    /// Pixels whose hit differs from the f64 reference with the same budget: f32's share.
    pub hit_differs_same_budget: f64,
    /// The floor under that share: pixels whose f64 hit changes when only the camera ray is
    /// rounded to f32 (what any f32 tracer gets wrong at best, DESIGN.md §3). Far away in H³
    /// a pixel covers many cells, so the hit there is decided below the pixel's size.
    pub hit_floor_f32: f64,
    /// Colour error against the exact reference, in 8-bit levels.
    pub mean_levels: f64,
    pub max_levels: u32,
    /// GPU rays that used up the whole budget (shown as fog).
    pub budget_exhausted: f64,
    /// Pixels more than 2 and more than 10 levels off the exact reference.
    pub over_2_levels: f64,
    pub over_10_levels: f64,
}

/// f32 against f64 along long rays.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct DriftRow {
    pub space: String,
    pub geometry: String,
    pub crossings: usize,
    pub rays: usize,
    /// Rays whose f32 face sequence still equals the f64 one.
    pub same_faces: f64,
    /// Median geodesic distance travelled by then (f64).
    pub median_distance: f64,
    /// Geodesic distance between the f32 and the f64 point (median and max over the rays
    /// that still agree; `None` when none does).
    pub median_position_error: Option<f64>,
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
    pub space: String,
    pub geometry: String,
    pub fog_factor: f64,
    pub fog_distance: f64,
    pub cutoff_distance: f64,
    /// The stated bound: the fog weight at the cut-off, per channel in [0, 1].
    pub bound: f64,
    pub max_error: f64,
    pub mean_error: f64,
    pub within_bound: bool,
    /// Reference rays (no cut-off) that used up [`EXACT_BUDGET`].
    pub reference_budget_exhausted: f64,
}

/// The automatic budget of a quality preset and what it costs and buys.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct AutoBudgetRow {
    pub space: String,
    pub geometry: String,
    pub quality: String,
    pub fog_factor: f64,
    pub miss_fraction_allowed: f64,
    #[serde(flatten)]
    pub choice: BudgetChoice,
}

/// The specialised shader against the unspecialised one (same view, same scene).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SpecialisationRow {
    pub space: String,
    pub geometry: String,
    pub width: u32,
    pub height: u32,
    pub budget: u32,
    pub specialised_ms: f64,
    pub general_ms: f64,
    /// `general_ms / specialised_ms`: how much faster specialising makes the frame.
    pub gain: f64,
    pub specialised_uniform_bytes: usize,
    pub general_uniform_bytes: usize,
    /// Pixels that differ between the two pictures (they compute the same formulas).
    pub differing_pixels: f64,
}

/// Stereo against mono: the same head, the same scene, the same size, the eyes traced by the
/// same shader (each timed interleaved with mono).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct StereoRow {
    pub space: String,
    pub geometry: String,
    pub width: u32,
    pub height: u32,
    pub budget: u32,
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
    pub device: Option<DeviceInfo>,
    /// "release" or "debug".
    pub build: String,
    pub cpu_threads: usize,
    pub timings: Vec<TimingRow>,
    pub errors: Vec<ErrorRow>,
    pub drift: Vec<DriftRow>,
    pub cutoff: Vec<CutoffRow>,
    pub auto_budgets: Vec<AutoBudgetRow>,
    pub specialisation: Vec<SpecialisationRow>,
    /// Absent from reports written before stereo existed.
    #[serde(default)]
    pub stereo: Vec<StereoRow>,
    /// Absent from reports written before meshes existed.
    #[serde(default)]
    pub meshes: Vec<MeshRow>,
}

/// A mesh at the cell's centre: frame time against triangle count, timed interleaved with
/// the same scene without the mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeshRow {
    pub space: String,
    pub geometry: String,
    pub width: u32,
    pub height: u32,
    pub budget: u32,
    pub triangles: usize,
    pub nodes: usize,
    pub depth: usize,
    /// Building the hierarchy on the CPU.
    pub build_ms: f64,
    pub with_mesh_ms: f64,
    pub without_mesh_ms: f64,
    /// `with_mesh_ms / without_mesh_ms` (measured in the same loop).
    pub ratio: f64,
}

/// One space with what the benchmark needs of it.
struct Subject {
    id: String,
    space: Space,
    inradius: f64,
    camera: Camera,
}

impl Subject {
    fn new(id: &str) -> Result<Self, BenchError> {
        let space = seed_space(id)?;
        Ok(Self {
            id: id.to_string(),
            inradius: invariants::inradius(&space),
            camera: Camera::default_for(&space),
            space,
        })
    }

    fn geometry(&self) -> String {
        self.space.geometry.name().to_string()
    }

    /// The scene packed for the GPU with a crossing budget.
    fn pack(&self, scene: &Scene, budget: u32) -> Result<GpuScene, BenchError> {
        GpuScene::new(&self.space, scene, budget).map_err(|error| BenchError::Scene {
            space: self.id.clone(),
            error,
        })
    }

    fn scene(&self, fog_factor: f64) -> Scene {
        Scene::default_for(&self.space, fog_factor * self.inradius)
    }
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
pub const DEFAULT_FOG_FACTOR: f64 = 3.0;

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
            + 2
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
    let mut report = BenchReport {
        device: harness.as_ref().map(|h| h.info().clone()),
        build: if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        }
        .to_string(),
        cpu_threads: rayon::current_num_threads(),
        ..Default::default()
    };
    for subject in &subjects {
        announce(progress, format!("{}: f32 drift", subject.id));
        report.drift.extend(drift(subject, config));
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
        let Some(harness) = harness.as_mut() else {
            continue;
        };
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
                    let r =
                        Reference::trace(subject, &scene, config.error_size, EXACT_BUDGET, false);
                    exact_cache.push((fog, r.clone()));
                    r
                }
            };
            let same = Reference::trace(subject, &scene, config.error_size, budget as usize, false);
            let rounded =
                Reference::trace(subject, &scene, config.error_size, budget as usize, true);
            let measured = gpu_pixels(harness, subject, &gpu, budget, config.error_size)?;
            let against_exact = measured.compare(&exact);
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
            });
            progress.inc(1);
        }
    }
    progress.finish_and_clear();
    Ok(report)
}

/// Median and spread of frame times (ms).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Stats {
    frames: usize,
    median: f64,
    p10: f64,
    p90: f64,
}

impl Stats {
    fn of(mut times: Vec<f64>) -> Self {
        times.sort_by(f64::total_cmp);
        let at = |q: f64| times[((times.len() - 1) as f64 * q).round() as usize];
        Self {
            frames: times.len(),
            median: at(0.5),
            p10: at(0.1),
            p90: at(0.9),
        }
    }
}

/// The whole uniform of a view of `layout` onto a packed scene.
fn uniform_words(layout: &ViewLayout, gpu: &GpuScene) -> Vec<u32> {
    let view = view_words(layout, [0, 0], &crate::render::gpu::ViewExtras::default());
    view.iter().chain(gpu.words.iter()).copied().collect()
}

/// Times the tracer and the baseline, alternating frame by frame so that both see the same
/// machine load; the first frame of each (pipeline compilation) is not counted.
fn time_setting(
    harness: &mut Harness,
    subject: &Subject,
    gpu: &GpuScene,
    (w, h): (u32, u32),
    config: &BenchConfig,
) -> Result<(Stats, Stats), BenchError> {
    let tracer = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
    let frame = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&subject.camera.layout(w, h), gpu),
        &gpu.data,
    );
    let baseline_frame = harness.frame(w, h, Output::Colour, &[], &[]);
    harness.draw(&tracer, &frame)?;
    harness.draw(&Program::Baseline, &baseline_frame)?;
    time_interleaved(
        harness,
        (&tracer, &frame),
        (&Program::Baseline, &baseline_frame),
        config,
    )
}

/// Times two programs frame by frame in turn (so both see the same machine load) for at
/// least `min_frames` and `min_seconds`, at most `max_frames`. Draw each once before: the
/// first frame compiles the pipeline.
fn time_interleaved(
    harness: &mut Harness,
    (pa, a): (&Program, &Frame),
    (pb, b): (&Program, &Frame),
    config: &BenchConfig,
) -> Result<(Stats, Stats), BenchError> {
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    let start = std::time::Instant::now();
    while ta.len() < config.max_frames.max(1)
        && (ta.len() < config.min_frames.max(1)
            || start.elapsed().as_secs_f64() < config.min_seconds)
    {
        ta.push(harness.draw(pa, a)?);
        tb.push(harness.draw(pb, b)?);
    }
    Ok((Stats::of(ta), Stats::of(tb)))
}

/// Times the specialised and the unspecialised shader on the same view, interleaved, at the
/// middle timed resolution.
fn specialisation(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<SpecialisationRow, BenchError> {
    let scene = subject.scene(DEFAULT_FOG_FACTOR);
    let special = subject.pack(&scene, budget)?;
    let general = special.generalised().ok_or(BenchError::Empty(
        "the scene is larger than the general shader's capacity",
    ))?;
    let (w, h) = config.middle_size();
    let mono = subject.camera.layout(w, h);
    let a = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&mono, &special),
        &special.data,
    );
    let b = harness.frame(
        w,
        h,
        Output::Colour,
        &uniform_words(&mono, &general),
        &general.data,
    );
    let (pa, pb) = (
        Program::Tracer(special.key, ViewKind::Mono, Output::Colour),
        Program::Tracer(general.key, ViewKind::Mono, Output::Colour),
    );
    harness.draw(&pa, &a)?;
    harness.draw(&pb, &b)?;
    let pixels_a = harness.read_pixels(&a)?;
    let pixels_b = harness.read_pixels(&b)?;
    let differing = pixels_a
        .chunks_exact(4)
        .zip(pixels_b.chunks_exact(4))
        .filter(|(x, y)| x != y)
        .count();
    let (sa, sb) = time_interleaved(harness, (&pa, &a), (&pb, &b), config)?;
    Ok(SpecialisationRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        specialised_ms: sa.median,
        general_ms: sb.median,
        gain: sb.median / sa.median,
        specialised_uniform_bytes: special.key.uniform_bytes(),
        general_uniform_bytes: general.key.uniform_bytes(),
        differing_pixels: differing as f64 / f64::from(w * h),
    })
}

/// Times side-by-side and anaglyph stereo against mono at the middle timed resolution, each
/// interleaved with mono.
fn stereo_cost(
    harness: &mut Harness,
    subject: &Subject,
    budget: u32,
    config: &BenchConfig,
) -> Result<StereoRow, BenchError> {
    let scene = subject.scene(DEFAULT_FOG_FACTOR);
    let gpu = subject.pack(&scene, budget)?;
    let (w, h) = config.middle_size();
    let ipd = default_ipd(subject.inradius);
    let eyes = eye_frames(&subject.space, subject.camera.frame, ipd).map(|e| e.frame);
    let frame_of = |harness: &mut Harness, mode: StereoMode| {
        let layout = ViewLayout::new(mode, false, eyes, subject.camera.fov_y_degrees, w, h);
        let words = uniform_words(&layout, &gpu);
        let program = Program::Tracer(gpu.key, mode.kind(), Output::Colour);
        (
            program,
            harness.frame(w, h, Output::Colour, &words, &gpu.data),
        )
    };
    let mono = frame_of(harness, StereoMode::Mono);
    let mut measured = Vec::new();
    for mode in [StereoMode::SideBySide, StereoMode::AnaglyphDubois] {
        let other = frame_of(harness, mode);
        harness.draw(&mono.0, &mono.1)?;
        harness.draw(&other.0, &other.1)?;
        let (m, o) = time_interleaved(harness, (&mono.0, &mono.1), (&other.0, &other.1), config)?;
        measured.push((m.median, o.median));
    }
    let [(mono_a, sbs), (mono_b, anaglyph)] = [measured[0], measured[1]];
    Ok(StereoRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        mono_ms: 0.5 * (mono_a + mono_b),
        side_by_side_ms: sbs,
        side_by_side_ratio: sbs / mono_a,
        anaglyph_ms: anaglyph,
        anaglyph_ratio: anaglyph / mono_b,
    })
}

/// The mesh of about `triangles` triangles: the cube for 12, else a torus knot whose
/// segments and sides give that count (`2·segments·sides`).
#[must_use]
pub fn bench_mesh(triangles: usize) -> crate::scene::mesh::MeshSource {
    if triangles <= 12 {
        return crate::scene::mesh::cube_source(1.0, 0);
    }
    let sides = ((triangles as f64 / 8.0).sqrt().round() as u32).max(3);
    let segments = ((triangles as f64 / (2.0 * f64::from(sides))).round() as u32).max(3);
    crate::scene::assets::torus_knot(3, 2, segments, sides)
}

/// Times the default scene (without its centre ball) with and without a mesh of about
/// `triangles` triangles at the cell's centre, interleaved, at the middle timed resolution.
fn mesh_cost(
    harness: &mut Harness,
    subject: &Subject,
    triangles: usize,
    budget: u32,
    config: &BenchConfig,
) -> Result<MeshRow, BenchError> {
    use crate::trace::{Material, MeshInstance, Object};
    let g = subject.space.geometry;
    let mut without = Scene::with_parts(
        &subject.space,
        DEFAULT_FOG_FACTOR * subject.inradius,
        crate::trace::SceneParts {
            centre_ball: false,
            ..Default::default()
        },
    );
    without.materials.push(Material {
        colour: glam::DVec3::new(0.9, 0.6, 0.3),
        ..Material::default()
    });
    let source = bench_mesh(triangles);
    let radius = source
        .positions
        .iter()
        .map(|p| p.length())
        .fold(0.0, f64::max);
    let started = std::time::Instant::now();
    let mesh = source
        .place(g, 0.5 * subject.inradius / radius)
        .map_err(|_| BenchError::Empty("the benchmark mesh could not be placed"))?;
    let build_ms = 1e3 * started.elapsed().as_secs_f64();
    let (nodes, depth, count) = (mesh.nodes.len(), mesh.depth(), mesh.triangles.len());
    let mut with = without.clone();
    let mesh_radius = mesh.radius;
    with.meshes.push(std::sync::Arc::new(mesh));
    with.objects.push(Object::Mesh(MeshInstance::new(
        g,
        0,
        g.rotation(glam::DVec3::new(1.0, 0.3, 0.2), 0.6),
        mesh_radius,
    )));
    let (w, h) = config.middle_size();
    let layout = subject.camera.layout(w, h);
    let frame_of = |harness: &mut Harness, scene: &Scene| -> Result<_, BenchError> {
        let gpu = subject.pack(scene, budget)?;
        let program = Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour);
        let frame = harness.frame(
            w,
            h,
            Output::Colour,
            &uniform_words(&layout, &gpu),
            &gpu.data,
        );
        Ok((program, frame))
    };
    let a = frame_of(harness, &with)?;
    let b = frame_of(harness, &without)?;
    harness.draw(&a.0, &a.1)?;
    harness.draw(&b.0, &b.1)?;
    let (sa, sb) = time_interleaved(harness, (&a.0, &a.1), (&b.0, &b.1), config)?;
    Ok(MeshRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        width: w,
        height: h,
        budget,
        triangles: count,
        nodes,
        depth,
        build_ms,
        with_mesh_ms: sa.median,
        without_mesh_ms: sb.median,
        ratio: sa.median / sb.median,
    })
}

/// Per pixel: what the ray met (`[object + 1, crossings, path, end]`) and its 8-bit colour.
#[derive(Clone, Debug, PartialEq)]
struct Reference {
    ids: Vec<[u32; 4]>,
    rgb: Vec<[u8; 3]>,
    /// Rays that used up the budget.
    exhausted: usize,
}

/// How one picture differs from another.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Difference {
    hit_differs: f64,
    mean_levels: f64,
    max_levels: u32,
    over_2_levels: f64,
    over_10_levels: f64,
}

impl Reference {
    /// The f64 reference picture with what each ray met; with `round_start`, each camera ray
    /// is first rounded to f32 (then traced in f64).
    fn trace(
        subject: &Subject,
        scene: &Scene,
        (w, h): (u32, u32),
        budget: usize,
        round_start: bool,
    ) -> Self {
        let walker = CellWalker::<DVec4>::new(&subject.space);
        let index = gpu_object_indices(scene);
        let g = subject.space.geometry;
        let layout = subject.camera.layout(w, h);
        let pixels: Vec<([u32; 4], [u8; 3], bool)> = (0..w * h)
            .into_par_iter()
            .map(|k| {
                let mut ray = layout.ray_at(g, k % w, k / w);
                if round_start {
                    ray.point = Vec4::from_f64(ray.point).to_f64();
                    ray.tangent = Vec4::from_f64(ray.tangent).to_f64();
                }
                let traced = first_hit_traced(&walker, scene, ray, budget);
                let colour = colour_of(g, scene, &traced.end).to_array().map(to_byte);
                let exhausted = matches!(traced.end, RayEnd::Budget(c) if c == budget);
                (traced.id(|o| index[o]), colour, exhausted)
            })
            .collect();
        Self {
            ids: pixels.iter().map(|p| p.0).collect(),
            rgb: pixels.iter().map(|p| p.1).collect(),
            exhausted: pixels.iter().filter(|p| p.2).count(),
        }
    }

    fn compare(&self, reference: &Reference) -> Difference {
        // A hit is the object and the faces crossed to it; fog and budget both show fog.
        let key = |id: &[u32; 4]| if id[3] == 1 { (id[0], id[2]) } else { (0, 0) };
        let n = self.ids.len().max(1) as f64;
        let hit_differs = self
            .ids
            .iter()
            .zip(&reference.ids)
            .filter(|(a, b)| key(a) != key(b))
            .count() as f64
            / n;
        let levels: Vec<u32> = self
            .rgb
            .iter()
            .zip(&reference.rgb)
            .map(|(a, b)| {
                (0..3)
                    .map(|c| u32::from(a[c].abs_diff(b[c])))
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        Difference {
            hit_differs,
            mean_levels: levels.iter().map(|&l| f64::from(l)).sum::<f64>() / n,
            max_levels: levels.iter().copied().max().unwrap_or(0),
            over_2_levels: levels.iter().filter(|&&l| l > 2).count() as f64 / n,
            over_10_levels: levels.iter().filter(|&&l| l > 10).count() as f64 / n,
        }
    }
}

/// The GPU's picture and hit ids of a setting.
fn gpu_pixels(
    harness: &mut Harness,
    subject: &Subject,
    gpu: &GpuScene,
    budget: u32,
    size: (u32, u32),
) -> Result<Reference, BenchError> {
    let words = uniform_words(&subject.camera.layout(size.0, size.1), gpu);
    let colour = harness.frame(size.0, size.1, Output::Colour, &words, &gpu.data);
    harness.draw(
        &Program::Tracer(gpu.key, ViewKind::Mono, Output::Colour),
        &colour,
    )?;
    let rgba = harness.read_pixels(&colour)?;
    let ids_frame = harness.frame(size.0, size.1, Output::HitId, &words, &gpu.data);
    harness.draw(
        &Program::Tracer(gpu.key, ViewKind::Mono, Output::HitId),
        &ids_frame,
    )?;
    let id_bytes = harness.read_pixels(&ids_frame)?;
    let ids: Vec<[u32; 4]> = bytemuck::cast_slice::<u8, u32>(&id_bytes)
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    Ok(Reference {
        exhausted: ids
            .iter()
            .filter(|id| id[3] == 3 && id[1] == budget)
            .count(),
        ids,
        rgb: rgba.chunks_exact(4).map(|p| [p[0], p[1], p[2]]).collect(),
    })
}

/// The conditioning factor `G(d)` of DESIGN.md §3.
#[must_use]
pub fn growth(geometry: Geometry, d: f64) -> f64 {
    match geometry {
        Geometry::Spherical => 1.0,
        Geometry::Euclidean => 1.0 + d,
        Geometry::Hyperbolic => d.exp(),
    }
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied()
}

/// f32 against f64 along `drift_rays` random rays, at each of `drift_crossings`.
fn drift(subject: &Subject, config: &BenchConfig) -> Vec<DriftRow> {
    let space = &subject.space;
    let g = space.geometry;
    let Some(&most) = config.drift_crossings.iter().max() else {
        return Vec::new();
    };
    let w64 = CellWalker::<DVec4>::new(space);
    let w32 = CellWalker::<Vec4>::new(space);
    let rays = sample_rays(space, config.drift_rays, 0xd71f7);
    let traces: Vec<_> = rays
        .par_iter()
        .map(|ray| {
            let exact = w64.trace(*ray, Limit::Crossings(most));
            let single = w32.trace(
                crate::trace::Ray {
                    point: Vec4::from_f64(ray.point),
                    tangent: Vec4::from_f64(ray.tangent),
                },
                Limit::Crossings(most),
            );
            (exact, single)
        })
        .collect();
    config
        .drift_crossings
        .iter()
        .map(|&n| {
            let mut agree = 0;
            let (mut positions, mut directions, mut distances) = (vec![], vec![], vec![]);
            let mut ratios: Vec<f64> = Vec::new();
            for (exact, single) in &traces {
                let (Some(a), Some(b)) = (exact.crossings.get(n - 1), single.crossings.get(n - 1))
                else {
                    continue;
                };
                distances.push(a.distance);
                let same = exact.crossings[..n]
                    .iter()
                    .zip(&single.crossings[..n])
                    .all(|(x, y)| x.face == y.face);
                if !same {
                    continue;
                }
                agree += 1;
                let p32 = g.project_point(b.ray.point.to_f64());
                let error = g.distance(a.ray.point, p32);
                positions.push(error);
                ratios.push(
                    error / (DRIFT_BOUND_FACTOR * F32_EPSILON * n as f64 * growth(g, a.distance)),
                );
                let v32 = g.unit_tangent(a.ray.point, b.ray.tangent.to_f64());
                let d = v32 - a.ray.tangent;
                let chord = g.form(d, d).max(0.0).sqrt();
                directions.push(2.0 * (0.5 * chord).min(1.0).asin());
            }
            let d = median(distances).unwrap_or(0.0);
            DriftRow {
                space: subject.id.clone(),
                geometry: subject.geometry(),
                crossings: n,
                rays: traces.len(),
                same_faces: agree as f64 / traces.len().max(1) as f64,
                median_distance: d,
                max_position_error: positions.iter().copied().reduce(f64::max),
                median_position_error: median(positions),
                median_direction_error: median(directions),
                bound: Some(DRIFT_BOUND_FACTOR * F32_EPSILON * n as f64 * growth(g, d))
                    .filter(|b| b.is_finite()),
                worst_bound_ratio: ratios.into_iter().reduce(f64::max),
            }
        })
        .collect()
}

/// The error of the fog cut-off: the f64 picture with it against one traced without it.
fn cutoff(subject: &Subject, fog_factor: f64, (w, h): (u32, u32)) -> CutoffRow {
    let scene = subject.scene(fog_factor);
    let mut uncut = scene.clone();
    // A weight of 1e-15 puts the cut-off ~34.5 λ away: nothing is cut off that f64 can see.
    uncut.shading.cutoff_weight = 1e-15;
    let walker = CellWalker::<DVec4>::new(&subject.space);
    let g = subject.space.geometry;
    let layout = subject.camera.layout(w, h);
    let errors: Vec<(f64, bool)> = (0..w * h)
        .into_par_iter()
        .map(|k| {
            let ray = layout.ray_at(g, k % w, k / w);
            let cut = first_hit_traced(&walker, &scene, ray, EXACT_BUDGET).end;
            let full = first_hit_traced(&walker, &uncut, ray, EXACT_BUDGET).end;
            let error = (colour_of(g, &scene, &cut) - colour_of(g, &uncut, &full))
                .abs()
                .max_element();
            (error, matches!(full, RayEnd::Budget(_)))
        })
        .collect();
    let n = errors.len().max(1) as f64;
    let max_error = errors.iter().map(|e| e.0).fold(0.0, f64::max);
    let bound = scene.shading.cutoff_weight;
    CutoffRow {
        space: subject.id.clone(),
        geometry: subject.geometry(),
        fog_factor,
        fog_distance: scene.shading.fog_distance,
        cutoff_distance: scene.shading.cutoff_distance(),
        bound,
        max_error,
        mean_error: errors.iter().map(|e| e.0).sum::<f64>() / n,
        within_bound: max_error <= bound,
        reference_budget_exhausted: errors.iter().filter(|e| e.1).count() as f64 / n,
    }
}

/// Writes `report` as `bench.json`, one CSV per table and the charts into `dir`.
pub fn write_report(
    report: &BenchReport,
    config: &BenchConfig,
    dir: &Path,
) -> Result<Vec<PathBuf>, BenchError> {
    let write_err = |path: &Path, e: &dyn std::fmt::Display| BenchError::Write {
        path: path.display().to_string(),
        error: e.to_string(),
    };
    std::fs::create_dir_all(dir).map_err(|e| write_err(dir, &e))?;
    let mut written = Vec::new();
    let json = dir.join("bench.json");
    let body = serde_json::to_string_pretty(&serde_json::json!({
        "config": config,
        "report": report,
    }))
    .map_err(|e| write_err(&json, &e))?;
    std::fs::write(&json, body).map_err(|e| write_err(&json, &e))?;
    written.push(json);
    let tables: [(&str, Vec<serde_json::Value>); 8] = [
        ("timings", to_values(&report.timings)),
        ("errors", to_values(&report.errors)),
        ("drift", to_values(&report.drift)),
        ("cutoff", to_values(&report.cutoff)),
        ("auto_budgets", to_values(&report.auto_budgets)),
        ("specialisation", to_values(&report.specialisation)),
        ("stereo", to_values(&report.stereo)),
        ("meshes", to_values(&report.meshes)),
    ];
    for (name, rows) in tables {
        let path = dir.join(format!("{name}.csv"));
        std::fs::write(&path, to_csv(&rows)).map_err(|e| write_err(&path, &e))?;
        written.push(path);
    }
    let summary = dir.join("summary.md");
    std::fs::write(&summary, summary_markdown(report)).map_err(|e| write_err(&summary, &e))?;
    written.push(summary);
    for (stem, chart) in charts(report) {
        let path = dir.join(stem);
        write_chart(&chart, &path)?;
        written.push(path.with_extension("png"));
        written.push(path.with_extension("svg"));
    }
    Ok(written)
}

/// Reads a `bench.json` written by [`write_report`] back (to redraw its charts and tables).
pub fn read_report(path: &Path) -> Result<(BenchConfig, BenchReport), BenchError> {
    let fail = |e: &dyn std::fmt::Display| BenchError::Write {
        path: path.display().to_string(),
        error: format!("cannot read it as a benchmark result: {e}"),
    };
    let text = std::fs::read_to_string(path).map_err(|e| fail(&e))?;
    #[derive(Deserialize)]
    struct File {
        config: BenchConfig,
        report: BenchReport,
    }
    let file: File = serde_json::from_str(&text).map_err(|e| fail(&e))?;
    Ok((file.config, file.report))
}

fn pct(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else if x < 0.001 {
        format!("{:.3}", 100.0 * x)
    } else {
        format!("{:.2}", 100.0 * x)
    }
}

/// The report's main tables as Markdown (for docs/performance.md).
#[must_use]
pub fn summary_markdown(report: &BenchReport) -> String {
    use std::fmt::Write as _;
    let mut md = String::new();
    let device = report.device.as_ref().map_or_else(
        || "no GPU (CPU measurements only)".to_string(),
        |d| {
            format!(
                "{} ({}, {}, {}); frame times from {}",
                d.name,
                d.device_type,
                d.backend,
                d.driver,
                if d.timestamps {
                    "GPU timestamps around the pass"
                } else {
                    "wall time around each synchronised submission"
                }
            )
        },
    );
    let _ = writeln!(
        md,
        "Device: {device}. Build: {}, {} CPU threads.\n",
        report.build, report.cpu_threads
    );
    let mut spaces: Vec<&String> = report.timings.iter().map(|t| &t.space).collect();
    spaces.dedup();
    let mut sizes: Vec<(u32, u32)> = report.timings.iter().map(|t| (t.width, t.height)).collect();
    sizes.sort_unstable();
    sizes.dedup();
    if !spaces.is_empty() {
        let _ = writeln!(
            md,
            "### Frame time at the automatic budget (quality High, fog {DEFAULT_FOG_FACTOR} inradii)\n"
        );
        let mut header = "| space | budget |".to_string();
        let mut rule = "|---|---:|".to_string();
        for (w, h) in &sizes {
            let _ = write!(header, " {w}×{h} ms (× trivial) |");
            rule.push_str("---:|");
        }
        let _ = writeln!(md, "{header}\n{rule}");
        for space in &spaces {
            let rows: Vec<&TimingRow> = report
                .timings
                .iter()
                .filter(|t| {
                    &t.space == *space
                        && t.budget_from == "auto-high"
                        && t.fog_factor == DEFAULT_FOG_FACTOR
                })
                .collect();
            let Some(first) = rows.first() else { continue };
            let mut line = format!("| {space} | {} |", first.budget);
            for size in &sizes {
                match rows.iter().find(|t| (t.width, t.height) == *size) {
                    Some(t) => {
                        let _ = write!(line, " {:.2} ({:.0}×) |", t.median_ms, t.ratio);
                    }
                    None => line.push_str(" – |"),
                }
            }
            let _ = writeln!(md, "{line}");
        }
        let mid = sizes[sizes.len() / 2];
        let _ = writeln!(
            md,
            "\n### Speed against error ({}×{} timings; errors at {}×{} against the f64 reference)\n",
            mid.0,
            mid.1,
            report.errors.first().map_or(0, |e| e.width),
            report.errors.first().map_or(0, |e| e.height)
        );
        let _ = writeln!(
            md,
            "| space | budget | fog (inradii) | ms | rays out of budget % | hit differs % | f32 share % | f32 floor % | mean levels | max levels | > 10 levels % |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        );
        for e in &report.errors {
            let ms = report
                .timings
                .iter()
                .find(|t| {
                    t.space == e.space
                        && t.budget == e.budget
                        && t.fog_factor == e.fog_factor
                        && t.budget_from == e.budget_from
                        && (t.width, t.height) == mid
                })
                .map_or(f64::NAN, |t| t.median_ms);
            let _ = writeln!(
                md,
                "| {} | {}{} | {} | {:.2} | {} | {} | {} | {} | {:.2} | {} | {} |",
                e.space,
                e.budget,
                if e.budget_from == "fixed" {
                    ""
                } else {
                    " (auto)"
                },
                e.fog_factor,
                ms,
                pct(e.budget_exhausted),
                pct(e.hit_differs),
                pct(e.hit_differs_same_budget),
                pct(e.hit_floor_f32),
                e.mean_levels,
                e.max_levels,
                pct(e.over_10_levels)
            );
        }
    }
    if !report.specialisation.is_empty() {
        let _ = writeln!(
            md,
            "\n### Specialised shader against the unspecialised one\n\n| space | size | budget | specialised ms | general ms | gain | uniform bytes (spec. / general) | pixels differing % |\n|---|---|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.specialisation {
            let _ = writeln!(
                md,
                "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {} / {} | {} |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.specialised_ms,
                r.general_ms,
                r.gain,
                r.specialised_uniform_bytes,
                r.general_uniform_bytes,
                pct(r.differing_pixels)
            );
        }
    }
    if !report.stereo.is_empty() {
        let _ = writeln!(
            md,
            "\n### Stereo against mono (same head and scene, each timed interleaved with mono)\n\n| space | size | budget | mono ms | side by side ms | × mono | anaglyph ms | × mono |\n|---|---|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.stereo {
            let _ = writeln!(
                md,
                "| {} | {}×{} | {} | {:.2} | {:.2} | {:.2}× | {:.2} | {:.2}× |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.mono_ms,
                r.side_by_side_ms,
                r.side_by_side_ratio,
                r.anaglyph_ms,
                r.anaglyph_ratio
            );
        }
    }
    if !report.meshes.is_empty() {
        let _ = writeln!(
            md,
            "\n### A mesh at the cell's centre: frame time against triangle count (each timed interleaved with the same scene without the mesh)\n\n| space | size | budget | triangles | nodes | depth | build ms | with mesh ms | without ms | × without |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
        );
        for r in &report.meshes {
            let _ = writeln!(
                md,
                "| {} | {}×{} | {} | {} | {} | {} | {:.1} | {:.2} | {:.2} | {:.2}× |",
                r.space,
                r.width,
                r.height,
                r.budget,
                r.triangles,
                r.nodes,
                r.depth,
                r.build_ms,
                r.with_mesh_ms,
                r.without_mesh_ms,
                r.ratio
            );
        }
    }
    let _ = writeln!(
        md,
        "\n### f32 against f64 along long rays (median over rays that keep the f64 faces)\n\n| space | crossings | same faces % | median distance | median position error | max position error | median direction error (rad) | bound 4ε·n·G(d) at the median distance | worst error / own bound |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for d in &report.drift {
        let e = |x: Option<f64>| x.map_or_else(|| "–".to_string(), |x| format!("{x:.1e}"));
        let _ = writeln!(
            md,
            "| {} | {} | {:.0} | {:.1} | {} | {} | {} | {} | {} |",
            d.space,
            d.crossings,
            100.0 * d.same_faces,
            d.median_distance,
            e(d.median_position_error),
            e(d.max_position_error),
            e(d.median_direction_error),
            e(d.bound),
            d.worst_bound_ratio
                .map_or_else(|| "–".to_string(), |r| format!("{r:.2}"))
        );
    }
    let _ = writeln!(
        md,
        "\n### The fog cut-off against its bound (f64, no cut-off as reference)\n\n| space | fog (inradii) | λ | cut-off distance | bound | max error | mean error | within |\n|---|---:|---:|---:|---:|---:|---:|---|"
    );
    for c in &report.cutoff {
        let _ = writeln!(
            md,
            "| {} | {} | {:.3} | {:.2} | {:.2e} | {:.2e} | {:.1e} | {} |",
            c.space,
            c.fog_factor,
            c.fog_distance,
            c.cutoff_distance,
            c.bound,
            c.max_error,
            c.mean_error,
            if c.within_bound { "yes" } else { "**no**" }
        );
    }
    let _ = writeln!(
        md,
        "\n### Automatic budgets (crossings) by quality and fog\n\n| space | fog (inradii) | low | medium | high | most needed |\n|---|---:|---:|---:|---:|---:|"
    );
    let mut keys: Vec<(&String, f64)> = report
        .auto_budgets
        .iter()
        .map(|b| (&b.space, b.fog_factor))
        .collect();
    keys.dedup();
    for (space, fog) in keys {
        let of = |q: &str| {
            report
                .auto_budgets
                .iter()
                .find(|b| &b.space == space && b.fog_factor == fog && b.quality == q)
                .map_or_else(|| "–".to_string(), |b| b.choice.budget.to_string())
        };
        let most = report
            .auto_budgets
            .iter()
            .find(|b| &b.space == space && b.fog_factor == fog)
            .map_or(0, |b| b.choice.most_needed);
        let _ = writeln!(
            md,
            "| {space} | {fog} | {} | {} | {} | {most} |",
            of("low"),
            of("medium"),
            of("high")
        );
    }
    md
}

fn to_values<T: Serialize>(rows: &[T]) -> Vec<serde_json::Value> {
    rows.iter()
        .map(|r| serde_json::to_value(r).expect("rows are plain data"))
        .collect()
}

/// Rows of JSON objects as CSV (columns in the first row's order).
fn to_csv(rows: &[serde_json::Value]) -> String {
    let Some(serde_json::Value::Object(first)) = rows.first() else {
        return String::new();
    };
    let columns: Vec<&String> = first.keys().collect();
    let mut out = columns
        .iter()
        .map(|c| c.as_str())
        .collect::<Vec<_>>()
        .join(",");
    out.push('\n');
    for row in rows {
        let cells: Vec<String> = columns
            .iter()
            .map(|c| match row.get(c.as_str()) {
                Some(serde_json::Value::String(s)) => s.clone(),
                Some(serde_json::Value::Null) | None => String::new(),
                Some(v) => v.to_string(),
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// One number read off an accuracy row (a chart's y axis).
type ErrorMeasure = fn(&ErrorRow) -> f64;

/// The charts of a report: speed against error, error against crossings.
#[must_use]
pub fn charts(report: &BenchReport) -> Vec<(&'static str, Chart)> {
    let mut charts = Vec::new();
    let spaces: Vec<&String> = {
        let mut s: Vec<&String> = report.errors.iter().map(|e| &e.space).collect();
        s.dedup();
        s
    };
    // Speed against error at the largest timed resolution, fixed budgets at the default fog.
    if let Some(size) = report.timings.iter().map(|t| (t.width, t.height)).max() {
        let measures: [(&str, &str, ErrorMeasure); 2] = [
            (
                "speed_vs_colour_error",
                "mean colour error against f64 (8-bit levels)",
                |e| e.mean_levels.max(1e-3),
            ),
            (
                "speed_vs_hit_error",
                "pixels whose hit differs from f64 (%)",
                |e| 100.0 * e.hit_differs.max(1e-5),
            ),
        ];
        for (stem, y_label, measure) in measures {
            let series = spaces
                .iter()
                .map(|space| {
                    let points = report
                        .errors
                        .iter()
                        .filter(|e| &&e.space == space && e.budget_from == "fixed")
                        .filter_map(|e| {
                            let t = report.timings.iter().find(|t| {
                                &t.space == *space
                                    && t.budget == e.budget
                                    && t.budget_from == "fixed"
                                    && (t.width, t.height) == size
                            })?;
                            Some((t.median_ms, measure(e)))
                        })
                        .collect();
                    Series {
                        name: space.to_string(),
                        points,
                        dashed: false,
                    }
                })
                .collect();
            charts.push((
                stem,
                Chart {
                    title: format!(
                        "Speed against error, {}×{}, budgets {}",
                        size.0,
                        size.1,
                        budget_list(report)
                    ),
                    x_label: "GPU frame time (ms)".into(),
                    y_label: y_label.into(),
                    log_x: true,
                    log_y: true,
                    series,
                    legend: Corner::LowerLeft,
                },
            ));
        }
    }
    // f32 drift against crossings, with the conditioning bound.
    let series = series_per_space(
        &report.drift,
        |d| &d.space,
        |d| Some((d.crossings as f64, d.median_position_error?.max(1e-12))),
    );
    charts.push((
        "drift",
        Chart {
            title: "f32 against f64: median position error of long rays".into(),
            x_label: "face crossings".into(),
            y_label: "geodesic distance f32 to f64".into(),
            log_x: true,
            log_y: true,
            series,
            legend: Corner::LowerRight,
        },
    ));
    // Mesh scenes: frame time against triangle count.
    if !report.meshes.is_empty() {
        let series = series_per_space(
            &report.meshes,
            |m| &m.space,
            |m| Some((m.triangles as f64, m.ratio)),
        );
        let size = report
            .meshes
            .first()
            .map(|m| format!("{}×{}", m.width, m.height))
            .unwrap_or_default();
        charts.push((
            "mesh_triangles",
            Chart {
                title: format!(
                    "A mesh at the cell's centre: GPU frame time against the same view without it ({size})"
                ),
                x_label: "triangles".into(),
                y_label: "frame time with / without the mesh".into(),
                log_x: true,
                log_y: true,
                series,
                legend: Corner::UpperLeft,
            },
        ));
    }
    charts
}

/// One series per space (in the rows' order of spaces) of the points `point` gives.
fn series_per_space<T>(
    rows: &[T],
    space: impl Fn(&T) -> &String,
    point: impl Fn(&T) -> Option<(f64, f64)>,
) -> Vec<Series> {
    let mut spaces: Vec<&String> = rows.iter().map(&space).collect();
    spaces.dedup();
    spaces
        .into_iter()
        .map(|name| Series {
            name: name.to_string(),
            points: rows
                .iter()
                .filter(|r| space(r) == name)
                .filter_map(&point)
                .collect(),
            dashed: false,
        })
        .collect()
}

fn budget_list(report: &BenchReport) -> String {
    let mut b: Vec<u32> = report
        .errors
        .iter()
        .filter(|e| e.budget_from == "fixed")
        .map(|e| e.budget)
        .collect();
    b.sort_unstable();
    b.dedup();
    b.iter().map(u32::to_string).collect::<Vec<_>>().join(", ")
}
