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

/// A tile's side in pixels: the unit a tile tracer would walk by its four corner rays.
pub(super) const TILE: u32 = 8;

/// The depths the tile statistics tell apart: corners parting at crossing 0, 1, 2, 3, at 4
/// or later, or never.
pub(super) const TILE_DEPTHS: usize = 6;

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
    /// The 90th percentile of the cells a ray passes.
    pub(super) segments_p90: f64,
    /// Of the 8 × 8 tiles, the share whose four corner rays first leave a cell copy by
    /// different faces at crossing 0, 1, 2, 3, at 4 or later, and (last) never: while the
    /// corners leave by the same face every ray between them does (the cell is convex), so
    /// a tile tracer would walk the tile once up to that depth and split it there.
    pub(super) tiles_parting: [f64; TILE_DEPTHS],
    /// The share of tiles in which some pixel comes near two faces at one point (near an
    /// edge or a vertex) before the corners part: a tile tracer must split those there too,
    /// or test the edge objects for all its pixels.
    pub(super) tiles_near_edge_before_parting: f64,
}

/// The crossing at which the face sequences of the given rays first differ (between two
/// rays that both crossed that far), or `None` when they never do.
pub(super) fn parting_depth(sequences: &[&[usize]]) -> Option<usize> {
    let longest = sequences.iter().map(|s| s.len()).max().unwrap_or(0);
    (0..longest).find(|&k| {
        let mut faces = sequences.iter().filter_map(|s| s.get(k));
        let first = faces.next();
        first.is_some_and(|f| faces.any(|g| g != f))
    })
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
    // Per pixel, the faces its segments leave by.
    let mut exits: Vec<Vec<usize>> = Vec::with_capacity((w * h) as usize);
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
            let mut left = Vec::with_capacity(crossings + 1);
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
                left.push(exit.face);
                skip = walker.entered(&exit);
                ray = walker.cross(&ray, &exit).0;
            }
            flags.push(pixel);
            exits.push(left);
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
    let mut lengths: Vec<usize> = flags.iter().map(Vec::len).collect();
    lengths.sort_unstable();
    let segments_p90 = lengths
        .get(((lengths.len() as f64 * 0.9) as usize).min(lengths.len().saturating_sub(1)))
        .map_or(0.0, |&n| n as f64);
    // The tiles, by their four corner pixels (the last row and column of a partial tile).
    let (mut tiles, mut parted, mut near_edge) = (0usize, [0usize; TILE_DEPTHS], 0usize);
    for ty in (0..h).step_by(TILE as usize) {
        for tx in (0..w).step_by(TILE as usize) {
            let (x1, y1) = ((tx + TILE).min(w) - 1, (ty + TILE).min(h) - 1);
            let corners: Vec<&[usize]> = [(tx, ty), (x1, ty), (tx, y1), (x1, y1)]
                .iter()
                .map(|&(x, y)| exits[(y * w + x) as usize].as_slice())
                .collect();
            let depth = parting_depth(&corners);
            tiles += 1;
            parted[depth.map_or(TILE_DEPTHS - 1, |k| k.min(TILE_DEPTHS - 2))] += 1;
            let shared = depth.unwrap_or(usize::MAX);
            let edge = (ty..=y1).any(|y| {
                (tx..=x1).any(|x| {
                    flags[(y * w + x) as usize]
                        .iter()
                        .take(shared)
                        .any(|&near| near)
                })
            });
            near_edge += usize::from(edge);
        }
    }
    Some(EdgeWork {
        segments_per_pixel: per(segments, (w * h) as usize),
        near_two_faces: per(near, segments),
        blocks_near_two_faces: per(blocks_near, blocks),
        tests_per_segment: per(tests, segments),
        segments_p90,
        tiles_parting: parted.map(|n| per(n, tiles)),
        tiles_near_edge_before_parting: per(near_edge, tiles),
    })
}

#[cfg(test)]
mod tests {
    use super::parting_depth;

    #[test]
    fn corners_part_where_two_that_got_that_far_leave_by_different_faces() {
        let (a, b) = ([3, 1, 4, 1, 5], [3, 1, 4, 2]);
        assert_eq!(parting_depth(&[&a, &b]), Some(3));
        assert_eq!(parting_depth(&[&a, &a, &a]), None);
        // A ray that stopped (met an object) earlier does not part the others.
        assert_eq!(parting_depth(&[&a, &a[..2]]), None);
        assert_eq!(parting_depth(&[&[7][..], &a]), Some(0));
        assert_eq!(parting_depth(&[&[][..], &[][..]]), None);
    }
}
