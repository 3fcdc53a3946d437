//! The CPU reference tracer: a camera ray per pixel walks the cell ([`crate::space::walk`]),
//! nearest object hit against exit face, until the fog cut-off or the crossing budget; and the
//! automatic crossing budget.

mod budget;
pub mod nil;
pub mod product;
mod render;
pub mod sl2r;

pub use budget::{BudgetChoice, MAX_AUTO_BUDGET, auto_budget, auto_budget_with_floor, sample_rays};
pub use render::{
    MAX_BOUNCES, MIRROR_OFFSET, PATH_HASH_START, RayEnd, RayStory, RenderSettings, SceneHit,
    ShadowWalk, TracedRay, colour_along, colour_of, colour_of_traced, first_hit, first_hit_culled,
    first_hit_traced, first_hit_walled, path_hash, ray_story, reflected_ray, render, render_view,
    render_with_progress, to_byte, trace_pixel, walls_of,
};

/// The picture of `layout` with the colour of each camera ray (a frame's fourth column its
/// point, the ray along `x·right + y·up − back`), rows in parallel; an anaglyph mixes both
/// eyes' colours. The renderers of the families that walk their own rays share it.
pub(crate) fn render_layout(
    layout: &crate::view::ViewLayout,
    colour_of_ray: impl Fn(crate::geometry::Ray<glam::DVec4>) -> glam::DVec3 + Sync,
) -> image::RgbImage {
    render_layout_by_eye(layout, |eye, u, v| {
        colour_of_ray(layout.frame_ray(eye, u, v))
    })
}

/// [`render_layout`] for a family whose camera ray is not a frame's column combination:
/// `colour_at(eye, u, v)` is the colour of eye `eye` at image point `(u, v)` (its frame is
/// `layout.frames[eye]`, its lens point `layout.lens.at(u, v)`).
pub(crate) fn render_layout_by_eye(
    layout: &crate::view::ViewLayout,
    colour_at: impl Fn(usize, f64, f64) -> glam::DVec3 + Sync,
) -> image::RgbImage {
    use rayon::prelude::*;
    let (width, height) = (layout.size[0] as u32, layout.size[1] as u32);
    let colour = |eye: usize, [u, v]: [f64; 2]| {
        colour_at(eye, u, v).clamp(glam::DVec3::ZERO, glam::DVec3::ONE)
    };
    let rows: Vec<Vec<u8>> = (0..height)
        .into_par_iter()
        .map(|j| {
            (0..width)
                .flat_map(|i| {
                    let (eye, uv) = layout.eye_at(f64::from(i) + 0.5, f64::from(j) + 0.5);
                    let c = match layout.kind {
                        crate::view::ViewKind::Anaglyph => {
                            layout.mix_anaglyph(colour(0, uv), colour(1, uv))
                        }
                        _ => colour(eye, uv),
                    };
                    c.to_array().map(to_byte)
                })
                .collect()
        })
        .collect();
    image::RgbImage::from_raw(width, height, rows.concat()).expect("width × height pixels")
}
