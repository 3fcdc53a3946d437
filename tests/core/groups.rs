//! Spaces from groups: generator files read and written, Dirichlet domains against the seed
//! cells and closed forms, the library against SnapPy's stored numbers, and every kind of
//! bad generator refused with the right error.

use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use bevy_curved_spaces::space::dirichlet::{
    DirichletOptions, dirichlet_space, space_from_matrices,
};
use bevy_curved_spaces::space::group::{Generators, GroupError, parse_gen, write_gen};
use bevy_curved_spaces::space::homology::{Homology, first_homology};
use bevy_curved_spaces::space::invariants::{circumradius, group_order, inradius, volume};
use bevy_curved_spaces::space::library::{CENSUS, library_space, quaternion_map};
use bevy_curved_spaces::space::{SEED_SPACES, Space, resolve_space, seed_space};
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4};
use std::f64::consts::PI;
use std::path::Path;

fn library(id: &str) -> Space {
    match library_space(id) {
        Some(Ok(s)) => s,
        Some(Err(e)) => panic!("{id}: {e}"),
        None => panic!("{id} is no library id"),
    }
}

fn max_entry(m: DMat4) -> f64 {
    m.to_cols_array()
        .iter()
        .fold(0.0_f64, |a, x| a.max(x.abs()))
}

/// Whether two cells are the same up to a rotation about the centre (proper, so the
/// handedness of twists counts) and a renumbering of faces: the rotation carries each face
/// plane of `a` onto one of `b`, partners onto partners, and conjugates the pairings.
fn congruent(a: &Space, b: &Space, tol: f64) -> bool {
    if a.geometry() != b.geometry() || a.faces().len() != b.faces().len() {
        return false;
    }
    let fa = a.faces();
    let fb = b.faces();
    // Two faces of `a` with independent normals fix the rotation.
    let i0 = 0;
    let Some(i1) = (1..fa.len()).find(|&i| fa[i].normal.cross(fa[i0].normal).length() > 0.1) else {
        return false;
    };
    let frame = |x: DVec3, y: DVec3| {
        let e0 = x.normalize();
        let e1 = (y - e0 * y.dot(e0)).normalize();
        DMat3::from_cols(e0, e1, e0.cross(e1))
    };
    let from = frame(fa[i0].normal, fa[i1].normal);
    for j0 in 0..fb.len() {
        for j1 in 0..fb.len() {
            if j0 == j1
                || (fb[j0].normal.dot(fb[j1].normal) - fa[i0].normal.dot(fa[i1].normal)).abs() > tol
            {
                continue;
            }
            let r3 = frame(fb[j0].normal, fb[j1].normal) * from.transpose();
            let r = DMat4::from_mat3(r3);
            let matched: Option<Vec<usize>> = fa
                .iter()
                .map(|f| {
                    fb.iter().position(|g| {
                        (r3 * f.normal - g.normal).length() < tol
                            && (f.offset - g.offset).abs() < tol * f.offset.max(1.0)
                    })
                })
                .collect();
            let Some(m) = matched else { continue };
            let ok = fa.iter().enumerate().all(|(i, f)| {
                fb[m[i]].partner == m[f.partner]
                    && max_entry(r * f.pairing * r.transpose() - fb[m[i]].pairing)
                        < tol * max_entry(f.pairing).max(1.0)
            });
            if ok {
                return true;
            }
        }
    }
    false
}

#[test]
fn generator_files_parse_with_comments_and_byte_order_mark() {
    let text = "\u{feff}# A torus\n#\tsecond line\n\
                1 0 0 0  0 1 0 0  0 0 1 0  1 0 0 1 # along x\n\
                1 0 0 0\n0 1 0 0\n0 0 1 0\n0 1 0 1\n\
                1 0 0 0 0 1 0 0 0 0 1 0 0 0 1 1\n";
    let file = parse_gen(text).unwrap();
    assert_eq!(file.comments, ["A torus", "second line"]);
    assert_eq!(file.matrices.len(), 3);
    // The bottom row of a .gen matrix is the image of the basepoint.
    assert_eq!(file.matrices[0] * ORIGIN, DVec4::new(1.0, 0.0, 0.0, 1.0));
    let space = space_from_matrices("t", "", &file.matrices, &DirichletOptions::default()).unwrap();
    assert_eq!(space.geometry(), Geometry::Euclidean);
    assert!((volume(&space) - 1.0).abs() < 1e-12);
}

