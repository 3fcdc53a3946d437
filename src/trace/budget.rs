//! The automatic crossing budget: the smallest budget with which (almost) every ray that
//! would show something within the fog cut-off still reaches it.
//!
//! A ray that runs out of crossings shows the fog colour. That is already its colour when it
//! meets nothing before the cut-off, so only rays that hit an object after many crossings
//! need a large budget. Sampling rays from random points of the cell in random directions
//! gives the distribution of the crossings a hit needs; the budget is its quantile at
//! `1 − miss_fraction`. A ray beyond the budget is then wrong by at most its fog weight
//! `e^(−d/λ)`, and at most `miss_fraction` of the sampled rays are.

use super::{RayEnd, first_hit};
use crate::geometry::Ray;
use crate::random::SplitMix64;
use crate::scene::CurvedScene;
use crate::space::CellWalker;
use crate::space::{Space, invariants};
use glam::DVec4;
use rayon::prelude::*;

/// The largest budget the automatic choice gives (the GPU loop's bound stays finite).
pub const MAX_AUTO_BUDGET: u32 = 1024;

/// `count` rays from points spread through the cell's inscribed ball (within `0.95 ×`
/// inradius of the centre) in directions uniform on the sphere.
#[must_use]
pub fn sample_rays(space: &Space, count: usize, seed: u64) -> Vec<Ray<DVec4>> {
    let g = space.geometry;
    let reach = 0.95 * invariants::inradius(space);
    let mut rng = SplitMix64(seed);
    (0..count)
        .map(|_| {
            let at = g.translation(rng.direction(), reach * rng.unit().cbrt()) * space.centre();
            let point = g.project_point(at);
            let dir = rng.direction();
            let tangent = g.unit_tangent(point, g.translation_to(point) * dir.extend(0.0));
            Ray { point, tangent }
        })
        .collect()
}

/// The budget chosen for a scene and what the sample said about it.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BudgetChoice {
    /// Crossings per ray.
    pub budget: u32,
    /// Fraction of the sampled rays that would hit something after more crossings than
    /// `budget` (shown as fog instead).
    pub missed_fraction: f64,
    /// The most crossings any sampled hit needed (capped at [`MAX_AUTO_BUDGET`]).
    pub most_needed: u32,
    /// Rays sampled.
    pub samples: usize,
    /// The least budget a frame-rate target may lower it to ([`auto_budget_with_floor`]):
    /// `budget` itself unless a floor fraction was given.
    #[serde(default)]
    pub floor: u32,
}

impl BudgetChoice {
    /// The budget for a share of it in (0, 1] (the plugin's `BudgetShare`): rounded
    /// up, never below [`Self::floor`] nor above [`Self::budget`].
    #[must_use]
    pub fn shared(&self, share: f32) -> u32 {
        let share = if share.is_finite() {
            f64::from(share).clamp(0.0, 1.0)
        } else {
            1.0
        };
        // Rounded up, but not for the f32 share's last bit (40 × 0.8 is 32).
        let wanted = (f64::from(self.budget) * share - 1e-6).ceil() as u32;
        wanted
            .clamp(self.floor.min(self.budget), self.budget)
            .max(1)
    }
}

/// The smallest budget with which at most `miss_fraction` of `samples` sampled rays miss an
/// object they would hit before the fog cut-off; at least 1, at most [`MAX_AUTO_BUDGET`].
#[must_use]
pub fn auto_budget(
    space: &Space,
    scene: &CurvedScene,
    miss_fraction: f64,
    samples: usize,
) -> BudgetChoice {
    auto_budget_with_floor(space, scene, miss_fraction, miss_fraction, samples)
}

/// [`auto_budget`], and from the same sample the floor a frame-rate target may lower the
/// budget to: the smallest budget with which at most `floor_fraction` of the rays miss
/// (at least `miss_fraction`; see the plugin's `Quality::floor_miss_fraction`).
#[must_use]
pub fn auto_budget_with_floor(
    space: &Space,
    scene: &CurvedScene,
    miss_fraction: f64,
    floor_fraction: f64,
    samples: usize,
) -> BudgetChoice {
    let walker = CellWalker::<DVec4>::new(space);
    let rays = sample_rays(space, samples.max(1), 0x5eed_b0d6e7);
    let cap = MAX_AUTO_BUDGET as usize;
    let needed: Vec<u32> = rays
        .par_iter()
        .map(|ray| match first_hit(&walker, scene, *ray, cap) {
            RayEnd::Hit(h) => h.crossings as u32,
            // Fog either way: any budget shows it.
            RayEnd::Fog(_) => 0,
            RayEnd::Budget(c) => c as u32,
        })
        .collect();
    choose_from_needed(needed, miss_fraction, floor_fraction)
}

/// The budget from the crossings each sampled ray needs (0 for one any budget shows): the
/// smallest with which at most `miss_fraction` of them need more, and the floor for
/// `floor_fraction`. At least 1.
pub(crate) fn choose_from_needed(
    mut needed: Vec<u32>,
    miss_fraction: f64,
    floor_fraction: f64,
) -> BudgetChoice {
    if needed.is_empty() {
        needed.push(0);
    }
    needed.sort_unstable();
    let n = needed.len();
    let at = |fraction: f64| {
        let allowed = ((fraction.clamp(0.0, 1.0) * n as f64).floor() as usize).min(n - 1);
        needed[n - 1 - allowed].max(1)
    };
    let budget = at(miss_fraction);
    let floor = at(floor_fraction.max(miss_fraction)).min(budget);
    let missed = needed.iter().filter(|&&c| c > budget).count();
    BudgetChoice {
        budget,
        missed_fraction: missed as f64 / n as f64,
        most_needed: needed[n - 1],
        samples: n,
        floor,
    }
}
