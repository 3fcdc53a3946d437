//! Objects that stick out of the cell through faces are drawn through their images under the
//! pairings (only the images that meet the cell), so they look whole from everywhere.

use crate::common::{compare, differing_fraction};
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::{Ball, CurvedScene, Object, PlaceError, SceneParts};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{SEED_SPACES, seed_space};
use bevy_curved_spaces::trace::{RenderSettings, render};
use bevy_curved_spaces::view::TraceCamera;
use glam::{DVec3, DVec4};

/// The default scene's edges and vertex balls sit on the cell's boundary and already come in
/// complete orbits: placing them one by one adds no ball (a vertex ball's images are the
/// other vertex balls) and changes no pixel; it may add tube images that only touch the cell
/// (an edge of a neighbouring cell whose flat end sits on a vertex), which cost time only.
#[test]
fn placing_the_default_scene_changes_no_pixel() {
    for seed in SEED_SPACES {
        let s = seed.build().expect("seed space builds");
        let fog = bevy_curved_spaces::scene::Shading::default_fog_distance(&s);
        let default = CurvedScene::default_for(&s, fog);
        let mut placed = CurvedScene::with_parts(
            &s,
            fog,
            SceneParts {
                edges: false,
                centrepiece: Centrepiece::None,
                avatar: false,
                clifford: false,
            },
        );
        for o in &default.objects {
            placed.place(&s, *o).expect("the object is in the cell");
        }
        let balls = |scene: &CurvedScene| {
            scene
                .objects
                .iter()
                .filter(|o| matches!(o, Object::Ball(_)))
                .count()
        };
        assert_eq!(
            balls(&placed),
            balls(&default),
            "{}: ball images added",
            seed.id
        );
        let camera = TraceCamera::default_for(&s);
        let settings = RenderSettings {
            width: 64,
            height: 36,
            max_crossings: 24,
        };
        let a = render(&s, &default, &camera, &settings);
        let b = render(&s, &placed, &camera, &settings);
        let differing = compare(&a, &b, 1).0.differing_pixels;
        assert!(
            differing <= 2,
            "{}: {differing} pixels changed by placing the default scene",
            seed.id
        );
    }
}

/// An empty scene lit only by ambient light (so lighting does not depend on the cell).
fn ambient_scene(space: &bevy_curved_spaces::space::Space) -> CurvedScene {
    let mut scene = CurvedScene::with_parts(
        space,
        2.0,
        SceneParts {
            edges: false,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        },
    );
    scene.shading.ambient = 1.0;
    scene
}

/// Translating the whole scene and the camera by the same vector changes nothing in the
/// 3-torus (its translations commute with the deck group): a ball at the centre and the same
/// ball moved onto a face corner (straddling three faces) give the same picture when placed,
/// and a visibly different one when the ball is just pushed into the scene.
/// How a torus object over a corner of three faces looks against the same object at the
/// centre seen from the same relative place: `object(at)` is the object centred at chart
/// point `at`, added to `base`. Returns the images placing added, and the fractions of
/// pixels that differ from the centred picture with the images and without them (the object
/// pushed as one).
fn straddling_in_the_torus(
    base: &CurvedScene,
    object: impl Fn(DVec3) -> Object,
) -> (usize, f64, f64) {
    let s = seed_space("torus").expect("builds");
    let g = s.geometry();
    let shift = DVec3::new(0.5, 0.5, 0.35);
    let eye = DVec3::new(0.1, -0.2, 0.38);
    let target = DVec3::new(0.0, 0.0, 0.0);
    let settings = RenderSettings {
        width: 96,
        height: 54,
        max_crossings: 64,
    };
    let centred = {
        let mut scene = base.clone();
        scene.place(&s, object(DVec3::ZERO)).expect("placed");
        let camera = TraceCamera::looking_at(g, eye, target, 70.0).expect("camera");
        render(&s, &scene, &camera, &settings)
    };
    // The shifted camera, wrapped back into the cell [-0.5, 0.5]³.
    let wrap = |v: DVec3| (v + DVec3::splat(0.5)).rem_euclid(DVec3::ONE) - DVec3::splat(0.5);
    let camera = TraceCamera::looking_at(
        g,
        wrap(eye + shift),
        wrap(eye + shift) + (target - eye),
        70.0,
    )
    .expect("camera");
    let mut straddling = base.clone();
    let added = straddling.place(&s, object(shift)).expect("placed");
    let placed = render(&s, &straddling, &camera, &settings);
    let mut naive = base.clone();
    naive.objects.push(object(shift));
    let pushed = render(&s, &naive, &camera, &settings);

    let differing = |a: &image::RgbImage, b: &image::RgbImage| differing_fraction(a, b, 2);
    (
        added,
        differing(&centred, &placed),
        differing(&centred, &pushed),
    )
}

