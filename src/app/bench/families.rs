//! The families whose pictures have their own tracer (Nil, SL̃(2,R)) in the benchmark, one
//! row shape for all: each space's default view at the middle timed size, timed in the
//! same rounds as Seifert–Weber's default view at the same size (the ratio measured in one
//! run), the crossings and the root finder's work a pixel takes, the GPU picture against
//! the f64 CPU reference, and the f64 and f32 walks against the exact (double-double) walk
//! over the family's bound ([`FamilyRow`]). A family gives its part through
//! [`BenchedFamily`]; the timing, the comparison and the counting are written once here.

use super::*;
use crate::view::ViewLayout;
use glam::DMat4;

/// A pixel differs where a channel is off by more than this (of 255).
const DIFFERING_LEVEL: u8 = 10;

/// A space of a family with its own tracer in the speed-against-error report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FamilyRow {
    /// The space's id.
    pub space: String,
    /// Timed picture width.
    pub width: u32,
    /// Timed picture height.
    pub height: u32,
    /// The crossing budget (the plugin's default for the space).
    pub budget: u32,
    /// Objects in the default scene (with their images where the family keeps them).
    pub objects: usize,
    /// Median frame time of the default view, ms.
    pub tracer_ms: f64,
    /// The constant-curvature space timed in the same rounds.
    pub reference_space: String,
    /// Median frame time of its default view, ms.
    pub reference_ms: f64,
    /// The median over rounds of the view's time over the reference's.
    pub ratio: f64,
    /// Mean face crossings a pixel's ray makes (CPU, at the error size).
    pub crossings_per_pixel: f64,
    /// Mean iterations of the root finders a pixel takes in the f64 CPU tracer (exits,
    /// distances, refinements; shadow rays included), at the error size.
    #[serde(default)]
    pub root_iterations_per_pixel: f64,
    /// Mean safe steps towards objects a pixel takes, likewise.
    #[serde(default)]
    pub safe_steps_per_pixel: f64,
    /// Share of pixels off by more than 10/255 in a channel, GPU against the f64 CPU
    /// reference at the error size.
    pub differing_pixels: f64,
    /// Mean of the largest channel difference, of 255.
    pub mean_error: f64,
    /// Median over walks of the end's error over the family's bound, f64 walk.
    pub f64_median: f64,
    /// Largest, f64 walk.
    pub f64_worst: f64,
    /// Median, f32 walk.
    pub f32_median: f64,
    /// Largest, f32 walk.
    pub f32_worst: f64,
}

/// The Nil rows' name before SL̃(2,R) shared them.
pub type NilRow = FamilyRow;

/// What a family gives its benchmark row: its space's default picture on the GPU and the
/// CPU, the crossings its rays make, and its walks' error over the family's bound.
pub(super) trait BenchedFamily: Sync {
    /// The space's id.
    fn id(&self) -> String;
    /// The plugin's default crossing budget for the space.
    fn budget(&self) -> u32;
    /// Objects in the default scene.
    fn objects(&self) -> usize;
    /// The default camera: its frame and vertical field of view.
    fn camera(&self) -> (DMat4, f64);
    /// The default scene packed for the GPU.
    fn gpu(&self) -> Result<GpuScene, BenchError>;
    /// The f64 CPU reference picture of `layout`.
    fn cpu_picture(&self, layout: &ViewLayout) -> image::RgbImage;
    /// Face crossings of the ray of the pixel `(i, j)` of `layout` before its object, the
    /// fog or the budget.
    fn crossings(&self, layout: &ViewLayout, i: u32, j: u32) -> usize;
    /// The median and largest error of walks in `f64` and in `f32` over the family's bound:
    /// `[f64 median, f64 worst, f32 median, f32 worst]`.
    fn walk_ratios(&self, rays: usize) -> [f64; 4];
}

/// Seifert–Weber's default view, packed once and timed beside each family's.
pub(super) struct Reference {
    gpu: GpuScene,
    layout: ViewLayout,
}

