//! Metric balls: the first hit of a ray is the first zero of `d(γ(t), c) − r` found by
//! brute force in double-double, to the root's conditioning; none is found where brute
//! force finds none; the normal is the distance's gradient (central differences).

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
            let aim =
                glam::DVec3::from_array(bevy_curved_spaces::space::nil::shortest(start, centre).1);
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
