//! Invariants of spaces from groups against closed forms and SnapPy's stored numbers:
//! volumes, homology, Euler characteristics, length spectra.

use super::*;

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
