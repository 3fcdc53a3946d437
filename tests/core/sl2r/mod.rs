//! SL̃(2,R)'s geodesic flow in closed form against an independent reference: the geodesic
//! equations of the Sasaki metric of `UT H²` in a chart, integrated at 45 digits by mpmath
//! (`scripts/sl2r-reference.py`, stored in `tests/data/sl2r_geodesics.json` with 40
//! digits), in double-double, f64 and f32; the exits and the walk of `UT Σ`.
//!
//! Each precision is measured against the reference and against the **conditioning
//! limit**: the exact flow (double-double) from the start rounded to that precision, as
//! close as any method can get from a rounded start. Along a hypercycle the frame's entries
//! grow like `e^{ωt}` and so do the errors of any start; along a circle they stay bounded.

mod covers;
mod distance;
#[cfg(feature = "scene-files")]
mod files;
mod light;
mod pictures;
mod walks;
mod walls;

use bevy_curved_spaces::geometry::{DoubleDouble, Real};
use bevy_curved_spaces::space::sl2r::{Sl2rRay, flow};
use serde_json::Value;

/// A double-double stored as two decimal strings (read by `str::parse`, correctly rounded).
fn dd(pair: &Value) -> DoubleDouble {
    let p = pair.as_array().expect("a pair");
    let part = |v: &Value| -> f64 { v.as_str().expect("a string").parse().expect("a number") };
    DoubleDouble::new(part(&p[0])) + DoubleDouble::new(part(&p[1]))
}

fn list(v: &Value) -> Vec<DoubleDouble> {
    v.as_array().expect("numbers").iter().map(dd).collect()
}

/// The frame `(e, e⊥, p)` of a model point `[p, e]`: `e⊥ = J(p × e)`.
pub(crate) fn frame_of<R: Real>(p: [R; 3], e: [R; 3]) -> [[R; 3]; 3] {
    let f = [
        p[1] * e[2] - p[2] * e[1],
        p[2] * e[0] - p[0] * e[2],
        -(p[0] * e[1] - p[1] * e[0]),
    ];
    [e, f, p]
}

fn ray_of(model: &[DoubleDouble], velocity: &[DoubleDouble]) -> Sl2rRay<DoubleDouble> {
    let p = [model[0], model[1], model[2]];
    let e = [model[3], model[4], model[5]];
    Sl2rRay {
        frame: frame_of(p, e),
        velocity: [velocity[0], velocity[1], velocity[2]],
    }
}

/// One sample of the reference: the start ray, the time, and the ray there.
struct Sample {
    case: String,
    start: Sl2rRay<DoubleDouble>,
    t: f64,
    end: Sl2rRay<DoubleDouble>,
    /// The chart's angle at the start and at `t` as the reference integrated it (lifted:
    /// never wrapped).
    theta: (f64, f64),
}

fn reference() -> Vec<Sample> {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sl2r_geodesics.json"),
    )
    .expect("the stored reference");
    let doc: Value = serde_json::from_str(&text).expect("JSON");
    let mut out = Vec::new();
    for case in doc["cases"].as_array().expect("cases") {
        let start = ray_of(&list(&case["model_dd"]), &list(&case["velocity_dd"]));
        let number =
            |v: &Value| -> f64 { v.as_str().expect("a number").parse().expect("a number") };
        for s in case["samples"].as_array().expect("samples") {
            out.push(Sample {
                case: case["name"].as_str().expect("name").to_string(),
                start,
                t: s["t"].as_str().expect("t").parse().expect("a time"),
                end: ray_of(&list(&s["model_dd"]), &list(&s["velocity_dd"])),
                theta: (number(&case["theta"]), number(&s["theta"])),
            });
        }
    }
    out
}

/// The largest difference of the two rays' `p`, `e` and velocity entries, each relative
/// to `1 + |entry|`.
fn gap(a: &Sl2rRay<DoubleDouble>, b: &Sl2rRay<DoubleDouble>) -> f64 {
    let entries = |r: &Sl2rRay<DoubleDouble>| {
        let mut v: Vec<DoubleDouble> = r.frame[2].to_vec();
        v.extend(r.frame[0]);
        v.extend(r.velocity);
        v
    };
    entries(a)
        .iter()
        .zip(entries(b).iter())
        .map(|(x, y)| ((*x - *y).abs().to_f64()) / (1.0 + y.abs().to_f64()))
        .fold(0.0, f64::max)
}

fn round_ray<R: Real>(r: &Sl2rRay<DoubleDouble>) -> Sl2rRay<R> {
    let round = |x: [DoubleDouble; 3]| x.map(|v| R::from_f64(v.to_f64()));
    Sl2rRay {
        frame: r.frame.map(round),
        velocity: round(r.velocity),
    }
}

