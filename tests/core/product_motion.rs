//! A player in a product space (`space::product::motion`): exact steps with parallel
//! transport, turns about the fibre, wraps through the faces with their pairings, and the
//! handedness a non-orientable space leaves.

use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::Limit;
use bevy_curved_spaces::space::product::motion::{
    ProductMotion, camera_frame, step_product_frame, turn_about_fibre, wrap_product_frame,
};
use bevy_curved_spaces::space::product::{ProductSpace, ProductWalker};
use bevy_curved_spaces::trace::product::default_camera;
use glam::{DMat4, DVec3, DVec4};

use crate::common::product;

fn start(space: &ProductSpace) -> DMat4 {
    let c = default_camera(space);
    camera_frame(c.point, c.frame)
}

/// The largest deviation of the frame's columns from orthonormal in the product metric, and
/// of the position from the surface's model.
fn frame_error(space: &ProductSpace, f: DMat4) -> f64 {
    let g = space.base();
    let p = f.w_axis;
    let on = p.x * p.x + p.y * p.y + g.kappa() * p.w * p.w - g.kappa();
    crate::common::product_frame_defect(g, f).max(on.abs())
}

#[test]
fn random_walks_stay_orthonormal_on_the_model_and_inside_the_cell() {
    for id in [
        "bitorus-circle",
        "crosscaps-circle",
        "sphere-circle-turn",
        "projective-plane-circle",
        "genus-three-circle",
    ] {
        let space = product(id);
        let step = 0.05 * space.base_inradius().min(space.length());
        let mut rng = SplitMix64(7);
        let mut f = start(&space);
        let mut crossings = 0;
        for k in 0..4000 {
            let motion = ProductMotion {
                translation: DVec3::new(rng.unit() - 0.5, rng.unit() - 0.5, -rng.unit())
                    .normalize()
                    * step,
                rotation: DVec3::new(
                    0.2 * (rng.unit() - 0.5),
                    0.3 * (rng.unit() - 0.5),
                    0.1 * (rng.unit() - 0.5),
                ),
                level: k % 2 == 0,
            };
            f = step_product_frame(space.base(), f, &motion);
            let (wrapped, crossed) = wrap_product_frame(&space, f, 1e-9);
            crossings += crossed.len();
            f = wrapped;
            assert!(
                space.outside_by(f.w_axis) < 1e-6,
                "{id}: step {k} left the cell by {}",
                space.outside_by(f.w_axis)
            );
            assert!(
                frame_error(&space, f) < 1e-9,
                "{id}: step {k}: {}",
                frame_error(&space, f)
            );
        }
        assert!(
            crossings > 10,
            "{id}: the walk crossed only {crossings} faces"
        );
    }
}

/// Walking straight ahead in small steps, wrapping as it goes, ends where the walker's
/// exact geodesic through the same faces ends.
#[test]
fn walking_straight_follows_the_walkers_geodesic() {
    for id in ["bitorus-circle", "crosscaps-circle", "sphere-circle-turn"] {
        let space = product(id);
        let mut f = start(&space);
        let walker = ProductWalker::<DVec4>::new(&space);
        let ray = Ray {
            point: f.w_axis,
            tangent: -f.z_axis,
        };
        let total = 6.0 * space.base_inradius().max(0.5);
        let (end, _) = walker.walk(ray, Limit::Distance(total), |_| true);
        let steps = 600;
        let ahead = ProductMotion {
            translation: DVec3::new(0.0, 0.0, -total / f64::from(steps)),
            ..ProductMotion::default()
        };
        for _ in 0..steps {
            f = wrap_product_frame(&space, step_product_frame(space.base(), f, &ahead), 0.0).0;
        }
        let gap = (f.w_axis - end.point).length();
        assert!(gap < 1e-8, "{id}: the walk ends {gap} from the geodesic");
        let heading = (-f.z_axis - end.tangent).length();
        assert!(heading < 1e-8, "{id}: the heading differs by {heading}");
    }
}

/// A side glued `x … x` reverses orientation: the frame comes back left-handed (its
/// determinant changes sign); a side glued `x … X` keeps it.
#[test]
fn crossing_a_reversing_side_flips_handedness() {
    for (id, flips) in [("crosscaps-circle", true), ("bitorus-circle", false)] {
        let space = product(id);
        let walker = ProductWalker::<DVec4>::new(&space);
        // Face 0's direction from the centre.
        let n = walker.covectors[0];
        let dir = DVec3::new(n.x, n.y, 0.0).normalize();
        let f = camera_frame(
            DVec4::W,
            [
                DVec4::new(-dir.y, dir.x, 0.0, 0.0),
                DVec4::Z,
                -DVec4::new(dir.x, dir.y, 0.0, 0.0),
            ],
        );
        let before = f.determinant();
        let far = ProductMotion {
            translation: DVec3::new(0.0, 0.0, -1.2 * space.base_inradius()),
            ..ProductMotion::default()
        };
        let (after, crossed) =
            wrap_product_frame(&space, step_product_frame(space.base(), f, &far), 0.0);
        assert_eq!(crossed.len(), 1, "{id}: one side crossed");
        assert_eq!(crossed[0].face, 0, "{id}");
        assert_eq!(
            before.signum() != after.determinant().signum(),
            flips,
            "{id}: determinant {before} → {}",
            after.determinant()
        );
    }
}

/// Turning about the fibre keeps every column's height part, keeps the frame orthonormal,
/// and a full turn comes back.
#[test]
fn turning_about_the_fibre_keeps_up() {
    let space = product("bitorus-circle");
    let f = start(&space);
    let g = space.base();
    let turned = turn_about_fibre(g, f, 0.7);
    for k in 0..3 {
        assert!((turned.col(k).z - f.col(k).z).abs() < 1e-12);
    }
    assert!(frame_error(&space, turned) < 1e-12);
    let mut back = f;
    for _ in 0..8 {
        back = turn_about_fibre(g, back, std::f64::consts::TAU / 8.0);
    }
    assert!((back - f).to_cols_array().iter().all(|x| x.abs() < 1e-12));
}

/// A height many circles up comes back in one wrap, turned by the turn's power: 4001
/// circles with a quarter turn is one quarter turn.
#[test]
fn a_far_height_wraps_back_at_once_with_the_turns_power() {
    let space = product("sphere-circle-turn");
    let f = start(&space);
    let circles = 4001.0;
    let mut far = f;
    far.w_axis.z += circles * space.length();
    let (wrapped, crossed) = wrap_product_frame(&space, far, 1e-9);
    assert_eq!(crossed.len(), 1, "{crossed:?}");
    let sides = space.polygon().sides.len();
    assert_eq!(crossed[0].face, sides, "the top (of {sides} sides)");
    assert!((wrapped.w_axis.z - f.w_axis.z).abs() < 1e-9);
    // Once up through the top is R⁻¹ (a quarter turn back).
    let (once, _) = {
        let mut up = f;
        up.w_axis.z += space.length();
        wrap_product_frame(&space, up, 1e-9)
    };
    assert!((wrapped.w_axis - once.w_axis).length() < 1e-9);
    assert!(space.outside_by(wrapped.w_axis) < 0.0);
}
