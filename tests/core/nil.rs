//! Nil's geodesic flow in closed form against an independent reference: the geodesic
//! equations of the metric integrated at 45 digits by mpmath (`scripts/nil-reference.py`,
//! stored in `tests/data/nil_geodesics.json` with 40 digits), in double-double, f64 and f32.
//!
//! Each precision is measured against the reference and against the **conditioning
//! limit**: the exact flow (double-double) started from the start rounded to that
//! precision, which is as close as any method can get from a rounded start. Nil's
//! geodesics spread polynomially (a start rounded by ε ends `O(ε t²)` away: the height
//! gains the area swept), so that limit grows with `t²`.

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

mod exits {
    use super::*;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::nil::exit::height_and_rate;
    use bevy_curved_spaces::space::nil::{horizontal_exit, vertical_exit};

    fn d(x: f64) -> DoubleDouble {
        DoubleDouble::new(x)
    }

    /// The first zero of `g` in `(0, end]` by brute force in double-double: a grid of
    /// `step`, then bisection to the last bit; with `|g′|` there (to leave out grazes).
    fn brute(
        g: impl Fn(DoubleDouble) -> DoubleDouble,
        end: f64,
        step: f64,
    ) -> Option<(DoubleDouble, f64)> {
        let mut a = 1e-12;
        let mut ga = g(d(a));
        while a < end {
            let b = (a + step).min(end);
            let gb = g(d(b));
            if (ga.to_f64() <= 0.0) != (gb.to_f64() <= 0.0) {
                let (mut lo, mut hi) = (d(a), d(b));
                for _ in 0..120 {
                    let mid = (lo + hi) * d(0.5);
                    if (g(mid).to_f64() <= 0.0) == (ga.to_f64() <= 0.0) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let slope = ((gb - ga) / d(b - a)).to_f64().abs();
                return Some((lo, slope));
            }
            (a, ga) = (b, gb);
        }
        None
    }

    fn rays(rng: &mut SplitMix64) -> Vec<NilRay<f64>> {
        let mut out = Vec::new();
        let special = [
            [0.6, 0.8, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 1e-9],
            [0.0, 1.0, -1e-12],
            [0.8, 0.0, 0.6],
            [0.01, 0.0, 0.99995],
        ];
        for i in 0..250 {
            let p = [rng.unit() - 0.5, rng.unit() - 0.5, (rng.unit() - 0.5) * 0.5];
            let v = if i < special.len() * 10 {
                let s = special[i % special.len()];
                let n = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
                s.map(|x| x / n)
            } else {
                rng.direction().to_array()
            };
            out.push(NilRay {
                point: p,
                velocity: v,
            });
        }
        out
    }

    fn widen(r: &NilRay<f64>) -> NilRay<DoubleDouble> {
        NilRay {
            point: r.point.map(d),
            velocity: r.velocity.map(d),
        }
    }

    /// Every crossing of the planes x = ½ (and y = −½) found by the closed form, in f64
    /// and double-double, is the first zero brute force finds, to the conditioning of the
    /// root (its time's rounding over the slope there); and none is found where brute
    /// force finds none.
    #[test]
    fn vertical_exits_are_the_first_crossings_to_the_last_bits() {
        let mut rng = SplitMix64(49);
        let (mut compared, mut worst_f64, mut worst_dd) = (0, 0.0_f64, 0.0_f64);
        for ray in rays(&mut rng) {
            for (n, r) in [([1.0, 0.0], 0.5), ([0.0, -1.0], 0.5), ([0.6, 0.8], 0.5)] {
                // Starts inside the half-plane, as in a cell.
                if n[0] * ray.point[0] + n[1] * ray.point[1] > r {
                    continue;
                }
                let exact = widen(&ray);
                let g = |t: DoubleDouble| {
                    let p = flow(&exact, t).point;
                    p[0] * d(n[0]) + p[1] * d(n[1]) - d(r)
                };
                let found = brute(g, 12.0, 1e-3);
                let ours = vertical_exit(&ray, n, r);
                let ours_dd = vertical_exit(&exact, n.map(d), d(r));
                match (found, ours, ours_dd) {
                    (Some((exact_t, slope)), Some(a), Some(b)) if slope > 1e-3 => {
                        let t = exact_t.to_f64();
                        let e64 = (a - t).abs() / (1.0 + t);
                        let edd = (b - exact_t).abs().to_f64() / (1.0 + t);
                        assert!(
                            e64 < 64.0 * f64::EPSILON / slope.min(1.0),
                            "{ray:?} {n:?}: f64 {a} brute {t}"
                        );
                        assert!(edd < 1e-28, "{ray:?} {n:?}: dd {b:?} brute {exact_t:?}");
                        worst_f64 = worst_f64.max(e64 * slope.min(1.0) / f64::EPSILON);
                        worst_dd = worst_dd.max(edd);
                        compared += 1;
                    }
                    (None, Some(a), _) => {
                        assert!(
                            a > 12.0,
                            "{ray:?} {n:?}: an exit at {a} where brute force finds none"
                        );
                    }
                    (Some((t, slope)), None, _) if slope > 1e-3 => {
                        panic!("{ray:?} {n:?}: no exit, brute force finds one at {t:?}");
                    }
                    _ => {}
                }
            }
        }
        assert!(compared > 300, "{compared} compared");
        println!(
            "vertical exits: {compared} compared, f64 worst {worst_f64:.2} ε (over the slope), dd worst {worst_dd:.1e}"
        );
    }

    /// Every crossing of the planes z = ±¼ found by bracketing between the height's turning
    /// points and refining is the first zero brute force finds.
    #[test]
    fn horizontal_exits_are_the_first_crossings_to_the_last_bits() {
        let mut rng = SplitMix64(50);
        let (mut compared, mut worst_f64, mut worst_dd) = (0, 0.0_f64, 0.0_f64);
        for ray in rays(&mut rng) {
            for h in [0.25, -0.25] {
                let exact = widen(&ray);
                let g = |t: DoubleDouble| height_and_rate(&exact, t).0 - d(h);
                let end = 8.0;
                let found = brute(g, end, 1e-3);
                let ours = horizontal_exit(&ray, h, end);
                // Without a bound, the same first crossing (to the root's conditioning: the
                // refinement starts from another bracket), or one past the bound.
                let unbounded = horizontal_exit(&ray, h, f64::INFINITY);
                let rate = height_and_rate(&ray, ours.unwrap_or(0.0)).1.abs().min(1.0);
                match (ours, unbounded) {
                    (Some(a), Some(b)) => assert!(
                        (a - b).abs() <= 64.0 * f64::EPSILON * (1.0 + a) / rate.max(1e-3),
                        "{ray:?} {h}: {a} and unbounded {b}"
                    ),
                    (Some(a), None) => panic!("{ray:?} {h}: {a}, none unbounded"),
                    (None, b) => assert!(b.is_none_or(|t| t > end), "{ray:?} {h}"),
                }
                let ours_dd = horizontal_exit(&exact, d(h), d(end));
                match (found, ours, ours_dd) {
                    (Some((exact_t, slope)), Some(a), Some(b)) if slope > 1e-3 => {
                        let t = exact_t.to_f64();
                        let e64 = (a - t).abs() / (1.0 + t);
                        assert!(
                            e64 < 64.0 * f64::EPSILON / slope.min(1.0),
                            "{ray:?} {h}: f64 {a} brute {t}"
                        );
                        let edd = (b - exact_t).abs().to_f64() / (1.0 + t);
                        assert!(edd < 1e-28, "{ray:?} {h}: dd {b:?} brute {exact_t:?}");
                        worst_dd = worst_dd.max(edd);
                        worst_f64 = worst_f64.max(e64 * slope.min(1.0) / f64::EPSILON);
                        compared += 1;
                    }
                    (None, Some(a), _) => {
                        panic!("{ray:?} {h}: an exit at {a} where brute force finds none")
                    }
                    (Some((t, slope)), None, _) if slope > 1e-3 => {
                        panic!("{ray:?} {h}: no exit, brute force finds one at {t:?}")
                    }
                    _ => {}
                }
            }
        }
        assert!(compared > 200, "{compared} compared");
        println!(
            "horizontal exits: {compared} compared, f64 worst {worst_f64:.2} ε (over the slope), dd worst {worst_dd:.1e}"
        );
    }
}

/// The walk through the box of `nil-K` over the walk contract: where it ends is the
/// universal cover's geodesic carried by an element of `Γ_K` (`A^p B^q C^m = (p, q,
/// pq/2 + m/K)`), long walks stay in the box, the f32 walk keeps the f64 walk's faces, and
/// a walk by distance split in two ends where the whole one does.
mod walks {
    use super::*;
    use bevy_curved_spaces::geometry::Ray;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::nil::NilWalker;
    use bevy_curved_spaces::space::{CellWalk, Limit};
    use glam::{DVec4, Vec4};