#[test]
fn malformed_generator_files_name_the_problem() {
    type Expected = fn(&GroupError) -> bool;
    let cases: [(&str, Expected); 4] = [
        (
            "1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 zero 1\n",
            |e| matches!(e, GroupError::NotANumber { line: 4, token } if token == "zero"),
        ),
        ("1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 nan 1\n", |e| {
            matches!(e, GroupError::NotFinite { line: 4, .. })
        }),
        ("1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 0\n", |e| {
            matches!(
                e,
                GroupError::PartialMatrix {
                    count: 15,
                    left: 15,
                    matrices: 0
                }
            )
        }),
        (&"0 ".repeat(16 * 65), |e| {
            matches!(e, GroupError::TooManyGenerators { max: 64, .. })
        }),
    ];
    for (text, expected) in cases {
        let e = parse_gen(text).unwrap_err();
        assert!(expected(&e), "{text:.40}: {e}");
    }
}

#[test]
fn generators_that_do_not_fit_name_the_cause() {
    let check = |matrices: &[DMat4], expected: fn(&GroupError) -> bool, what: &str| {
        let e =
            space_from_matrices("x", "", matrices, &DirichletOptions::default()).expect_err(what);
        assert!(expected(&e), "{what}: {e}");
        assert!(!e.to_string().is_empty());
    };
    let t = |v: DVec3| {
        let mut m = DMat4::IDENTITY;
        m.w_axis = v.extend(1.0);
        m
    };
    let scaled = DMat4::from_diagonal(DVec4::new(2.0, 1.0, 1.0, 1.0));
    check(
        &[t(DVec3::X), scaled],
        |e| matches!(e, GroupError::NotAnIsometry { matrix: 2, .. }),
        "a scaling",
    );
    let rotation = quaternion_map(DQuat::from_rotation_z(0.5), DQuat::IDENTITY);
    check(
        &[t(DVec3::X), rotation],
        |e| {
            matches!(
                e,
                GroupError::MixedGeometries {
                    first: 1,
                    second: 2,
                    ..
                }
            )
        },
        "a translation and a rotation of S³",
    );
    check(
        &[DMat4::from_rotation_z(0.3)],
        |e| matches!(e, GroupError::FixesBasepoint { .. }),
        "a rotation about the basepoint",
    );
    // Two glides whose product is a rotation about the basepoint.
    let a = DMat4::from_rotation_z(PI / 2.0) * t(DVec3::X);
    let b = t(DVec3::X);
    let e = space_from_matrices("x", "", &[a, b], &DirichletOptions::default());
    assert!(
        matches!(e, Err(GroupError::FixesBasepoint { .. })),
        "a product fixing the basepoint: {e:?}"
    );
    check(
        &[t(DVec3::X), t(DVec3::X * 1.00001), t(DVec3::Y), t(DVec3::Z)],
        |e| matches!(e, GroupError::NotDiscrete { .. }),
        "translations 1 and 1.00001",
    );
    let near_seventh = quaternion_map(
        DQuat::from_rotation_z(2.0 * PI / 7.0 + 2e-5),
        DQuat::IDENTITY,
    );
    check(
        &[near_seventh],
        |e| matches!(e, GroupError::NotDiscrete { .. }),
        "almost a seventh turn of S³",
    );
    check(
        &[t(DVec3::X), t(DVec3::Y)],
        |e| matches!(e, GroupError::NotCocompact { .. }),
        "two translations",
    );
    let g = Geometry::Hyperbolic;
    check(
        &[g.translation(DVec3::X, 1.0)],
        |e| matches!(e, GroupError::NotCocompact { .. }),
        "one loxodromic",
    );
    // A Lorentz matrix that swaps the sheets of the hyperboloid.
    let swap = DMat4::from_diagonal(DVec4::new(1.0, 1.0, 1.0, -1.0)) * g.translation(DVec3::X, 1.0);
    check(
        &[swap],
        |e| matches!(e, GroupError::NotAnIsometry { .. }),
        "a sheet swap",
    );
    // A rotation fixing a great circle: its orbit of o lies on a circle, so the domain
    // reaches π/2, and it is an orbifold group (not drawn there).
    let p = 2.0 * PI / 5.0;
    let rotation_zw = DMat4::from_cols(
        DVec4::X,
        DVec4::Y,
        DVec4::new(0.0, 0.0, p.cos(), p.sin()),
        DVec4::new(0.0, 0.0, -p.sin(), p.cos()),
    );
    let e = space_from_matrices("x", "", &[rotation_zw], &DirichletOptions::default()).unwrap_err();
    assert!(
        matches!(&e, GroupError::ReachesEquator { what } if what.contains("orbifold")),
        "{e}"
    );
    let bad_basepoint = DirichletOptions {
        basepoint: Some(DVec3::new(2.0, 0.0, 0.0)),
        ..DirichletOptions::default()
    };
    let weeks = parse_gen(CENSUS[0].generators).unwrap().matrices;
    let e = space_from_matrices("x", "", &weeks, &bad_basepoint).unwrap_err();
    assert!(matches!(e, GroupError::BadBasepoint { .. }), "{e}");
}

