//! The SL̃(2,R) spaces in the benchmark ([`super::families`]): the default view of each
//! `unit-tangent-WORD`, and its f64 and f32 walks against the double-double walk over the
//! conditioning limit (how far the exact walk moves when its start moves by one rounding:
//! along a hypercycle both grow like `e^{ωt}`, so their ratio is the measure).

use super::families::{BenchedFamily, FamilyRow, Reference, family_row, median_and_worst};
use super::*;
use crate::plugin::sl2r::DEFAULT_SL2R_BUDGET;
use crate::space::sl2r::UnitTangentSpace;
use crate::space::sl2r::accuracy::{random_start, walk_error};
use crate::space::sl2r::walk::Sl2rWalker;
use crate::trace::sl2r::{Sl2rScene, camera_ray, default_camera, default_scene, first_hit};
use crate::view::ViewLayout;
use glam::{DMat4, DVec4};

/// The length of each walk against the double-double walk.
pub(super) const WALK_DISTANCE: f64 = 8.0;

/// The space of `id`, or the reason it is none.
fn sl2r(id: &str) -> Result<UnitTangentSpace, BenchError> {
    match crate::space::sl2r::sl2r_space(id) {
        Some(Ok(space)) => Ok(space),
        Some(Err(e)) => Err(BenchError::Family(format!("{id}: {e}"))),
        None => Err(BenchError::Family(format!(
            "{id} is no SL̃(2,R) space (their ids are unit-tangent-WORD, such as unit-tangent-bitorus)"
        ))),
    }
}

/// Checks the ids before the run: each names an SL̃(2,R) space.
pub fn check_sl2r(ids: &[String]) -> Result<(), BenchError> {
    ids.iter().try_for_each(|id| sl2r(id).map(|_| ()))
}

/// An SL̃(2,R) space with its default scene.
struct Sl2rBench {
    id: String,
    space: UnitTangentSpace,
    scene: Sl2rScene,
}

/// The median and largest of `rays` walks' error over their conditioning limit, in the
/// precision `V`.
fn walk_ratios<V: crate::geometry::Vector4>(space: &UnitTangentSpace, rays: usize) -> (f64, f64) {
    let mut rng = crate::random::SplitMix64(0x5121);
    use crate::geometry::Real as _;
    let eps = V::Real::EPSILON.to_f64();
    median_and_worst(
        (0..rays.max(1))
            .map(|_| {
                let start = random_start(space, &mut rng);
                let e = walk_error::<V>(space, &start, WALK_DISTANCE);
                e.error / e.limit.max(eps)
            })
            .collect(),
    )
}

impl BenchedFamily for Sl2rBench {
    fn id(&self) -> String {
        self.id.clone()
    }

    fn budget(&self) -> u32 {
        DEFAULT_SL2R_BUDGET
    }

    fn objects(&self) -> usize {
        self.scene.tubes.len() + self.scene.balls.len()
    }

    fn camera(&self) -> (DMat4, f64) {
        let camera = default_camera(&self.space);
        (camera.frame, camera.fov_y_degrees)
    }

    fn gpu(&self) -> Result<GpuScene, BenchError> {
        GpuScene::sl2r(&self.space, &self.scene, self.budget()).map_err(|error| BenchError::Scene {
            space: self.id(),
            error,
        })
    }

    fn cpu_picture(&self, layout: &ViewLayout) -> image::RgbImage {
        crate::trace::sl2r::render_sl2r_view(
            &self.space,
            &self.scene,
            layout,
            self.budget() as usize,
        )
    }

    fn crossings(&self, layout: &ViewLayout, i: u32, j: u32) -> usize {
        use crate::space::walk::CellWalk;
        let walker = Sl2rWalker::<DVec4>::new(&self.space);
        let budget = self.budget() as usize;
        let [u, v] = super::families::pixel_point(layout, i, j);
        let (x, y) = layout.lens.at(u, v);
        let ray = camera_ray(&layout.frames[0], x, y);
        match first_hit(&walker, &self.scene, ray, budget) {
            Some(hit) => hit.crossings,
            None => walker
                .trace(
                    Sl2rWalker::<DVec4>::ray_of(&ray),
                    crate::space::Limit::Distance(self.scene.cutoff_distance()),
                )
                .crossings
                .len()
                .min(budget),
        }
    }

    fn walk_ratios(&self, rays: usize) -> [f64; 4] {
        let (a, b) = walk_ratios::<DVec4>(&self.space, rays);
        let (c, d) = walk_ratios::<glam::Vec4>(&self.space, rays);
        [a, b, c, d]
    }
}

/// The rows of `config.sl2r`.
pub(super) fn sl2r_rows(
    harness: &mut Harness,
    config: &BenchConfig,
    progress: &ProgressBar,
) -> Result<Vec<FamilyRow>, BenchError> {
    let reference = Reference::new(config)?;
    config
        .sl2r
        .iter()
        .map(|id| {
            let space = sl2r(id)?;
            let scene = default_scene(&space);
            let bench = Sl2rBench {
                id: id.clone(),
                space,
                scene,
            };
            family_row(harness, config, &reference, &bench, progress)
        })
        .collect()
}
