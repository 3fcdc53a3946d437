//! The product spaces (H²×R, S²×R) in the benchmark: for each, its default view at the
//! middle timed size with the automatic budget, timed in the same rounds as a
//! constant-curvature space's default view at the same size (so the ratio is measured in
//! one run), the crossings a pixel makes, the GPU picture against the f64 CPU reference,
//! and the f64 and f32 walks against the double-double walk relative to their
//! conditioning limits ([`ProductRow`]).

use super::*;
use crate::plugin::render::gpu::GpuScene;
use crate::space::AnySpace;
use crate::space::product::accuracy::product_walk_accuracy;
use crate::space::product::{ProductSpace, ProductWalker};
use crate::trace::product::{
    ProductRayEnd, default_camera, default_scene, first_product_hit, product_auto_budget,
    render_product,
};
use crate::view::ViewLayout;
use glam::DVec4;

/// The constant-curvature space whose default view each product's is timed against.
pub const PRODUCT_REFERENCE_SPACE: &str = "seifert-weber";

/// Crossings of each walk against the double-double reference.
const WALK_CROSSINGS: usize = 100;

/// A pixel differs where a channel is off by more than this (of 255).
const DIFFERING_LEVEL: u8 = 10;

/// A product space in the speed-against-error report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ProductRow {
    /// Library id.
    pub space: String,
    /// `H2xR` or `S2xR`.
    pub geometry: String,
    /// Timed picture width.
    pub width: u32,
    /// Timed picture height.
    pub height: u32,
    /// The automatic crossing budget (quality High).
    pub budget: u32,
    /// Median frame time of the product's default view, ms.
    pub tracer_ms: f64,
    /// The constant-curvature space timed in the same rounds.
    pub reference_space: String,
    /// Its automatic budget.
    pub reference_budget: u32,
    /// Median frame time of its default view, ms.
    pub reference_ms: f64,
    /// The median over rounds of the product's time over the reference's.
    pub ratio: f64,
    /// Mean face crossings a pixel's ray makes (CPU, at the error size).
    pub crossings_per_pixel: f64,
    /// Share of pixels off by more than 10/255 in a channel, GPU against the f64 CPU
    /// reference at the error size.
    pub differing_pixels: f64,
    /// Mean of the largest channel difference, of 255.
    pub mean_error: f64,
    /// Median over the walks' crossings of error / conditioning limit, f64 walk.
    pub f64_median: f64,
    /// Largest, f64 walk.
    pub f64_worst: f64,
    /// Median, f32 walk.
    pub f32_median: f64,
    /// Largest, f32 walk.
    pub f32_worst: f64,
}

/// A product space by id, through the crate's one registry ([`AnySpace::resolve`]).
fn product(id: &str) -> Result<ProductSpace, BenchError> {
    let space = AnySpace::named(id)
        .map_err(|e| BenchError::Product(format!("{id} is not a product space: {e}")))?;
    match space {
        AnySpace::Product(p) => Ok(std::sync::Arc::unwrap_or_clone(p)),
        AnySpace::Nil(n) => Err(BenchError::Product(format!(
            "{id} is a Nil space, not a product space: {}",
            n.description()
        ))),
        AnySpace::Sl2r(s) => Err(BenchError::Product(format!(
            "{id} is an SL̃(2,R) space, not a product space: {}",
            s.description()
        ))),
        AnySpace::Constant(s) => Err(BenchError::Product(format!(
            "{id} is {}, not a product space: --spaces benches the constant-curvature spaces",
            if s.geometry() == crate::geometry::Geometry::Euclidean {
                "a flat space (E³: a flat word's product is one)".to_string()
            } else {
                format!("a space of constant curvature ({})", s.geometry().name())
            }
        ))),
    }
}

/// Checks that every id names a product space.
pub fn check_products(ids: &[String]) -> Result<(), BenchError> {
    ids.iter().try_for_each(|id| product(id).map(|_| ()))
}

/// Median and largest of error / conditioning over the walks' crossings (split and
/// saturated crossings left out).
fn walk_ratios<V: crate::geometry::Vector4>(space: &ProductSpace, rays: usize) -> (f64, f64) {
    let mut random = crate::random::SplitMix64(0x0b1d_face);
    let mut ratios: Vec<f64> = Vec::new();
    for _ in 0..rays.max(1) {
        let d = random.direction();
        let start = crate::space::product::ray_from_centre(d);
        for c in product_walk_accuracy::<V>(space, start, WALK_CROSSINGS) {
            if let Some(r) = c.ratio()
                && c.conditioning < crate::space::accuracy::SATURATED
            {
                ratios.push(r);
            }
        }
    }
    if ratios.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    ratios.sort_by(f64::total_cmp);
    (ratios[ratios.len() / 2], ratios[ratios.len() - 1])
}

