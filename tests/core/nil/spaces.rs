//! The spaces `nil-K` over the geometry contract: frames carried by parallel transport
//! (against the transport equation integrated by fine Runge–Kutta steps), kept orthonormal
//! and in the box by the wrap, each wrap a left translation by an element of `Γ_K` that
//! leaves the axes alone; the registry's ids.

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

#[test]
fn a_level_walk_round_a_square_climbs_by_its_area() {
    // E₃ up: walking forward `s` and turning a quarter left four times comes back to the
    // same (x, y) and heading, higher by the enclosed area s² (dz = ½(x dy − y dx)), the
    // axes unchanged (walking is a left translation); in small steps as a player walks.
    let space = NilSpace::new(1);
    let start = DMat4::from_cols(
        glam::DVec4::X,
        glam::DVec4::Z,
        glam::DVec4::new(0.0, -1.0, 0.0, 0.0),
        glam::DVec4::new(0.0, 0.0, 0.0, 1.0),
    );
    let s = 0.3;
    let steps = 30;
    let mut f = start;
    for _ in 0..4 {
        for _ in 0..steps {
            let motion = FrameMotion {
                translation: DVec3::new(0.0, 0.0, -s / f64::from(steps)),
                rotation: DVec3::ZERO,
                level: true,
            };
            f = space.step_frame(f, &motion);
            assert!(
                (f.y_axis.truncate() - DVec3::Z).length() < 1e-12,
                "up left E₃"
            );
        }
        let turn = FrameMotion {
            translation: DVec3::ZERO,
            rotation: DVec3::new(0.0, std::f64::consts::FRAC_PI_2, 0.0),
            level: true,
        };
        f = space.step_frame(f, &turn);
    }
    let p = f.w_axis;
    assert!(p.x.abs() < 1e-12 && p.y.abs() < 1e-12, "back at {p}");
    assert!(
        (p.z.abs() - s * s).abs() < 1e-12,
        "climbed {} for an area {}",
        p.z,
        s * s
    );
    for (a, b) in [
        (f.x_axis, start.x_axis),
        (f.y_axis, start.y_axis),
        (f.z_axis, start.z_axis),
    ] {
        assert!(
            (a - b).length() < 1e-12,
            "the heading turned: {a} against {b}"
        );
    }
    // Unlevelled, the same walk moves by parallel transport: up leaves E₃.
    let tilted = space.step_frame(
        start,
        &FrameMotion {
            translation: DVec3::new(0.0, 0.0, -s),
            rotation: DVec3::ZERO,
            level: false,
        },
    );
    assert!((tilted.y_axis.truncate() - DVec3::Z).length() > 0.1);
}