#[test]
fn every_seed_space_round_trips_through_a_generator_file() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let text = write_gen(&space);
        let file = parse_gen(&text).unwrap();
        let faces = space.faces().len();
        let pairs = space
            .faces()
            .iter()
            .enumerate()
            .filter(|(i, f)| f.partner >= *i)
            .count();
        assert_eq!(file.matrices.len(), pairs, "{}", seed.id);
        let back = space_from_matrices(seed.id, "", &file.matrices, &DirichletOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", seed.id));
        assert_eq!(back.faces().len(), faces, "{}", seed.id);
        assert!(
            congruent(&space, &back, 1e-9),
            "{}: the Dirichlet domain of its own pairings is not its cell",
            seed.id
        );
        assert!((volume(&back) - volume(&space)).abs() < 1e-9 * volume(&space));
    }
}

#[test]
fn library_spaces_equal_the_seed_spaces_they_name() {
    assert!(congruent(
        &library("seifert-weber-group"),
        &seed_space("seifert-weber").unwrap(),
        1e-9
    ));
    let icosahedral = library("binary-icosahedral");
    let poincare = seed_space("poincare").unwrap();
    assert!(
        congruent(&icosahedral, &poincare, 1e-9),
        "the binary icosahedral group's Dirichlet domain is not the Poincaré dodecahedron"
    );
}

#[test]
fn spherical_volumes_are_two_pi_squared_over_the_group_order() {
    let mut cases: Vec<(String, usize)> = vec![
        ("binary-tetrahedral".into(), 24),
        ("binary-octahedral".into(), 48),
        ("binary-icosahedral".into(), 120),
        ("mirrored-tetrahedron".into(), 16),
    ];
    for n in [2, 3, 5, 8] {
        cases.push((format!("prism-{n}"), 4 * n));
    }
    for (p, q) in [(5, 2), (7, 2), (7, 3), (8, 3), (12, 5), (60, 7), (60, 11)] {
        cases.push((format!("lens-{p}-{q}"), p));
    }
    // Cells reaching π/2: the 3-sphere, projective space, lenses L(P, 1) and L(P, P − 1).
    cases.push(("three-sphere".into(), 1));
    cases.push(("projective-space".into(), 2));
    for p in [3, 7, 60] {
        cases.push((format!("lens-{p}-1"), p));
        cases.push((format!("lens-{p}-{}", p - 1), p));
    }
    for (id, order) in cases {
        let s = library(&id);
        let expected = 2.0 * PI * PI / order as f64;
        assert!(
            (volume(&s) - expected).abs() < 1e-9 * expected,
            "{id}: volume {} against 2π²/{order}",
            volume(&s)
        );
        assert_eq!(group_order(&s), Some(order), "{id}");
    }
}

#[test]
fn flat_volumes_are_lattice_covolumes_over_the_holonomy() {
    use bevy_curved_spaces::space::invariants::holonomy_order;
    let cases = [
        ("torus-1-2-3", 6.0, 1),
        ("torus-hexagonal", 0.75f64.sqrt(), 1),
        ("torus-fcc", 2.0, 1),
        ("torus-bcc", 4.0, 1),
        // Glide² = (0, 0, 1): lattice covolume 1 (Pc) and ½ (Cc), holonomy 2.
        ("first-amphicosm", 0.5, 2),
        ("second-amphicosm", 0.25, 2),
        // Screw² = (0, 0, 1), glide² = (1, 0, 0), and (0, 1, 0): covolume 1, holonomy 4.
        ("first-amphidicosm", 0.25, 4),
        ("second-amphidicosm", 0.25, 4),
    ];
    for (id, v, holonomy) in cases {
        let s = library(id);
        assert!((volume(&s) - v).abs() < 1e-12, "{id}: {}", volume(&s));
        assert_eq!(holonomy_order(&s), Some(holonomy), "{id}");
    }
}