/// Mean crossings a pixel's ray makes before its object or the fog, at `(w, h)`.
fn crossings_per_pixel(
    space: &ProductSpace,
    scene: &crate::trace::product::ProductScene,
    camera: &crate::trace::product::ProductCamera,
    (w, h): (u32, u32),
    budget: usize,
) -> f64 {
    use rayon::prelude::*;
    let walker = ProductWalker::<DVec4>::new(space);
    let total: usize = (0..h)
        .into_par_iter()
        .map(|j| {
            (0..w)
                .map(
                    |i| match first_product_hit(&walker, scene, camera.ray(i, j, w, h), budget) {
                        ProductRayEnd::Hit { crossings, .. } => crossings,
                        ProductRayEnd::Budget(c) => c,
                        // A fog ray crossed faces too, but the walk does not count them: walk it.
                        ProductRayEnd::Fog => walker
                            .trace(
                                camera.ray(i, j, w, h),
                                crate::space::Limit::Distance(scene.cutoff_distance()),
                            )
                            .crossings
                            .len()
                            .min(budget),
                    },
                )
                .sum::<usize>()
        })
        .sum();
    total as f64 / f64::from(w * h)
}

/// The rows of `config.products`.
pub(super) fn product_rows(
    harness: &mut Harness,
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<Vec<ProductRow>, BenchError> {
    let (w, h) = config.middle_size();
    let reference = Subject::new(PRODUCT_REFERENCE_SPACE)?;
    let reference_scene = reference.scene(DEFAULT_FOG_FACTOR);
    let reference_budget = auto_budget(
        &reference.space,
        &reference_scene,
        Quality::High.miss_fraction(),
        config.budget_samples,
    )
    .budget;
    let reference_gpu = reference.pack(&reference_scene, reference_budget)?;
    let reference_layout = reference.camera.layout(w, h);
    let mut rows = Vec::new();
    for id in &config.products {
        announce(
            progress,
            format!("{id}: the product against {PRODUCT_REFERENCE_SPACE}"),
        );
        let space = product(id)?;
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let budget = product_auto_budget(
            &space,
            &scene,
            camera.point,
            Quality::High.miss_fraction(),
            config.budget_samples,
        )
        .budget;
        let gpu = GpuScene::product(&space, &scene, budget).map_err(|error| BenchError::Scene {
            space: id.clone(),
            error,
        })?;
        let frame = crate::space::product::motion::camera_frame(camera.point, camera.frame);
        let layout = |(w, h)| ViewLayout::camera(frame, camera.fov_y_degrees, w, h);
        let (ratio, tracer_ms, reference_ms) = timing::against_reference(
            harness,
            config,
            (w, h),
            (&gpu, &layout((w, h))),
            (&reference_gpu, &reference_layout),
        )?;
        // The GPU picture against the CPU reference at the error size.
        let (ew, eh) = config.error_size;
        let cpu = render_product(&space, &scene, &camera, ew, eh, budget as usize);
        let (differing_pixels, mean_error) =
            timing::gpu_against_cpu(harness, &gpu, &layout((ew, eh)), &cpu, DIFFERING_LEVEL)?;
        let (f64_median, f64_worst) = walk_ratios::<DVec4>(&space, config.conditioning_rays);
        let (f32_median, f32_worst) = walk_ratios::<glam::Vec4>(&space, config.conditioning_rays);
        rows.push(ProductRow {
            space: id.clone(),
            geometry: space.geometry_name().to_string(),
            width: w,
            height: h,
            budget,
            tracer_ms,
            reference_space: PRODUCT_REFERENCE_SPACE.into(),
            reference_budget,
            reference_ms,
            ratio,
            crossings_per_pixel: crossings_per_pixel(
                &space,
                &scene,
                &camera,
                (ew, eh),
                budget as usize,
            ),
            differing_pixels,
            mean_error,
            f64_median,
            f64_worst,
            f32_median,
            f32_worst,
        });
        progress.inc(1);
    }
    Ok(rows)
}
