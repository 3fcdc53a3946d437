//! The Nil spaces in the benchmark: for each `nil-K`, its default view at the middle timed
//! size, timed in the same rounds as Seifert–Weber's default view at the same size (the
//! ratio measured in one run), the crossings a pixel makes, the GPU picture against the
//! f64 CPU reference, and the f64 and f32 walks against the exact geodesic over
//! `ε (1 + t²)` ([`NilRow`]).

use super::*;
use crate::plugin::nil::default_nil_budget;
use crate::plugin::render::gpu::GpuScene;
use crate::space::nil::NilSpace;
use crate::space::nil::accuracy::walk_error;
use crate::trace::nil::{NilRayEnd, default_camera, default_scene, first_nil_hit, render_nil_view};
use crate::view::ViewLayout;
use glam::DVec4;

/// Walks per space against the exact geodesic, and their length.
pub(super) const WALK_DISTANCE: f64 = 8.0;

/// A pixel differs where a channel is off by more than this (of 255).
const DIFFERING_LEVEL: u8 = 10;

/// A Nil space in the speed-against-error report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct NilRow {
    /// `nil-K`.
    pub space: String,
    /// Timed picture width.
    pub width: u32,
    /// Timed picture height.
    pub height: u32,
    /// The crossing budget (the plugin's default for the space).
    pub budget: u32,
    /// Objects in the default scene (with their images in the box).
    pub objects: usize,
    /// Median frame time of the default view, ms.
    pub tracer_ms: f64,
    /// The constant-curvature space timed in the same rounds.
    pub reference_space: String,
    /// Median frame time of its default view, ms.
    pub reference_ms: f64,
    /// The median over rounds of the Nil view's time over the reference's.
    pub ratio: f64,
    /// Mean face crossings a pixel's ray makes (CPU, at the error size).
    pub crossings_per_pixel: f64,
    /// Mean iterations of the root finder a pixel takes in the f64 CPU tracer (exits, the
    /// distance's winding, refinements; shadow rays included), at the error size.
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
    /// Median over walks of the end's error / (ε (1 + t²)), f64 walk.
    pub f64_median: f64,
    /// Largest, f64 walk.
    pub f64_worst: f64,
    /// Median, f32 walk.
    pub f32_median: f64,
    /// Largest, f32 walk.
    pub f32_worst: f64,
}

/// `nil-K` by its K.
fn nil(k: u32) -> Result<NilSpace, BenchError> {
    match crate::space::nil::nil_space(&format!("nil-{k}")) {
        Some(Ok(space)) => Ok(space),
        Some(Err(e)) => Err(BenchError::Nil(e.to_string())),
        None => Err(BenchError::Nil(format!("nil-{k} is no Nil space"))),
    }
}

/// Checks the K's before the run: each names a Nil space.
pub fn check_nil(ks: &[u32]) -> Result<(), BenchError> {
    ks.iter().try_for_each(|&k| nil(k).map(|_| ()))
}

