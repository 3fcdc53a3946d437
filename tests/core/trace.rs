//! The crossing walk: against the universal cover, against independent models (unfolded
//! torus, quaternions), on hard rays through edges and vertices, and f32 against f64.

use bevy_curved_spaces::geometry::{Geometry, Vector4};
use bevy_curved_spaces::geometry::{Ray, chart_ray};
use bevy_curved_spaces::space::{CellWalker, Limit, Trace};
use bevy_curved_spaces::space::{SEED_SPACES, Space, seed_space};
use glam::{DMat4, DQuat, DVec3, DVec4, Vec4};
use proptest::prelude::*;

fn space(id: &str) -> Space {
    seed_space(id).unwrap()
}

fn walk(s: &Space, from: DVec3, dir: DVec3, limit: Limit) -> (Ray<DVec4>, Trace<DVec4>) {
    let start = chart_ray(s.geometry(), from, dir).unwrap();
    (start, CellWalker::<DVec4>::new(s).trace(start, limit))
}

fn seed_ids() -> impl Strategy<Value = &'static str> {
    prop::sample::select(SEED_SPACES.iter().map(|s| s.id).collect::<Vec<_>>())
}

fn unit() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("non-zero", |(x, y, z)| x * x + y * y + z * z > 1e-2)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// A start point well inside the cell (a fifth of the inradius from the centre).
fn start_point(s: &Space, u: DVec3, frac: f64) -> DVec3 {
    let r = bevy_curved_spaces::space::invariants::inradius(s);
    s.geometry()
        .to_chart(s.geometry().translation(u, 0.2 * frac * r) * s.centre())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The product of the applied pairings maps each cell point back onto the straight
    /// geodesic of the universal cover: `H_k⁻¹ X_k = γ(t_k)`, to 1e-12 per crossing in E³
    /// and S³. In H³ the entries of `H_k` grow like e^d, so the check itself rounds to about
    /// ε·e^(2d) (ε·e^d from the walk, as much again from forming `H_k⁻¹`).
    #[test]
    fn tracing_follows_the_universal_cover(id in seed_ids(), u in unit(), dir in unit(), frac in 0.0..1.0f64) {
        let s = space(id);
        let g = s.geometry();
        // H³ amplifies rounding like e^d (docs/design.md §3): fewer crossings keep d moderate.
        let n = if g == Geometry::Hyperbolic { 8 } else { 30 };
        let (start, trace) = walk(&s, start_point(&s, u, frac), dir, Limit::Crossings(n));
        prop_assert_eq!(trace.crossings.len(), n);
        let mut h = DMat4::IDENTITY;
        for (i, c) in trace.crossings.iter().enumerate() {
            h = s.faces()[c.face].pairing * h;
            let back = g.inverse(h) * c.ray.point;
            let (straight, _) = g.geodesic(start.point, start.tangent, c.distance);
            // `back` lies anywhere on S³ (the cover), so no projection into the chart's
            // hemisphere.
            let err = g.distance(back, straight);
            let bound = 1e-12 * (i + 1) as f64 + 64.0 * f64::EPSILON * (2.0 * c.distance * -g.kappa()).exp();
            prop_assert!(err <= bound, "{id}: crossing {i}: error {err:e} > {bound:e}");
        }
    }

    /// Tracing a distance forward, turning round and tracing it back returns to the start.
    #[test]
    fn there_and_back_again(id in seed_ids(), u in unit(), dir in unit(), d in 0.5..4.0f64) {
        let s = space(id);
        let g = s.geometry();
        let (start, there) = walk(&s, start_point(&s, u, 0.5), dir, Limit::Distance(d));
        let walker = CellWalker::<DVec4>::new(&s);
        let turned = Ray { point: there.end.point, tangent: -there.end.tangent };
        let back = walker.trace(turned, Limit::Distance(d));
        let err = g.distance(back.end.point, start.point);
        let bound = 1e-11 + 64.0 * f64::EPSILON * (2.0 * d * -g.kappa()).exp();
        prop_assert!(err <= bound, "{id}: returned {err:e} from the start");
        prop_assert!((g.form(back.end.tangent, -start.tangent) - 1.0).abs() <= bound);
        let forward: Vec<usize> = there.crossings.iter().map(|c| c.face).collect();
        let backward: Vec<usize> = back.crossings.iter().rev().map(|c| s.faces()[c.face].partner).collect();
        prop_assert_eq!(forward, backward);
    }

    /// The 3-torus against unfolding in R³: the straight line crosses the planes
    /// `x_a = k + ½` at known times, and the entry point is the line wrapped into the cube.
    #[test]
    fn torus_matches_unfolding(from in (-0.45..0.45f64, -0.45..0.45f64, -0.45..0.45f64), dir in unit()) {
        let s = space("torus");
        let x0 = DVec3::new(from.0, from.1, from.2);
        let (_, trace) = walk(&s, x0, dir, Limit::Crossings(40));
        let mut events: Vec<(f64, usize)> = Vec::new();
        for axis in 0..3 {
            let d = dir[axis];
            if d.abs() < 1e-9 {
                continue;
            }
            for k in 0..200 {
                let plane = if d > 0.0 { k as f64 + 0.5 } else { -(k as f64) - 0.5 };
                events.push(((plane - x0[axis]) / d, 2 * axis + usize::from(d < 0.0)));
            }
        }
        events.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (c, (t, face)) in trace.crossings.iter().zip(&events) {
            prop_assert!((c.distance - t).abs() < 1e-12 * (1.0 + t), "distance {} vs {t}", c.distance);
            prop_assert_eq!(c.face, *face);
            let unfolded = x0 + *t * dir;
            let wrapped = unfolded - (unfolded + DVec3::splat(0.5) - DVec3::splat(1e-9)).floor();
            let point = s.geometry().to_chart(c.ray.point);
            // On the crossed face the coordinate is ∓½; compare the others.
            for a in 0..3 {
                if a != face / 2 {
                    prop_assert!((point[a] - wrapped[a]).abs() < 1e-11, "{point} vs {wrapped}");
                }
            }
        }
    }
}

