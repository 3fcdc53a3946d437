//! The reference renderer: hit distances against brute force in the universal cover, the
//! fog cut-off's error bound, and pictures of every seed space.

use bevy_curved_spaces::geometry::ORIGIN;
use bevy_curved_spaces::scene::{Ball, CurvedScene, Object, Shading};
use bevy_curved_spaces::space::CellWalker;
use bevy_curved_spaces::space::invariants::{elements_near, inradius};
use bevy_curved_spaces::space::{SEED_SPACES, Space, seed_space};
use bevy_curved_spaces::trace::{RayEnd, RenderSettings, first_hit, render, trace_pixel};
use bevy_curved_spaces::view::TraceCamera;
use glam::{DVec3, DVec4};

/// A scene holding only a ball at the centre.
fn ball_scene(space: &Space, radius: f64, fog: f64) -> CurvedScene {
    let mut scene = CurvedScene::default_for(space, fog);
    scene.objects = vec![Object::Ball(Ball::new(
        space.geometry(),
        space.centre(),
        radius,
        DVec3::ONE,
    ))];
    scene
}

fn directions(n: usize) -> impl Iterator<Item = DVec3> {
    // A golden-spiral spread of directions over the sphere.
    (0..n).map(move |i| {
        let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
        let a = i as f64 * 2.399_963_229_728_653;
        let r = (1.0 - z * z).sqrt();
        DVec3::new(r * a.cos(), r * a.sin(), z)
    })
}

/// In the 3-torus the first ball hit is the nearest of the lattice copies `c + n`, `n ∈ Z³`,
/// met by the straight line in R³.
#[test]
fn torus_hits_match_the_lattice_of_copies() {
    let s = seed_space("torus").unwrap();
    let radius = 0.12;
    let scene = ball_scene(&s, radius, 2.0);
    let walker = CellWalker::<DVec4>::new(&s);
    let eye = DVec3::new(0.21, -0.33, 0.4);
    let mut hits = 0;
    for dir in directions(400) {
        let ray = bevy_curved_spaces::geometry::chart_ray(s.geometry(), eye, dir).unwrap();
        let mut brute = f64::INFINITY;
        // The cut-off (2 ln 510 ≈ 12.5) keeps every hit within 13 cells.
        for x in -14..=14 {
            for y in -14..=14 {
                for z in -14..=14 {
                    let c = DVec3::new(x as f64, y as f64, z as f64);
                    let d = eye - c;
                    let b = d.dot(dir);
                    let disc = b * b - (d.length_squared() - radius * radius);
                    if disc >= 0.0 {
                        let t = -b - disc.sqrt();
                        if t > 0.0 {
                            brute = brute.min(t);
                        }
                    }
                }
            }
        }
        match first_hit(&walker, &scene, ray, 10_000) {
            RayEnd::Hit(h) => {
                hits += 1;
                assert!(
                    (h.distance - brute).abs() < 1e-11,
                    "{} vs {brute}",
                    h.distance
                );
            }
            _ => assert!(
                brute >= scene.shading.cutoff_distance(),
                "missed a copy at {brute}"
            ),
        }
    }
    assert!(hits > 100, "only {hits} rays hit a copy");
}

/// In the Poincaré space the first ball hit is the nearest of the 120 copies `h(c)` met by
/// the great circle (a ray that meets none circles S³ until its crossing budget) `γ(t) = cos t p + sin t v`: `⟨γ(t), h c⟩ = A cos(t − t₀) = cos ρ`.
#[test]
fn poincare_hits_match_the_120_copies() {
    let s = seed_space("poincare").unwrap();
    let g = s.geometry();
    let radius = 0.08;
    let scene = ball_scene(&s, radius, 10.0);
    let walker = CellWalker::<DVec4>::new(&s);
    let group = elements_near(&s, f64::INFINITY, 1000).unwrap();
    let eye = DVec3::new(0.05, 0.08, -0.1);
    let mut hits = 0;
    for dir in directions(300) {
        let ray = bevy_curved_spaces::geometry::chart_ray(g, eye, dir).unwrap();
        let mut brute = f64::INFINITY;
        for h in &group {
            let c = *h * ORIGIN;
            let (a, b) = (ray.point.dot(c), ray.tangent.dot(c));
            let amplitude = a.hypot(b);
            if amplitude >= radius.cos() {
                let t0 = b.atan2(a);
                let half = (radius.cos() / amplitude).acos();
                let t = (t0 - half).rem_euclid(2.0 * std::f64::consts::PI);
                brute = brute.min(t);
            }
        }
        match first_hit(&walker, &scene, ray, 10_000) {
            RayEnd::Hit(h) => {
                hits += 1;
                assert!(
                    (h.distance - brute).abs() < 1e-10,
                    "{} vs {brute}",
                    h.distance
                );
            }
            end => assert!(brute.is_infinite(), "missed the copy at {brute}: {end:?}"),
        }
    }
    assert!(hits > 100, "only {hits} rays hit a copy");
}