/// The median and the largest error of `rays` walks in the precision `V`, over
/// `ε (1 + t²)`.
fn walk_ratios<V: crate::geometry::Vector4>(
    space: &NilSpace,
    rays: usize,
    epsilon: f64,
) -> (f64, f64) {
    let k = space.k();
    let mut random = crate::random::SplitMix64(0x0417_u64.wrapping_add(u64::from(k)));
    let h = space.half_height();
    let mut ratios: Vec<f64> = (0..rays.max(1))
        .map(|_| {
            let d = random.direction();
            let p = DVec4::new(
                random.unit() - 0.5,
                random.unit() - 0.5,
                (2.0 * random.unit() - 1.0) * h,
                1.0,
            );
            let start = crate::geometry::Ray {
                point: p,
                tangent: d.extend(0.0),
            };
            walk_error::<V>(k, start, WALK_DISTANCE)
                / (epsilon * (1.0 + WALK_DISTANCE * WALK_DISTANCE))
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    (ratios[ratios.len() / 2], ratios[ratios.len() - 1])
}

/// Mean crossings a pixel's ray makes before its object or the fog (or the budget).
fn crossings_per_pixel(
    space: &NilSpace,
    scene: &crate::trace::nil::NilScene,
    layout: &ViewLayout,
    budget: usize,
) -> f64 {
    use crate::space::walk::CellWalk;
    let walker = crate::space::nil::NilWalker::<DVec4>::new(space.k());
    let (w, h) = (layout.size[0] as u32, layout.size[1] as u32);
    let mut total = 0usize;
    for j in 0..h {
        for i in 0..w {
            let (_, [u, v]) = layout.eye_at(f64::from(i) + 0.5, f64::from(j) + 0.5);
            let ray = layout.frame_ray(0, u, v);
            let t = ray.tangent.truncate().normalize();
            let start = crate::space::nil::NilRay {
                point: ray.point.truncate().to_array(),
                velocity: t.to_array(),
            };
            total += match first_nil_hit(&walker, scene, start, scene.cutoff_distance(), budget) {
                NilRayEnd::Hit { crossings, .. } => crossings,
                NilRayEnd::Budget(c) => c,
                NilRayEnd::Fog => walker
                    .trace(
                        crate::geometry::Ray {
                            point: ray.point,
                            tangent: t.extend(0.0),
                        },
                        crate::space::Limit::Distance(scene.cutoff_distance()),
                    )
                    .crossings
                    .len()
                    .min(budget),
            };
        }
    }
    total as f64 / f64::from(w * h)
}

/// The rows of `config.nil`.
pub(super) fn nil_rows(
    harness: &mut Harness,
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<Vec<NilRow>, BenchError> {
    let (w, h) = config.middle_size();
    let reference = Subject::new(products::PRODUCT_REFERENCE_SPACE)?;
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
    for &k in &config.nil {
        let id = format!("nil-{k}");
        announce(
            progress,
            format!("{id}: against {}", products::PRODUCT_REFERENCE_SPACE),
        );
        let space = nil(k)?;
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let budget = default_nil_budget(&space);
        let gpu = GpuScene::nil(&space, &scene, budget).map_err(|error| BenchError::Scene {
            space: id.clone(),
            error,
        })?;
        let layout = |(w, h)| {
            ViewLayout::new(
                Default::default(),
                false,
                [camera.frame; 2],
                camera.fov_y_degrees,
                w,
                h,
            )
        };
        let (ratio, tracer_ms, reference_ms) = timing::against_reference(
            harness,
            config,
            (w, h),
            (&gpu, &layout((w, h))),
            (&reference_gpu, &reference_layout),
        )?;
        let (ew, eh) = config.error_size;
        // The CPU reference on one thread, so that its root finding is counted there.
        let one_thread = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .map_err(|e| BenchError::Nil(format!("a thread for the CPU reference: {e}")))?;
        let (cpu, (iterations, steps)) = one_thread.install(|| {
            let before = crate::space::nil::work();
            let cpu = render_nil_view(&space, &scene, &layout((ew, eh)), budget as usize);
            let after = crate::space::nil::work();
            (cpu, (after.0 - before.0, after.1 - before.1))
        });
        let pixels = f64::from(ew * eh);
        let root_iterations_per_pixel = iterations as f64 / pixels;
        let safe_steps_per_pixel = steps as f64 / pixels;
        let (differing_pixels, mean_error) =
            timing::gpu_against_cpu(harness, &gpu, &layout((ew, eh)), &cpu, DIFFERING_LEVEL)?;
        let (f64_median, f64_worst) =
            walk_ratios::<DVec4>(&space, config.conditioning_rays, f64::EPSILON);
        let (f32_median, f32_worst) =
            walk_ratios::<glam::Vec4>(&space, config.conditioning_rays, F32_EPSILON);
        rows.push(NilRow {
            space: id,
            width: w,
            height: h,
            budget,
            objects: scene.objects.len(),
            tracer_ms,
            reference_space: products::PRODUCT_REFERENCE_SPACE.into(),
            reference_ms,
            ratio,
            crossings_per_pixel: crossings_per_pixel(
                &space,
                &scene,
                &layout((ew, eh)),
                budget as usize,
            ),
            root_iterations_per_pixel,
            safe_steps_per_pixel,
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