impl Reference {
    /// [`products::PRODUCT_REFERENCE_SPACE`] at its automatic budget, at the middle size.
    pub(super) fn new(config: &BenchConfig) -> Result<Self, BenchError> {
        let (w, h) = config.middle_size();
        let reference = Subject::new(products::PRODUCT_REFERENCE_SPACE)?;
        let scene = reference.scene(DEFAULT_FOG_FACTOR);
        let budget = auto_budget(
            &reference.space,
            &scene,
            Quality::High.miss_fraction(),
            config.budget_samples,
        )
        .budget;
        Ok(Self {
            gpu: reference.pack(&scene, budget)?,
            layout: reference.camera.layout(w, h),
        })
    }
}

/// The median and the largest of `ratios`.
pub(super) fn median_and_worst(mut ratios: Vec<f64>) -> (f64, f64) {
    if ratios.is_empty() {
        return (0.0, 0.0);
    }
    ratios.sort_by(f64::total_cmp);
    (ratios[ratios.len() / 2], ratios[ratios.len() - 1])
}

/// The row of one space: its default view timed against `reference`, the f64 CPU reference
/// drawn on one thread (so that the root finders' counters see all its work), the GPU
/// against it, the crossings a pixel makes and the walks' error.
pub(super) fn family_row(
    harness: &mut Harness,
    config: &BenchConfig,
    reference: &Reference,
    family: &impl BenchedFamily,
    progress: &ProgressBar,
) -> Result<FamilyRow, BenchError> {
    let id = family.id();
    announce(
        progress,
        format!("{id}: against {}", products::PRODUCT_REFERENCE_SPACE),
    );
    let (w, h) = config.middle_size();
    let gpu = family.gpu()?;
    let (frame, fov) = family.camera();
    let layout = |(w, h)| ViewLayout::camera(frame, fov, w, h);
    let (ratio, tracer_ms, reference_ms) = timing::against_reference(
        harness,
        config,
        (w, h),
        (&gpu, &layout((w, h))),
        (&reference.gpu, &reference.layout),
    )?;
    let (ew, eh) = config.error_size;
    let error_layout = layout((ew, eh));
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| BenchError::Family(format!("a thread for the CPU reference: {e}")))?;
    let (cpu, (iterations, steps)) = one_thread.install(|| {
        let before = crate::space::roots::work();
        let cpu = family.cpu_picture(&error_layout);
        let after = crate::space::roots::work();
        (cpu, (after.0 - before.0, after.1 - before.1))
    });
    let pixels = f64::from(ew * eh);
    let (differing_pixels, mean_error) =
        timing::gpu_against_cpu(harness, &gpu, &error_layout, &cpu, DIFFERING_LEVEL)?;
    let crossings: usize = (0..eh)
        .flat_map(|j| (0..ew).map(move |i| (i, j)))
        .map(|(i, j)| family.crossings(&error_layout, i, j))
        .sum();
    let [f64_median, f64_worst, f32_median, f32_worst] =
        family.walk_ratios(config.conditioning_rays);
    progress.inc(1);
    Ok(FamilyRow {
        space: id,
        width: w,
        height: h,
        budget: family.budget(),
        objects: family.objects(),
        tracer_ms,
        reference_space: products::PRODUCT_REFERENCE_SPACE.into(),
        reference_ms,
        ratio,
        crossings_per_pixel: crossings as f64 / pixels,
        root_iterations_per_pixel: iterations as f64 / pixels,
        safe_steps_per_pixel: steps as f64 / pixels,
        differing_pixels,
        mean_error,
        f64_median,
        f64_worst,
        f32_median,
        f32_worst,
    })
}

/// The point of the pixel `(i, j)`'s centre in `layout`'s first eye, before the lens.
pub(super) fn pixel_point(layout: &ViewLayout, i: u32, j: u32) -> [f64; 2] {
    layout.eye_at(f64::from(i) + 0.5, f64::from(j) + 0.5).1
}
