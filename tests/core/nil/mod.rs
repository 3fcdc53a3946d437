//! Nil's geodesic flow in closed form against an independent reference: the geodesic
//! equations of the metric integrated at 45 digits by mpmath (`scripts/nil-reference.py`,
//! stored in `tests/data/nil_geodesics.json` with 40 digits), in double-double, f64 and f32.
//!
//! Each precision is measured against the reference and against the **conditioning
//! limit**: the exact flow (double-double) started from the start rounded to that
//! precision, which is as close as any method can get from a rounded start. Nil's
//! geodesics spread polynomially (a start rounded by ε ends `O(ε t²)` away: the height
//! gains the area swept), so that limit grows with `t²`.

mod balls;
mod distances;
mod exits;
#[cfg(feature = "scene-files")]
mod files;
mod pictures;
mod shadows;
mod spaces;
mod walks;

use bevy_curved_spaces::geometry::{DoubleDouble, Real};
use bevy_curved_spaces::space::nil::{NilRay, flow, group_product};
use serde_json::Value;

/// A double-double stored as two decimal strings (read by `str::parse`, correctly rounded).
fn dd(pair: &Value) -> DoubleDouble {
    let p = pair.as_array().expect("a pair");
    let part = |v: &Value| -> f64 { v.as_str().expect("a string").parse().expect("a number") };
    DoubleDouble::new(part(&p[0])) + DoubleDouble::new(part(&p[1]))
}

fn triple(v: &Value) -> [DoubleDouble; 3] {
    let a = v.as_array().expect("three");
    [dd(&a[0]), dd(&a[1]), dd(&a[2])]
}

/// One sample of the reference: the start ray, the time, and the ray there.
struct Sample {
    case: String,
    start: NilRay<DoubleDouble>,
    t: f64,
    end: NilRay<DoubleDouble>,
}

fn reference() -> Vec<Sample> {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/nil_geodesics.json"),
    )
    .expect("the stored reference");
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    let mut out = Vec::new();
    for case in doc["cases"].as_array().expect("cases") {
        let start = NilRay {
            point: triple(&case["start_dd"]),
            velocity: triple(&case["velocity_dd"]),
        };
        for s in case["samples"].as_array().expect("samples") {
            out.push(Sample {
                case: case["name"].as_str().expect("name").to_string(),
                start,
                t: s["t"].as_str().expect("t").parse().expect("a time"),
                end: NilRay {
                    point: triple(&s["point_dd"]),
                    velocity: triple(&s["velocity_dd"]),
                },
            });
        }
    }
    out
}

/// The largest difference of two rays' entries, each relative to `1 + |entry|`.
fn gap(a: &NilRay<DoubleDouble>, b: &NilRay<DoubleDouble>) -> f64 {
    a.point
        .iter()
        .chain(&a.velocity)
        .zip(b.point.iter().chain(&b.velocity))
        .map(|(x, y)| ((*x - *y).abs().to_f64()) / (1.0 + y.abs().to_f64()))
        .fold(0.0, f64::max)
}

fn round_ray<R: Real>(r: &NilRay<DoubleDouble>) -> NilRay<R> {
    let round = |x: [DoubleDouble; 3]| x.map(|v| R::from_f64(v.to_f64()));
    NilRay {
        point: round(r.point),
        velocity: round(r.velocity),
    }
}

fn widen<R: Real>(r: &NilRay<R>) -> NilRay<DoubleDouble> {
    let widen = |x: [R; 3]| x.map(|v| DoubleDouble::new(v.to_f64()));
    NilRay {
        point: widen(r.point),
        velocity: widen(r.velocity),
    }
}

/// The flow in precision `R` from the start rounded to `R`, its error against the
/// reference, and the conditioning limit (the exact flow from that rounded start).
fn errors<R: Real>(s: &Sample) -> (f64, f64) {
    let start = round_ray::<R>(&s.start);
    let walked = flow(&start, R::from_f64(s.t));
    let exact_from_rounded = flow(&widen(&start), DoubleDouble::new(s.t));
    (
        gap(&widen(&walked), &s.end),
        gap(&exact_from_rounded, &s.end),
    )
}

