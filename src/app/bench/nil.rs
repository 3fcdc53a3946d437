//! The Nil spaces in the benchmark ([`super::families`]): the default view of each `nil-K`,
//! and its walks against the exact geodesic over `ε (1 + t²)`.

use super::families::{BenchedFamily, FamilyRow, Reference, family_row, median_and_worst};
use super::*;
use crate::plugin::nil::default_nil_budget;
use crate::space::nil::accuracy::walk_error;
use crate::space::nil::{NilRay, NilSpace, NilWalker};
use crate::trace::nil::{NilRayEnd, NilScene, default_camera, default_scene, first_nil_hit};
use crate::view::ViewLayout;
use glam::{DMat4, DVec4};

/// Walks per space against the exact geodesic, and their length.
pub(super) const WALK_DISTANCE: f64 = 8.0;

/// `nil-K` by its K.
fn nil(k: u32) -> Result<NilSpace, BenchError> {
    match crate::space::nil::nil_space(&format!("nil-{k}")) {
        Some(Ok(space)) => Ok(space),
        Some(Err(e)) => Err(BenchError::Family(e.to_string())),
        None => Err(BenchError::Family(format!("nil-{k} is no Nil space"))),
    }
}

/// Checks the K's before the run: each names a Nil space.
pub fn check_nil(ks: &[u32]) -> Result<(), BenchError> {
    ks.iter().try_for_each(|&k| nil(k).map(|_| ()))
}

/// A Nil space with its default scene.
struct NilBench {
    space: NilSpace,
    scene: NilScene,
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
    median_and_worst(
        (0..rays.max(1))
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
            .collect(),
    )
}

impl BenchedFamily for NilBench {
    fn id(&self) -> String {
        format!("nil-{}", self.space.k())
    }

    fn budget(&self) -> u32 {
        default_nil_budget(&self.space)
    }

    fn objects(&self) -> usize {
        self.scene.objects.len()
    }

    fn camera(&self) -> (DMat4, f64) {
        let camera = default_camera(&self.space);
        (camera.frame, camera.fov_y_degrees)
    }

    fn gpu(&self) -> Result<GpuScene, BenchError> {
        GpuScene::nil(&self.space, &self.scene, self.budget()).map_err(|error| BenchError::Scene {
            space: self.id(),
            error,
        })
    }

    fn cpu_picture(&self, layout: &ViewLayout) -> image::RgbImage {
        crate::trace::nil::render_nil_view(&self.space, &self.scene, layout, self.budget() as usize)
    }

    fn crossings(&self, layout: &ViewLayout, i: u32, j: u32) -> usize {
        use crate::space::walk::CellWalk;
        let walker = NilWalker::<DVec4>::new(self.space.k());
        let budget = self.budget() as usize;
        let [u, v] = super::families::pixel_point(layout, i, j);
        let ray = layout.frame_ray(0, u, v);
        let t = ray.tangent.truncate().normalize();
        let start = NilRay {
            point: ray.point.truncate().to_array(),
            velocity: t.to_array(),
        };
        let cutoff = self.scene.cutoff_distance();
        match first_nil_hit(&walker, &self.scene, start, cutoff, budget) {
            NilRayEnd::Hit { crossings, .. } => crossings,
            NilRayEnd::Budget(c) => c,
            NilRayEnd::Fog => walker
                .trace(
                    crate::geometry::Ray {
                        point: ray.point,
                        tangent: t.extend(0.0),
                    },
                    crate::space::Limit::Distance(cutoff),
                )
                .crossings
                .len()
                .min(budget),
        }
    }

    fn walk_ratios(&self, rays: usize) -> [f64; 4] {
        let (a, b) = walk_ratios::<DVec4>(&self.space, rays, f64::EPSILON);
        let (c, d) = walk_ratios::<glam::Vec4>(&self.space, rays, F32_EPSILON);
        [a, b, c, d]
    }
}

/// The rows of `config.nil`.
pub(super) fn nil_rows(
    harness: &mut Harness,
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<Vec<FamilyRow>, BenchError> {
    let reference = Reference::new(config)?;
    config
        .nil
        .iter()
        .map(|&k| {
            let space = nil(k)?;
            let scene = default_scene(&space);
            family_row(
                harness,
                config,
                &reference,
                &NilBench { space, scene },
                progress,
            )
        })
        .collect()
}