fn widen<R: Real>(r: &Sl2rRay<R>) -> Sl2rRay<DoubleDouble> {
    let widen = |x: [R; 3]| x.map(|v| DoubleDouble::new(v.to_f64()));
    Sl2rRay {
        frame: r.frame.map(widen),
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
    assert!(samples.len() >= 18, "{} samples", samples.len());
    let mut worst = 0.0_f64;
    for s in &samples {
        let ours = flow(&s.start, DoubleDouble::new(s.t));
        let e = gap(&ours, &s.end);
        worst = worst.max(e);
        assert!(
            e < 1e-28 * (1.0 + s.t).exp(),
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
            // The evaluation's own few roundings, growing as the frame's entries do.
            let own = 16.0 * eps * (1.0 + s.t) * s.t.exp();
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

/// Rays of every kind: a hypercycle, a horocycle, a circle, the fibre, and `ω²` within
/// 10⁻¹² of 0 on both sides.
pub(crate) fn velocities() -> Vec<[f64; 3]> {
    let h = 0.5_f64.sqrt();
    let mut v = vec![
        [0.6, -0.8, 0.0],
        [0.0, 0.0, 1.0],
        [0.3, 0.4, 0.866_025_403_784_438_6],
        [h, 0.0, h],
        [0.8 * 1.1_f64.cos(), 0.8 * 1.1_f64.sin(), -0.6],
    ];
    for d in [1e-12, -1e-12, 1e-6, -1e-6] {
        v.push([h * (1.0 + d), 0.0, -h]);
    }
    v.into_iter()
        .map(|v| {
            let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|x| x / n)
        })
        .collect()
}

/// A ray at a point off the origin with the velocity `v`, in double-double.
pub(crate) fn start(v: [f64; 3]) -> Sl2rRay<DoubleDouble> {
    let d = DoubleDouble::new;
    // From the origin with e at angle 0.7, flown 0.6 along the ray itself.
    let (c, s) = (d(0.7_f64.cos()), d(0.7_f64.sin()));
    let n = (c * c + s * s).sqrt();
    let ray = Sl2rRay {
        frame: frame_of([d(0.0), d(0.0), d(1.0)], [c / n, s / n, d(0.0)]),
        velocity: v.map(d),
    };
    flow(&ray, d(0.6))
}

#[test]
fn the_flow_keeps_its_speed_and_frame_composes_and_commutes_with_isometries() {
    let d = DoubleDouble::new;
    let lorentz =
        |u: [DoubleDouble; 3], v: [DoubleDouble; 3]| u[0] * v[0] + u[1] * v[1] - u[2] * v[2];
    for v in velocities() {
        let ray = start(v);
        for (t, s) in [(0.5, 1.25), (2.0, 1.5), (1e-3, 3.0)] {
            let whole = flow(&ray, d(t) + d(s));
            let parts = flow(&flow(&ray, d(t)), d(s));
            assert!(
                gap(&whole, &parts) < 1e-28 * (1.0 + t + s).exp(),
                "{v:?}: {:e}",
                gap(&whole, &parts)
            );
            // The frame stays Lorentz-orthonormal, the speed 1, the vertical rate c.
            let [e, f, p] = whole.frame;
            for (x, want) in [
                (lorentz(p, p), -1.0),
                (lorentz(e, e), 1.0),
                (lorentz(f, f), 1.0),
                (lorentz(e, p), 0.0),
                (lorentz(f, p), 0.0),
                (lorentz(e, f), 0.0),
            ] {
                assert!(
                    (x - d(want)).abs().to_f64() < 1e-28 * (1.0 + t + s).exp(),
                    "{v:?}: the frame left SO(2,1) by {:e}",
                    (x - d(want)).abs().to_f64()
                );
            }
            let speed = |r: &Sl2rRay<DoubleDouble>| {
                r.velocity
                    .iter()
                    .map(|x| *x * *x)
                    .fold(d(0.0), |a, b| a + b)
            };
            assert!((speed(&whole) - speed(&ray)).abs().to_f64() < 1e-30);
            assert_eq!(whole.velocity[2], ray.velocity[2]);
            // A rotation and a boost of H² (an isometry, acting on the frame) commute with
            // the flow.
            let (c, sn) = (d(0.6), d(0.8));
            let (ch, sh) = (d(1.25), d(0.75));
            let rot = [[c, -sn, d(0.0)], [sn, c, d(0.0)], [d(0.0), d(0.0), d(1.0)]];
            let boost = [[ch, d(0.0), sh], [d(0.0), d(1.0), d(0.0)], [sh, d(0.0), ch]];
            for m in [rot, boost] {
                let moved = bevy_curved_spaces::space::sl2r::flow::moved_by(&m, &ray);
                let a = flow(&moved, d(t));
                let b = bevy_curved_spaces::space::sl2r::flow::moved_by(&m, &flow(&ray, d(t)));
                assert!(gap(&a, &b) < 1e-28 * (1.0 + t).exp(), "{v:?}");
            }
        }
    }
}

#[test]
fn the_three_kinds_meet_without_a_seam() {
    // ω² crossing 0: the flow is continuous (no test picks a formula), in f64.
    let h = 0.5_f64.sqrt();
    let at = |d: f64| {
        let v = [h * (1.0 + d), 0.0, h];
        let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let ray = Sl2rRay {
            frame: frame_of([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            velocity: v.map(|x| x / n),
        };
        flow(&ray, 3.0).frame[2]
    };
    let zero = at(0.0);
    for d in [1e-15, -1e-15, 1e-12, -1e-12] {
        let p = at(d);
        let gap = (0..3).map(|i| (p[i] - zero[i]).abs()).fold(0.0, f64::max);
        // The path itself moves by O(d t²); rounding adds a few ε.
        assert!(
            gap < 10.0 * d.abs() + 1e-14,
            "a seam of {gap:e} at ω² ~ {d:e}"
        );
    }
}
