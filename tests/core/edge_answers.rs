//! Answers that were once silently wrong at the edges of the input: projective space taken for
//! an orbifold, a product walk that stopped short on a long circle, a direction or a circle
//! too large or too small for f64, a lamp point or radius past what f64 holds, an error bound
//! that overflowed into 0, and a systole search that visited tens of thousands of elements.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::light_images::{FluenceError, fluence, fluence_within};
use bevy_curved_spaces::space::Limit;
use bevy_curved_spaces::space::invariants::injectivity_radius;
use bevy_curved_spaces::space::product::{ProductSpace, ProductWalker, chart_ray, product_space};
use glam::{DVec3, DVec4};
use std::f64::consts::FRAC_PI_2;

use crate::common::{library_space as space, product};

#[test]
fn projective_space_is_a_manifold_and_a_mirror_is_still_a_mirror() {
    let rp3 = space("projective-space");
    // Its one face, the equator, is glued to itself by the antipodal map: no mirror.
    assert!(!rp3.has_mirrors());
    assert!(rp3.manifold(), "RP³ = L(2,1) is a manifold");
    let r = injectivity_radius(&rp3).expect("a manifold has an injectivity radius");
    assert!((r - FRAC_PI_2).abs() < 1e-9, "{r}");
    // A face glued to itself by the reflection in it is a mirror, as before.
    let cube = space("mirrored-cube");
    assert!(cube.has_mirrors() && !cube.manifold());
}

/// The first crossing of a ray from the centre of `space` along the chart direction `dir`,
/// walked by crossings in f64: its face and distance.
fn first_crossing(space: &ProductSpace, dir: DVec3) -> Option<(usize, f64)> {
    let start = chart_ray(space.base(), DVec3::ZERO, dir).unwrap();
    let walker = ProductWalker::<DVec4>::new(space);
    let mut first = None;
    walker.walk(start, Limit::Crossings(1), |c| {
        first = Some((c.face, c.distance));
        false
    });
    first
}

#[test]
fn a_walk_on_a_long_circle_reaches_the_top() {
    // The sphere with no sides: the ray goes round it many times before it rises L/2.
    for (id, length) in [
        ("surface-aA-circle-100", 100.0),
        ("surface-aA-circle-1e6", 1e6),
    ] {
        let s = product(id);
        let dir = DVec3::new(1.0, 2.0, 3.0);
        let rise = dir.z / dir.length();
        let (face, d) = first_crossing(&s, dir).unwrap_or_else(|| panic!("{id}: no crossing"));
        let walker = ProductWalker::<DVec4>::new(&s);
        assert_eq!(face, walker.top(), "{id}");
        let want = 0.5 * length / rise;
        assert!((d - want).abs() <= 1e-9 * want, "{id}: {d} against {want}");
    }
    // With sides (the projective plane's hemisphere) and a slow rise: many side crossings,
    // then the top, never a stop without one.
    let s = product("surface-aa-circle-1000");
    let (_, d) = first_crossing(&s, DVec3::new(1.0, 0.0, 1e-3)).expect("a crossing");
    assert!(d.is_finite() && d > 0.0);
}

#[test]
fn a_level_ray_round_the_sphere_ends_by_distance_but_never_crosses() {
    let s = product("sphere-circle");
    let walker = ProductWalker::<DVec4>::new(&s);
    let start = chart_ray(s.base(), DVec3::ZERO, DVec3::X).unwrap();
    let mut crossed = 0;
    let (_, d) = walker.walk(start, Limit::Crossings(3), |_| {
        crossed += 1;
        true
    });
    assert_eq!(crossed, 0);
    // By distance it goes the whole way: round the great circle 1.5 times, to the antipode.
    let (end, d_end) = walker.walk(start, Limit::Distance(3.0 * std::f64::consts::PI), |_| true);
    assert_eq!(d_end, 3.0 * std::f64::consts::PI);
    assert!(
        (end.point - DVec4::new(0.0, 0.0, 0.0, -1.0)).length() < 1e-12,
        "{end:?}"
    );
    assert!(d.is_finite());
}

#[test]
fn a_huge_direction_is_a_direction() {
    let s = product("bitorus-circle");
    let big = chart_ray(s.base(), DVec3::ZERO, DVec3::new(1e200, 0.0, 1e200)).unwrap();
    let unit = chart_ray(s.base(), DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)).unwrap();
    assert!((big.tangent - unit.tangent).length() < 1e-15, "{big:?}");
    assert!(chart_ray(s.base(), DVec3::ZERO, DVec3::new(1e-320, 0.0, 0.0)).is_ok());
    assert!(chart_ray(s.base(), DVec3::ZERO, DVec3::ZERO).is_err());
    assert!(chart_ray(s.base(), DVec3::ZERO, DVec3::new(f64::NAN, 0.0, 1.0)).is_err());
}