#[test]
fn the_ten_flat_manifolds_are_told_apart_by_orientability_and_homology() {
    // (id, orientable, H₁) from Wolf's classification.
    let cases = [
        ("torus", true, "Z + Z + Z"),
        ("half-turn", true, "Z/2 + Z/2 + Z"),
        ("quarter-turn", true, "Z/2 + Z"),
        ("third-turn", true, "Z/3 + Z"),
        ("sixth-turn", true, "Z"),
        ("hantzsche-wendt", true, "Z/4 + Z/4"),
        ("first-amphicosm", false, "Z/2 + Z + Z"),
        ("second-amphicosm", false, "Z + Z"),
        ("first-amphidicosm", false, "Z/2 + Z/2 + Z"),
        ("second-amphidicosm", false, "Z/4 + Z"),
    ];
    for (id, orientable, h1) in cases {
        let s = resolve_space(id, Path::new(""), &DirichletOptions::default()).unwrap();
        assert!(s.manifold(), "{id}");
        assert_eq!(s.orientable(), orientable, "{id}");
        assert_eq!(first_homology(&s), Homology::parse(h1).unwrap(), "{id}");
    }
}

#[test]
fn homology_of_spherical_spaces_is_the_abelianised_group() {
    let cases = [
        ("poincare", "0"),
        ("binary-icosahedral", "0"),
        ("binary-tetrahedral", "Z/3"),
        ("binary-octahedral", "Z/2"),
        ("prism-2", "Z/2 + Z/2"),
        ("prism-3", "Z/4"),
        ("prism-4", "Z/2 + Z/2"),
        ("lens-7-2", "Z/7"),
        ("lens-7-1", "Z/7"),
        ("projective-space", "Z/2"),
        ("three-sphere", "0"),
        ("lens-60-7", "Z/60"),
        ("seifert-weber", "Z/5 + Z/5 + Z/5"),
    ];
    for (id, h1) in cases {
        let s = resolve_space(id, Path::new(""), &DirichletOptions::default()).unwrap();
        assert_eq!(first_homology(&s), Homology::parse(h1).unwrap(), "{id}");
    }
}

/// SnapPy's numbers, stored beside each shipped census file.
#[derive(serde::Deserialize)]
struct Reference {
    name: String,
    volume: f64,
    homology: String,
    inradius: f64,
    outradius: f64,
}

#[test]
fn census_manifolds_match_snappy() {
    for (i, m) in CENSUS.iter().enumerate() {
        let id = format!("census-{}", i + 1);
        let s = library(&id);
        let r: Reference = serde_json::from_str(m.reference).unwrap();
        assert_eq!(r.name, m.snappy_name);
        assert!(s.manifold() && s.orientable(), "{id}");
        let v = volume(&s);
        assert!(
            (v - r.volume).abs() < 1e-9 * r.volume,
            "{id} ({}): volume {v} against SnapPy's {}",
            r.name,
            r.volume
        );
        assert_eq!(
            first_homology(&s),
            Homology::parse(&r.homology).unwrap(),
            "{id}"
        );
        // The same basepoint as SnapPy's domain, so the same radii.
        assert!((inradius(&s) - r.inradius).abs() < 1e-9, "{id} inradius");
        assert!(
            (circumradius(&s) - r.outradius).abs() < 1e-9,
            "{id} circumradius"
        );
    }
    assert!(congruent(&library("weeks"), &library("census-1"), 1e-12));
}

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
fn every_library_manifold_has_euler_characteristic_zero() {
    let mut ids: Vec<String> = [
        "binary-tetrahedral",
        "binary-octahedral",
        "binary-icosahedral",
        "prism-2",
        "prism-7",
        "lens-5-2",
        "lens-7-3",
        "lens-60-7",
        "torus-hexagonal",
        "torus-fcc",
        "torus-bcc",
        "first-amphicosm",
        "second-amphicosm",
        "first-amphidicosm",
        "second-amphidicosm",
        "seifert-weber-group",
    ]
    .map(String::from)
    .to_vec();
    ids.extend((1..=CENSUS.len()).map(|n| format!("census-{n}")));
    for id in ids {
        let s = library(&id);
        assert!(s.manifold(), "{id}");
        let pairs = s
            .faces()
            .iter()
            .enumerate()
            .filter(|(i, f)| f.partner >= *i)
            .count() as i64;
        let chi = s.vertex_cycles().len() as i64 - s.edge_cycles().len() as i64 + pairs - 1;
        assert_eq!(chi, 0, "{id}");
        for cycle in s.edge_cycles() {
            assert_eq!(cycle.order, 1, "{id}");
            assert!((cycle.angle_sum - 2.0 * PI).abs() < 1e-9, "{id}");
        }
    }
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

#[test]
fn the_census_loads_from_its_shipped_files_as_from_the_library() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/spaces/census");
    let from_file = resolve_space("m003_-3_1.gen", &dir, &DirichletOptions::default()).unwrap();
    assert!(congruent(&from_file, &library("weeks"), 1e-12));
}

