//! Every image of a lamp: the fluence summed over the deck group against a direct lattice
//! sum (3-torus), the 120 images of the Poincaré space and reciprocity, the lamp's radius
//! where S³ focuses its light again, and the tail's bound against a longer sum.

use bevy_curved_spaces::geometry::Geometry;
use bevy_curved_spaces::scene::light_images::{FluenceError, fluence};
use bevy_curved_spaces::space::Space;
use glam::{DVec3, DVec4};

use crate::common::library_space as space;

fn chart(s: &Space, x: [f64; 3]) -> DVec4 {
    s.geometry().from_chart(DVec3::from_array(x)).unwrap()
}

#[test]
fn the_torus_fluence_is_its_lattice_sum() {
    let s = space("torus");
    let (lamp, at) = ([0.1, -0.2, 0.05], [-0.3, 0.25, 0.4]);
    let (fog, reach, r0) = (0.7, 4.5, 0.05);
    let f = fluence(&s, chart(&s, lamp), chart(&s, at), fog, reach, r0).unwrap();
    // The unit cube's lattice, summed directly.
    let (mut count, mut sum) = (0, 0.0);
    for i in -6i32..=6 {
        for j in -6i32..=6 {
            for k in -6i32..=6 {
                let image =
                    DVec3::from_array(lamp) + DVec3::new(f64::from(i), f64::from(j), f64::from(k));
                let d = (image - DVec3::from_array(at)).length();
                if d <= reach {
                    count += 1;
                    sum += (-d / fog).exp() / d.max(r0).powi(2);
                }
            }
        }
    }
    assert_eq!(f.images, count);
    assert!(
        ((f.exact - sum) / sum).abs() < 1e-12,
        "{} against {sum}",
        f.exact
    );
    // The tail's mean against the lattice sum out to 12: within its bound, and close.
    let far = fluence(&s, chart(&s, lamp), chart(&s, at), fog, 12.0, r0).unwrap();
    let (near, long) = (f.total(), far.total());
    assert!(
        (near - long).abs() <= f.bound + far.bound,
        "{near} against {long}"
    );
    assert!((near - long).abs() < 1e-3 * long, "{near} against {long}");
    // In E³ the bound is about ρ/λ of the tail (ρ the lamp's farthest cell point: the
    // count's uncertainty is a shell that thick, the tail lies within a few λ of R): a
    // thinner fog than the cell is wide leaves it loose, a thicker one tight.
    let thick = fluence(&s, chart(&s, lamp), chart(&s, at), 5.0, 8.0, r0).unwrap();
    assert!(f.bound / f.tail > 1.0, "{} of {}", f.bound, f.tail);
    assert!(
        thick.bound / thick.tail < 0.5,
        "{} of {}",
        thick.bound,
        thick.tail
    );
}

#[test]
fn the_poincare_space_has_120_images_and_light_is_reciprocal() {
    let s = space("poincare");
    let (a, b) = (chart(&s, [0.1, 0.05, -0.08]), chart(&s, [-0.12, 0.2, 0.1]));
    let f = fluence(&s, a, b, 0.9, 1.0, 0.05).unwrap();
    assert_eq!(f.images, 120);
    assert_eq!((f.tail, f.bound), (0.0, 0.0));
    let back = fluence(&s, b, a, 0.9, 1.0, 0.05).unwrap();
    assert!(((f.exact - back.exact) / f.exact).abs() < 1e-12);
    // −1 is in the group: a lamp's light focuses on itself again from the antipode. The
    // lamp's radius keeps it finite, and a smaller lamp is brighter there.
    let at_lamp = fluence(&s, a, a, 0.9, 1.0, 0.05).unwrap();
    let smaller = fluence(&s, a, a, 0.9, 1.0, 0.01).unwrap();
    assert!(at_lamp.exact.is_finite() && smaller.exact > 10.0 * at_lamp.exact);
}

#[test]
fn reciprocity_holds_in_seifert_weber_and_the_tail_is_within_its_bound() {
    let s = space("seifert-weber");
    let (a, b) = (chart(&s, [0.2, 0.1, -0.1]), chart(&s, [-0.15, 0.3, 0.2]));
    let fog = 1.0;
    let f = fluence(&s, a, b, fog, 2.5, 0.05).unwrap();
    let back = fluence(&s, b, a, fog, 2.5, 0.05).unwrap();
    assert_eq!(f.images, back.images);
    assert!(((f.exact - back.exact) / f.exact).abs() < 1e-12);
    let long = fluence(&s, a, b, fog, 3.5, 0.05).unwrap();
    assert!(long.images > 5 * f.images);
    let gap = (f.total() - long.total()).abs();
    assert!(
        gap <= f.bound + long.bound,
        "{gap} past {}",
        f.bound + long.bound
    );
    eprintln!(
        "seifert-weber: reach 2.5 total {:.6} ({} images, tail {:.4} ± {:.3}), reach 3.5 {:.6} ({} images): off by {gap:.2e}",
        f.total(),
        f.images,
        f.tail,
        f.bound,
        long.total(),
        long.images
    );
}

#[test]
fn bad_numbers_are_refused_by_name() {
    let s = space("torus");
    let p = DVec4::W;
    assert_eq!(
        fluence(&s, p, p, f64::INFINITY, 1.0, 0.05),
        Err(FluenceError::Fog(f64::INFINITY))
    );
    assert_eq!(
        fluence(&s, p, p, 1.0, 0.0, 0.05),
        Err(FluenceError::Reach(0.0))
    );
    assert!(matches!(
        fluence(&s, p, p, 1.0, 1.0, f64::NAN),
        Err(FluenceError::Radius(_))
    ));
    assert!(matches!(
        fluence(&space("seifert-weber"), p, p, 1.0, 9.0, 0.05),
        Err(FluenceError::TooMany { .. })
    ));
    let _ = Geometry::Euclidean;
}
