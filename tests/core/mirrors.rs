//! Mirrors: the reflection law at a mirror ball (the walk goes on from the hit with the
//! tangent turned about the normal, checked against the reflection worked out in the
//! chart), a half mirror as the mix of a plain surface and a whole mirror, and the tiling
//! seen in a mirror ball.

use bevy_curved_spaces::geometry::Ray;
use bevy_curved_spaces::scene::{Ball, CurvedScene, Object, SceneParts};
use bevy_curved_spaces::space::{CellWalker, Space, seed_space};
use bevy_curved_spaces::trace::{RayEnd, colour_along, first_hit, reflected_ray};
use bevy_curved_spaces::view::TraceCamera;
use glam::{DVec3, DVec4};

const BUDGET: usize = 12;

/// The default scene's edges and a ball of reflectance `r` at the centre (instead of the
/// centre ball), in fog of distance `fog`.
fn mirror_scene(s: &Space, r: f64, fog: f64) -> CurvedScene {
    let g = s.geometry();
    let parts = SceneParts {
        centrepiece: bevy_curved_spaces::scene::Centrepiece::None,
        avatar: false,
        ..SceneParts::default()
    };
    let mut scene = CurvedScene::with_parts(s, fog, parts);
    let radius = 0.4 * bevy_curved_spaces::space::invariants::inradius(s);
    let ball = Ball::new(g, s.centre(), radius, DVec3::new(0.8, 0.7, 0.9)).with_reflectance(r);
    scene.place(s, Object::Ball(ball)).expect("inside the cell");
    scene
}

/// Camera rays of the default view that hit the mirror ball (the last object).
fn rays_on_the_ball(s: &Space, scene: &CurvedScene) -> Vec<(Ray<DVec4>, f64, DVec4, DVec4, usize)> {
    let g = s.geometry();
    let walker = CellWalker::<DVec4>::new(s);
    let camera = TraceCamera::default_for(s);
    let (w, h) = (48, 27);
    let mirror = scene.objects.len() - 1;
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let ray = camera.ray(g, i, j, w, h);
            if let RayEnd::Hit(hit) = first_hit(&walker, scene, ray, BUDGET)
                && hit.object == mirror
                && hit.crossings < BUDGET
            {
                out.push((
                    ray,
                    hit.distance,
                    hit.hit.point,
                    hit.hit.normal,
                    hit.crossings,
                ));
            }
        }
    }
    out
}

#[test]
fn a_mirror_ball_reflects_by_the_law_of_reflection() {
    let s = seed_space("torus").expect("seed");
    let walker = CellWalker::<DVec4>::new(&s);
    // Fog so thin that the distance already travelled does not matter (and no tail of
    // images, which such a fog would make large).
    let mut scene = mirror_scene(&s, 1.0, 1e4);
    scene
        .set_lighting(&s, bevy_curved_spaces::scene::lighting::Lighting::NEAREST)
        .unwrap();
    let rays = rays_on_the_ball(&s, &scene);
    assert!(rays.len() > 20, "{} rays on the ball", rays.len());
    for (ray, _, point, normal, crossings) in rays {
        // In the torus's chart the ray is straight: the incoming direction is the camera
        // ray's own, and the reflection is d − 2 (d·n) n with n the sphere's normal.
        let d = ray.tangent.truncate().normalize();
        let x = point.truncate() / point.w;
        let n = (x - s.centre().truncate()).normalize();
        assert!((normal.truncate().normalize() - n).length() < 1e-9);
        let out = d - 2.0 * d.dot(n) * n;
        let from = x + out * bevy_curved_spaces::trace::MIRROR_OFFSET;
        let seen = colour_along(
            &walker,
            &scene,
            None,
            None,
            Ray {
                point: from.extend(1.0),
                tangent: out.extend(0.0),
            },
            BUDGET - crossings - 1,
        );
        let mirrored = colour_along(&walker, &scene, None, None, ray, BUDGET);
        assert!(
            (mirrored - seen).abs().max_element() < 1e-3,
            "{mirrored} against {seen}"
        );
    }
}

#[test]
fn a_half_mirror_is_the_mix_of_a_surface_and_a_mirror() {
    let s = seed_space("seifert-weber").expect("seed");
    let walker = CellWalker::<DVec4>::new(&s);
    let fog = bevy_curved_spaces::scene::Shading::default_fog_distance(&s);
    let [plain, half, whole] = [0.0, 0.5, 1.0].map(|r| mirror_scene(&s, r, fog));
    let rays = rays_on_the_ball(&s, &plain);
    assert!(rays.len() > 20, "{} rays on the ball", rays.len());
    let g = s.geometry();
    let mirror = plain.objects.len() - 1;
    let (mut differ, mut twice) = (0, 0);
    for (ray, ..) in rays {
        // With one bounce the colour is linear in the reflectance; a ray that comes back to
        // the mirror (a copy of it in another cell) would see r² of it.
        let RayEnd::Hit(h) = first_hit(&walker, &plain, ray, BUDGET) else {
            unreachable!("the ray hits the ball")
        };
        let again = first_hit(&walker, &plain, reflected_ray(g, &h), BUDGET);
        if matches!(again, RayEnd::Hit(h) if h.object == mirror) {
            twice += 1;
            continue;
        }
        let [a, b, c] =
            [&plain, &half, &whole].map(|sc| colour_along(&walker, sc, None, None, ray, BUDGET));
        assert!(
            (b - 0.5 * (a + c)).abs().max_element() < 1e-12,
            "{b} is not the mix of {a} and {c}"
        );
        if (a - c).abs().max_element() > 0.05 {
            differ += 1;
        }
    }
    assert!(
        differ > 10,
        "the mirror shows something else than the ball: {differ} ({twice} seen twice)"
    );
}
