//! The seed spaces: validation, invariants against the literature and independent
//! computations, and broken spaces rejected with the right error.

use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use bevy_curved_spaces::space::catalog::{
    CUBE_NORMALS, affine, dodecahedron_normals, dodecahedron_offset, twisted_dodecahedron,
};
use bevy_curved_spaces::space::file::{SpaceRecord, load_space_file};
use bevy_curved_spaces::space::invariants::*;
use bevy_curved_spaces::space::{FaceSpec, Pairing, SEED_SPACES, Space, SpaceError, seed_space};
use glam::{DMat3, DMat4, DVec3};
use std::f64::consts::PI;

fn space(id: &str) -> Space {
    seed_space(id).unwrap_or_else(|e| panic!("{id}: {e}"))
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * b.abs().max(1.0)
}

#[test]
fn every_seed_space_is_valid_and_of_the_right_kind() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap_or_else(|e| panic!("{}: {e}", seed.id));
        let mirrored = seed.id.starts_with("mirrored");
        assert_eq!(s.manifold(), !mirrored, "{}", seed.id);
        assert_eq!(s.orientable(), !mirrored, "{}", seed.id);
        assert_eq!(s.has_mirrors(), mirrored, "{}", seed.id);
        for c in s.edge_cycles() {
            assert!(
                close(c.angle_sum * c.order as f64, 2.0 * PI, 1e-12),
                "{}",
                seed.id
            );
        }
        // Euler characteristic of a closed 3-manifold is 0 (V − E + F − C, C the cells).
        if s.manifold() {
            let pairs = s.faces().len() / 2;
            let chi = s.vertex_cycles().len() as i64 - s.edge_cycles().len() as i64 + pairs as i64
                - s.cells().len() as i64;
            assert_eq!(chi, 0, "{}", seed.id);
        }
    }
}

/// The laws every validated space obeys: pairings are isometries, partners' pairings are
/// inverse, and each pairing carries its face's vertices onto the partner's.
#[test]
fn pairings_are_isometries_with_inverse_partners() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let g = s.geometry();
        for (i, f) in s.faces().iter().enumerate() {
            assert!(g.isometry_defect(f.pairing) < 1e-12, "{} face {i}", seed.id);
            let back = s.faces()[f.partner].pairing * f.pairing;
            assert!(
                (back - DMat4::IDENTITY)
                    .abs()
                    .to_cols_array()
                    .iter()
                    .all(|x| *x < 1e-12)
            );
            for &v in &f.vertices {
                let image = g.to_chart(f.pairing * s.vertex_point(v));
                let on_partner = s.faces()[f.partner]
                    .vertices
                    .iter()
                    .any(|&w| (s.vertices()[w] - image).length() < 1e-12);
                assert!(on_partner, "{} face {i} vertex {v}", seed.id);
            }
        }
    }
}

/// Regular dodecahedron of dihedral angle `beta`: its edge length, from the two vertices
/// of the edge between faces 0 and 2 (faces 3 and 4 close its ends).
fn dodecahedron_edge(g: Geometry, beta: f64) -> f64 {
    let n = dodecahedron_normals();
    let r = dodecahedron_offset(g, beta);
    let vertex = |a: usize, b: usize, c: usize| {
        let m = DMat3::from_cols(n[a], n[b], n[c]).transpose();
        m.inverse() * DVec3::splat(r)
    };
    let (p, q) = (vertex(0, 2, 4), vertex(0, 2, 3));
    g.distance(g.from_chart(p).unwrap(), g.from_chart(q).unwrap())
}

