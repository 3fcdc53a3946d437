//! Jacobi's elliptic functions (`geometry::elliptic`, what Sol's geodesics are written with)
//! in f64 and double-double against mpmath at 50 digits (`scripts/elliptic-reference.py`,
//! `tests/data/elliptic.json`): the parameter from 0 to 1 (within 1e-12 of both ends), the
//! argument from 0 past four periods and negative.
//!
//! Each value is compared with the reference over what rounding the argument's `2ᴺa_N·u`
//! alone costs: the amplitude carries an absolute error of about `ε·(1 + |u|)` (the descent
//! halves what `φ_N` had), so every function is held to a few units of that; `F(φ|m)` to a
//! few units of `ε·(1 + |F| + |φ|·∂F/∂φ)`, its conditioning in `φ`.

use bevy_curved_spaces::geometry::elliptic::Parameter;
use bevy_curved_spaces::geometry::{DoubleDouble, Real};
use serde_json::Value;

fn dd(pair: &Value) -> DoubleDouble {
    let p = pair.as_array().expect("a pair");
    let part = |v: &Value| -> f64 { v.as_str().expect("a string").parse().expect("a number") };
    DoubleDouble::new(part(&p[0])) + DoubleDouble::new(part(&p[1]))
}

fn reference() -> Value {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/elliptic.json"
    ))
    .expect("tests/data/elliptic.json");
    serde_json::from_str(&text).expect("JSON")
}

/// A value of the precision under test, exactly as a double-double.
trait Exact: Real {
    fn exact(self) -> DoubleDouble;
}

impl Exact for f64 {
    fn exact(self) -> DoubleDouble {
        DoubleDouble::new(self)
    }
}

impl Exact for DoubleDouble {
    fn exact(self) -> DoubleDouble {
        self
    }
}

