//! The walk through the box of `nil-K` over the walk contract: where it ends is the
//! universal cover's geodesic carried by an element of `Γ_K` (`A^p B^q C^m = (p, q,
//! pq/2 + m/K)`), long walks stay in the box, the f32 walk keeps the f64 walk's faces, and
//! a walk by distance split in two ends where the whole one does.

use super::*;
use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::nil::NilWalker;
use bevy_curved_spaces::space::{CellWalk, Limit};
use glam::{DVec4, Vec4};

fn start(rng: &mut SplitMix64, k: u32) -> Ray<DVec4> {
    let h = 0.5 / f64::from(k);
    let v = rng.direction();
    Ray {
        point: DVec4::new(
            rng.unit() - 0.5,
            rng.unit() - 0.5,
            (2.0 * rng.unit() - 1.0) * h,
            1.0,
        ),
        tangent: v.extend(0.0),
    }
}

fn as_nil(r: &Ray<DVec4>) -> NilRay<DoubleDouble> {
    let d = DoubleDouble::new;
    NilRay {
        point: [d(r.point.x), d(r.point.y), d(r.point.z)],
        velocity: [d(r.tangent.x), d(r.tangent.y), d(r.tangent.z)],
    }
}

#[test]
fn a_walk_ends_on_the_cover_geodesic_carried_by_the_lattice() {
    let mut rng = SplitMix64(51);
    let mut worst = 0.0_f64;
    for k in [1, 3, 50] {
        let walker = NilWalker::<DVec4>::new(k);
        for _ in 0..60 {
            let s = start(&mut rng, k);
            let distance = 0.5 + 6.0 * rng.unit();
            let (end, walked) = CellWalk::walk(&walker, s, Limit::Distance(distance), |_| true);
            assert_eq!(walked, distance);
            // g = end · γ(T)⁻¹, with γ the cover geodesic (double-double).
            let cover = flow(&as_nil(&s), DoubleDouble::new(distance));
            let inverse = cover.point.map(|x| -x);
            let e = as_nil(&end);
            let g = group_product(e.point, inverse).map(|x| x.to_f64());
            let (p, q) = (g[0].round(), g[1].round());
            let m = (g[2] - p * q / 2.0) * f64::from(k);
            let off = (g[0] - p)
                .abs()
                .max((g[1] - q).abs())
                .max((m - m.round()).abs() / f64::from(k));
            let tolerance = 1e-12 * (1.0 + distance * distance) * f64::from(k);
            assert!(
                off < tolerance,
                "nil-{k}: the end is {off:e} off the lattice's image"
            );
            for i in 0..3 {
                let dv = (e.velocity[i] - cover.velocity[i]).abs().to_f64();
                assert!(dv < tolerance, "nil-{k}: velocity {i} off by {dv:e}");
            }
            worst = worst.max(off / (1.0 + distance * distance));
        }
    }
    println!("walks against the cover: worst {worst:.1e} (over 1 + d²)");
}

#[test]
fn long_walks_stay_in_the_box() {
    let mut rng = SplitMix64(52);
    for k in [1, 3, 50] {
        let h = 0.5 / f64::from(k);
        let walker = NilWalker::<DVec4>::new(k);
        let s = start(&mut rng, k);
        let mut count = 0usize;
        let mut worst = 0.0_f64;
        let (end, _) = CellWalk::walk(&walker, s, Limit::Crossings(100_000), |c| {
            count += 1;
            let p = c.ray.point;
            let out = (p.x.abs() - 0.5).max(p.y.abs() - 0.5).max(p.z.abs() - h);
            worst = worst.max(out);
            true
        });
        assert_eq!(count, 100_000, "nil-{k}: the walk stopped after {count}");
        assert!(worst <= 0.0, "nil-{k}: {worst:e} out of the box");
        let speed = end.tangent.truncate().length();
        assert!((speed - 1.0).abs() < 1e-12, "nil-{k}: speed {speed}");
    }
}

#[test]
fn f32_walks_keep_the_f64_faces_and_split_walks_compose() {
    let mut rng = SplitMix64(53);
    let (mut same, mut total) = (0, 0);
    for k in [1, 3] {
        let w64 = NilWalker::<DVec4>::new(k);
        let w32 = NilWalker::<Vec4>::new(k);
        for _ in 0..100 {
            let s = start(&mut rng, k);
            let t64 = CellWalk::trace(&w64, s, Limit::Crossings(8));
            let s32 = Ray {
                point: s.point.as_vec4(),
                tangent: s.tangent.as_vec4(),
            };
            let t32 = CellWalk::trace(&w32, s32, Limit::Crossings(8));
            for (a, b) in t64.crossings.iter().zip(&t32.crossings).take(3) {
                total += 1;
                same += usize::from(a.face == b.face);
            }
            let (whole, _) = CellWalk::walk(&w64, s, Limit::Distance(3.0), |_| true);
            let (half, _) = CellWalk::walk(&w64, s, Limit::Distance(1.25), |_| true);
            let (rest, _) = CellWalk::walk(&w64, half, Limit::Distance(1.75), |_| true);
            let gap = (whole.point - rest.point).abs().max_element();
            assert!(gap < 1e-11, "nil-{k}: split walk {gap:e} apart");
        }
    }
    // Only rays passing within f32's rounding of an edge may differ.
    assert!(
        same * 100 >= total * 98,
        "{same} of {total} faces kept in f32"
    );
}
