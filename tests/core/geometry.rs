//! Laws of the geometry core: isometries preserve the form, inverses invert, geodesics stay
//! on the model at unit speed, distances are accurate near and far.

use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use glam::{DMat4, DVec3, DVec4};
use proptest::prelude::*;

fn geometry() -> impl Strategy<Value = Geometry> {
    prop::sample::select(Geometry::ALL.to_vec())
}

fn direction() -> impl Strategy<Value = DVec3> {
    (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64)
        .prop_filter("non-zero", |(x, y, z)| x * x + y * y + z * z > 1e-3)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z).normalize())
}

/// A random isometry: a product of a translation, a rotation about a point and a reflection.
fn isometry() -> impl Strategy<Value = (Geometry, DMat4)> {
    (
        geometry(),
        direction(),
        0.0..1.2f64,
        direction(),
        -3.0..3.0f64,
        direction(),
        0.0..0.6f64,
        any::<bool>(),
    )
        .prop_map(|(g, u, t, axis, angle, n, r, reflect)| {
            let p = g.translation(u, t * 0.7) * ORIGIN;
            let mut m = g.translation(u, t) * g.rotation_about(p, axis, angle);
            if reflect {
                m *= g.reflection(n.extend(-r));
            }
            (g, m)
        })
}

fn point(g: Geometry, u: DVec3, t: f64) -> DVec4 {
    g.translation(u, t) * ORIGIN
}

proptest! {
    #[test]
    fn isometries_preserve_the_form((g, m) in isometry(), u in direction(), w in direction(), t in 0.0..1.0f64) {
        prop_assert!(g.isometry_defect(m) < 1e-12, "defect {}", g.isometry_defect(m));
        let p = point(g, u, t);
        let a = g.unit_tangent(p, w.extend(0.0));
        let b = g.unit_tangent(p, u.cross(w).extend(0.0) + 0.3 * a);
        prop_assert!((g.form(m * a, m * b) - g.form(a, b)).abs() < 1e-12);
        let q = point(g, w, 0.5 * t);
        prop_assert!((g.distance(m * p, m * q) - g.distance(p, q)).abs() < 1e-12);
    }

    #[test]
    fn inverse_inverts((g, m) in isometry()) {
        let i = g.inverse(m) * m - DMat4::IDENTITY;
        let worst = i.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()));
        prop_assert!(worst < 1e-12, "g⁻¹g − I = {worst}");
    }

    #[test]
    fn geodesics_have_unit_speed(g in geometry(), u in direction(), w in direction(), t in 0.0..1.5f64, s in 0.0..1.2f64) {
        let p = point(g, u, s);
        let v = g.unit_tangent(p, w.extend(0.0));
        let (q, dq) = g.geodesic(p, v, t);
        prop_assert!((g.form(dq, dq) - 1.0).abs() < 1e-12);
        prop_assert!(g.form(q, dq).abs() < 1e-12 || g == Geometry::Euclidean);
        prop_assert!((g.distance(p, q) - t).abs() < 1e-12 * (1.0 + t));
        // The translation along the geodesic is the same map.
        let via_translation = g.translation(w, t) * ORIGIN;
        prop_assert!(g.distance(via_translation, g.geodesic(ORIGIN, w.extend(0.0), t).0) < 1e-12);
    }

    #[test]
    fn translations_along_any_geodesic(g in geometry(), u in direction(), w in direction(), s in 0.0..1.0f64, t in -1.5..1.5f64) {
        let p = point(g, u, s);
        let v = g.unit_tangent(p, w.extend(0.0));
        let m = g.translation_along(p, v, t);
        prop_assert!(g.isometry_defect(m) < 1e-12);
        let (q, dq) = g.geodesic(p, v, t);
        prop_assert!(g.distance(m * p, q) < 1e-12);
        prop_assert!((m * v - dq).length() < 1e-11);
    }

    #[test]
    fn reflections_are_involutions_fixing_their_plane(g in geometry(), n in direction(), r in 0.05..0.6f64, u in direction()) {
        let cov = n.extend(-r);
        let m = g.reflection(cov);
        let sq = m * m - DMat4::IDENTITY;
        prop_assert!(sq.to_cols_array().iter().all(|x| x.abs() < 1e-12));
        prop_assert!((m.determinant() + 1.0).abs() < 1e-12);
        // A point of the plane n·x = r stays put.
        let x = n * r + 0.2 * (u - u.dot(n) * n);
        if let Ok(p) = g.from_chart(x) {
            prop_assert!(g.distance(m * p, p) < 1e-12);
        }
    }

    #[test]
    fn frames_orthonormalize(g in geometry(), u in direction(), t in 0.0..1.0f64, noise in prop::array::uniform16(-1e-3..1e-3f64)) {
        let frame = g.translation(u, t) * g.rotation(u.cross(DVec3::Y + u), 0.7);
        let noisy = frame + DMat4::from_cols_array(&noise);
        prop_assert!(g.frame_defect(noisy) > 1e-6);
        let fixed = g.orthonormalize_frame(noisy);
        prop_assert!(g.frame_defect(fixed) < 1e-14, "defect {}", g.frame_defect(fixed));
        prop_assert!(g.distance(fixed.w_axis, frame.w_axis) < 1e-2);
    }

    #[test]
    fn chart_round_trip(g in geometry(), u in direction(), r in 0.0..0.95f64, d in direction()) {
        let x = u * r;
        let p = g.from_chart(x).unwrap();
        prop_assert!((g.to_chart(p) - x).length() < 1e-14);
        let v = g.tangent_from_chart(p, d).unwrap();
        prop_assert!((g.form(v, v) - 1.0).abs() < 1e-13);
        prop_assert!((g.chart_direction(p, v) - d).length() < 1e-12);
    }
}