/// Volume of a regular dodecahedron by Schläfli's formula `κ dV = ½ Σ ℓ dα` (30 edges),
/// integrated from the Euclidean dihedral angle (volume 0) with `β = α_E ∓ u²` and
/// composite Simpson: independent of the face quadrature in `volume`.
fn schlaefli_volume(g: Geometry, alpha: f64) -> f64 {
    let alpha_e = (-1.0 / 5.0_f64.sqrt()).acos();
    let sign = (alpha_e - alpha).signum();
    let u_max = (alpha_e - alpha).abs().sqrt();
    let f = |u: f64| {
        if u == 0.0 {
            0.0
        } else {
            15.0 * dodecahedron_edge(g, alpha_e - sign * u * u) * 2.0 * u
        }
    };
    let n = 4000;
    let h = u_max / n as f64;
    let mut sum = f(0.0) + f(u_max);
    for i in 1..n {
        sum += f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * h / 3.0
}

#[test]
fn volumes_match_exact_values_and_schlaefli() {
    let exact = [
        ("torus", 1.0),
        ("half-turn", 1.0),
        ("quarter-turn", 1.0),
        ("third-turn", 3.0_f64.sqrt() / 2.0),
        ("sixth-turn", 3.0_f64.sqrt() / 2.0),
        // The Hantzsche–Wendt lattice of translations is 2Z³ (volume 8), holonomy of order 4.
        ("hantzsche-wendt", 2.0),
        ("mirrored-cube", 1.0),
        // S³ has volume 2π², the binary icosahedral group order 120.
        ("poincare", PI * PI / 60.0),
    ];
    for (id, v) in exact {
        let got = volume(&space(id));
        assert!(close(got, v, 1e-11), "{id}: volume {got}, expected {v}");
    }
    let sw = volume(&space("seifert-weber"));
    let sw_schlaefli = schlaefli_volume(Geometry::Hyperbolic, 2.0 * PI / 5.0);
    assert!(
        close(sw, sw_schlaefli, 1e-9),
        "{sw} vs Schläfli {sw_schlaefli}"
    );
    // Regina's test suite gives 11.1990647 (7 digits) for the Weber–Seifert space.
    assert!((sw - 11.1990647).abs() < 5e-8, "{sw}");
    let rd = volume(&space("mirrored-dodecahedron"));
    let rd_schlaefli = schlaefli_volume(Geometry::Hyperbolic, PI / 2.0);
    assert!(
        close(rd, rd_schlaefli, 1e-9),
        "{rd} vs Schläfli {rd_schlaefli}"
    );
    // Schläfli in S³ gives the Poincaré cell too.
    let p = schlaefli_volume(Geometry::Spherical, 2.0 * PI / 3.0);
    assert!(close(p, PI * PI / 60.0, 1e-9), "Schläfli Poincaré {p}");
}

#[test]
fn dihedral_angles_and_cycles_match_the_construction() {
    let cases = [
        ("seifert-weber", 72.0, 6, 5, 1),
        ("poincare", 120.0, 10, 3, 5),
        ("mirrored-dodecahedron", 90.0, 30, 1, 20),
        ("torus", 90.0, 3, 4, 1),
        ("mirrored-cube", 90.0, 12, 1, 8),
    ];
    for (id, degrees, cycles, per_cycle, vertex_cycles) in cases {
        let s = space(id);
        for e in s.edges() {
            assert!(close(e.dihedral.to_degrees(), degrees, 1e-12), "{id}");
        }
        assert_eq!(s.edge_cycles().len(), cycles, "{id}");
        assert!(
            s.edge_cycles().iter().all(|c| c.edges.len() == per_cycle),
            "{id}"
        );
        assert_eq!(s.vertex_cycles().len(), vertex_cycles, "{id}");
    }
}

#[test]
fn radii_and_edge_lengths() {
    let torus = space("torus");
    assert!(close(inradius(&torus), 0.5, 1e-15));
    assert!(close(circumradius(&torus), 3.0_f64.sqrt() / 2.0, 1e-15));
    assert_eq!(edge_length(&torus), Some(1.0));
    // The hexagonal prism has edges 1/√3 and 1: no common length.
    assert_eq!(edge_length(&space("third-turn")), None);
    // Rhombic dodecahedron with faces at 1/√2: edge √3/2.
    let hw = edge_length(&space("hantzsche-wendt")).unwrap();
    assert!(close(hw, 3.0_f64.sqrt() / 2.0, 1e-14));
    // Poincaré: the 120-cell inscribed in the unit 3-sphere has chord edge 1/(φ²√2)
    // (Coxeter, Regular Polytopes); its inradius is π/10 (face centres of the 120-cell are
    // a fifth of π apart).
    let p = space("poincare");
    let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let chord = 2.0 * (edge_length(&p).unwrap() / 2.0).sin();
    assert!(
        close(chord, 1.0 / (phi * phi * 2.0_f64.sqrt()), 1e-14),
        "{chord}"
    );
    assert!(close(inradius(&p), PI / 10.0, 1e-14));
    // The edge length of the dodecahedra agrees with the independent vertex computation.
    for (id, g, beta) in [
        ("seifert-weber", Geometry::Hyperbolic, 2.0 * PI / 5.0),
        ("mirrored-dodecahedron", Geometry::Hyperbolic, PI / 2.0),
    ] {
        let e = edge_length(&space(id)).unwrap();
        assert!(close(e, dodecahedron_edge(g, beta), 1e-13), "{id}");
    }
}

#[test]
fn groups_and_injectivity_radii() {
    let holonomy = [
        ("torus", 1),
        ("half-turn", 2),
        ("quarter-turn", 4),
        ("third-turn", 3),
        ("sixth-turn", 6),
        ("hantzsche-wendt", 4),
        ("mirrored-cube", 8),
    ];
    for (id, order) in holonomy {
        assert_eq!(holonomy_order(&space(id)), Some(order), "{id}");
    }
    assert_eq!(holonomy_order(&space("poincare")), None);
    // The binary icosahedral group has order 120.
    assert_eq!(group_order(&space("poincare")), Some(120));
    // Its shortest elements (order 10) move every point by π/5.
    let inj = injectivity_radius(&space("poincare")).unwrap();
    assert!(close(inj, PI / 10.0, 1e-9), "{inj}");
    // Flat: the shortest translations and screw motions have length 1.
    for id in [
        "torus",
        "half-turn",
        "quarter-turn",
        "third-turn",
        "sixth-turn",
        "hantzsche-wendt",
    ] {
        let r = injectivity_radius(&space(id)).unwrap();
        assert!(close(r, 0.5, 1e-12), "{id}: {r}");
    }
    assert_eq!(injectivity_radius(&space("mirrored-cube")), None);
}

#[test]
fn seifert_weber_closed_geodesics() {
    let s = space("seifert-weber");
    let spectrum = closed_geodesics(&s, GEODESIC_SPECTRUM_LENGTH).expect("enumerated");
    assert!(!spectrum.is_empty());
    // The six geodesics through opposite face centres have length 2·inradius, and six more
    // share their complex length (2r + 3πi/5): twelve, by the conjugacy classes and by the
    // chord sums alike (`groups::length_spectra_agree_by_two_routes_and_with_snappy`). The
    // old count by tracing axes through the cell said six.
    let through_faces = 2.0 * inradius(&s);
    let entry = spectrum
        .iter()
        .find(|g| (g.length - through_faces).abs() < 1e-9)
        .expect("face-centre geodesics");
    assert_eq!(entry.count, 12);
    // Sorted, within the range, and the systole is twice the injectivity radius.
    assert!(spectrum.windows(2).all(|w| w[0].length < w[1].length));
    assert!(
        spectrum
            .iter()
            .all(|g| g.length <= GEODESIC_SPECTRUM_LENGTH && g.count > 0)
    );
    let inj = injectivity_radius(&s).unwrap();
    assert!(close(spectrum[0].length, 2.0 * inj, 1e-9));
    // Brute force without the separation pruning: every element moving the centre by at
    // most 2R + systole (R the circumradius) has translation length ≥ the systole.
    let g = s.geometry();
    let reach = 2.0 * circumradius(&s) + spectrum[0].length;
    let near = bfs_by_orbit_distance(&s, reach);
    let shortest = near
        .iter()
        .skip(1)
        .map(|&h| displacement(g, h))
        .fold(f64::INFINITY, f64::min);
    assert!(close(shortest, spectrum[0].length, 1e-9), "{shortest}");
}

/// Every group element `h` with `d(o, h o) ≤ reach`, by plain breadth-first search with the
/// orbit-distance bound only (cells met by the segment from `o` to `h o` have orbit points
/// within `reach + R`).
fn bfs_by_orbit_distance(s: &Space, reach: f64) -> Vec<DMat4> {
    let g = s.geometry();
    let slack = circumradius(s);
    let key = |m: DMat4| (m * ORIGIN).to_array().map(|x| (x * 1e5).round() as i64);
    let mut seen = std::collections::HashSet::from([key(DMat4::IDENTITY)]);
    let mut queue = std::collections::VecDeque::from([DMat4::IDENTITY]);
    let mut out = vec![DMat4::IDENTITY];
    while let Some(m) = queue.pop_front() {
        for f in s.faces() {
            let next = m * f.pairing;
            let d = g.distance(ORIGIN, next * ORIGIN);
            if d > reach + slack || !seen.insert(key(next)) {
                continue;
            }
            if d <= reach {
                out.push(next);
            }
            queue.push_back(next);
        }
    }
    out
}

fn sw_like(dihedral: f64, twist: f64) -> Result<Space, SpaceError> {
    twisted_dodecahedron("test", "", Geometry::Hyperbolic, dihedral, twist)
}

#[test]
fn the_mirror_image_twist_is_also_a_manifold() {
    let left = sw_like(2.0 * PI / 5.0, -3.0 * PI / 5.0).expect("mirror image of Seifert–Weber");
    assert!(left.manifold() && left.orientable());
    assert!(close(volume(&left), volume(&space("seifert-weber")), 1e-12));
}

#[test]
fn broken_spaces_are_rejected_with_the_right_error() {
    // Wrong twist: π/5 on the 72° dodecahedron closes edges in cycles of three (216°).
    match sw_like(2.0 * PI / 5.0, PI / 5.0) {
        Err(SpaceError::EdgeAngleSum { angle_sum_deg, .. }) => {
            assert!((angle_sum_deg - 216.0).abs() < 1e-6, "{angle_sum_deg}")
        }
        other => panic!("expected EdgeAngleSum, got {other:?}"),
    }
    // Wrong dihedral angle: the Seifert–Weber gluing on an 80° dodecahedron sums to 400°.
    match sw_like(80f64.to_radians(), 3.0 * PI / 5.0) {
        Err(SpaceError::EdgeAngleSum { angle_sum_deg, .. }) => {
            assert!((angle_sum_deg - 400.0).abs() < 1e-6)
        }
        other => panic!("expected EdgeAngleSum, got {other:?}"),
    }
    // A twist that does not carry vertices to vertices.
    assert!(matches!(
        sw_like(2.0 * PI / 5.0, 2.0 * PI / 5.0),
        Err(SpaceError::FaceNotMapped { .. })
    ));
    // Mirrors at 72° do not tile around an edge (2·72° does not divide 360°).
    let g = Geometry::Hyperbolic;
    let r = dodecahedron_offset(g, 2.0 * PI / 5.0);
    let mirrors: Vec<FaceSpec> = dodecahedron_normals()
        .iter()
        .enumerate()
        .map(|(i, &n)| FaceSpec::paired(n, r, i, g.reflection(n.extend(-r))))
        .collect();
    assert!(matches!(
        Space::new("m", "", g, &mirrors),
        Err(SpaceError::EdgeAngleSum { .. })
    ));

    let e = Geometry::Euclidean;
    let cube = |f: &dyn Fn(usize, DVec3) -> Option<Pairing>| -> Vec<FaceSpec> {
        CUBE_NORMALS
            .iter()
            .enumerate()
            .map(|(i, &n)| FaceSpec {
                normal: n,
                offset: 0.5,
                pairing: f(i, n),
            })
            .collect()
    };
    let translate = |i: usize, n: DVec3| {
        Some(Pairing {
            partner: i ^ 1,
            matrix: affine(DMat3::IDENTITY, -n),
        })
    };
    assert!(Space::new("ok", "", e, &cube(&translate)).is_ok());
    // A missing pairing.
    let missing = cube(&|i, n| if i == 3 { None } else { translate(i, n) });
    assert_eq!(
        Space::new("t", "", e, &missing).unwrap_err(),
        SpaceError::MissingPairing { face: 3 }
    );
    // A missing face: the cell is open towards −z.
    let open: Vec<FaceSpec> = cube(&|i, n| {
        Some(Pairing {
            partner: i,
            matrix: e.reflection(n.extend(-0.5)),
        })
    })[..5]
        .to_vec();
    match Space::new("t", "", e, &open) {
        Err(SpaceError::NotBounded { direction }) => {
            assert!((DVec3::from_array(direction) - DVec3::NEG_Z).length() < 1e-12)
        }
        other => panic!("expected NotBounded, got {other:?}"),
    }
    // Not an isometry.
    let scaled = cube(&|i, n| {
        translate(i, n).map(|p| Pairing {
            matrix: if i == 0 {
                p.matrix * DMat4::from_scale(DVec3::splat(1.01))
            } else {
                p.matrix
            },
            ..p
        })
    });
    assert!(matches!(
        Space::new("t", "", e, &scaled),
        Err(SpaceError::NotAnIsometry { face: 0, .. })
    ));
    // Translation by too little: the face lands off its partner.
    let short = cube(&|i, n| {
        Some(Pairing {
            partner: i ^ 1,
            matrix: affine(DMat3::IDENTITY, -0.9 * n),
        })
    });
    assert!(matches!(
        Space::new("t", "", e, &short),
        Err(SpaceError::NotInverse { .. }) | Err(SpaceError::FaceNotMapped { .. })
    ));
    let short_pair = cube(&|i, n| {
        let s = if i < 2 { 0.9 } else { 1.0 };
        Some(Pairing {
            partner: i ^ 1,
            matrix: affine(DMat3::IDENTITY, -s * n),
        })
    });
    assert!(matches!(
        Space::new("t", "", e, &short_pair),
        Err(SpaceError::FaceNotMapped {
            face: 0,
            partner: 1,
            ..
        })
    ));
    // Partners that do not name each other.
    let crossed = cube(&|i, n| {
        translate(i, n).map(|p| Pairing {
            partner: if i == 0 { 2 } else { p.partner },
            ..p
        })
    });
    assert!(matches!(
        Space::new("t", "", e, &crossed),
        Err(SpaceError::PartnerNotMutual { face: 0, .. })
    ));
    // Pairings that are not inverse to each other: both z faces screw the same way.
    let screw = affine(DMat3::from_rotation_z(PI / 2.0), DVec3::Z);
    let same_way = cube(&|i, n| match i {
        4 => Some(Pairing {
            partner: 5,
            matrix: affine(DMat3::from_rotation_z(PI / 2.0), -DVec3::Z),
        }),
        5 => Some(Pairing {
            partner: 4,
            matrix: screw,
        }),
        _ => translate(i, n),
    });
    assert!(matches!(
        Space::new("t", "", e, &same_way),
        Err(SpaceError::NotInverse {
            face: 4,
            partner: 5,
            ..
        })
    ));
    // A face the pairing maps onto its partner but with the cell on the same side.
    let flip = cube(&|i, n| {
        if i < 2 {
            Some(Pairing {
                partner: i ^ 1,
                matrix: affine(
                    DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0)),
                    DVec3::ZERO,
                ),
            })
        } else {
            translate(i, n)
        }
    });
    assert!(matches!(
        Space::new("t", "", e, &flip),
        Err(SpaceError::FaceNotMapped { face: 0, .. })
    ));
    // The messages name what is wrong.
    let msg = Space::new("t", "", e, &missing).unwrap_err().to_string();
    assert!(msg.contains("face 3"), "{msg}");
    assert!(matches!(
        seed_space("klein-bottle"),
        Err(SpaceError::UnknownSpace(_))
    ));
}