    fn start(rng: &mut SplitMix64, k: u32) -> Ray<DVec4> {
        let h = 0.5 / f64::from(k);
        let v = rng.direction();
        Ray {
            point: DVec4::new(
                rng.unit() - 0.5,
                rng.unit() - 0.5,
                (2.0 * rng.unit() - 1.0) * h,
                1.0,
            ),
            tangent: v.extend(0.0),
        }
    }

    fn as_nil(r: &Ray<DVec4>) -> NilRay<DoubleDouble> {
        let d = DoubleDouble::new;
        NilRay {
            point: [d(r.point.x), d(r.point.y), d(r.point.z)],
            velocity: [d(r.tangent.x), d(r.tangent.y), d(r.tangent.z)],
        }
    }

    #[test]
    fn a_walk_ends_on_the_cover_geodesic_carried_by_the_lattice() {
        let mut rng = SplitMix64(51);
        let mut worst = 0.0_f64;
        for k in [1, 3, 50] {
            let walker = NilWalker::<DVec4>::new(k);
            for _ in 0..60 {
                let s = start(&mut rng, k);
                let distance = 0.5 + 6.0 * rng.unit();
                let (end, walked) = CellWalk::walk(&walker, s, Limit::Distance(distance), |_| true);
                assert_eq!(walked, distance);
                // g = end · γ(T)⁻¹, with γ the cover geodesic (double-double).
                let cover = flow(&as_nil(&s), DoubleDouble::new(distance));
                let inverse = cover.point.map(|x| -x);
                let e = as_nil(&end);
                let g = group_product(e.point, inverse).map(|x| x.to_f64());
                let (p, q) = (g[0].round(), g[1].round());
                let m = (g[2] - p * q / 2.0) * f64::from(k);
                let off = (g[0] - p)
                    .abs()
                    .max((g[1] - q).abs())
                    .max((m - m.round()).abs() / f64::from(k));
                let tolerance = 1e-12 * (1.0 + distance * distance) * f64::from(k);
                assert!(
                    off < tolerance,
                    "nil-{k}: the end is {off:e} off the lattice's image"
                );
                for i in 0..3 {
                    let dv = (e.velocity[i] - cover.velocity[i]).abs().to_f64();
                    assert!(dv < tolerance, "nil-{k}: velocity {i} off by {dv:e}");
                }
                worst = worst.max(off / (1.0 + distance * distance));
            }
        }
        println!("walks against the cover: worst {worst:.1e} (over 1 + d²)");
    }

