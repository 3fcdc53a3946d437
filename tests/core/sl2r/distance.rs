//! SL̃(2,R)'s inverse exponential map, its distance floor and its metric balls: the
//! shortest geodesic between two frames found again from the geodesic that made them, the
//! floor below every distance, and balls met where the ray first comes within the radius.

use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::sl2r::accuracy::random_start;
use bevy_curved_spaces::space::sl2r::ball::{MAX_SL2R_BALL_RADIUS, ball_hit, normal};
use bevy_curved_spaces::space::sl2r::distance::{TRUSTED_LENGTH, distance_floor, shortest};
use bevy_curved_spaces::space::sl2r::{Sl2rRay, flow, sl2r_space};
use std::f64::consts::PI;

fn frames_apart(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> f64 {
    (0..3)
        .flat_map(|i| (0..3).map(move |j| (a[i][j] - b[i][j]).abs()))
        .fold(0.0, f64::max)
}

/// Geodesics shorter than the injectivity radius (`π`) are the shortest: the solver finds
/// each again, its length and its start direction, from its two ends — every kind of
/// geodesic (hypercycles, horocycles, circles, the fibre) and every length up to 2.9.
#[test]
fn the_shortest_geodesic_is_the_one_that_made_the_pair() {
    let space = sl2r_space("unit-tangent-bitorus").unwrap().unwrap();
    let mut rng = SplitMix64(0x0d15);
    let mut worst: f64 = 0.0;
    let mut directions = vec![
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.6, 0.0, 0.8],
        [0.0, 1.0 / 2f64.sqrt(), 1.0 / 2f64.sqrt()],
        [0.3, 0.4, (1.0f64 - 0.25).sqrt()],
    ];
    directions.extend((0..400).map(|_| rng.direction().to_array()));
    for (k, v) in directions.into_iter().enumerate() {
        let start = random_start(&space, &mut rng);
        let t = [1e-9_f64, 1e-4, 0.3, 1.0, 2.0, 2.9][k % 6].max(2.9 * rng.unit() * (k % 2) as f64);
        let ray = Sl2rRay {
            frame: start.frame,
            velocity: v,
        };
        let end = flow(&ray, t);
        let (length, found) = shortest(&start.frame, &end.frame)
            .unwrap_or_else(|| panic!("no geodesic found for {v:?} over {t}"));
        assert!(
            (length - t).abs() <= 1e-12 * (1.0 + t),
            "{v:?}: length {length} for {t}"
        );
        let again = flow(
            &Sl2rRay {
                frame: start.frame,
                velocity: found,
            },
            length,
        );
        let gap = frames_apart(&again.frame, &end.frame);
        worst = worst.max(gap);
        assert!(gap < 1e-11, "{v:?} over {t}: reached {gap:e} from the end");
        if t > 1e-6 {
            let dv = (0..3).map(|i| (found[i] - v[i]).abs()).fold(0.0, f64::max);
            assert!(
                dv < 1e-9 / t.min(1.0),
                "{v:?} over {t}: direction {found:?}"
            );
        }
    }
    eprintln!("shortest geodesics found again: worst end {worst:e}");
    // Beyond the trusted length there is no answer, not a wrong one: a horizontal pair 3.69
    // apart (the base distance, whose geodesic is the horizontal one: φ(0) = 0 exactly).
    let a = bevy_curved_spaces::space::sl2r::chart_frame(0.0, 0.0, 0.0);
    let b = bevy_curved_spaces::space::sl2r::chart_frame(20.0, 0.0, 0.0);
    assert_eq!(shortest(&a, &b), None);
    assert!((distance_floor(&a, &b) - 20f64.asinh()).abs() < 1e-12);
}

/// The floor never exceeds the distance, and on the two extremes it is the distance: the
/// horizontal geodesics (the base distance) and, turned on the spot, within a factor of it.
#[test]
fn the_floor_is_below_every_distance() {
    let space = sl2r_space("unit-tangent-bitorus").unwrap().unwrap();
    let mut rng = SplitMix64(0xf100);
    for _ in 0..2000 {
        let start = random_start(&space, &mut rng);
        let v = rng.direction().to_array();
        let t = (TRUSTED_LENGTH - 0.2) * rng.unit();
        let end = flow(
            &Sl2rRay {
                frame: start.frame,
                velocity: v,
            },
            t,
        );
        let floor = distance_floor(&start.frame, &end.frame);
        assert!(
            floor <= t * (1.0 + 1e-12) + 1e-14,
            "floor {floor} over {t} for {v:?}"
        );
    }
    // Horizontal: the floor is the length.
    let start = random_start(&space, &mut rng);
    let end = flow(
        &Sl2rRay {
            frame: start.frame,
            velocity: [0.6, 0.8, 0.0],
        },
        1.5,
    );
    assert!((distance_floor(&start.frame, &end.frame) - 1.5).abs() < 1e-12);
    // Turned by a half turn on the spot: the floor is far from 0.
    let end = flow(
        &Sl2rRay {
            frame: start.frame,
            velocity: [0.0, 0.0, 1.0],
        },
        PI,
    );
    assert!(distance_floor(&start.frame, &end.frame) > 1.9);
}