fn quaternion(v: DVec4) -> DQuat {
    DQuat::from_xyzw(v.x, v.y, v.z, v.w)
}

/// The binary icosahedral group, written out from its standard coordinates: the 8 units,
/// the 16 `(±1 ± i ± j ± k)/2`, and the 96 even permutations of `(0, ±1, ±φ⁻¹, ±φ)/2`.
fn binary_icosahedral() -> Vec<DVec4> {
    let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let mut out = Vec::new();
    for i in 0..4 {
        for s in [1.0, -1.0] {
            let mut v = DVec4::ZERO;
            v[i] = s;
            out.push(v);
        }
    }
    for bits in 0..16 {
        out.push(DVec4::from_array(std::array::from_fn(|i| {
            if bits >> i & 1 == 1 { -0.5 } else { 0.5 }
        })));
    }
    let even = [
        [0, 1, 2, 3],
        [0, 2, 3, 1],
        [0, 3, 1, 2],
        [1, 0, 3, 2],
        [1, 2, 0, 3],
        [1, 3, 2, 0],
        [2, 0, 1, 3],
        [2, 1, 3, 0],
        [2, 3, 0, 1],
        [3, 0, 2, 1],
        [3, 1, 0, 2],
        [3, 2, 1, 0],
    ];
    let base = [0.0, 1.0, 1.0 / phi, phi];
    for p in even {
        for signs in 0..8 {
            // Components in the order (1, i, j, k), stored as glam's (x, y, z, w) = (i, j, k, 1).
            let mut v = [0.0; 4];
            for (k, &pos) in p.iter().enumerate() {
                let sign = if k > 0 && signs >> (k - 1) & 1 == 1 {
                    -1.0
                } else {
                    1.0
                };
                v[pos] = sign * base[k] / 2.0;
            }
            out.push(DVec4::new(v[1], v[2], v[3], v[0]));
        }
    }
    out
}

/// Poincaré against quaternion arithmetic: model points are unit quaternions
/// `w + xi + yj + zk`, every pairing is a right multiplication by an element of the binary
/// icosahedral group, the deck group is exactly that group, and a traced ray's cell points
/// are the straight geodesic's points multiplied by the product of those quaternions.
#[test]
fn poincare_matches_quaternion_arithmetic() {
    let s = space("poincare");
    let group = binary_icosahedral();
    assert_eq!(group.len(), 120);
    let in_group = |q: DVec4| group.iter().any(|e| (*e - q).length() < 1e-12);
    let mut quats = Vec::new();
    for f in s.faces() {
        let q = quaternion(f.pairing * DVec4::W);
        for basis in [DVec4::X, DVec4::Y, DVec4::Z, DVec4::W] {
            let by_matrix = f.pairing * basis;
            let by_quaternion = DVec4::from(quaternion(basis) * q);
            assert!(
                (by_matrix - by_quaternion).length() < 1e-14,
                "not a right multiplication"
            );
        }
        assert!(in_group(DVec4::from(q)), "{q:?} is not in 2I");
        quats.push(q);
    }
    // The whole deck group is 2I.
    let elements =
        bevy_curved_spaces::space::invariants::elements_near(&s, f64::INFINITY, 1000).unwrap();
    assert_eq!(elements.len(), 120);
    for e in &elements {
        assert!(in_group(e * DVec4::W));
    }
    // Rays: X_k = γ(t_k) Q_k with Q_k = q_{f_1} ⋯ q_{f_k}.
    for (from, dir) in [
        (DVec3::new(0.05, -0.1, 0.02), DVec3::new(0.3, 0.9, -0.2)),
        (DVec3::ZERO, DVec3::new(-0.7, 0.1, 0.6)),
    ] {
        let (start, trace) = walk(&s, from, dir, Limit::Crossings(200));
        let mut product = DQuat::IDENTITY;
        for (i, c) in trace.crossings.iter().enumerate() {
            product *= quats[c.face];
            let (straight, _) = s
                .geometry()
                .geodesic(start.point, start.tangent, c.distance);
            let expected = DVec4::from(quaternion(straight) * product);
            let err = (expected - c.ray.point).length();
            assert!(err < 1e-12 * (i + 1) as f64, "crossing {i}: {err:e}");
        }
    }
}

