//! The inverse of the exponential map: the shortest geodesic's length and start velocity.
//! Walked, it reaches the target; no geodesic of another winding to the target is
//! shorter; the distance is symmetric, obeys the triangle inequality, and on the vertical
//! axis is the vertical line's up to 2π and the helix's beyond.

use super::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::nil::distance::{distance, reached, shortest};

fn point(rng: &mut SplitMix64, size: f64) -> [f64; 3] {
    [
        (rng.unit() - 0.5) * size,
        (rng.unit() - 0.5) * size,
        (rng.unit() - 0.5) * size,
    ]
}

#[test]
fn the_shortest_geodesic_reaches_its_target() {
    let mut rng = SplitMix64(56);
    let mut worst = 0.0_f64;
    for i in 0..2000 {
        let size = [0.01, 1.0, 4.0, 20.0][i % 4];
        let (p, q) = (point(&mut rng, size), point(&mut rng, size));
        let r = reached(p, q);
        let gap = (0..3).map(|k| (r[k] - q[k]).abs()).fold(0.0, f64::max);
        worst = worst.max(gap / (1.0 + size * size));
        assert!(
            gap < 1e-11 * (1.0 + size * size),
            "{p:?} → {q:?}: off by {gap:e}"
        );
        let (_, v) = shortest(p, q);
        assert!(((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 1.0).abs() < 1e-14);
    }
    // In double-double, to 28 digits.
    let d = DoubleDouble::new;
    for _ in 0..50 {
        let (p, q) = (point(&mut rng, 3.0), point(&mut rng, 3.0));
        let r = reached(p.map(d), q.map(d));
        for k in 0..3 {
            assert!((r[k] - d(q[k])).abs().to_f64() < 1e-28, "{p:?} → {q:?}");
        }
    }
    println!("shortest geodesics reach their targets: worst {worst:.1e} (over 1 + size²)");
}

/// Every geodesic from the origin to `q` winds by a root of the height equation on its
/// own branch `(2πk, 2π(k+1))`; the ones on the further branches are longer.
#[test]
fn no_geodesic_of_another_winding_is_shorter() {
    let mut rng = SplitMix64(57);
    for _ in 0..300 {
        let q = point(&mut rng, 6.0);
        let (x, y, z) = (q[0], q[1], q[2].abs());
        let rho2 = x * x + y * y;
        let best = distance([0.0; 3], q);
        for k in 1..4 {
            // Bisection of h on (2πk, 2π(k+1)): increasing there too.
            let h = |t: f64| t + rho2 * (t - t.sin()) / (8.0 * (t / 2.0).sin().powi(2)) - z;
            let two_pi = std::f64::consts::TAU;
            let (mut lo, mut hi) = (two_pi * k as f64 + 1e-9, two_pi * (k + 1) as f64 - 1e-9);
            if !(h(lo) < 0.0 && h(hi) > 0.0) {
                continue;
            }
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if h(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let s = (lo / 2.0).sin();
            let length = lo / (2.0 * s.abs()) * (rho2 + 4.0 * s * s).sqrt();
            assert!(
                length >= best - 1e-12,
                "{q:?}: winding {k} gives {length} < {best}"
            );
        }
    }
}

#[test]
fn the_distance_is_a_metric_and_knows_the_vertical_axis() {
    let mut rng = SplitMix64(58);
    for _ in 0..500 {
        let (p, q, r) = (
            point(&mut rng, 4.0),
            point(&mut rng, 4.0),
            point(&mut rng, 4.0),
        );
        let (pq, qp) = (distance(p, q), distance(q, p));
        assert!((pq - qp).abs() < 1e-12 * (1.0 + pq), "{pq} {qp}");
        assert!(distance(p, r) <= pq + distance(q, r) + 1e-12);
    }
    let pi = std::f64::consts::PI;
    for z in [0.5, 3.0, 2.0 * pi, 7.0, 30.0] {
        let want = if z <= 2.0 * pi {
            z
        } else {
            2.0 * pi * (z / pi - 1.0).sqrt()
        };
        assert!((distance([0.0; 3], [0.0, 0.0, z]) - want).abs() < 1e-14);
        assert!((distance([0.0; 3], [0.0, 0.0, -z]) - want).abs() < 1e-14);
        // Just off the axis the distance is continuous.
        let off = distance([0.0; 3], [1e-9, 0.0, z]);
        assert!((off - want).abs() < 1e-6, "{z}: {off} against {want}");
    }
    // A horizontal step is the straight line.
    assert!((distance([0.0; 3], [0.3, -0.4, 0.0]) - 0.5).abs() < 1e-16);
}
