//! The product spaces' lamp lit along every image (`trace::product::lighting`): each image
//! is where a ray walked through the faces finds the lamp, along every path (the windings
//! round S² too); no image a brute-force product of generators reaches is missing; the
//! tail's mean against a sum to a much larger reach; a shadow cast through a face.

use bevy_curved_spaces::geometry::{Geometry, Ray};
use bevy_curved_spaces::scene::lighting::{LightPaths, Lighting};
use bevy_curved_spaces::space::product::ProductWalker;
use bevy_curved_spaces::space::walk::Limit;
use bevy_curved_spaces::trace::product::lighting::{
    cell_circumradius, lamp_images, paths_to, product_fluence, product_gather, product_tail_fluence,
};
use bevy_curved_spaces::trace::product::{
    ProductObject, ProductRayEnd, ProductScene, ProductShape, default_scene, first_product_hit,
    product_occluded,
};
use glam::{DMat4, DVec3, DVec4};
use std::collections::HashSet;

use crate::common::product;

/// A point of the cell: surface distance `rho` from the centre in direction `angle`, at
/// height `z`.
fn point(g: Geometry, rho: f64, angle: f64, z: f64) -> DVec4 {
    let (c, s) = g.cs(rho);
    DVec4::new(s * angle.cos(), s * angle.sin(), z, c)
}

const SPACES: [&str; 5] = [
    "bitorus-circle-turn",
    "crosscaps-circle",
    "sphere-circle-turn",
    "projective-plane-circle",
    "genus-three-circle",
];

/// The product distance.
fn distance(g: Geometry, p: DVec4, q: DVec4) -> f64 {
    let d = DVec4::new(p.x - q.x, p.y - q.y, 0.0, p.w - q.w);
    let chord = (d.x * d.x + d.y * d.y + g.kappa() * d.w * d.w)
        .max(0.0)
        .sqrt();
    let rho = match g {
        Geometry::Spherical => 2.0 * (0.5 * chord).min(1.0).asin(),
        _ => 2.0 * (0.5 * chord).asinh(),
    };
    rho.hypot(p.z - q.z)
}

/// A ray from a point of the cell along each path to each image, walked through the faces
/// as a camera ray is, meets a tiny ball at the lamp at the path's length: the images are
/// the walk's own, the turn's direction included, and so are the windings round S².
#[test]
fn each_path_to_an_image_is_where_a_walked_ray_meets_the_lamp() {
    for id in SPACES {
        let space = product(id);
        let g = space.base();
        let mut scene = default_scene(&space);
        let lamp = scene.light;
        let tiny = 1e-3;
        scene.objects = vec![ProductObject {
            shape: ProductShape::Point(lamp),
            radius: tiny,
            colour: DVec3::ONE,
        }];
        scene.fog_distance = 1e3;
        let walker = ProductWalker::<DVec4>::new(&space);
        let x = point(g, 0.4 * space.scale(), 2.0, -0.2 * space.length());
        // On S² far enough to wind all the way round.
        let reach = if g == Geometry::Spherical { 5.0 } else { 3.0 } * space.scale();
        let (images, covered) = lamp_images(&space, lamp, reach);
        assert!(
            covered > 0.0 && images.len() > 1,
            "{id}: {} images",
            images.len()
        );
        let (mut paths, mut windings) = (0, 0);
        for q in &images {
            paths_to(g, x, *q, covered, |p| {
                paths += 1;
                if p.length > distance(g, x, *q) + 1e-9 {
                    windings += 1;
                }
                let ray = Ray {
                    point: x,
                    tangent: p.tangent,
                };
                match first_product_hit(&walker, &scene, ray, 256) {
                    ProductRayEnd::Hit { distance, .. } => assert!(
                        (distance - (p.length - tiny)).abs() < 1e-6,
                        "{id}: the image {q} along a path of length {} is met at {distance}",
                        p.length
                    ),
                    other => panic!(
                        "{id}: the path to {q} of length {} ends {other:?}",
                        p.length
                    ),
                }
            });
        }
        assert!(paths >= 2, "{id}: {paths} paths");
        if g == Geometry::Spherical {
            assert!(
                covered > std::f64::consts::TAU && windings >= 2,
                "{id}: {windings} windings within {covered}"
            );
        }
    }
}