/// Stopping at the fog cut-off changes no pixel by more than the stated bound (half an
/// 8-bit step) against tracing on to a thousand times smaller weight.
#[test]
fn fog_cutoff_respects_its_bound() {
    for id in ["torus", "seifert-weber", "poincare", "mirrored-cube"] {
        let s = seed_space(id).unwrap();
        let fog = 1.5 * inradius(&s);
        let scene = CurvedScene::default_for(&s, fog);
        let mut far = scene.clone();
        far.shading.cutoff_weight = scene.shading.cutoff_weight / 1000.0;
        let walker = CellWalker::<DVec4>::new(&s);
        let camera = TraceCamera::default_for(&s);
        let mut worst = 0.0f64;
        for j in 0..24 {
            for i in 0..40 {
                let ray = camera.ray(s.geometry(), i, j, 40, 24);
                let near = trace_pixel(&walker, &scene, ray, 100_000);
                let exact = trace_pixel(&walker, &far, ray, 100_000);
                worst = worst.max((near - exact).abs().max_element());
            }
        }
        assert!(
            worst <= scene.shading.cutoff_weight * (1.0 + 1e-9),
            "{id}: {worst}"
        );
    }
}

/// Every seed space renders a picture with the centre ball, edges of several cycles and
/// fog, the same twice.
#[test]
fn every_seed_space_renders() {
    for seed in SEED_SPACES {
        let s = seed.build().unwrap();
        let scene = CurvedScene::default_for(&s, Shading::default_fog_distance(&s));
        let camera = TraceCamera::default_for(&s);
        let settings = RenderSettings {
            width: 96,
            height: 54,
            max_crossings: 64,
        };
        let image = render(&s, &scene, &camera, &settings);
        assert_eq!(image.dimensions(), (96, 54));
        let fog = scene
            .shading
            .fog_colour
            .to_array()
            .map(|x| (x * 255.0).round() as u8);
        let non_fog = image.pixels().filter(|p| p.0 != fog).count();
        assert!(
            non_fog > 96 * 54 / 2,
            "{}: only {non_fog} pixels show anything",
            seed.id
        );
        assert_eq!(image, render(&s, &scene, &camera, &settings), "{}", seed.id);
        // The camera of the default view hits the centre ball somewhere near the middle.
        let walker = CellWalker::<DVec4>::new(&s);
        let centre_ball = scene.objects.len() - 1;
        let sees_ball = (0..54).any(|j| {
            (0..96).any(|i| {
                matches!(first_hit(&walker, &scene, camera.ray(s.geometry(), i, j, 96, 54), 64),
                    RayEnd::Hit(h) if h.object == centre_ball && h.crossings == 0)
            })
        });
        assert!(sees_ball, "{}: the centre ball is not in view", seed.id);
    }
}

/// The inspector's story of a ray is the ray the renderer traces: the same end, and its
/// faces hash to the same path, with distances that grow.
#[test]
fn a_rays_story_is_the_traced_ray() {
    use bevy_curved_spaces::trace::{
        PATH_HASH_START, first_hit_traced, path_hash, ray_story, sample_rays,
    };
    for id in ["seifert-weber", "quarter-turn", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).unwrap();
        let scene = bevy_curved_spaces::scene::CurvedScene::default_for(
            &space,
            bevy_curved_spaces::scene::Shading::default_fog_distance(&space),
        );
        let walker = bevy_curved_spaces::space::CellWalker::<glam::DVec4>::new(&space);
        for ray in sample_rays(&space, 200, 5) {
            let traced = first_hit_traced(&walker, &scene, ray, 16);
            let story = ray_story(&walker, &scene, ray, 16);
            assert_eq!(story.end, traced.end, "{id}");
            let path = story
                .crossings
                .iter()
                .fold(PATH_HASH_START, |h, (f, _)| path_hash(h, *f));
            assert_eq!(path, traced.path, "{id}");
            assert!(story.crossings.windows(2).all(|w| w[0].1 < w[1].1));
        }
    }
}

/// A flat cell has no length of its own: every flat seed space scaled by a power of two
/// (2 to 2²⁰, exact) renders the picture it renders at unit size, default scene and view
/// included. (A scene once capped lengths at π/4, so a cell scaled by 16 showed fog only.)
#[test]
fn flat_cells_render_the_same_at_every_scale() {
    use bevy_curved_spaces::geometry::Geometry;
    use bevy_curved_spaces::space::FaceSpec;
    let settings = RenderSettings {
        width: 64,
        height: 36,
        max_crossings: 24,
    };
    let picture = |s: &Space| {
        let scene = CurvedScene::default_for(s, Shading::default_fog_distance(s));
        render(s, &scene, &TraceCamera::default_for(s), &settings)
    };
    for seed in SEED_SPACES {
        let unit = seed.build().unwrap();
        if unit.geometry() != Geometry::Euclidean {
            continue;
        }
        let at_unit = picture(&unit);
        for k in [1, 4, 6, 10, 20] {
            let scale = 2f64.powi(k);
            let cells: Vec<Vec<FaceSpec>> = unit
                .cells()
                .iter()
                .map(|cell| {
                    unit.faces()[cell.clone()]
                        .iter()
                        .map(|f| {
                            let mut pairing = f.pairing;
                            pairing.w_axis = (pairing.w_axis.truncate() * scale).extend(1.0);
                            FaceSpec::paired(f.normal, f.offset * scale, f.partner, pairing)
                        })
                        .collect()
                })
                .collect();
            let scaled =
                Space::new_cells(unit.name(), unit.description(), Geometry::Euclidean, &cells)
                    .unwrap();
            let image = picture(&scaled);
            let differing = image
                .pixels()
                .zip(at_unit.pixels())
                .filter(|(a, b)| a.0.iter().zip(b.0).any(|(x, y)| x.abs_diff(y) > 2))
                .count();
            assert!(
                differing <= 64 * 36 / 100,
                "{} scaled by 2^{k}: {differing} of {} pixels differ from unit size",
                seed.id,
                64 * 36
            );
        }
    }
}
