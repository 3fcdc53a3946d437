//! Dirichlet domains: stable under more elements, another basepoint, the library's
//! families and their parameters, cells that reach the equator, mirrored lenses.

use super::*;

#[test]
fn the_domain_does_not_change_when_more_elements_are_tried() {
    for id in ["census-1", "census-10", "seifert-weber-group"] {
        let s = library(id);
        let text = write_gen(&s);
        let generators = Generators::new(&parse_gen(&text).unwrap().matrices).unwrap();
        let wide = DirichletOptions {
            min_radius: 2.0 * circumradius(&s) + 2.5,
            ..DirichletOptions::default()
        };
        let again = dirichlet_space(id, "", &generators, &wide).unwrap();
        assert!(congruent(&s, &again, 1e-9), "{id}");
    }
}

#[test]
fn a_moved_basepoint_gives_another_domain_of_the_same_space() {
    let s = resolve_space("half-turn", Path::new(""), &DirichletOptions::default()).unwrap();
    let file = parse_gen(&write_gen(&s)).unwrap();
    let moved = DirichletOptions {
        basepoint: Some(DVec3::new(0.2, 0.1, 0.0)),
        ..DirichletOptions::default()
    };
    let other = space_from_matrices("moved", "", &file.matrices, &moved).unwrap();
    assert!((volume(&other) - volume(&s)).abs() < 1e-12);
    assert_eq!(first_homology(&other), first_homology(&s));
    assert!(!congruent(&other, &s, 1e-6), "the cell should change shape");
}

#[test]
fn bad_family_parameters_are_named() {
    for (id, needle) in [
        ("lens-6-3", "common factor 3"),
        ("lens-5-5", "1 ≤ Q < P"),
        ("lens-2-1", "projective-space"),
        ("lens-1001-2", "P ≤ 1000"),
        ("prism-1", "2 ≤ N"),
        ("census-11", "census-10"),
        ("census-0", "census-10"),
        ("torus-1-0-1", "positive"),
        ("torus-1-1-1e9", "1000 to 1"),
    ] {
        match library_space(id) {
            Some(Err(e)) => assert!(e.contains(needle), "{id}: {e}"),
            other => panic!("{id}: {:?}", other.map(|r| r.map(|s| s.name().to_string()))),
        }
    }
    assert!(library_space("lens-x-2").is_none());
    assert!(library_space("prism").is_none());
}

/// A long random walk in the Weeks manifold and a lens space stays in the cell, with a
/// valid frame.
#[test]
fn a_long_walk_stays_in_the_cell() {
    use bevy_curved_spaces::plugin::components::{PlayerMotion, PlayerSettings};
    use bevy_curved_spaces::plugin::player::step_frame;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::wrap_into_cell;
    for id in ["weeks", "lens-7-2", "lens-7-1", "projective-space"] {
        let space = library(id);
        let g = space.geometry();
        let r = inradius(&space);
        let margin = PlayerSettings::default().wrap_margin;
        let mut rng = SplitMix64(7);
        let mut next = || 2.0 * rng.unit() - 1.0;
        let mut frame = bevy_curved_spaces::view::TraceCamera::default_for(&space).frame;
        let mut crossings = 0;
        for step in 0..100_000 {
            let motion = PlayerMotion {
                translation: DVec3::new(next(), next(), next()) * 0.2 * r,
                rotation: DVec3::new(next(), next(), next()) * 0.2,
            };
            let (wrapped, crossed) = wrap_into_cell(&space, step_frame(g, frame, &motion), margin);
            frame = wrapped;
            crossings += crossed.len();
            if step % 1000 == 999 {
                let outside = space.outside_by(frame.w_axis);
                assert!(outside <= 2.0 * margin, "{id} step {step}: {outside:.3e}");
                assert!(g.frame_defect(frame) < 1e-9, "{id} step {step}");
            }
        }
        assert!(crossings > 1000, "{id}: only {crossings} crossings");
    }
}