#[test]
fn a_circle_whose_half_is_not_a_number_is_refused() {
    for id in [
        "surface-abABcdCD-circle-5e-324",
        "surface-abABcdCD-circle-4e-308",
        "surface-aA-circle-5e-324",
    ] {
        match product_space(id) {
            Some(Err(e)) => assert!(e.contains("4.4502e-308"), "{id}: {e}"),
            other => panic!("{id}: {other:?}"),
        }
    }
    // The smallest accepted circle makes a cell of positive height.
    let s = product("surface-abABcdCD-circle-4.4502e-308");
    assert!(0.5 * s.length() > 0.0);
    assert!(
        !product("surface-abABcdCD-circle-1e308")
            .volume()
            .is_finite()
    );
}

#[test]
fn a_chart_point_past_f64_squares_is_not_the_zero_vector() {
    let s3 = Geometry::Spherical;
    let p = s3.from_chart(DVec3::new(1e160, 0.0, 0.0)).unwrap();
    assert!((p.length() - 1.0).abs() < 1e-15 && p.x > 0.999_999, "{p:?}");
    let poincare = space("poincare");
    assert!(poincare.outside_by(p) > 0.1, "{}", poincare.outside_by(p));
    // Ordinary points are untouched by the rescaling (it applies past 1e150 only).
    let q = s3.from_chart(DVec3::new(0.3, -2.0, 7.0)).unwrap();
    assert_eq!(q, s3.project_point(DVec4::new(0.3, -2.0, 7.0, 1.0)));
}

#[test]
fn lamp_radii_past_f64_are_refused_and_small_ones_stay_finite() {
    let s = space("torus");
    let p = s.geometry().from_chart(DVec3::new(0.1, 0.0, 0.0)).unwrap();
    assert!(matches!(
        fluence(&s, p, p, 1.0, 1.0, 1e-160),
        Err(FluenceError::Radius(_))
    ));
    let f = fluence(&s, p, p, 1.0, 1.0, 1e-150).unwrap();
    assert!(f.exact.is_finite() && f.bound.is_finite(), "{f:?}");
}

#[test]
fn the_bound_holds_in_thick_hyperbolic_fog() {
    // sinh(2r) overflows sixty fog distances out: the bound once came out 0 here.
    let s = space("seifert-weber");
    let chart = |x: [f64; 3]| s.geometry().from_chart(DVec3::from_array(x)).unwrap();
    let (lamp, at) = (chart([0.0, 0.0, 0.0]), chart([0.2, 0.1, 0.0]));
    for fog in [6.0, 12.0] {
        let f = fluence(&s, lamp, at, fog, 2.0, 0.05).unwrap();
        let check = fluence(&s, lamp, at, fog, 3.0, 0.05).unwrap();
        let gap = (f.total() - check.total()).abs();
        assert!(f.bound.is_finite() && f.bound > 0.0, "fog {fog}: {f:?}");
        assert!(
            gap <= f.bound + check.bound,
            "fog {fog}: {gap} past {}",
            f.bound
        );
    }
}

#[test]
fn the_light_never_comes_out_null() {
    let torus = space("torus");
    let poincare = space("poincare");
    let at = |s: &bevy_curved_spaces::space::Space| {
        s.geometry().from_chart(DVec3::new(0.1, 0.0, 0.0)).unwrap()
    };
    let origin = DVec4::W;
    // S³ with nearly no fog: 1 − e^(−2π/λ) kept by expm1; the sum is a number or refused.
    for fog in [1e300, 1e307, 1e308] {
        match fluence(&poincare, origin, at(&poincare), fog, 1.0, 0.05) {
            Ok(f) => assert!(f.total().is_finite(), "fog {fog}: {f:?}"),
            Err(e) => assert!(matches!(e, FluenceError::Overflow { .. }), "{e}"),
        }
    }
    // E³ with a fog so long that the tail overflows: refused by name.
    assert!(matches!(
        fluence(&torus, origin, at(&torus), 1e308, 1.0, 0.05),
        Err(FluenceError::Overflow { .. })
    ));
    // The shortest reach there is: a finite bound.
    let f = fluence(&torus, origin, at(&torus), 1.0, 5e-324, 0.05).unwrap();
    assert!(f.bound.is_finite() && f.tail.is_finite(), "{f:?}");
}

#[test]
fn the_default_reach_bounds_the_rest_within_a_percent_where_it_can() {
    let torus = space("torus");
    let chart = |x: [f64; 3]| torus.geometry().from_chart(DVec3::from_array(x)).unwrap();
    let fog = bevy_curved_spaces::scene::Shading::default_fog_distance(&torus);
    let (f, within) = fluence_within(
        &torus,
        chart([0.1, -0.2, 0.05]),
        chart([-0.3, 0.25, 0.4]),
        fog,
        0.05,
        0.01,
    )
    .unwrap();
    assert!(within, "{f:?}");
    assert!(f.bound <= 0.01 * f.total(), "{f:?}");
    // And the bound holds: against a sum out to twice the reach.
    let far = fluence(
        &torus,
        chart([0.1, -0.2, 0.05]),
        chart([-0.3, 0.25, 0.4]),
        fog,
        2.0 * f.reach,
        0.05,
    )
    .unwrap();
    assert!((f.total() - far.total()).abs() <= f.bound + far.bound);
    // A huge fog is refused as a fog: the light overflows (not "a reach of inf").
    let e = fluence_within(
        &torus,
        chart([0.0; 3]),
        chart([0.1, 0.0, 0.0]),
        1e308,
        0.05,
        0.01,
    )
    .unwrap_err();
    assert!(matches!(e, FluenceError::Overflow { .. }), "{e}");
    assert!(e.to_string().contains("--fog"), "{e}");
}

