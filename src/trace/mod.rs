//! The CPU reference tracer: a camera ray per pixel walks the cell ([`crate::space::walk`]),
//! nearest object hit against exit face, until the fog cut-off or the crossing budget; and the
//! automatic crossing budget.

mod budget;
pub mod product;
mod render;

pub use budget::{BudgetChoice, MAX_AUTO_BUDGET, auto_budget, auto_budget_with_floor, sample_rays};
pub use render::{
    MAX_BOUNCES, MIRROR_OFFSET, PATH_HASH_START, RayEnd, RayStory, RenderSettings, SceneHit,
    ShadowWalk, TracedRay, colour_along, colour_of, colour_of_traced, first_hit, first_hit_culled,
    first_hit_traced, first_hit_walled, path_hash, ray_story, reflected_ray, render, render_view,
    render_with_progress, to_byte, trace_pixel, walls_of,
};