/// The cells beyond the chart: what they are made of, their invariants, their round trip
/// through a generator file, and walks through them that never divide by `w`.
#[test]
fn cells_reaching_the_equator_are_whole_spaces() {
    use bevy_curved_spaces::space::invariants::injectivity_radius;
    use bevy_curved_spaces::space::{CellWalker, Limit};
    let sphere = library("three-sphere");
    assert!(sphere.reaches_equator() && sphere.faces().is_empty());
    assert!((inradius(&sphere) - PI).abs() < 1e-12);
    assert_eq!(injectivity_radius(&sphere), Some(PI));
    let rp3 = library("projective-space");
    assert_eq!(rp3.faces().len(), 1);
    assert_eq!(rp3.faces()[0].partner, 0);
    assert!((circumradius(&rp3) - PI / 2.0).abs() < 1e-12);
    let lens = library("lens-7-1");
    assert_eq!(lens.faces().len(), 2);
    assert!((inradius(&lens) - PI / 7.0).abs() < 1e-12);
    // A Clifford translation's two rotation angles are equal: the displacement, a double
    // root of its trace polynomial, is known only to about √ε of the pairing's rounding.
    assert!((injectivity_radius(&lens).unwrap() - PI / 7.0).abs() < 2e-8);
    // Every lens L(P, Q) about a Hopf circle's point is such a lens too.
    assert!(library("lens-9-8").reaches_equator());
    assert!(!library("lens-9-2").reaches_equator());
    // Round trips.
    for s in [&rp3, &lens] {
        let file = parse_gen(&write_gen(s)).unwrap();
        let back =
            space_from_matrices("back", "", &file.matrices, &DirichletOptions::default()).unwrap();
        assert!(back.reaches_equator());
        assert!((volume(&back) - volume(s)).abs() < 1e-12);
        assert_eq!(first_homology(&back), first_homology(s));
    }
    // A walk by crossings ends in the 3-sphere although it never crosses (steps of π/4,
    // at most 16 in a row), and a walk by distance goes round it.
    let walker = CellWalker::<DVec4>::new(&sphere);
    let camera = bevy_curved_spaces::view::TraceCamera::default_for(&sphere);
    let ray = camera.ray(Geometry::Spherical, 10, 10, 20, 20);
    let trace = walker.trace(ray, Limit::Crossings(5));
    assert!(trace.crossings.is_empty());
    let round = walker.trace(ray, Limit::Distance(2.0 * PI));
    assert!(Geometry::Spherical.distance(round.end.point, ray.point) < 1e-9);
    // In projective space a ray comes back to its start after π, turned round by −I.
    let walker = CellWalker::<DVec4>::new(&rp3);
    let trace = walker.trace(ray, Limit::Distance(PI));
    assert_eq!(trace.crossings.len(), 1);
    assert!(Geometry::Spherical.distance(trace.end.point, ray.point) < 1e-9);
}