/// The worst error over the reference of each function, in units of `ε·(1 + |u|)`, for the
/// precision `R` with machine epsilon `eps`.
fn worst<R: Exact>(eps: f64) -> Vec<(&'static str, f64, String)> {
    let data = reference();
    let mut worst: Vec<(&'static str, f64, String)> = ["K", "E", "sn", "cn", "dn", "am", "Z", "F"]
        .into_iter()
        .map(|n| (n, 0.0, String::new()))
        .collect();
    let mut note = |i: usize, err: f64, at: String| {
        if err > worst[i].1 || err.is_nan() {
            worst[i] = (worst[i].0, err, at);
        }
    };
    let off = |x: R, r: DoubleDouble| (x.exact() - r).hi.abs();
    for case in data["cases"].as_array().expect("cases") {
        let m = dd(&case["m"]);
        let p = Parameter::<R>::new(R::from_f64(m.hi)).expect("a parameter");
        let name = format!("m = {:e}", m.hi);
        note(
            0,
            off(p.k(), dd(&case["k"])) / (eps * dd(&case["k"]).hi),
            name.clone(),
        );
        note(
            1,
            off(p.e(), dd(&case["e"])) / (eps * dd(&case["e"]).hi),
            name.clone(),
        );
        for v in case["values"].as_array().expect("values") {
            let u = dd(&v["u"]).hi;
            let scale = eps * (1.0 + u.abs());
            let at = format!("{name}, u = {u}");
            let (sn, cn, dn) = p.sn_cn_dn(R::from_f64(u));
            note(2, off(sn, dd(&v["sn"])) / scale, at.clone());
            note(3, off(cn, dd(&v["cn"])) / scale, at.clone());
            note(4, off(dn, dd(&v["dn"])) / scale, at.clone());
            note(
                5,
                off(p.am(R::from_f64(u)), dd(&v["am"])) / scale,
                at.clone(),
            );
            note(6, off(p.zeta(R::from_f64(u)), dd(&v["zeta"])) / scale, at);
        }
        for v in case["incomplete"].as_array().expect("incomplete") {
            let phi = dd(&v["phi"]).hi;
            let f = dd(&v["f"]);
            // F's slope in φ is 1/√(m₁ + m cos²φ): near φ = π/2 with m near 1 an ulp of φ
            // moves it that much, and so does the ascent's own rounding.
            let slope = 1.0 / ((1.0 - m.hi) + m.hi * phi.cos().powi(2)).sqrt();
            let scale = eps * (1.0 + f.hi.abs() + phi.abs() * slope);
            note(
                7,
                off(p.f(R::from_f64(phi)), f) / scale,
                format!("{name}, φ = {phi}"),
            );
        }
    }
    worst
}

#[test]
fn jacobis_functions_in_f64_are_the_references_to_a_few_units() {
    let worst = worst::<f64>(f64::EPSILON);
    for (name, err, at) in &worst {
        println!("f64 {name}: worst {err:.2} units of ε(1 + |u|), at {at}");
    }
    for (name, err, at) in &worst {
        assert!(*err < 16.0, "f64 {name}: {err:.2} units at {at}");
    }
}

#[test]
fn jacobis_functions_in_double_double_are_the_references_to_a_few_units() {
    let eps = 2f64.powi(-104);
    let worst = worst::<DoubleDouble>(eps);
    for (name, err, at) in &worst {
        println!("double-double {name}: worst {err:.2} units of ε(1 + |u|), at {at}");
    }
    for (name, err, at) in &worst {
        assert!(*err < 64.0, "double-double {name}: {err:.2} units at {at}");
    }
}

/// The identities the functions must keep whatever the reference: `sn² + cn² = 1`,
/// `dn² + m·sn² = 1`, `am` undoes `F`, the quarter period, the zeta function vanishing at
/// multiples of `K` and odd; and the parameters outside `[0, 1]` refused.
#[test]
fn the_identities_hold_and_bad_parameters_are_refused() {
    for m in [0.0, 1e-9, 0.2, 0.5, 0.8, 1.0 - 1e-9, 1.0] {
        let p = Parameter::<f64>::new(m).unwrap();
        for u in [-3.0, -0.4, 0.0, 0.25, 1.1, 2.9, 6.0] {
            let (sn, cn, dn) = p.sn_cn_dn(u);
            assert!((sn * sn + cn * cn - 1.0).abs() < 1e-15, "m {m} u {u}");
            assert!((dn * dn + m * sn * sn - 1.0).abs() < 1e-15, "m {m} u {u}");
            assert!((p.zeta(-u) + p.zeta(u)).abs() < 1e-15, "Z odd, m {m} u {u}");
            if m < 1.0 {
                // F's slope is 1/dn: where dn is small the amplitude's rounding grows by it.
                let phi = p.am(u);
                let off = (p.f(phi) - u).abs();
                assert!(
                    off < 1e-14 * (1.0 + u.abs()) / dn,
                    "F(am u) = u, m {m} u {u}: off by {off:e} (dn {dn:e})"
                );
            }
        }
        if m < 1.0 {
            let k = p.k();
            let (sn, cn, _) = p.sn_cn_dn(k);
            assert!(
                (sn - 1.0).abs() < 1e-15 && cn.abs() < 1e-14 * (1.0 + k),
                "m {m}: sn K"
            );
            assert!(p.zeta(k).abs() < 1e-14 * k && p.zeta(2.0 * k).abs() < 1e-14 * k);
        }
    }
    // From the moduli: m near 1 keeps k′ whole.
    let kp = 1e-10;
    let p = Parameter::<f64>::from_moduli((1.0 - kp * kp).sqrt(), kp).unwrap();
    assert!(p.m1 == kp * kp && p.k().is_finite() && p.k() > 20.0);
    for bad in [-0.1, 1.1, f64::NAN, f64::INFINITY] {
        assert!(Parameter::<f64>::new(bad).is_none(), "m = {bad}");
    }
    assert!(Parameter::<f64>::from_moduli(0.5, -0.1).is_none());
}