/// A ray meets a ball where it first comes within the radius: nothing before the hit is
/// inside (sampled), the hit is on the sphere (to 1e-12), and the normal there is the unit
/// gradient of the distance (central differences along the ray agree with `⟨v, n⟩`).
#[test]
fn balls_are_met_where_the_ray_first_comes_within_the_radius() {
    let space = sl2r_space("unit-tangent-bitorus").unwrap().unwrap();
    let mut rng = SplitMix64(0xba11);
    let (mut hits, mut misses) = (0, 0);
    for k in 0..300 {
        let start = random_start(&space, &mut rng);
        // The centre a short geodesic away, the ray aimed roughly back at it.
        let to_centre = rng.direction().to_array();
        let centre = flow(
            &Sl2rRay {
                frame: start.frame,
                velocity: to_centre,
            },
            0.6 + rng.unit(),
        )
        .frame;
        let jitter = rng.direction() * 0.5;
        let v = (glam::DVec3::from_array(to_centre) + jitter)
            .normalize()
            .to_array();
        let radius = MAX_SL2R_BALL_RADIUS * (0.2 + 0.8 * rng.unit());
        let ray = Sl2rRay {
            frame: start.frame,
            velocity: v,
        };
        let distance_at =
            |t: f64| shortest(&centre, &flow(&ray, t).frame).map_or(f64::INFINITY, |(d, _)| d);
        match ball_hit(&ray, &centre, radius, 4.0) {
            Some(t) => {
                hits += 1;
                assert!(
                    (distance_at(t) - radius).abs() < 1e-12,
                    "case {k}: the hit is {} from the centre, radius {radius}",
                    distance_at(t)
                );
                for i in 0..50 {
                    let s = t * f64::from(i) / 50.0;
                    assert!(
                        distance_at(s) > radius,
                        "case {k}: inside at {s} before {t}"
                    );
                }
                let at = flow(&ray, t);
                let n = normal(&centre, &at.frame).expect("a normal on the sphere");
                let h = 1e-6;
                let rate = (distance_at(t + h) - distance_at(t - h)) / (2.0 * h);
                let dot: f64 = (0..3).map(|i| n[i] * at.velocity[i]).sum();
                assert!(
                    (rate - dot).abs() < 1e-6,
                    "case {k}: rate {rate} against {dot}"
                );
            }
            None => {
                misses += 1;
                for i in 0..400 {
                    let s = 4.0 * f64::from(i) / 400.0;
                    assert!(
                        distance_at(s) > radius - 1e-9,
                        "case {k}: missed but inside at {s}"
                    );
                }
            }
        }
    }
    assert!(hits > 50 && misses > 20, "{hits} hits, {misses} misses");
}

/// The inverse exponential map against the 45-digit reference: from the two ends of every
/// stored geodesic shorter than the trusted length, `shortest` finds its length and its
/// starting velocity again (the reference integrated the geodesic equations; nothing of the
/// closed form is in it).
#[test]
fn the_shortest_geodesic_between_the_references_ends_is_the_one_integrated() {
    let mut checked = 0;
    for s in super::reference() {
        if s.t >= TRUSTED_LENGTH {
            continue;
        }
        let round = |r: &Sl2rRay<bevy_curved_spaces::geometry::DoubleDouble>| {
            r.frame.map(|v| v.map(|x| x.hi))
        };
        let (length, velocity) = shortest(&round(&s.start), &round(&s.end))
            .unwrap_or_else(|| panic!("{} at {}: no geodesic found", s.case, s.t));
        assert!(
            (length - s.t).abs() < 1e-11 * (1.0 + s.t),
            "{} at {}: length {length}",
            s.case,
            s.t
        );
        let want = s.start.velocity.map(|x| x.hi);
        let off = (0..3)
            .map(|i| (velocity[i] - want[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            off < 1e-9,
            "{} at {}: velocity {velocity:?} against {want:?}",
            s.case,
            s.t
        );
        checked += 1;
    }
    assert!(
        checked >= 8,
        "only {checked} samples shorter than the trusted length"
    );
}