/// Rays aimed exactly at vertices and edge midpoints, and within 1e-12 of them, leave
/// through valid faces and never leave the cell.
#[test]
fn rays_through_edges_and_vertices_stay_in_the_cell() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let mut targets: Vec<DVec3> = s.vertices().to_vec();
        targets.extend(
            s.edges()
                .iter()
                .map(|e| (s.vertices()[e.vertices[0]] + s.vertices()[e.vertices[1]]) / 2.0),
        );
        let nudges = [
            DVec3::ZERO,
            DVec3::new(1e-12, -1e-12, 0.0),
            DVec3::new(0.0, 1e-12, 1e-12),
        ];
        for target in &targets {
            for nudge in nudges {
                let (_, trace) = walk(&s, DVec3::ZERO, *target + nudge, Limit::Crossings(40));
                assert_eq!(trace.crossings.len(), 40, "{}: ray stopped early", seed.id);
                // Through a vertex the ray hops around it at zero distance, but it gets past:
                // no endless loop of zero-length crossings.
                let r = bevy_curved_spaces::space::invariants::circumradius(&s);
                assert!(
                    trace.crossings[39].distance > r,
                    "{}: stuck at a vertex",
                    seed.id
                );
                for c in &trace.crossings {
                    let p = c.ray.point;
                    assert!(p.is_finite() && c.distance.is_finite(), "{}: NaN", seed.id);
                    let out = s.outside_by(p);
                    assert!(out <= 1e-12, "{}: {out:e} outside the cell", seed.id);
                }
            }
        }
    }
}

/// f32 (the GPU's arithmetic) against f64 on a 30-crossing ray in every space: the drift is
/// printed; flat and spherical spaces keep the same faces and stay within 1e-4, while in H³
/// the e^d growth of rounding makes f32 part ways after a handful of crossings.
#[test]
fn f32_against_f64_drift() {
    eprintln!(
        "{:<22} {:>10} {:>12} {:>12} {:>14}",
        "space", "same faces", "drift @10", "drift @30", "distance @30"
    );
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let g = s.geometry();
        let start = chart_ray(
            g,
            DVec3::new(0.01, 0.02, -0.015),
            DVec3::new(0.31, -0.52, 0.79),
        )
        .unwrap();
        let exact = CellWalker::<DVec4>::new(&s).trace(start, Limit::Crossings(30));
        let single = CellWalker::<Vec4>::new(&s).trace(
            Ray {
                point: Vec4::from_f64(start.point),
                tangent: Vec4::from_f64(start.tangent),
            },
            Limit::Crossings(30),
        );
        let same = exact
            .crossings
            .iter()
            .zip(&single.crossings)
            .take_while(|(a, b)| a.face == b.face)
            .count();
        let drift = |k: usize| {
            let a = exact.crossings[k - 1].ray.point;
            let b = single.crossings[k - 1].ray.point.to_f64();
            (g.to_chart(a) - g.to_chart(b)).length()
        };
        eprintln!(
            "{:<22} {:>10} {:>12.3e} {:>12.3e} {:>14.3}",
            seed.id,
            same,
            drift(10),
            drift(30),
            exact.crossings[29].distance
        );
        match g {
            Geometry::Hyperbolic => assert!(same >= 4, "{}: f32 parts after {same}", seed.id),
            _ => {
                assert_eq!(same, 30, "{}", seed.id);
                assert!(drift(30) < 1e-4, "{}: drift {}", seed.id, drift(30));
            }
        }
    }
}