#[derive(serde::Deserialize)]
struct SpectrumEntry {
    length: f64,
    multiplicity: usize,
}

#[derive(serde::Deserialize)]
struct SpectrumReference {
    length_spectrum_cutoff: f64,
    length_spectrum: Vec<SpectrumEntry>,
}

/// SnapPy's length spectrum summed over torsion: (length, count), to 1e-6.
fn snappy_spectrum(reference: &str) -> (f64, Vec<(f64, usize)>) {
    let r: SpectrumReference = serde_json::from_str(reference).unwrap();
    let mut out: Vec<(f64, usize)> = Vec::new();
    let mut entries = r.length_spectrum;
    entries.sort_by(|a, b| a.length.total_cmp(&b.length));
    for e in entries {
        match out.last_mut() {
            Some(last) if (e.length - last.0).abs() < 1e-6 => last.1 += e.multiplicity,
            _ => out.push((e.length, e.multiplicity)),
        }
    }
    (r.length_spectrum_cutoff, out)
}

/// The length spectrum from conjugacy classes, against the chord sums (whole numbers, the
/// same counts) and, for the census, against SnapPy.
#[test]
fn length_spectra_agree_by_two_routes_and_with_snappy() {
    use bevy_curved_spaces::space::invariants::{closed_geodesics, closed_geodesics_by_chords};
    let mut cases: Vec<(String, Option<&str>)> = CENSUS
        .iter()
        .enumerate()
        .map(|(i, m)| (format!("census-{}", i + 1), Some(m.reference)))
        .collect();
    cases.push(("seifert-weber".into(), None));
    for (id, reference) in cases {
        let s = resolve_space(&id, Path::new(""), &DirichletOptions::default()).unwrap();
        let cutoff = reference.map_or(2.5, |r| snappy_spectrum(r).0 - 1e-3);
        let classes = closed_geodesics(&s, cutoff).unwrap();
        let chords = closed_geodesics_by_chords(&s, cutoff).unwrap();
        eprintln!("{id}: classes {classes:?}");
        eprintln!("{id}: chords {chords:?}");
        assert_eq!(classes.len(), chords.len(), "{id}: lengths differ");
        for (c, (l, n)) in classes.iter().zip(&chords) {
            assert!(
                (c.length - l).abs() < 1e-9,
                "{id}: {} against {l}",
                c.length
            );
            assert!(
                (n - c.count as f64).abs() < 1e-6,
                "{id} at {l}: {} classes, chords say {n}",
                c.count
            );
        }
        if let Some(r) = reference {
            let (_, snappy) = snappy_spectrum(r);
            let snappy: Vec<(f64, usize)> =
                snappy.into_iter().filter(|(l, _)| *l <= cutoff).collect();
            let ours: Vec<(f64, usize)> = classes.iter().map(|c| (c.length, c.count)).collect();
            assert_eq!(
                ours.len(),
                snappy.len(),
                "{id}: {ours:?} against SnapPy's {snappy:?}"
            );
            for (a, b) in ours.iter().zip(&snappy) {
                assert!(
                    (a.0 - b.0).abs() < 1e-9 && a.1 == b.1,
                    "{id}: {a:?} against {b:?}"
                );
            }
        }
    }
}