#[test]
fn the_closed_form_is_the_integrated_geodesic_to_28_digits() {
    let samples = reference();
    assert!(samples.len() >= 20, "{} samples", samples.len());
    let mut worst = 0.0_f64;
    for s in &samples {
        let ours = flow(&s.start, DoubleDouble::new(s.t));
        let e = gap(&ours, &s.end);
        worst = worst.max(e);
        assert!(
            e < 1e-28 * (1.0 + s.t * s.t),
            "{} at t = {}: {e:e}",
            s.case,
            s.t
        );
    }
    println!("double-double against the 40-digit reference: worst {worst:.2e}");
}

#[test]
fn f64_and_f32_flows_are_within_a_few_times_the_conditioning_limit() {
    let samples = reference();
    for (name, eps, errors_of) in [
        (
            "f64",
            f64::EPSILON,
            errors::<f64> as fn(&Sample) -> (f64, f64),
        ),
        ("f32", f64::from(f32::EPSILON), errors::<f32>),
    ] {
        let (mut errors, mut limits) = (Vec::new(), Vec::new());
        for s in &samples {
            let (error, limit) = errors_of(s);
            // The evaluation's own few roundings, growing as the conditioning does.
            let own = 16.0 * eps * (1.0 + s.t * s.t);
            assert!(
                error <= 4.0 * limit + own,
                "{name} {} at t = {}: error {error:e}, conditioning limit {limit:e}",
                s.case,
                s.t
            );
            errors.push(error / eps);
            limits.push(limit / eps);
        }
        for v in [&mut errors, &mut limits] {
            v.sort_by(f64::total_cmp);
        }
        let n = errors.len();
        println!(
            "{name}: error in units of ε median {:.2}, worst {:.2}; the conditioning limit \
             (the exact flow from the rounded start) median {:.2}, worst {:.2}",
            errors[n / 2],
            errors[n - 1],
            limits[n / 2],
            limits[n - 1]
        );
    }
}

#[test]
fn the_flow_keeps_its_speed_composes_and_commutes_with_translations() {
    let d = DoubleDouble::new;
    let cases = [
        [0.6, -0.8, 0.0],
        [0.0, 0.0, 1.0],
        [0.3, 0.4, 0.866_025_403_784_438_6],
        [0.999_999_999_999, 0.0, 1.414_213_562e-6],
    ];
    for v in cases {
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let ray = NilRay {
            point: [d(0.25), d(-0.5), d(0.125)],
            velocity: v.map(|x| d(x / n)),
        };
        for (t, s) in [(0.5, 1.25), (3.0, 4.0), (1e-3, 7.0)] {
            let whole = flow(&ray, d(t) + d(s));
            let parts = flow(&flow(&ray, d(t)), d(s));
            assert!(
                gap(&whole, &parts) < 1e-28 * (1.0 + (t + s).powi(2)),
                "{v:?}"
            );
            let speed = |r: &NilRay<DoubleDouble>| {
                r.velocity
                    .iter()
                    .map(|x| *x * *x)
                    .fold(d(0.0), |a, b| a + b)
            };
            assert!((speed(&whole) - speed(&ray)).abs().to_f64() < 1e-30);
            let g = [d(1.0), d(-2.0), d(0.5)];
            let moved = NilRay {
                point: group_product(g, ray.point),
                ..ray
            };
            let carried = NilRay {
                point: group_product(g, whole.point),
                ..whole
            };
            assert!(gap(&flow(&moved, d(t) + d(s)), &carried) < 1e-28 * (1.0 + (t + s).powi(2)));
        }
    }
}

/// On both sides of the switch from the series to `sin` and `cos` (`|ct| = 2`) the flow
/// agrees to the last bits: no seam in the picture where rays cross it.
#[test]
fn series_and_closed_form_agree_where_they_meet() {
    use bevy_curved_spaces::space::nil::flow::flow_terms;
    for c in [0.5_f64, -0.9, 1.0] {
        let t = 2.0 / c.abs();
        let (below, above) = (t * (1.0 - 1e-15), t * (1.0 + 1e-15));
        let (a, b) = (flow_terms(c, below), flow_terms(c, above));
        for (x, y) in [(a.0, b.0), (a.1, b.1), (a.2, b.2)] {
            assert!((x - y).abs() <= 1e-13 * (1.0 + y.abs()), "{c}: {x} {y}");
        }
    }
}
