//! Sol's torus bundles (`space::sol::bundle`): the lattice diagonalises the gluing, the
//! invariants (volume τ, H₁ = Z ⊕ coker(A − I)), and ids and gluings that are no Sol bundle
//! refused with the geometry they have instead.

use bevy_curved_spaces::space::sol::{SolError, TorusBundle};

/// `Q A Q⁻¹ = diag(λ, 1/λ)` with `det Q = 1`: `Q A = diag(λ, 1/λ) Q` entry by entry.
fn check_lattice(bundle: &TorusBundle) {
    let q = bundle.q;
    let a = bundle.matrix.map(|r| r.map(|x| x as f64));
    let det = q[0][0] * q[1][1] - q[0][1] * q[1][0];
    assert!((det - 1.0).abs() < 1e-12, "{}: det Q = {det}", bundle.id());
    let scale = q.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    for (i, ev) in [bundle.lambda, 1.0 / bundle.lambda].into_iter().enumerate() {
        for j in 0..2 {
            let qa = q[i][0] * a[0][j] + q[i][1] * a[1][j];
            let want = ev * q[i][j];
            assert!(
                (qa - want).abs() < 1e-12 * scale * bundle.lambda,
                "{}: (QA)[{i}][{j}] = {qa}, λQ = {want}",
                bundle.id()
            );
        }
    }
    // The lattice's basis is Q's columns.
    let l = bundle.lattice();
    assert_eq!(l, [[q[0][0], q[1][0]], [q[0][1], q[1][1]]]);
}

#[test]
fn the_lattice_diagonalises_the_gluing_and_the_invariants_are_right() {
    let golden = (1.0 + 5f64.sqrt()) / 2.0;
    for (id, lambda, homology) in [
        ("torus-bundle-2-1-1-1", golden * golden, "Z"),
        ("torus-bundle-3-1-2-1", 2.0 + 3f64.sqrt(), "Z/2 + Z"),
        ("torus-bundle-1-1-1-2", golden * golden, "Z"),
        (
            "torus-bundle-5-2-2-1",
            3.0 + 2.0 * 2f64.sqrt(),
            "Z/2 + Z/2 + Z",
        ),
        ("torus-bundle-2--1-1-0", f64::NAN, ""),
        ("torus-bundle-100-1-99-1", f64::NAN, "Z/99 + Z"),
    ] {
        let result = TorusBundle::from_id(id).expect("a torus bundle id");
        if id == "torus-bundle-2--1-1-0" {
            // Trace 2, a shear: Nil, not Sol.
            let e = result.unwrap_err().to_string();
            assert!(e.contains("Nil"), "{e}");
            continue;
        }
        let bundle = result.unwrap_or_else(|e| panic!("{id}: {e}"));
        assert_eq!(bundle.id(), id);
        check_lattice(&bundle);
        if lambda.is_finite() {
            assert!((bundle.lambda - lambda).abs() < 1e-14 * lambda, "{id}: λ");
        }
        assert_eq!(bundle.tau, bundle.lambda.ln());
        assert_eq!(bundle.volume(), bundle.tau);
        assert_eq!(bundle.homology().to_string(), homology, "{id}");
    }
    // A large trace keeps the lattice exact: 1/λ from the product, not a difference.
    let big = TorusBundle::new([[9999, 1], [9998, 1]]).unwrap();
    check_lattice(&big);
    assert!((big.lambda * (1.0 / big.lambda) - 1.0).abs() < 1e-15);
}

#[test]
fn ids_and_gluings_that_are_no_sol_bundle_are_refused_with_the_reason() {
    for (id, says) in [
        ("torus-bundle-1-0-0-1", "3-torus"),
        ("torus-bundle-1-1-0-1", "Nil"),
        ("torus-bundle--1-0-0--1", "half turn"),
        ("torus-bundle-0--1-1-0", "finite order"),
        ("torus-bundle-0-1--1-1", "finite order"),
        ("torus-bundle-2-1-1-2", "determinant 3"),
        ("torus-bundle--3--1--2--1", "trace -4 < −2"),
        ("torus-bundle-2-1-1", "3 entries"),
        ("torus-bundle-2-1-1-1-0", "5 entries"),
        ("torus-bundle-2-x-1-1", "whole number"),
        ("torus-bundle-2.5-1-1-1", "whole number"),
        ("torus-bundle-2-1-1-", "ends with a dash"),
        ("torus-bundle-", "0 entries"),
        ("torus-bundle-99999999999999999999-1-1-1", "too large"),
        ("torus-bundle-20001-1-20000-1", "larger than 10000"),
        ("torus-bundle-2-1-1-1 ", "whole number"),
    ] {
        let e = TorusBundle::from_id(id)
            .expect("a torus bundle id")
            .expect_err(id)
            .to_string();
        assert!(e.contains(says), "{id}: {e}");
    }
    assert!(TorusBundle::from_id("nil-3").is_none());
    // The refusal of a negative trace names the bundle of −A, which is Sol.
    let e = TorusBundle::new([[-3, -1], [-2, -1]]).unwrap_err();
    assert!(matches!(e, SolError::NegativeTrace { trace: -4, .. }));
    assert!(e.to_string().contains("torus-bundle-3-1-2-1"), "{e}");
}
