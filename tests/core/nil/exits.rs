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