    #[test]
    fn long_walks_stay_in_the_box() {
        let mut rng = SplitMix64(52);
        for k in [1, 3, 50] {
            let h = 0.5 / f64::from(k);
            let walker = NilWalker::<DVec4>::new(k);
            let s = start(&mut rng, k);
            let mut count = 0usize;
            let mut worst = 0.0_f64;
            let (end, _) = CellWalk::walk(&walker, s, Limit::Crossings(100_000), |c| {
                count += 1;
                let p = c.ray.point;
                let out = (p.x.abs() - 0.5).max(p.y.abs() - 0.5).max(p.z.abs() - h);
                worst = worst.max(out);
                true
            });
            assert_eq!(count, 100_000, "nil-{k}: the walk stopped after {count}");
            assert!(worst <= 0.0, "nil-{k}: {worst:e} out of the box");
            let speed = end.tangent.truncate().length();
            assert!((speed - 1.0).abs() < 1e-12, "nil-{k}: speed {speed}");
        }
    }

    #[test]
    fn f32_walks_keep_the_f64_faces_and_split_walks_compose() {
        let mut rng = SplitMix64(53);
        let (mut same, mut total) = (0, 0);
        for k in [1, 3] {
            let w64 = NilWalker::<DVec4>::new(k);
            let w32 = NilWalker::<Vec4>::new(k);
            for _ in 0..100 {
                let s = start(&mut rng, k);
                let t64 = CellWalk::trace(&w64, s, Limit::Crossings(8));
                let s32 = Ray {
                    point: s.point.as_vec4(),
                    tangent: s.tangent.as_vec4(),
                };
                let t32 = CellWalk::trace(&w32, s32, Limit::Crossings(8));
                for (a, b) in t64.crossings.iter().zip(&t32.crossings).take(3) {
                    total += 1;
                    same += usize::from(a.face == b.face);
                }
                let (whole, _) = CellWalk::walk(&w64, s, Limit::Distance(3.0), |_| true);
                let (half, _) = CellWalk::walk(&w64, s, Limit::Distance(1.25), |_| true);
                let (rest, _) = CellWalk::walk(&w64, half, Limit::Distance(1.75), |_| true);
                let gap = (whole.point - rest.point).abs().max_element();
                assert!(gap < 1e-11, "nil-{k}: split walk {gap:e} apart");
            }
        }
        // Only rays passing within f32's rounding of an edge may differ.
        assert!(
            same * 100 >= total * 98,
            "{same} of {total} faces kept in f32"
        );
    }
}

/// The spaces `nil-K` over the geometry contract: frames carried by parallel transport
/// (against the transport equation integrated by fine Runge–Kutta steps), kept orthonormal
/// and in the box by the wrap, each wrap a left translation by an element of `Γ_K` that
/// leaves the axes alone; the registry's ids.
mod spaces {
    use super::*;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::nil::{NilSpace, nil_space, transport};
    use bevy_curved_spaces::space::{AnySpace, Family, FrameMotion, FrameSpace};
    use glam::{DMat4, DVec3};