#[test]
fn distances_are_accurate_near_and_far() {
    for g in Geometry::ALL {
        let u = DVec3::new(0.3, -0.5, 0.8).normalize();
        // Nearby points: errors at the rounding of the coordinates (~1e-16), where acos of a
        // rounded dot product would be off by ~1e-8.
        for t in [1e-12, 1e-9, 1e-6, 1e-3] {
            let p = point(g, DVec3::X, 0.4);
            let (q, _) = g.geodesic(p, g.unit_tangent(p, u.extend(0.0)), t);
            let d = g.distance(p, q);
            assert!((d - t).abs() <= 1e-15 + 1e-12 * t, "{g:?}: d({t}) = {d}");
        }
    }
    // Far points in H³: coordinates of size e^d known to relative ε fix the point only to
    // about ε·e^d (docs/design.md §3), and the distance stays within that conditioning bound.
    let g = Geometry::Hyperbolic;
    for t in [1.0, 5.0, 15.0, 30.0] {
        let q = g.translation(DVec3::Y, t) * ORIGIN;
        let d = g.distance(ORIGIN, q);
        let bound = 4.0 * f64::EPSILON * f64::exp(t);
        assert!(
            (d - t).abs() <= bound,
            "H³ d = {d}, expected {t} ± {bound:e}"
        );
    }
    // Antipodal points in S³ are π apart, not NaN.
    let s = Geometry::Spherical;
    assert!((s.distance(ORIGIN, -ORIGIN) - std::f64::consts::PI).abs() < 1e-15);
}

#[test]
fn bad_chart_points_are_errors() {
    let h = Geometry::Hyperbolic;
    assert!(h.from_chart(DVec3::new(0.8, 0.7, 0.0)).is_err());
    assert!(h.from_chart(DVec3::new(f64::NAN, 0.0, 0.0)).is_err());
    let p = h.from_chart(DVec3::ZERO).unwrap();
    assert!(h.tangent_from_chart(p, DVec3::ZERO).is_err());
}

#[test]
fn look_at_builds_a_right_handed_frame() {
    for g in Geometry::ALL {
        let f = g
            .look_at(
                DVec3::new(0.1, 0.2, 0.3),
                DVec3::new(-0.2, 0.0, 0.1),
                DVec3::Y,
            )
            .unwrap();
        assert!(g.frame_defect(f) < 1e-13);
        // Transported to the origin, right × up = back.
        let a = g.inverse(g.translation_to(f.w_axis));
        let (r, u, b) = (
            (a * f.x_axis).truncate(),
            (a * f.y_axis).truncate(),
            (a * f.z_axis).truncate(),
        );
        assert!((r.cross(u) - b).length() < 1e-12, "{g:?}");
        // The camera looks at the target: −back is the tangent towards it.
        let target = g.from_chart(DVec3::new(-0.2, 0.0, 0.1)).unwrap();
        let towards = g.tangent_towards(f.w_axis, target);
        assert!((g.form(-f.z_axis, towards) - 1.0).abs() < 1e-12);
    }
}

/// A NaN or infinite component anywhere in a direction is an error, and a NaN entry makes
/// an isometry's defect NaN (never "small"): `f64::max` passes over NaN, so checks built
/// on the largest component or entry once accepted such inputs.
#[test]
fn nan_anywhere_is_never_a_direction_or_an_isometry() {
    for g in Geometry::ALL {
        let p = g.from_chart(DVec3::new(0.1, 0.0, 0.0)).unwrap();
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for i in 0..3 {
                let mut d = DVec3::new(1.0, 0.5, 0.25);
                d[i] = bad;
                assert!(g.tangent_from_chart(p, d).is_err(), "{g:?} {d:?}");
            }
        }
        for i in 0..16 {
            let mut entries = glam::DMat4::IDENTITY.to_cols_array();
            entries[i] = f64::NAN;
            let m = glam::DMat4::from_cols_array(&entries);
            assert!(
                g.isometry_defect(m).partial_cmp(&1.0) != Some(std::cmp::Ordering::Less),
                "{g:?} entry {i}: defect {}",
                g.isometry_defect(m)
            );
        }
    }
}