#[test]
fn space_files_round_trip_and_reject_mistakes() {
    let dir = std::env::temp_dir().join(format!("curved-spaces-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for id in [
        "seifert-weber",
        "mirrored-cube",
        "hantzsche-wendt",
        "torus-two-cells",
    ] {
        let s = space(id);
        let path = dir.join(format!("{id}.json"));
        std::fs::write(
            &path,
            serde_json::to_string(&SpaceRecord::from_space(&s)).unwrap(),
        )
        .unwrap();
        let back = load_space_file(&path).unwrap();
        assert_eq!(back.edge_cycles().len(), s.edge_cycles().len());
        assert_eq!(back.cells(), s.cells());
        assert!(close(volume(&back), volume(&s), 1e-12));
    }
    let bad = [
        ("{", "not valid"),
        (
            r#"{"name":"x","geometry":"elliptic","faces":[]}"#,
            "not valid",
        ),
        (
            r#"{"name":"x","geometry":"euclidean","faces":[]}"#,
            "at least 4 faces",
        ),
        (
            r#"{"name":"x","geometry":"euclidean","faces":[{"normal":[1,0,0],"offset":0.5,"mirror":true,"partner":0}]}"#,
            "face 0",
        ),
        (
            r#"{"name":"x","geometry":"euclidean","faces":[{"normal":[1,0,0],"offset":0.5,"mirror":true,"cell":1}]}"#,
            "face 0: `cell` 1 follows cell 0: list the faces cell by cell",
        ),
    ];
    for (i, (text, expect)) in bad.iter().enumerate() {
        let path = dir.join(format!("bad{i}.json"));
        std::fs::write(&path, text).unwrap();
        let msg = load_space_file(&path).unwrap_err().to_string();
        assert!(msg.contains(expect) && msg.contains("bad"), "{msg}");
    }
    let missing = load_space_file(&dir.join("nope.json"))
        .unwrap_err()
        .to_string();
    assert!(missing.contains("cannot read"), "{missing}");
    std::fs::remove_dir_all(&dir).ok();
}

mod hostile_files {
    use super::*;
    use proptest::prelude::*;

    fn records() -> Vec<SpaceRecord> {
        [
            "torus",
            "hantzsche-wendt",
            "seifert-weber",
            "poincare",
            "mirrored-cube",
            "torus-two-cells",
        ]
        .iter()
        .map(|id| SpaceRecord::from_space(&space(id)))
        .collect()
    }

    fn hostile() -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(f64::NAN),
            Just(f64::INFINITY),
            Just(-f64::INFINITY),
            Just(0.0),
            Just(1e300),
            Just(-1.0),
            -2.0..2.0f64,
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Any number of a space file replaced by garbage gives a space or an error, never a
        /// panic; the seed spaces' exact numbers are the only ones that pass validation
        /// unchanged in kind.
        #[test]
        fn corrupted_space_files_never_panic(which in 0usize..6, face in 0usize..12, slot in 0usize..20, value in hostile()) {
            let mut record = records().swap_remove(which);
            let face = face % record.faces.len();
            let f = &mut record.faces[face];
            match slot {
                0..=2 => f.normal[slot] = value,
                3 => f.offset = value,
                _ => match f.pairing.as_mut() {
                    Some(m) => m[(slot - 4) / 4][(slot - 4) % 4] = value,
                    None => f.offset = value,
                },
            }
            let _ = record.build("fuzz");
        }

        /// Dropping or swapping faces is an error or a valid space, never a panic.
        #[test]
        fn reshuffled_faces_never_panic(which in 0usize..6, drop in 0usize..12, partner in 0usize..14) {
            let mut record = records().swap_remove(which);
            let n = record.faces.len();
            if let Some(p) = record.faces[drop % n].partner.as_mut() {
                *p = partner;
            }
            let _ = record.build("fuzz");
            record.faces.remove(drop % n);
            prop_assert!(record.build("fuzz").is_err());
        }

        /// Any face moved to another cell (or to a cell number far out of range), or the
        /// faces of several cells cut off at any point, gives a space or an error naming
        /// the problem, never a panic: the loader of the `cell` key, the cells' checks
        /// (overlap, origin, joined) and the walk over them.
        #[test]
        fn faces_moved_between_cells_never_panic(which in 0usize..6, face in 0usize..14, cell in prop_oneof![0usize..4, Just(usize::MAX), Just(1usize << 40)], keep in 4usize..14) {
            let mut record = records().swap_remove(which);
            let n = record.faces.len();
            record.faces[face % n].cell = cell;
            let moved = record.build("fuzz");
            if let Err(e) = &moved {
                prop_assert!(!e.to_string().is_empty());
            }
            let mut cut = records().swap_remove(which);
            cut.faces.truncate(keep.min(cut.faces.len()));
            if let Ok(space) = cut.build("fuzz") {
                let walker = bevy_curved_spaces::space::CellWalker::<glam::DVec4>::new(&space);
                let ray = bevy_curved_spaces::geometry::chart_ray(space.geometry(), glam::DVec3::ZERO, glam::DVec3::new(0.3, 0.5, 0.7)).expect("a ray");
                let _ = walker.trace(ray, bevy_curved_spaces::space::Limit::Crossings(32));
            }
        }
    }
}