/// The lens L(7,1)'s edge is a great circle at π/2 without vertices: the default scene draws
/// it as four quarter tubes, and a ray towards a point of it meets one of them.
#[test]
fn the_lens_edge_circle_is_drawn_and_hit() {
    use bevy_curved_spaces::scene::{CurvedScene, Object, SceneParts, Shading};
    use bevy_curved_spaces::space::CellWalker;
    use bevy_curved_spaces::trace::{RayEnd, first_hit};
    let lens = library("lens-7-1");
    let scene = CurvedScene::with_parts(
        &lens,
        Shading::default_fog_distance(&lens),
        SceneParts::default(),
    );
    let tubes: Vec<_> = scene
        .objects
        .iter()
        .filter_map(|o| match o {
            Object::Tube(t) => Some(t),
            _ => None,
        })
        .collect();
    assert_eq!(tubes.len(), 4);
    for t in &tubes {
        // On both faces' great spheres, at π/2 from the centre, a quarter circle long.
        for p in [t.a, t.b] {
            assert!(lens.faces().iter().all(|f| f.covector.dot(p).abs() < 1e-12));
            assert!((Geometry::Spherical.distance(ORIGIN, p) - PI / 2.0).abs() < 1e-12);
        }
        assert!((Geometry::Spherical.distance(t.a, t.b) - PI / 2.0).abs() < 1e-12);
    }
    // From beside the centre ball towards the middle of the first quarter.
    let g = Geometry::Spherical;
    let target = g.project_point(tubes[0].a + tubes[0].b);
    let eye = g.project_point(DVec4::new(0.0, 0.0, 0.0, 1.0) + 0.2 * (tubes[0].a - tubes[0].b));
    let point = eye;
    let tangent = g.tangent_towards(point, target);
    let walker = CellWalker::<DVec4>::new(&lens);
    let end = first_hit(
        &walker,
        &scene,
        bevy_curved_spaces::geometry::Ray { point, tangent },
        16,
    );
    match end {
        RayEnd::Hit(hit) => assert!(
            matches!(scene.objects[hit.object], Object::Tube(_)),
            "hit object {} instead of a tube",
            hit.object
        ),
        other => panic!("the ray towards the circle met nothing: {other:?}"),
    }
}

/// The flat families with a stretched lattice keep their kind (orientability, H₁) and
/// their volume is the stretched lattice's covolume over the holonomy order.
#[test]
fn flat_manifolds_take_their_lattice_shape_as_parameters() {
    use bevy_curved_spaces::space::invariants::holonomy_order;
    let s3 = 0.75f64.sqrt();
    // (family, id with sizes, unit-cell covolume per unit of A·B·C, orientable, H₁).
    let cases = [
        ("half-turn", "half-turn-1-2-3", 1.0, true, "Z/2 + Z/2 + Z"),
        (
            "hantzsche-wendt",
            "hantzsche-wendt-1-2-3",
            1.0,
            true,
            "Z/4 + Z/4",
        ),
        (
            "first-amphicosm",
            "first-amphicosm-1-2-3",
            1.0,
            false,
            "Z/2 + Z + Z",
        ),
        (
            "second-amphicosm",
            "second-amphicosm-1-2-3",
            0.5,
            false,
            "Z + Z",
        ),
        (
            "first-amphidicosm",
            "first-amphidicosm-1-2-3",
            1.0,
            false,
            "Z/2 + Z/2 + Z",
        ),
        (
            "second-amphidicosm",
            "second-amphidicosm-1-2-3",
            1.0,
            false,
            "Z/4 + Z",
        ),
        ("quarter-turn", "quarter-turn-2-3", 1.0, true, "Z/2 + Z"),
        ("third-turn", "third-turn-2-3", s3, true, "Z/3 + Z"),
        ("sixth-turn", "sixth-turn-2-3", s3, true, "Z"),
    ];
    for (family, id, covolume, orientable, h1) in cases {
        let s = library(id);
        let holonomy = holonomy_order(&s).unwrap() as f64;
        // A·B·C = 6 for 1-2-3; 2·2·3 = 12 for A-C = 2-3.
        let abc = if id.matches('-').count() - family.matches('-').count() == 3 {
            6.0
        } else {
            12.0
        };
        let expected = covolume * abc / holonomy;
        assert!(
            (volume(&s) - expected).abs() < 1e-9 * expected,
            "{id}: volume {} against {expected}",
            volume(&s)
        );
        assert!(s.manifold(), "{id}");
        assert_eq!(s.orientable(), orientable, "{id}");
        assert_eq!(first_homology(&s), Homology::parse(h1).unwrap(), "{id}");
    }
    for bad in [
        "half-turn-0-1-1",
        "quarter-turn-1-2000",
        "hantzsche-wendt-1-1-inf",
    ] {
        assert!(
            matches!(library_space(bad), Some(Err(ref e)) if e.contains("1000 to 1")),
            "{bad}"
        );
    }
}

