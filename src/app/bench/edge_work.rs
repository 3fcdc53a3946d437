//! What the rays of the edges view do, counted on the CPU reference: how many cells they
//! pass, how many of those segments come near two faces at one point (only those can meet
//! an edge tube or a vertex ball, and only those make the GPU visit the buckets of face
//! pairs), and in how many blocks of neighbouring pixels at least one does. A GPU (or a
//! software rasteriser's SIMD lanes) runs a block's pixels in step, so a block pays for a
//! pair visit when any of its pixels needs one: the last figure explains the edges' cost
//! better than the first.

use super::Subject;
use crate::scene::{CurvedScene, FaceCulling};
use crate::space::CellWalker;
use crate::trace::{RayEnd, first_hit};
use glam::DVec4;

/// Pixels a block holds, as 4 × 2: the eight lanes of a 256-bit SIMD register, the way
/// a software rasteriser runs fragments (a GPU's warps are larger, so its share is higher).
pub(super) const BLOCK: (u32, u32) = (4, 2);

/// The work the edges view's rays do (see the module's documentation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct EdgeWork {
    /// Cells a ray passes on average (its segments, up to its hit, the fog or the budget).
    pub(super) segments_per_pixel: f64,
    /// The share of those segments that come near two faces at one point.
    pub(super) near_two_faces: f64,
    /// The share of block segments (a block's pixels at the same segment count) in which
    /// at least one pixel's segment comes near two faces at one point.
    pub(super) blocks_near_two_faces: f64,
    /// Edge objects tested per segment once culled (on the CPU, whose test per object also
    /// asks that the segment be near all of its faces at one point), against all of them
    /// in every cell unculled.
    pub(super) tests_per_segment: f64,
}

/// The work of `subject`'s default view onto `scene` (with its edges) at `budget` crossings
/// and `size`, or `None` where the scene has no culling (no edges).
pub(super) fn edge_work(
    subject: &Subject,
    scene: &CurvedScene,
    budget: u32,
    (w, h): (u32, u32),
) -> Option<EdgeWork> {
    let space = &subject.space;
    let culling = FaceCulling::new(space, scene)?;
    let walker = CellWalker::<DVec4>::new(space);
    let g = space.geometry();
    let masked: Vec<usize> = (0..scene.objects.len())
        .filter(|&i| culling.masks[i] != 0)
        .collect();
    // Per pixel, per segment: whether it comes near two faces at one point.
    let mut flags: Vec<Vec<bool>> = Vec::with_capacity((w * h) as usize);
    let (mut segments, mut near, mut tests) = (0usize, 0usize, 0usize);
    for j in 0..h {
        for i in 0..w {
            let start = subject.camera.ray(g, i, j, w, h);
            let crossings = match first_hit(&walker, scene, start, budget as usize) {
                RayEnd::Hit(hit) => hit.crossings,
                RayEnd::Fog(n) | RayEnd::Budget(n) => n,
            };
            let mut ray = walker.normalized(start);
            let mut skip = None;
            let mut pixel = Vec::with_capacity(crossings + 1);
            for _ in 0..=crossings {
                let Some(exit) = walker.exit(&ray, skip) else {
                    break;
                };
                let s = exit.ratio();
                let (p, v) = (ray.point, ray.tangent);
                let at_once = culling.near_at_once(p, v, s);
                let faces = culling.near_faces(p, v, s);
                tests += masked
                    .iter()
                    .filter(|&&o| {
                        culling.may_meet(o, faces) && culling.may_meet_at_once(o, p, v, s)
                    })
                    .count();
                pixel.push(at_once);
                near += usize::from(at_once);
                segments += 1;
                skip = walker.entered(&exit);
                ray = walker.cross(&ray, &exit).0;
            }
            flags.push(pixel);
        }
    }
    let (mut blocks, mut blocks_near) = (0usize, 0usize);
    for by in (0..h).step_by(BLOCK.1 as usize) {
        for bx in (0..w).step_by(BLOCK.0 as usize) {
            let pixels: Vec<&Vec<bool>> = (by..(by + BLOCK.1).min(h))
                .flat_map(|y| (bx..(bx + BLOCK.0).min(w)).map(move |x| (y * w + x) as usize))
                .map(|k| &flags[k])
                .collect();
            let longest = pixels.iter().map(|f| f.len()).max().unwrap_or(0);
            blocks += longest;
            blocks_near += (0..longest)
                .filter(|&k| pixels.iter().any(|f| f.get(k).copied().unwrap_or(false)))
                .count();
        }
    }
    let per = |a: usize, b: usize| if b == 0 { 0.0 } else { a as f64 / b as f64 };
    Some(EdgeWork {
        segments_per_pixel: per(segments, (w * h) as usize),
        near_two_faces: per(near, segments),
        blocks_near_two_faces: per(blocks_near, blocks),
        tests_per_segment: per(tests, segments),
    })
}