/// What is not a regular file of at most `MAX_SPACE_FILE_BYTES` is refused before anything
/// is read: a directory, a FIFO (which would block), `/dev/zero` (which never ends) and a
/// (sparse) file one byte over the limit, each with its own message.
#[test]
fn space_files_that_are_not_regular_or_too_large_are_refused_at_once() {
    use bevy_curved_spaces::files::MAX_SPACE_FILE_BYTES;
    let dir = crate::common::scratch_dir("space-files-special");
    let refused = |path: &std::path::Path, expect: &str| {
        let started = std::time::Instant::now();
        let e = load_space_file(path).expect_err("refused").to_string();
        assert!(e.contains(expect), "{}: {e}", path.display());
        assert!(e.contains(&path.display().to_string()), "{e}");
        assert!(
            started.elapsed().as_secs_f64() < 5.0,
            "{}: slow",
            path.display()
        );
    };
    refused(&dir, "a directory");
    if std::path::Path::new("/dev/zero").exists() {
        refused(std::path::Path::new("/dev/zero"), "not a regular file");
    }
    let fifo = dir.join("fifo.json");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        refused(&fifo, "not a regular file");
    }
    let huge = dir.join("huge.json");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(MAX_SPACE_FILE_BYTES + 1)
        .unwrap();
    refused(&huge, "more than the limit");
    let binary = dir.join("binary.json");
    std::fs::write(&binary, [0xff, 0xfe, 0x00, 0x80]).unwrap();
    refused(&binary, "not UTF-8");
}

