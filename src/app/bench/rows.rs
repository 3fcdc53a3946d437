//! What a benchmark run measured: one row type per part of the report, and the report.

use super::*;

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
    /// The product spaces (absent from reports written before they existed).
    #[serde(default)]
    pub products: Vec<super::ProductRow>,
    /// The Nil spaces (absent from older reports).
    #[serde(default)]
    pub nil: Vec<super::FamilyRow>,
    /// The SL̃(2,R) spaces (absent from older reports).
    #[serde(default)]
    pub sl2r: Vec<super::FamilyRow>,
    /// The lightings' frame time against error (absent from reports written before them).
    #[serde(default)]
    pub lighting: Vec<super::LightingRow>,
}

/// The tracer against a straightforward tracer of the same walk (the shader variant
/// [`GpuScene::straightforward`]: arc length and trigonometric functions, a division a
/// face, plain f32 pairings, every lamp image summed) on the plainest view: the camera at the cell's centre looking
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
    /// The 90th percentile of the cells a ray passes.
    #[serde(default)]
    pub segments_p90: f64,
    /// Nanoseconds of the culled frame per pixel-segment (`with_edges_ms` over the pixels
    /// times `segments_per_pixel`): the cost of one crossing with all that goes with it.
    #[serde(default)]
    pub ns_per_segment: f64,
    /// Of the 8 × 8 pixel tiles, the shares by the crossing at which their four corner rays
    /// first leave a cell copy by different faces.
    #[serde(default, flatten)]
    pub tiles: TileShares,
    /// The share of 8 × 8 tiles in which some pixel comes near two faces at one point
    /// before the corners part.
    #[serde(default)]
    pub tiles_near_edge_before_parting: f64,
}

/// Of the 8 × 8 pixel tiles of a view, the share whose four corner rays first leave a cell
/// copy by different faces at crossing 0, 1, 2, 3, at 4 or later, or never: a tile tracer
/// walks a tile once while its corners agree (the cell is convex, so every ray between them
/// leaves by the same face) and splits it where they part.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct TileShares {
    /// Corners parting at the first exit.
    #[serde(default)]
    pub tiles_parting_at_0: f64,
    /// At the second.
    #[serde(default)]
    pub tiles_parting_at_1: f64,
    /// At the third.
    #[serde(default)]
    pub tiles_parting_at_2: f64,
    /// At the fourth.
    #[serde(default)]
    pub tiles_parting_at_3: f64,
    /// At the fifth or later.
    #[serde(default)]
    pub tiles_parting_later: f64,
    /// Never: the corners leave by the same faces as far as they all go.
    #[serde(default)]
    pub tiles_never_parting: f64,
}

impl TileShares {
    /// The shares in order (at 0, 1, 2, 3, later, never).
    #[must_use]
    pub fn shares(&self) -> [f64; 6] {
        [
            self.tiles_parting_at_0,
            self.tiles_parting_at_1,
            self.tiles_parting_at_2,
            self.tiles_parting_at_3,
            self.tiles_parting_later,
            self.tiles_never_parting,
        ]
    }

    /// From the shares in that order.
    #[must_use]
    pub fn from_shares(s: [f64; 6]) -> Self {
        Self {
            tiles_parting_at_0: s[0],
            tiles_parting_at_1: s[1],
            tiles_parting_at_2: s[2],
            tiles_parting_at_3: s[3],
            tiles_parting_later: s[4],
            tiles_never_parting: s[5],
        }
    }
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

impl BenchReport {
    /// A report with nothing measured yet: the device (if any), the build and the threads.
    pub(super) fn empty(harness: Option<&Harness>) -> Self {
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