    /// `∇_U W` in the left-invariant frame (the connection of the module's docs).
    fn connection(u: DVec3, w: DVec3) -> DVec3 {
        0.5 * DVec3::new(
            u.y * w.z + u.z * w.y,
            -u.x * w.z - u.z * w.x,
            u.x * w.y - u.y * w.x,
        )
    }

    /// `w` carried along the geodesic of `u0` for `t` by the transport equation
    /// `ẇ = −∇_U W`, with `U` the flow's velocity, in 20 000 RK4 steps.
    fn integrated(u0: DVec3, w: DVec3, t: f64) -> DVec3 {
        let steps = 20_000;
        let h = t / f64::from(steps);
        let c = u0.z;
        let u = |s: f64| {
            let (sn, cs) = (c * s).sin_cos();
            DVec3::new(u0.x * cs - u0.y * sn, u0.x * sn + u0.y * cs, c)
        };
        let f = |s: f64, w: DVec3| -connection(u(s), w);
        let mut w = w;
        for i in 0..steps {
            let s = f64::from(i) * h;
            let k1 = f(s, w);
            let k2 = f(s + h / 2.0, w + k1 * (h / 2.0));
            let k3 = f(s + h / 2.0, w + k2 * (h / 2.0));
            let k4 = f(s + h, w + k3 * h);
            w += (k1 + 2.0 * k2 + 2.0 * k3 + k4) * (h / 6.0);
        }
        w
    }