/// The torus written as a space file scaled by `factor` (offsets and translations).
fn scaled_torus(factor: f64) -> Result<Space, String> {
    let mut record = serde_json::to_value(SpaceRecord::from_space(&space("torus"))).unwrap();
    for face in record["faces"].as_array_mut().unwrap() {
        let offset = face["offset"].as_f64().unwrap();
        face["offset"] = serde_json::json!(offset * factor);
        for row in 0..3 {
            let t = face["pairing"][row][3].as_f64().unwrap();
            face["pairing"][row][3] = serde_json::json!(t * factor);
        }
    }
    let record: SpaceRecord = serde_json::from_value(record).unwrap();
    record.build("scaled.json").map_err(|e| e.to_string())
}

/// A flat space is valid at any scale f64 holds (the checks' tolerances were absolute, and
/// the torus at 2⁻²⁰ was "a redundant inequality"), its invariants scale with it, and a
/// degenerate cell is still refused at any scale.
#[test]
fn flat_spaces_are_valid_at_any_scale() {
    for k in [-40, -30, -20, -1, 1, 20, 300, 500] {
        let s = 2f64.powi(k);
        let torus = scaled_torus(s).unwrap_or_else(|e| panic!("2^{k}: {e}"));
        assert!(close(inradius(&torus), 0.5 * s, 1e-14), "2^{k}");
        assert!(close(edge_length(&torus).unwrap(), s, 1e-14), "2^{k}");
        let v = volume(&torus);
        if k <= 300 {
            assert!(close(v, s * s * s, 1e-12), "2^{k}: volume {v}");
        } else {
            assert!(v.is_infinite(), "2^{k}: volume {v}");
        }
    }
    // Two opposite faces at different distances: the translation does not map one onto the
    // other, at any scale.
    for k in [-30, 0, 300] {
        let s = 2f64.powi(k);
        let mut record = serde_json::to_value(SpaceRecord::from_space(&space("torus"))).unwrap();
        record["faces"][0]["offset"] = serde_json::json!(0.75 * s);
        for face in record["faces"].as_array_mut().unwrap().iter_mut().skip(1) {
            let offset = face["offset"].as_f64().unwrap();
            face["offset"] = serde_json::json!(offset * s);
        }
        for face in record["faces"].as_array_mut().unwrap() {
            for row in 0..3 {
                let t = face["pairing"][row][3].as_f64().unwrap();
                face["pairing"][row][3] = serde_json::json!(t * s);
            }
        }
        let record: SpaceRecord = serde_json::from_value(record).unwrap();
        assert!(record.build("bad.json").is_err(), "2^{k}: accepted");
    }
}
