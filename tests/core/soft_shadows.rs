//! Soft shadows from a lamp of finite radius ([`shadow_directions`], [`gather`]): every
//! shadow ray meets the lamp and together they fill its disc, evenly by solid angle, in the
//! three geometries; and a penumbra cast through a face of the 3-torus hides the share of
//! the lamp that an independent integration over the lamp's disc says.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::Ball;
use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting, shadow_directions};
use bevy_curved_spaces::space::invariants::inradius;
use glam::{DVec3, DVec4};

use crate::lighting::lit_in_the_torus;

use crate::common::library_space as space;

/// The least distance from `q` to the geodesic from `p` along the unit tangent `v`, over
/// lengths `0..=t_max`: a fine scan, then a ternary search about its best sample (the
/// distance from a point to a geodesic has one minimum there).
fn closest_approach(g: Geometry, p: DVec4, v: DVec4, q: DVec4, t_max: f64) -> f64 {
    let at = |t: f64| g.distance(g.project_point(g.geodesic(p, v, t).0), q);
    let steps = 4000;
    let h = t_max / f64::from(steps);
    let best = (0..=steps)
        .map(|i| f64::from(i) * h)
        .min_by(|a, b| at(*a).total_cmp(&at(*b)))
        .unwrap();
    let (mut lo, mut hi) = ((best - h).max(0.0), (best + h).min(t_max));
    for _ in 0..100 {
        let (a, b) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if at(a) < at(b) {
            hi = b;
        } else {
            lo = a;
        }
    }
    at(0.5 * (lo + hi))
}

/// Each shadow ray towards a lamp of radius `r` passes within `r` of its centre, the
/// outermost ones near its rim, spread evenly by solid angle (the mean of `1 − cos θ` is
/// half the disc's `1 − cos α`), in E³, H³ and S³ (there also past π/2, where the disc looks
/// larger again); one sample, or a point lamp, is the ray to the centre.
#[test]
fn every_shadow_ray_meets_the_lamp_and_they_fill_its_disc() {
    for (id, lamp_at, radius) in [
        ("torus", 0.8, 0.12),
        ("seifert-weber", 0.8, 0.12),
        ("poincare", 0.8, 0.12),
        ("poincare", 2.0, 0.3),
    ] {
        let s = space(id);
        let g = s.geometry();
        let r = inradius(&s);
        let o = bevy_curved_spaces::geometry::ORIGIN;
        let p = g.project_point(g.translation(DVec3::new(1.0, 0.5, -0.2).normalize(), 0.3 * r) * o);
        let q = g.project_point(g.translation(DVec3::new(-0.3, 0.2, 1.0).normalize(), lamp_at) * o);
        let d = g.distance(p, q);
        let l = g.tangent_towards(p, q);
        let radius = radius * r;
        assert_eq!(shadow_directions(g, p, l, d, radius, 1), vec![l]);
        assert_eq!(shadow_directions(g, p, l, d, 0.0, 16), vec![l]);
        let n = 32;
        let dirs = shadow_directions(g, p, l, d, radius, n);
        assert_eq!(dirs.len(), n as usize);
        let sin_alpha = g.s(radius) / g.s(d).abs();
        let versine = 1.0 - (1.0 - sin_alpha * sin_alpha).sqrt();
        let mut farthest: f64 = 0.0;
        let mut mean_versine = 0.0;
        for v in &dirs {
            assert!(
                (g.form(*v, *v) - 1.0).abs() < 1e-12
                    && (g.project_tangent(p, *v) - *v).abs().max_element() < 1e-12,
                "{id}: a unit tangent at the point"
            );
            let h = closest_approach(g, p, *v, q, 2.0 * d);
            assert!(
                h <= radius * (1.0 + 1e-7),
                "{id} (lamp {d:.2} away): a shadow ray passes {h} from the lamp of radius {radius}"
            );
            farthest = farthest.max(h);
            mean_versine += (1.0 - g.form(*v, l)) / f64::from(n);
        }
        assert!(
            farthest > 0.95 * radius,
            "{id}: the rays reach only {farthest} of the lamp's radius {radius}"
        );
        assert!(
            (mean_versine - 0.5 * versine).abs() < 1e-9 * versine,
            "{id}: by solid angle, the mean 1 − cos θ is {mean_versine}, not half of {versine}"
        );
    }
}