/// The mirrored lenses: the dihedral group of order 2n generated by two reflections whose
/// mirrors contain the great circle `z = w = 0` and meet there at π/n (Curved Spaces'
/// "Mirrored Lens 2n" files, rebuilt here from that definition). Their Dirichlet domain
/// about the origin is a lens reaching π/2; it loads as an orbifold with two mirror faces,
/// the right volume, inradius, edge order and homology, and rays walked in it stay in the
/// cell and come back mirrored.
#[test]
fn mirrored_lenses_load_walk_and_stay_in_their_cell() {
    use bevy_curved_spaces::space::{CellWalker, Limit};
    use bevy_curved_spaces::trace::sample_rays;
    // Reflection of the zw-plane across the line at angle t from the w axis.
    let reflection = |t: f64| {
        let (c, s) = ((2.0 * t).cos(), (2.0 * t).sin());
        DMat4::from_cols(
            DVec4::X,
            DVec4::Y,
            DVec4::new(0.0, 0.0, -c, s),
            DVec4::new(0.0, 0.0, s, c),
        )
    };
    for n in [2u32, 3, 4, 6, 12] {
        let half = PI / (2.0 * f64::from(n));
        let gens = [reflection(half), reflection(-half)];
        for g in &gens {
            assert!(max_entry(*g * *g - DMat4::IDENTITY) < 1e-15);
        }
        let space = space_from_matrices("lens", "", &gens, &DirichletOptions::default())
            .unwrap_or_else(|e| panic!("mirrored lens {}: {e}", 2 * n));
        let order = 2 * n as usize;
        assert!(space.reaches_equator() && !space.manifold() && !space.orientable());
        assert_eq!(space.faces().len(), 2);
        assert!(
            space
                .faces()
                .iter()
                .enumerate()
                .all(|(i, f)| f.is_mirror(i))
        );
        assert_eq!(group_order(&space), Some(order));
        assert!((volume(&space) - 2.0 * PI * PI / order as f64).abs() < 1e-9);
        assert!((inradius(&space) - half).abs() < 1e-12);
        assert_eq!(space.edge_cycles().len(), 1);
        assert_eq!(space.edge_cycles()[0].order, n);
        // D_n abelianised: Z/2 for n odd, Z/2 + Z/2 for n even.
        let h = first_homology(&space);
        let want: Vec<u64> = if n % 2 == 1 { vec![2] } else { vec![2, 2] };
        assert_eq!((h.rank, h.torsion.clone()), (0, want), "D{n}: {h}");
        // Rays walked through the mirrors stay in the cell, 20 crossings on.
        let walker = CellWalker::<DVec4>::new(&space);
        for ray in sample_rays(&space, 24, 0x1e5) {
            let trace = walker.trace(ray, Limit::Distance(6.0 * PI));
            assert!(space.outside_by(trace.end.point) < 1e-9);
            assert!(!trace.crossings.is_empty());
        }
    }
    // One mirror: the hemisphere on the origin's side of it.
    let one = space_from_matrices(
        "mirror",
        "",
        &[reflection(0.3)],
        &DirichletOptions::default(),
    )
    .unwrap();
    assert_eq!(one.faces().len(), 1);
    assert!(one.faces()[0].is_mirror(0) && !one.manifold());
    assert!((volume(&one) - PI * PI).abs() < 1e-9);
    // A rotation fixing a great circle is still refused, with the reason.
    let turn = DMat4::from_cols(
        DVec4::X,
        DVec4::Y,
        DVec4::new(0.0, 0.0, 0.5, 0.75f64.sqrt()),
        DVec4::new(0.0, 0.0, -(0.75f64.sqrt()), 0.5),
    );
    let refused = space_from_matrices("turn", "", &[turn], &DirichletOptions::default());
    assert!(
        matches!(refused, Err(GroupError::ReachesEquator { .. })),
        "{refused:?}"
    );
}
