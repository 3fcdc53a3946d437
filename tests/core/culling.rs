//! Face culling (`scene::culling`): the objects it skips cannot be hit, so every ray ends as
//! it does without it, on random rays and on the hard ones (through edges and vertices,
//! grazing the edge tubes); and it skips most of the edge objects' tests.

use bevy_curved_spaces::geometry::{Ray, chart_ray};
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::{Ball, CurvedScene, FaceCulling, Object, SceneParts, Tube};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{CellWalker, SEED_SPACES, Space};
use bevy_curved_spaces::trace::{first_hit_culled, first_hit_traced, sample_rays};
use glam::{DVec3, DVec4};

const BUDGET: usize = 24;

/// Camera rays from the centre through every vertex and every edge's midpoint, and rays
/// aimed a tube's radius (±1e-9) beside each edge's midpoint: they graze the edge tubes.
fn hard_rays(space: &Space) -> Vec<Ray<DVec4>> {
    let g = space.geometry();
    let tube = 0.05 * inradius(space);
    let v = space.vertices();
    let mut rays: Vec<Ray<DVec4>> = v
        .iter()
        .filter_map(|&p| chart_ray(g, DVec3::ZERO, p).ok())
        .collect();
    for e in space.edges() {
        let [a, b] = e.vertices.map(|i| v[i]);
        let mid = (a + b) / 2.0;
        rays.extend(chart_ray(g, DVec3::ZERO, mid).ok());
        // Sideways from the edge in the chart, about the tube's radius (its chart size
        // differs by geometry and place, so a spread of offsets).
        let side = (b - a).cross(mid).normalize_or_zero();
        for k in [-1.5, -1.02, -1.0, -0.98, -0.5, 0.5, 0.98, 1.0, 1.02, 1.5] {
            rays.extend(chart_ray(g, DVec3::ZERO, mid + side * k * tube).ok());
        }
        // Along the edge itself, from its midpoint.
        rays.extend(chart_ray(g, mid * 0.999, b - a).ok());
    }
    rays
}

fn assert_same_ends(space: &Space, scene: &CurvedScene, rays: &[Ray<DVec4>], what: &str) {
    let walker = CellWalker::<DVec4>::new(space);
    let culling = FaceCulling::new(space, scene);
    for (i, &ray) in rays.iter().enumerate() {
        let plain = first_hit_traced(&walker, scene, ray, BUDGET);
        let culled = first_hit_culled(&walker, scene, culling.as_ref(), ray, BUDGET);
        assert_eq!(plain, culled, "{what}: ray {i} ends otherwise when culled");
    }
}

#[test]
fn culled_rays_end_as_unculled_ones_in_every_seed_space() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let scene = CurvedScene::default_for(&space, 3.0 * inradius(&space));
        // Several cells: every object is tested in every cell.
        if space.cells().len() > 1 {
            assert_eq!(FaceCulling::new(&space, &scene), None, "{}", seed.id);
            continue;
        }
        let culling = FaceCulling::new(&space, &scene)
            .unwrap_or_else(|| panic!("{}: the default scene has edges to cull", seed.id));
        // Every edge tube and vertex ball has a mask; the centre ball has none.
        let edge_objects = space.edges().len() + space.vertices().len();
        assert!(
            culling.masked_objects() >= edge_objects,
            "{}: {} of {edge_objects} edge objects masked",
            seed.id,
            culling.masked_objects()
        );
        let mut rays = sample_rays(&space, 400, 7);
        rays.extend(hard_rays(&space));
        assert_same_ends(&space, &scene, &rays, seed.id);
    }
}

