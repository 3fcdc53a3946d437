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
mod families;
mod lighting;
mod nil;
mod plot;
mod products;
mod report;
mod rows;
mod runs;
mod sl2r;
mod timing;

use crate::plugin::components::Quality;
use crate::plugin::render::gpu::GpuScene;
use crate::scene::CurvedScene;
use crate::space::{Space, invariants, seed_space};
use crate::trace::{BudgetChoice, auto_budget};
use crate::view::TraceCamera;
pub use accuracy::growth;
use accuracy::*;
use indicatif::{ProgressBar, ProgressStyle};
pub use lighting::{
    LIGHTING_ERROR_SIZE, LightingRow, REFERENCE_LIGHTING, SOFT_LAMP, SOFT_REFERENCE, run_lighting,
};
pub use report::{
    charts, read_report, summary_markdown, write_edges_report, write_report, write_scene_report,
};
use serde::{Deserialize, Serialize};
pub use timing::bench_mesh;
use timing::*;

pub use harness::{BASELINE_WGSL, DeviceInfo, Frame, Harness, HarnessError, Output, Program};

pub use families::{FamilyRow, NilRow};
pub use nil::check_nil;
pub use plot::{Chart, Corner, PlotError, Series, write_chart};
pub use products::{PRODUCT_REFERENCE_SPACE, ProductRow, check_products};
pub use rows::{
    AutoBudgetRow, BenchReport, ConditioningPoint, ConditioningRow, CutoffRow, DriftRow, EdgesRow,
    ErrorRow, MeshRow, SpecialisationRow, StereoRow, StraightforwardRow, TileShares, TimingRow,
};
#[cfg(feature = "scene-files")]
pub use runs::run_scene;
pub use runs::{
    DEFAULT_FOG_FACTOR, run, run_edges, run_nil, run_products, run_sl2r, run_straightforward,
};
pub use sl2r::check_sl2r;

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
    /// Product spaces (H²×R, S²×R) by library id ([`ProductRow`]); absent from older
    /// configurations.
    #[serde(default)]
    pub products: Vec<String>,
    /// Nil spaces by their K ([`FamilyRow`]); absent from older configurations.
    #[serde(default)]
    pub nil: Vec<u32>,
    /// SL̃(2,R) spaces by id ([`FamilyRow`]); absent from older configurations.
    #[serde(default)]
    pub sl2r: Vec<String>,
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
            products: crate::space::product::PRODUCT_ALIASES
                .iter()
                .map(|a| a.id.to_string())
                .collect(),
            nil: vec![1, 3, 50],
            sl2r: vec![
                "unit-tangent-bitorus".into(),
                "unit-tangent-abABcdCDefEF".into(),
            ],
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
            products: vec!["projective-plane-circle".into()],
            nil: vec![1],
            sl2r: vec!["unit-tangent-bitorus".into()],
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
        error: crate::plugin::render::gpu::GpuSceneError,
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
    /// A member of the library's families could not be built (the reason is attached).
    #[error("{0}")]
    Library(String),
    /// A product space id is wrong (the reason is attached).
    #[error("{0}")]
    Product(String),
    /// A space of a family with its own tracer (Nil, SL̃(2,R)) is wrong, or its row could
    /// not be measured (the reason is attached).
    #[error("{0}")]
    Family(String),
    /// A lighting could not be set (the reason is attached).
    #[error("the lighting cannot be used: {0}")]
    Lighting(String),
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

/// The automatic budgets chosen for a space: (fog factor, quality, budget).
type ChosenBudgets = Vec<(f64, Quality, u32)>;

/// A seed space, or a member of the library's families (`weeks`, `census-3`, …), by id.
///
/// # Errors
/// When `id` names neither, or a family member with bad parameters.
pub fn bench_space(id: &str) -> Result<Space, BenchError> {
    match crate::space::library::library_space(id) {
        Some(built) => built.map_err(BenchError::Library),
        None => Ok(seed_space(id)?),
    }
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
        let space = bench_space(id)?;
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