/// The fuzz suite's share for generator files: shipped and exported `.gen` texts mutated
/// (numbers made hostile, lines dropped, the text cut short, bytes flipped, matrices
/// dropped or repeated). Every outcome is a space or a clear error, never a panic, and
/// within a time bound; a space that loads has finite faces and pairings.
#[test]
fn mutated_generator_files_are_refused_cleanly_or_load() {
    use crate::common::HOSTILE;
    use bevy_curved_spaces::random::SplitMix64;
    let mut texts: Vec<String> = CENSUS[..2]
        .iter()
        .map(|m| m.generators.to_string())
        .collect();
    for id in [
        "torus",
        "hantzsche-wendt",
        "poincare",
        "mirrored-cube",
        "seifert-weber",
    ] {
        texts.push(write_gen(&seed_space(id).unwrap()));
    }
    // Cells beyond the chart: a free lens and a mirrored lens of order 6 (two reflections).
    texts.push(write_gen(&library("lens-7-1")));
    let (c, s) = ((PI / 3.0).cos(), (PI / 3.0).sin());
    texts.push(format!(
        "1 0 0 0\n0 1 0 0\n0 0 {} {s}\n0 0 {s} {c}\n\n1 0 0 0\n0 1 0 0\n0 0 {} {}\n0 0 {} {c}\n",
        -c, -c, -s, -s
    ));
    let mut rng = SplitMix64(0x6E6E);
    let mut pick = |n: usize| ((rng.unit() * n as f64) as usize).min(n.saturating_sub(1));
    let options = DirichletOptions {
        max_elements: 20_000,
        ..DirichletOptions::default()
    };
    let (mut loaded, mut refused) = (0, 0);
    for case in 0..128 {
        let base = &texts[case % texts.len()];
        let mut lines: Vec<String> = base.lines().map(String::from).collect();
        let mutation = case % 6;
        match mutation {
            0 => {
                // A number made hostile.
                let i = pick(lines.len());
                let words: Vec<&str> = lines[i].split_whitespace().collect();
                if !words.is_empty() && !lines[i].starts_with('#') {
                    let k = pick(words.len());
                    let mut w: Vec<String> = words.iter().map(|s| s.to_string()).collect();
                    w[k] = HOSTILE[pick(HOSTILE.len())].to_string();
                    lines[i] = w.join(" ");
                }
            }
            1 => {
                let i = pick(lines.len());
                lines.remove(i);
            }
            2 => {
                let keep = pick(lines.len());
                lines.truncate(keep);
            }
            3 => {
                // A matrix dropped (a subgroup, perhaps of infinite index).
                let numbers: Vec<usize> = (0..lines.len())
                    .filter(|&i| !lines[i].starts_with('#') && !lines[i].trim().is_empty())
                    .collect();
                if numbers.len() >= 4 {
                    let start = 4 * pick(numbers.len() / 4);
                    for &i in numbers[start..start + 4].iter().rev() {
                        lines.remove(i);
                    }
                }
            }
            4 => {
                // A matrix repeated (harmless: duplicates are the same element).
                let body: Vec<String> = lines
                    .iter()
                    .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
                    .take(4)
                    .cloned()
                    .collect();
                lines.extend(body);
            }
            _ => {
                // A byte flipped.
                let mut bytes = lines.join("\n").into_bytes();
                if !bytes.is_empty() {
                    let i = pick(bytes.len());
                    bytes[i] ^= 1 << pick(8);
                }
                lines = String::from_utf8_lossy(&bytes)
                    .lines()
                    .map(String::from)
                    .collect();
            }
        }
        let text = lines.join("\n");
        let start = std::time::Instant::now();
        let result = parse_gen(&text)
            .and_then(|file| space_from_matrices("fuzz", "", &file.matrices, &options));
        let took = start.elapsed().as_secs_f64();
        assert!(
            took < 30.0,
            "case {case} (mutation {mutation}) took {took:.1} s"
        );
        match result {
            Ok(space) => {
                loaded += 1;
                for f in space.faces() {
                    assert!(
                        f.covector.is_finite() && f.pairing.is_finite(),
                        "case {case}"
                    );
                }
                assert!(volume(&space).is_finite() && volume(&space) > 0.0);
            }
            Err(e) => {
                refused += 1;
                assert!(!e.to_string().is_empty());
            }
        }
    }
    eprintln!("generator fuzz: {loaded} loaded, {refused} refused");
    assert!(loaded > 0 && refused > 0);
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