/// Over random rays, how many objects the culled walk tests per segment, against how many
/// the plain walk tests.
fn tests_per_segment(space: &Space, scene: &CurvedScene) -> (f64, f64) {
    let walker = CellWalker::<DVec4>::new(space);
    let culling = FaceCulling::new(space, scene).unwrap();
    let (mut segments, mut tested) = (0usize, 0usize);
    for ray in sample_rays(space, 200, 11) {
        let mut ray = walker.normalized(ray);
        let mut skip = None;
        for _ in 0..8 {
            let Some(exit) = walker.exit(&ray, skip) else {
                break;
            };
            let near = culling.near_faces(ray.point, ray.tangent, exit.ratio());
            segments += 1;
            tested += (0..scene.objects.len())
                .filter(|&o| {
                    culling.may_meet(o, near)
                        && culling.may_meet_at_once(o, ray.point, ray.tangent, exit.ratio())
                })
                .count();
            ray = walker.cross(&ray, &exit).0;
            skip = Some(walker.partners[exit.face]);
        }
    }
    (tested as f64 / segments as f64, scene.objects.len() as f64)
}

#[test]
fn culling_skips_most_edge_tests() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        // Several cells have no culling (the test above).
        if space.cells().len() > 1 {
            continue;
        }
        let scene = CurvedScene::default_for(&space, 3.0 * inradius(&space));
        let (tested, all) = tests_per_segment(&space, &scene);
        // The centre ball is tested everywhere. A segment enters through one face and
        // leaves through another: only where it passes near the edge between them (near
        // both faces at one point) are that edge and its ends tested. Measured: 0.3–0.7
        // edge objects a segment of 20–50.
        let unmasked = all - FaceCulling::new(&space, &scene).unwrap().masked_objects() as f64;
        assert!(
            tested - unmasked <= 1.0,
            "{}: {tested:.2} of {all} objects tested per segment",
            seed.id
        );
    }
}

/// Balls and tubes of random sizes placed on faces, edges, vertices and anywhere: the
/// culled walk ends as the plain one, wherever the culling's distance falls.
#[test]
fn random_objects_near_faces_are_never_skipped_when_met() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let g = space.geometry();
        let r = inradius(&space);
        let mut rng = SplitMix64(99);
        let vertex = |i: usize| space.vertex_point(i);
        let mut objects = Vec::new();
        for k in 0..24 {
            let radius = r * (0.01 + 0.2 * rng.unit());
            let colour = DVec3::splat(0.5);
            let object = match k % 4 {
                // On a vertex.
                0 => Object::Ball(Ball::new(
                    g,
                    vertex(k % space.vertices().len()),
                    radius,
                    colour,
                )),
                // Along an edge, or part of one.
                1 => {
                    let e = &space.edges()[k % space.edges().len()];
                    let (a, b) = (vertex(e.vertices[0]), vertex(e.vertices[1]));
                    let t = rng.unit();
                    let part = g.project_point(a * (1.0 - t) + b * t);
                    Object::Tube(Tube::new(g, a, part, radius, colour))
                }
                // Near a face, a little inside or outside it.
                2 => {
                    let f = &space.faces()[k % space.faces().len()];
                    let at = f.normal * f.offset * (0.9 + 0.2 * rng.unit());
                    Object::Ball(Ball::new(g, g.from_chart(at).unwrap(), radius, colour))
                }
                // Between two vertices across the cell.
                _ => {
                    let n = space.vertices().len();
                    Object::Tube(Tube::new(
                        g,
                        vertex(k % n),
                        vertex((3 * k + 1) % n),
                        radius,
                        colour,
                    ))
                }
            };
            objects.push(object);
        }
        let scene = CurvedScene::new(objects, Vec::new(), Default::default()).adding_parts(
            &space,
            SceneParts {
                avatar: false,
                ..Default::default()
            },
        );
        let mut rays = sample_rays(&space, 300, 5);
        rays.extend(hard_rays(&space));
        assert_same_ends(
            &space,
            &scene,
            &rays,
            &format!("{} random objects", seed.id),
        );
    }
}

/// A scene with nothing along the faces is not culled: no mask would skip anything.
#[test]
fn scenes_without_edges_have_no_culling() {
    for seed in SEED_SPACES {
        let space = seed.build().unwrap();
        let scene = CurvedScene::with_parts(
            &space,
            3.0 * inradius(&space),
            SceneParts {
                edges: false,
                ..Default::default()
            },
        );
        assert!(FaceCulling::new(&space, &scene).is_none(), "{}", seed.id);
    }
}
