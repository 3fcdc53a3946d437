//! The shadow of a geodesic in the plane (`space::nil::shadow_within`): when it first comes
//! within a distance of a point, in closed form, against the flow sampled finely — for
//! horizontal rays (straight shadows), tiny and large vertical speeds, vertical rays, and
//! starts inside.

use bevy_curved_spaces::space::nil::{NilRay, flow, shadow_within};

/// The planar distance from the ray's point at `t` to `b`.
fn planar(ray: &NilRay<f64>, t: f64, b: [f64; 2]) -> f64 {
    let p = flow(ray, t).point;
    (p[0] - b[0]).hypot(p[1] - b[1])
}

#[test]
fn the_shadow_comes_within_the_radius_where_the_closed_form_says() {
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut entered = 0;
    for case in 0..3000 {
        let c = match case % 6 {
            0 => 0.0,
            1 => 1e-9 * (next() - 0.5),
            2 => 0.999_999 * (2.0 * next() - 1.0).signum(),
            3 => 1.0,
            _ => 2.0 * next() - 1.0,
        };
        let angle = 2.0 * std::f64::consts::PI * next();
        let a = (1.0 - c * c).max(0.0).sqrt();
        let ray = NilRay {
            point: [next() - 0.5, next() - 0.5, next() - 0.5],
            velocity: [a * angle.cos(), a * angle.sin(), c],
        };
        let b = [2.0 * next() - 1.0, 2.0 * next() - 1.0];
        let r = 0.02 + 0.3 * next();
        let horizon = 6.0;
        let found = shadow_within(&ray, b, r);
        // The first sample within r, at steps of 1e-4.
        let steps = 60_000;
        let first = (0..=steps)
            .map(|i| horizon * f64::from(i) / f64::from(steps))
            .find(|&t| planar(&ray, t, b) <= r);
        match (found, first) {
            (None, None) => {}
            (Some((t_in, t_out, period)), _) if t_in > horizon => {
                assert!(
                    first.is_none_or(|t| t > horizon - 2e-4),
                    "case {case}: {first:?}"
                );
                assert!(t_out >= t_in && period > 0.0);
            }
            (Some((t_in, t_out, _)), Some(t)) => {
                entered += 1;
                assert!(
                    t_in <= t + 1e-9,
                    "case {case}: closed form {t_in}, sampled {t}"
                );
                assert!(
                    t_in >= t - 2e-4,
                    "case {case}: closed form {t_in}, sampled {t}"
                );
                if t_in > 0.0 {
                    let d = planar(&ray, t_in, b);
                    assert!(
                        (d - r).abs() < 1e-9,
                        "case {case}: at t_in the shadow is {d}"
                    );
                } else {
                    assert!(planar(&ray, 0.0, b) <= r + 1e-12);
                }
                // Inside all the visit: sampled within r up to t_out (or the horizon).
                let end = t_out.min(horizon);
                for i in 1..10 {
                    let s = t_in + (end - t_in) * f64::from(i) / 10.0;
                    assert!(planar(&ray, s, b) <= r + 1e-9, "case {case}: left at {s}");
                }
            }
            (found, first) => panic!("case {case}: closed form {found:?}, sampled {first:?}"),
        }
    }
    assert!(entered > 200, "only {entered} rays came within the radius");
}