/// Every image that a product of up to five generators (the face pairings, the circle's
/// step each way) reaches within the distance the lamp's images cover is among them: the
/// walk outwards through the cells misses none.
#[test]
fn no_image_a_product_of_generators_reaches_is_missing() {
    for id in [
        "bitorus-circle-turn",
        "crosscaps-circle",
        "sphere-circle-turn",
    ] {
        let space = product(id);
        let g = space.base();
        let lamp = default_scene(&space).light;
        let walker = ProductWalker::<DVec4>::new(&space);
        let reach = 2.0 * space.scale();
        let (images, covered) = lamp_images(&space, lamp, reach);
        let within = covered + cell_circumradius(&space);
        let key = |q: DVec4| {
            let r = |x: f64| (x * 1e5).round() as i64;
            (r(q.x), r(q.y), r(q.z), r(q.w))
        };
        let have: HashSet<_> = images.iter().map(|q| key(*q)).collect();
        let mut generators: Vec<(DMat4, f64)> = walker.pairings.iter().map(|m| (*m, 0.0)).collect();
        generators.push((walker.up.0, -space.length()));
        generators.push((walker.down.0, space.length()));
        let mut layer = vec![(DMat4::IDENTITY, 0.0)];
        let mut checked = 0;
        for _ in 0..5 {
            let mut next = Vec::new();
            for (m, z) in &layer {
                for (gm, gz) in &generators {
                    next.push((*m * *gm, z + gz));
                }
            }
            for (m, z) in &next {
                let b = *m * DVec4::new(lamp.x, lamp.y, 0.0, lamp.w);
                let q = DVec4::new(b.x, b.y, lamp.z + z, b.w);
                if distance(g, space.centre(), q) < within - 1e-6 {
                    checked += 1;
                    assert!(have.contains(&key(q)), "{id}: the image {q} is missing");
                }
            }
            next.retain(|(m, z)| {
                let c = *m * DVec4::W;
                distance(g, space.centre(), DVec4::new(c.x, c.y, *z, c.w)) < within + 6.0
            });
            layer = next;
        }
        assert!(checked > images.len(), "{id}: {checked} checked");
    }
}

/// The fluence summed within the default reach with the tail's mean is nearer the sum to
/// four times that reach (with its own tail) than the exact sum alone, and within half the
/// tail of it.
#[test]
fn the_tail_stands_for_the_far_images() {
    for id in ["bitorus-circle", "sphere-circle", "crosscaps-circle"] {
        let space = product(id);
        let g = space.base();
        let lamp = default_scene(&space).light;
        let fog = 3.0 * space.scale();
        let x = point(g, 0.3 * space.scale(), 1.0, 0.1 * space.length());
        let short = 2.0 * space.scale();
        let (n, exact, tail, _) = product_fluence(&space, lamp, x, fog, short);
        let (far_n, far_exact, far_tail, _) = product_fluence(&space, lamp, x, fog, 4.0 * short);
        assert!(far_n > n, "{id}: {far_n} paths against {n}");
        let reference = far_exact + far_tail;
        let with = (exact + tail - reference).abs();
        let without = (exact - reference).abs();
        assert!(
            with < without && with < 0.5 * tail,
            "{id}: {n} paths {exact} + tail {tail} against {reference} ({far_n} paths)"
        );
        assert!((product_tail_fluence(short, fog, space.volume()) - tail).abs() < 1e-12);
    }
}

/// In H²×R, a ball halfway along the path from a point to a lamp image in the cell above
/// (the path crosses the top) shadows that image only: the point loses that path's light
/// and keeps the rest; with the cap below that image it is lit again.
#[test]
fn a_shadow_is_cast_through_the_top() {
    let space = product("bitorus-circle");
    let g = space.base();
    let walker = ProductWalker::<DVec4>::new(&space);
    let mut scene: ProductScene = default_scene(&space);
    scene.objects.clear();
    let lighting = Lighting {
        paths: LightPaths::Images,
        reach_inradii: 4.0,
        tail: false,
        shadows: 64,
        ..Lighting::default()
    };
    let lamp = point(g, 0.2, 0.5, -0.3 * space.length());
    scene.set_lighting(&space, lamp, lighting).unwrap();
    let x = point(g, 0.1, 2.5, 0.4 * space.length());
    // The nearest image above, reached through the top.
    let (index, path) = scene
        .lamp
        .images
        .iter()
        .enumerate()
        .filter(|(_, q)| q.z > 0.5 * space.length())
        .find_map(|(k, q)| {
            let mut found = None;
            paths_to(g, x, *q, scene.lamp.reach, |p| found = Some(p));
            found.map(|p| (k, p))
        })
        .expect("an image above within the reach");
    assert!(index < lighting.shadows as usize);
    let ray = Ray {
        point: x,
        tangent: path.tangent,
    };
    let crossed = walker.trace(ray, Limit::Distance(0.5 * path.length));
    assert!(!crossed.crossings.is_empty(), "the path crosses a face");
    let middle = walker
        .walk(ray, Limit::Distance(0.5 * path.length), |_| true)
        .0
        .point;
    let unlit = |scene: &ProductScene, normal: DVec4| {
        let mut occluded = |p, v, len| {
            product_occluded(
                &walker,
                scene,
                Ray {
                    point: p,
                    tangent: v,
                },
                len,
                64,
            )
        };
        product_gather(g, scene, x, normal, &mut occluded)
    };
    let normal = path.tangent;
    let open = unlit(&scene, normal);
    scene.objects.push(ProductObject {
        shape: ProductShape::Point(middle),
        radius: 0.05,
        colour: DVec3::ONE,
    });
    let shadowed = unlit(&scene, normal);
    let share = (-path.length / scene.fog_distance).exp() / path.spread;
    assert!(
        (open - shadowed - share).abs() < 1e-9 * open,
        "the shadow takes {} of {open}; the path brings {share}",
        open - shadowed
    );
    // Past the cap the image is lit unshadowed.
    scene.lighting.shadows = index as u32;
    let capped = unlit(&scene, normal);
    assert!(capped > shadowed && capped <= open);
}