    #[test]
    fn parallel_transport_is_the_transport_equations_solution() {
        let mut rng = SplitMix64(54);
        let mut worst = 0.0_f64;
        for _ in 0..12 {
            let u0 = rng.direction();
            let t = 0.5 + 4.0 * rng.unit();
            let frame = DMat4::IDENTITY;
            let moved = transport(frame, u0, t);
            for (axis, column) in [
                (DVec3::X, moved.x_axis),
                (DVec3::Y, moved.y_axis),
                (DVec3::Z, moved.z_axis),
            ] {
                let want = integrated(u0, axis, t);
                worst = worst.max((column.truncate() - want).abs().max_element());
            }
            // The velocity is parallel: carried, it is the flow's velocity.
            let carried = DMat3::from_cols(
                moved.x_axis.truncate(),
                moved.y_axis.truncate(),
                moved.z_axis.truncate(),
            ) * u0;
            let end = flow(
                &NilRay {
                    point: [0.0; 3],
                    velocity: u0.to_array(),
                },
                t,
            );
            assert!(
                (carried - DVec3::from_array(end.velocity))
                    .abs()
                    .max_element()
                    < 1e-13
            );
            assert!(
                (moved.w_axis.truncate() - DVec3::from_array(end.point))
                    .abs()
                    .max_element()
                    < 1e-15
            );
        }
        assert!(worst < 1e-12, "closed form and RK4 differ by {worst:e}");
        println!("parallel transport against RK4: worst {worst:.1e}");
    }
    use glam::DMat3;

    #[test]
    fn a_player_walks_in_the_box_with_orthonormal_axes() {
        let mut rng = SplitMix64(55);
        for k in [1, 3, 50] {
            let space = NilSpace::new(k);
            let mut frame = DMat4::IDENTITY;
            let mut crossings = 0;
            for _ in 0..5000 {
                let motion = FrameMotion {
                    translation: (rng.direction() * 0.2 * space.scale()),
                    rotation: DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, 0.0) * 0.3,
                    level: false,
                };
                let stepped = space.step_frame(frame, &motion);
                let (wrapped, crossed) = space.wrap_frame(stepped, 0.0);
                for c in &crossed {
                    // A left translation: the axes are kept, the point moved by the matrix.
                    let moved = c.pairing * stepped.w_axis;
                    assert!(moved.w == 1.0);
                }
                if !crossed.is_empty() {
                    assert_eq!(wrapped.x_axis, stepped.x_axis);
                }
                crossings += crossed.len();
                frame = wrapped;
                assert!(
                    space.outside_by(frame.w_axis) <= 1e-12,
                    "nil-{k}: out of the box"
                );
                assert!(
                    space.frame_defect(frame) < 1e-12,
                    "nil-{k}: axes not orthonormal"
                );
            }
            assert!(crossings > 100, "nil-{k}: {crossings} crossings");
        }
    }

    #[test]
    fn the_registry_sends_nil_ids_to_the_nil_family() {
        let space = AnySpace::named("nil-7").expect("nil-7");
        assert_eq!(space.family(), Family::Nil);
        assert_eq!(space.geometry_name(), "Nil");
        assert!((space.volume() - 1.0 / 7.0).abs() < 1e-16);
        assert_eq!(AnySpace::named("heisenberg").unwrap().name(), "nil-1");
        for bad in ["nil-0", "nil-1.5", "nil-x"] {
            let e = AnySpace::named(bad).expect_err("refused");
            assert!(e.contains("whole number"), "{e}");
        }
        assert!(nil_space("torus").is_none());
        // A start far outside the box is brought in by the lattice.
        let ray = NilSpace::new(3)
            .chart_ray(DVec3::new(1e6 + 0.25, -2e5, 123.4), DVec3::X)
            .expect("a ray");
        assert!(NilSpace::new(3).outside_by(ray.point) <= 0.0);
        assert!((ray.point.x - 0.25).abs() < 1e-9);
    }
}

/// The inverse of the exponential map: the shortest geodesic's length and start velocity.
/// Walked, it reaches the target; no geodesic of another winding to the target is
/// shorter; the distance is symmetric, obeys the triangle inequality, and on the vertical
/// axis is the vertical line's up to 2π and the helix's beyond.
mod distances {
    use super::*;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::nil::distance::{distance, reached, shortest};

    fn point(rng: &mut SplitMix64, size: f64) -> [f64; 3] {
        [
            (rng.unit() - 0.5) * size,
            (rng.unit() - 0.5) * size,
            (rng.unit() - 0.5) * size,
        ]
    }