/// The share of a lamp's disc (centre `lamp`, radius `lamp_radius`, seen from `p`) that a
/// ball (`centre`, `radius`) leaves open, integrated over the disc by solid angle on a fine
/// grid with the ray–sphere test in the chart: independent of the shadow walk and the
/// spiral.
fn open_share(p: DVec3, lamp: DVec3, lamp_radius: f64, centre: DVec3, radius: f64) -> f64 {
    let to = lamp - p;
    let d = to.length();
    let l = to / d;
    let e1 = l.any_orthonormal_vector();
    let e2 = l.cross(e1);
    let versine = 1.0 - (1.0 - (lamp_radius / d).powi(2)).sqrt();
    let steps = 600;
    let mut open = 0usize;
    for i in 0..steps {
        let u = (f64::from(i) + 0.5) / f64::from(steps);
        let cos = 1.0 - u * versine;
        let sin = (1.0 - cos * cos).sqrt();
        for k in 0..steps {
            let phi = std::f64::consts::TAU * (f64::from(k) + 0.5) / f64::from(steps);
            let v = l * cos + (e1 * phi.cos() + e2 * phi.sin()) * sin;
            // |p + t v − c|² = ρ²: t² + 2 b t + c₀ = 0.
            let m = p - centre;
            let b = m.dot(v);
            let c0 = m.length_squared() - radius * radius;
            let disc = b * b - c0;
            let hit = disc >= 0.0 && {
                let t = -b - disc.sqrt();
                t > 0.0 && t < d
            };
            open += usize::from(!hit);
        }
    }
    open as f64 / f64::from(steps * steps)
}

/// A penumbra through a face of the 3-torus: a point facing −x is lit only by the lamp's
/// image through the −x face, 0.4 away; a ball's image between them, moved across the line
/// of sight, hides all of the lamp (umbra), part of it (penumbra: the share an independent
/// integration gives, to the spiral's sampling error) or none of it.
#[test]
fn a_penumbra_is_cast_through_a_face() {
    let s = space("torus");
    let g = s.geometry();
    let lamp = DVec4::new(0.2, 0.0, 0.0, 1.0);
    let p = DVec4::new(-0.4, 0.0, 0.0, 1.0);
    let n = DVec4::new(-1.0, 0.0, 0.0, 0.0);
    let (fog, r0, lamp_radius, ball_radius) = (0.7, 0.01, 0.08, 0.06);
    let lit_by = |ball_y: f64, samples: u32| {
        let lighting = Lighting {
            paths: LightPaths::Images,
            reach_inradii: 1.5,
            tail: false,
            shadows: 4,
            lamp_radius_inradii: lamp_radius / inradius(&s),
            soft_samples: samples,
        };
        let at = DVec4::new(0.4, ball_y, 0.0, 1.0);
        let ball = Ball::new(g, at, ball_radius, DVec3::ONE);
        let (e, light) = lit_in_the_torus(lighting, (fog, r0), lamp, ball, (p, n));
        assert!((light.radius - lamp_radius).abs() < 1e-12);
        e
    };
    let through_the_face = (-0.4f64 / fog).exp() / 0.16;
    let image = DVec3::new(-0.8, 0.0, 0.0);
    let p3 = p.truncate();
    let mut shares = Vec::new();
    for ball_y in [0.0, 0.035, 0.06, 0.085, 0.2] {
        let expected = open_share(
            p3,
            image,
            lamp_radius,
            DVec3::new(-0.6, ball_y, 0.0),
            ball_radius,
        );
        let share = lit_by(ball_y, 64) / through_the_face;
        println!("ball at y = {ball_y}: open {share:.4}, integrated {expected:.4}");
        assert!(
            (share - expected).abs() < 0.04,
            "ball at y = {ball_y}: 64 shadow rays see {share:.4} of the lamp, the integral {expected:.4}"
        );
        // One ray is the hard shadow: all or nothing, by the lamp's centre.
        let hard = lit_by(ball_y, 1) / through_the_face;
        assert!(
            hard.abs() < 1e-9 || (hard - 1.0).abs() < 1e-9,
            "one ray: {hard}"
        );
        shares.push(expected);
    }
    assert!(shares[0] < 1e-9, "the umbra: {}", shares[0]);
    assert!(
        shares[1..4].iter().all(|s| *s > 0.05 && *s < 0.95),
        "a penumbra between: {shares:?}"
    );
    assert!(
        (shares[4] - 1.0).abs() < 1e-9,
        "the ball aside: {}",
        shares[4]
    );
    assert!(
        shares.windows(2).all(|w| w[0] <= w[1]),
        "more of the lamp shows as the ball moves away: {shares:?}"
    );
}