#[test]
fn a_ball_straddling_torus_faces_looks_as_if_it_were_whole() {
    let s = seed_space("torus").expect("builds");
    let g = s.geometry();
    let ball = |at: DVec3| {
        Object::Ball(Ball::new(
            g,
            g.from_chart(at).expect("chart point"),
            0.3,
            DVec3::new(0.9, 0.6, 0.3),
        ))
    };
    let (added, with_images, without) = straddling_in_the_torus(&ambient_scene(&s), ball);
    assert!(
        added >= 4,
        "a ball over a corner of three faces needs images, got {added}"
    );
    assert!(
        with_images < 0.002,
        "{:.2} % of pixels differ with the images",
        100.0 * with_images
    );
    assert!(
        without > 0.05,
        "without images only {:.2} % differ: the test would not see a missing image",
        100.0 * without
    );
}

/// In every space a ball near a face gets images that all meet the cell, and a point of the
/// ball just outside a face is inside the image beyond its partner.
#[test]
fn images_cover_the_part_outside_each_face() {
    for seed in SEED_SPACES {
        let s = seed.build().expect("seed space builds");
        let g = s.geometry();
        let r = inradius(&s);
        // The first face of the space (a seam between cells is none: a ball crossing it
        // needs no image).
        let first = (0..s.faces().len())
            .find(|&f| !s.is_seam(f))
            .expect("a face");
        let face = &s.faces()[first];
        // A ball centred 0.1 r inside that face with radius 0.3 r.
        let centre = g
            .from_chart(face.normal * face.offset)
            .expect("chart point");
        let inward = g
            .tangent_from_chart(centre, -face.normal)
            .expect("direction");
        let (c, _) = g.geodesic(centre, inward, 0.1 * r);
        let c = g.project_point(c);
        let mut scene = ambient_scene(&s);
        scene
            .place(&s, Object::Ball(Ball::new(g, c, 0.3 * r, DVec3::ONE)))
            .expect("placed");
        assert!(scene.objects.len() >= 2, "{}: no image", seed.id);
        // The point 0.1 r beyond face 0 along its normal is in the ball (0.2 r from c);
        // the pairing maps it inside the cell, where an image must contain it.
        let (beyond, _) = g.geodesic(centre, -inward, 0.1 * r);
        let mapped = g.project_point(face.pairing * g.project_point(beyond));
        assert!(
            s.outside_by(mapped) < 0.0,
            "{}: mapped point outside",
            seed.id
        );
        let covered = scene.objects.iter().any(|o| match o {
            Object::Ball(b) => g.distance(b.centre, mapped) < b.radius,
            _ => false,
        });
        assert!(
            covered,
            "{}: no image covers the part beyond face 0",
            seed.id
        );
    }
}

#[test]
fn misplaced_and_oversized_objects_are_refused() {
    let s = seed_space("poincare").expect("builds");
    let g = s.geometry();
    let far = g
        .from_chart(DVec3::new(3.0, 0.0, 0.0))
        .expect("chart point");
    let mut scene = ambient_scene(&s);
    let outside = scene.place(&s, Object::Ball(Ball::new(g, far, 0.01, DVec3::ONE)));
    assert!(
        matches!(outside, Err(PlaceError::Outside(d, _)) if d > 0.1),
        "{outside:?}"
    );
    let t = seed_space("torus").expect("builds");
    let huge = scene.place(
        &t,
        Object::Ball(Ball::new(t.geometry(), DVec4::W, 9.0, DVec3::ONE)),
    );
    assert_eq!(huge, Err(PlaceError::TooLarge));
    assert!(
        PlaceError::TooLarge
            .to_string()
            .contains("smaller than the cell"),
        "the message says what to do"
    );
}

/// A textured cube mesh straddling a corner of three torus faces looks whole: the same
/// picture as the centred cube seen from the same relative place. Without its images
/// (pushed as one object) the picture differs.
#[test]
fn a_mesh_straddling_torus_faces_looks_as_if_it_were_whole() {
    use bevy_curved_spaces::scene::mesh::cube_source;
    use bevy_curved_spaces::scene::{MeshInstance, SurfaceMaterial};
    let s = seed_space("torus").expect("builds");
    let g = s.geometry();
    let mut base = ambient_scene(&s);
    base.materials.push(SurfaceMaterial {
        colour: DVec3::new(0.3, 0.7, 0.9),
        ..SurfaceMaterial::default()
    });
    base.meshes.push(std::sync::Arc::new(
        cube_source(0.18, 0).place(g, 1.0).expect("cube"),
    ));
    let radius = base.meshes[0].radius;
    let turn = g.rotation(DVec3::new(0.3, 1.0, 0.2), 0.5);
    let cube = |at: DVec3| {
        let frame = g.translation_to(g.from_chart(at).expect("chart point")) * turn;
        Object::Mesh(MeshInstance::new(g, 0, frame, radius))
    };
    let (added, with_images, without) = straddling_in_the_torus(&base, cube);
    assert!(added >= 4, "a cube over a corner needs images, got {added}");
    assert!(
        with_images < 0.002,
        "{:.2} % of pixels differ with the images",
        100.0 * with_images
    );
    assert!(
        without > 0.02,
        "without images only {:.2} % differ: the test would not see a missing image",
        100.0 * without
    );
}