    #[test]
    fn the_shortest_geodesic_reaches_its_target() {
        let mut rng = SplitMix64(56);
        let mut worst = 0.0_f64;
        for i in 0..2000 {
            let size = [0.01, 1.0, 4.0, 20.0][i % 4];
            let (p, q) = (point(&mut rng, size), point(&mut rng, size));
            let r = reached(p, q);
            let gap = (0..3).map(|k| (r[k] - q[k]).abs()).fold(0.0, f64::max);
            worst = worst.max(gap / (1.0 + size * size));
            assert!(
                gap < 1e-11 * (1.0 + size * size),
                "{p:?} → {q:?}: off by {gap:e}"
            );
            let (_, v) = shortest(p, q);
            assert!(((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() - 1.0).abs() < 1e-14);
        }
        // In double-double, to 28 digits.
        let d = DoubleDouble::new;
        for _ in 0..50 {
            let (p, q) = (point(&mut rng, 3.0), point(&mut rng, 3.0));
            let r = reached(p.map(d), q.map(d));
            for k in 0..3 {
                assert!((r[k] - d(q[k])).abs().to_f64() < 1e-28, "{p:?} → {q:?}");
            }
        }
        println!("shortest geodesics reach their targets: worst {worst:.1e} (over 1 + size²)");
    }

    /// Every geodesic from the origin to `q` winds by a root of the height equation on its
    /// own branch `(2πk, 2π(k+1))`; the ones on the further branches are longer.
    #[test]
    fn no_geodesic_of_another_winding_is_shorter() {
        let mut rng = SplitMix64(57);
        for _ in 0..300 {
            let q = point(&mut rng, 6.0);
            let (x, y, z) = (q[0], q[1], q[2].abs());
            let rho2 = x * x + y * y;
            let best = distance([0.0; 3], q);
            for k in 1..4 {
                // Bisection of h on (2πk, 2π(k+1)): increasing there too.
                let h = |t: f64| t + rho2 * (t - t.sin()) / (8.0 * (t / 2.0).sin().powi(2)) - z;
                let two_pi = std::f64::consts::TAU;
                let (mut lo, mut hi) = (two_pi * k as f64 + 1e-9, two_pi * (k + 1) as f64 - 1e-9);
                if !(h(lo) < 0.0 && h(hi) > 0.0) {
                    continue;
                }
                for _ in 0..100 {
                    let mid = 0.5 * (lo + hi);
                    if h(mid) < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let s = (lo / 2.0).sin();
                let length = lo / (2.0 * s.abs()) * (rho2 + 4.0 * s * s).sqrt();
                assert!(
                    length >= best - 1e-12,
                    "{q:?}: winding {k} gives {length} < {best}"
                );
            }
        }
    }

    #[test]
    fn the_distance_is_a_metric_and_knows_the_vertical_axis() {
        let mut rng = SplitMix64(58);
        for _ in 0..500 {
            let (p, q, r) = (
                point(&mut rng, 4.0),
                point(&mut rng, 4.0),
                point(&mut rng, 4.0),
            );
            let (pq, qp) = (distance(p, q), distance(q, p));
            assert!((pq - qp).abs() < 1e-12 * (1.0 + pq), "{pq} {qp}");
            assert!(distance(p, r) <= pq + distance(q, r) + 1e-12);
        }
        let pi = std::f64::consts::PI;
        for z in [0.5, 3.0, 2.0 * pi, 7.0, 30.0] {
            let want = if z <= 2.0 * pi {
                z
            } else {
                2.0 * pi * (z / pi - 1.0).sqrt()
            };
            assert!((distance([0.0; 3], [0.0, 0.0, z]) - want).abs() < 1e-14);
            assert!((distance([0.0; 3], [0.0, 0.0, -z]) - want).abs() < 1e-14);
            // Just off the axis the distance is continuous.
            let off = distance([0.0; 3], [1e-9, 0.0, z]);
            assert!((off - want).abs() < 1e-6, "{z}: {off} against {want}");
        }
        // A horizontal step is the straight line.
        assert!((distance([0.0; 3], [0.3, -0.4, 0.0]) - 0.5).abs() < 1e-16);
    }
}

/// Metric balls: the first hit of a ray is the first zero of `d(γ(t), c) − r` found by
/// brute force in double-double, to the root's conditioning; none is found where brute
/// force finds none; the normal is the distance's gradient (central differences).
mod balls {
    use super::*;
    use bevy_curved_spaces::random::SplitMix64;
    use bevy_curved_spaces::space::nil::{ball_hit, distance, normal};

    #[test]
    fn ball_hits_are_the_first_zeros_of_the_distance() {
        let d = DoubleDouble::new;
        let mut rng = SplitMix64(59);
        let (mut hits, mut misses, mut worst) = (0, 0, 0.0_f64);
        for i in 0..150 {
            let start = [rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5];
            let centre = [
                rng.unit() * 2.0 - 1.0,
                rng.unit() * 2.0 - 1.0,
                rng.unit() * 2.0 - 1.0,
            ];
            let radius = 0.1 + 0.4 * rng.unit();
            // Two rays in three aimed near the centre (along the shortest geodesic to it,
            // turned a little), the rest anywhere.
            let v = if i % 3 == 0 {
                rng.direction().to_array()
            } else {
                let aim = glam::DVec3::from_array(
                    bevy_curved_spaces::space::nil::shortest(start, centre).1,
                );
                (aim + rng.direction() * 0.6 * rng.unit())
                    .normalize()
                    .to_array()
            };
            let ray = NilRay {
                point: start,
                velocity: v,
            };
            let t_max = 4.0;
            let ours = ball_hit(&ray, centre, radius, t_max);
            // Brute force: the distance every 2e-3 in double-double, then bisection.
            let exact = NilRay {
                point: start.map(d),
                velocity: v.map(d),
            };
            let g = |t: DoubleDouble| distance(centre.map(d), flow(&exact, t).point) - d(radius);
            let mut found = None;
            let (mut a, mut ga) = (0.0, g(d(0.0)));
            if ga.to_f64() <= 0.0 {
                found = Some((d(0.0), 1.0));
            }
            while found.is_none() && a < t_max {
                let b = (a + 2e-3_f64).min(t_max);
                let gb = g(d(b));
                if gb.to_f64() <= 0.0 {
                    let (mut lo, mut hi) = (d(a), d(b));
                    for _ in 0..110 {
                        let mid = (lo + hi) * d(0.5);
                        if g(mid).to_f64() > 0.0 {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    let slope = ((ga - gb) / d(b - a)).to_f64();
                    found = Some((lo, slope));
                }
                (a, ga) = (b, gb);
            }
            match (found, ours) {
                (Some((t, slope)), Some(h)) if slope > 1e-2 => {
                    let e = (h - t.to_f64()).abs();
                    assert!(e < 1e-12 / slope, "hit {h} against {t:?} (slope {slope})");
                    worst = worst.max(e * slope);
                    hits += 1;
                }
                (None, Some(h)) => panic!("a hit at {h} where brute force finds none"),
                (Some((t, slope)), None) if slope > 1e-2 => {
                    panic!("a miss where brute force hits at {t:?} (slope {slope}): {ray:?}")
                }
                (None, None) => misses += 1,
                _ => {}
            }
        }
        assert!(hits > 50 && misses > 20, "{hits} hits, {misses} misses");
        println!("metric ball hits: {hits} hits, {misses} misses, worst {worst:.1e} × slope");
    }

    #[test]
    fn the_normal_is_the_gradient_of_the_distance() {
        let mut rng = SplitMix64(60);
        for _ in 0..100 {
            let c = [rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5];
            let p = [
                rng.unit() * 2.0 - 1.0,
                rng.unit() * 2.0 - 1.0,
                rng.unit() * 2.0 - 1.0,
            ];
            let n = normal(c, p);
            let h = 1e-6;
            for (i, axis) in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
                .iter()
                .enumerate()
            {
                // Along the geodesic of E_i through p, both ways.
                let step = |s: f64| {
                    flow(
                        &NilRay {
                            point: p,
                            velocity: *axis,
                        },
                        s,
                    )
                    .point
                };
                let slope = (distance(c, step(h)) - distance(c, step(-h))) / (2.0 * h);
                assert!(
                    (slope - n[i]).abs() < 1e-6,
                    "{c:?} {p:?}: ∂{i} {slope} against {}",
                    n[i]
                );
            }
        }
    }
}