#[test]
fn a_many_sided_surface_finds_its_systole_among_few_elements() {
    // A 52-letter word: genus 13 with one vertex, a 52-gon with corners of 2π/52. Its
    // circumradius is about 6.3 and its inradius 3.5: searching within the systole plus
    // twice the circumradius once took tens of thousands of elements.
    let word: String = (0..13)
        .map(|k| {
            let (a, b) = (
                (b'a' + 2 * (k % 13) as u8) as char,
                (b'b' + 2 * (k % 13) as u8) as char,
            );
            format!("{a}{b}{}{}", a.to_ascii_uppercase(), b.to_ascii_uppercase())
        })
        .collect();
    assert_eq!(word.len(), 52);
    let s = product(&format!("surface-{word}-circle-100"));
    let r = s
        .injectivity_radius(5_000)
        .expect("found within 5000 elements");
    assert!(r > 0.0 && r.is_finite(), "{r}");
}

#[test]
fn an_exported_cell_is_the_exact_cell_rounded_once() {
    use bevy_curved_spaces::geometry::DoubleDouble;
    use bevy_curved_spaces::space::SEED_SPACES;
    use bevy_curved_spaces::space::file::SpaceRecord;
    let mut checked = 0;
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let Some(exact) = space.exact() else {
            continue;
        };
        let record = SpaceRecord::from_space(&space);
        for (f, (face, want)) in record.faces.iter().zip(&exact.faces).enumerate() {
            let normal = want.normal.map(DoubleDouble::round_f64);
            assert_eq!(face.normal, normal, "{} face {f}", seed.id);
            assert_eq!(face.offset, want.offset.round_f64(), "{} face {f}", seed.id);
            if let Some(pairing) = face.pairing {
                // Written row by row.
                let m = want.pairing.round_f64().transpose().to_cols_array_2d();
                assert_eq!(pairing, m, "{} face {f}", seed.id);
            }
            checked += 1;
        }
    }
    assert!(checked > 50, "{checked} faces");
}

#[test]
fn a_frame_past_the_equator_of_the_three_sphere_keeps_its_point() {
    use bevy_curved_spaces::space::frame_on_model;
    use glam::DMat4;
    let s3 = space("three-sphere");
    // The frame 3 along x from the centre: its point (sin 3, 0, 0, cos 3) has w < 0.
    let (sin, cos) = 3f64.sin_cos();
    let frame = DMat4::from_cols(
        DVec4::new(cos, 0.0, 0.0, -sin),
        DVec4::Y,
        DVec4::Z,
        DVec4::new(sin, 0.0, 0.0, cos),
    );
    let kept = frame_on_model(&s3, frame);
    assert!((kept.w_axis - frame.w_axis).length() < 1e-12, "{kept:?}");
    assert!((kept.x_axis - frame.x_axis).length() < 1e-12, "{kept:?}");
    // Where points stay in w > 0 (Poincaré), it is the usual projection.
    let poincare = space("poincare");
    let f = bevy_curved_spaces::view::TraceCamera::default_for(&poincare).frame;
    assert_eq!(
        frame_on_model(&poincare, f),
        Geometry::Spherical.orthonormalize_frame(f)
    );
}

#[test]
fn the_packing_of_the_images_tightens_the_hyperbolic_bound() {
    // Disjoint balls of half the lamp's shortest image distance bound the count of images
    // by V(r + p)/V(p): in H³ far below V(r + ρ)/vol (ρ ≈ 1.9 in Seifert–Weber, e^(2ρ) ≈ 45).
    let s = space("seifert-weber");
    let chart = |x: [f64; 3]| s.geometry().from_chart(DVec3::from_array(x)).unwrap();
    let (lamp, at) = (chart([0.0; 3]), chart([0.1, 0.05, 0.0]));
    let fog = bevy_curved_spaces::scene::Shading::default_fog_distance(&s);
    let (f, _) = fluence_within(&s, lamp, at, fog, 0.05, 0.01).unwrap();
    assert!(f.bound < 0.2 * f.total(), "{f:?}");
    // And it holds: the sums to this reach and to one a unit shorter (the default is near
    // the image limit) agree within their two bounds.
    let short = fluence(&s, lamp, at, fog, f.reach - 1.0, 0.05).unwrap();
    let gap = (f.total() - short.total()).abs();
    assert!(
        gap <= f.bound + short.bound,
        "{gap} past {}",
        f.bound + short.bound
    );
}
