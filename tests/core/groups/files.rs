//! Generator files: parsed with comments and byte-order marks, malformed and mutated ones
//! refused by name, every seed space round-tripped.

use super::*;

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
        // One generator a pair of faces, none for a seam between cells (the identity).
        let pairs = space
            .faces()
            .iter()
            .enumerate()
            .filter(|(i, f)| f.partner >= *i && !space.is_seam(*i))
            .count();
        assert_eq!(file.matrices.len(), pairs, "{}", seed.id);
        let back = space_from_matrices(seed.id, "", &file.matrices, &DirichletOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", seed.id));
        // A space of several cells comes back as the Dirichlet domain of its group: one
        // cell, of the same volume.
        if space.cells().len() > 1 {
            assert_eq!(back.cells().len(), 1);
            assert!((volume(&back) - volume(&space)).abs() < 1e-9 * volume(&space));
            continue;
        }
        assert_eq!(back.faces().len(), faces, "{}", seed.id);
        assert!(
            congruent(&space, &back, 1e-9),
            "{}: the Dirichlet domain of its own pairings is not its cell",
            seed.id
        );
        assert!((volume(&back) - volume(&space)).abs() < 1e-9 * volume(&space));
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
