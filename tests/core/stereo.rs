//! Stereo that stays correct in curved space: the parallax of an object at a known distance
//! is the one each geometry predicts for eyes offset along geodesics, the eye axis turns
//! with the head, eyes near a face are wrapped with their own pairings, and the layouts put
//! each eye where it belongs. All measured on the f64 CPU reference (the GPU is compared
//! against it in tests/gpu.rs).

use crate::common::differing_fraction;
use bevy_curved_spaces::geometry::{Geometry, ORIGIN};
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::lighting::Lighting;
use bevy_curved_spaces::scene::{Ball, CurvedScene, Object, SceneParts, Shading};
use bevy_curved_spaces::space::CellWalker;
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::{Space, seed_space};
use bevy_curved_spaces::trace::{RayEnd, RenderSettings, first_hit, render_view};
use bevy_curved_spaces::view::StereoMode;
use bevy_curved_spaces::view::stereo::{StereoError, check_ipd, eye_frames, offset_eye};
use bevy_curved_spaces::view::{Lens, PixelRays, ViewKind, ViewLayout};
use glam::{DMat4, DVec3, DVec4};

/// A scene with one ball and nothing else (no edges, no centre ball).
fn lone_ball(space: &Space, centre: DVec4, radius: f64) -> CurvedScene {
    let mut scene = CurvedScene::with_parts(
        space,
        Shading::default_fog_distance(space),
        SceneParts {
            edges: false,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        },
    );
    let ball = Ball::new(space.geometry(), centre, radius, DVec3::ONE);
    scene
        .place(space, Object::Ball(ball))
        .expect("inside the cell");
    scene
}

/// The head at distance `d/2` from the cell's centre on the +z axis looking along −z at a
/// ball at distance `d/2` on the −z axis: the ball is `d` straight ahead.
fn head_and_ball(space: &Space, d: f64, radius: f64) -> (DMat4, CurvedScene) {
    let g = space.geometry();
    let head = g.translation(DVec3::Z, d / 2.0);
    let centre = g.translation(DVec3::Z, -d / 2.0) * ORIGIN;
    (head, lone_ball(space, centre, radius))
}

/// The centroid, in each eye's frustum coordinates `(x, y)` (tangent of the angle from the
/// eye's view axis), of the pixels whose ray hits the ball before crossing any face. Index 0
/// is the left eye; `z` is the pixel count.
fn ball_centroids(
    space: &Space,
    scene: &CurvedScene,
    layout: &ViewLayout,
    w: u32,
    h: u32,
) -> [DVec3; 2] {
    let walker = CellWalker::<DVec4>::new(space);
    let mut sums = [DVec3::ZERO; 2];
    for j in 0..h {
        for i in 0..w {
            let PixelRays::One(ray) = layout.rays_at(space.geometry(), i, j) else {
                panic!("a split layout has one ray per pixel");
            };
            // The ball itself, not its copies seen through faces (they are farther and show
            // less parallax).
            if let RayEnd::Hit(hit) = first_hit(&walker, scene, ray, 8)
                && hit.crossings == 0
            {
                let (eye, [u, v]) = layout.eye_at(f64::from(i) + 0.5, f64::from(j) + 0.5);
                let (x, y) = layout.lens.at(u, v);
                sums[eye] += DVec3::new(x, y, 1.0);
            }
        }
    }
    sums.map(|s| {
        assert!(s.z > 50.0, "the ball covers only {} pixels of an eye", s.z);
        DVec3::new(s.x / s.z, s.y / s.z, s.z)
    })
}

const WIDTH: u32 = 320;
const HEIGHT: u32 = 160;
const FOV: f64 = 50.0;

/// Pixels per unit of frustum coordinate in the side-by-side layout used here.
fn pixels_per_unit() -> f64 {
    f64::from(HEIGHT) / 2.0 / (FOV.to_radians() / 2.0).tan()
}

/// Measures the ball's direction from both eyes and checks it against `tan θ` predicted by
/// the geometry for eyes `ipd` apart and a ball `d` ahead. Returns the measured disparity in
/// pixels.
///
/// The ball's outline is a circular cone of half-angle α about the direction θ, so in the
/// picture an ellipse whose centre (the centroid of its pixels) is at
/// `(tan(θ+α) + tan(θ−α)) / 2`, a little outside `tan θ`; `sin α = S(r)/S(D)` for a ball of
/// radius r at distance D (S = sin, id, sinh).
fn measured_disparity(space: &Space, d: f64, ipd: f64, predicted_tan: f64) -> f64 {
    let g = space.geometry();
    let radius = 0.08;
    let (head, scene) = head_and_ball(space, d, radius);
    let centre = g.translation(DVec3::Z, -d / 2.0) * ORIGIN;
    let eyes = eye_frames(space, head, ipd).map(|e| e.frame);
    let layout = ViewLayout::new(StereoMode::SideBySide, false, eyes, FOV, WIDTH, HEIGHT);
    let [left, right] = ball_centroids(space, &scene, &layout, WIDTH, HEIGHT);
    let px = pixels_per_unit();
    for (name, c, eye, sign) in [
        ("left", left, eyes[0], 1.0),
        ("right", right, eyes[1], -1.0),
    ] {
        let theta = sign * predicted_tan.atan();
        let alpha = (g.s(radius) / g.s(g.distance(eye.w_axis, centre))).asin();
        let want = ((theta + alpha).tan() + (theta - alpha).tan()) / 2.0;
        // A pixelated ellipse's centroid is within a small fraction of a pixel of its centre.
        assert!(
            (c.x - want).abs() * px < 0.2,
            "{}: the {name} eye sees the ball at x = {:.5}, the geometry predicts {want:.5} ({:.2} px off)",
            space.name(),
            c.x,
            (c.x - want).abs() * px
        );
        assert!(c.y.abs() * px < 0.2, "{name} eye: vertical offset {}", c.y);
    }
    (left.x - right.x) * px
}

#[test]
fn disparity_in_the_torus_is_what_flat_geometry_predicts() {
    let space = seed_space("torus").expect("seed");
    let (d, ipd) = (0.6, 0.06);
    // Eyes ±b/2 from the head, the ball d ahead: tan θ = (b/2)/d.
    let disparity = measured_disparity(&space, d, ipd, (ipd / 2.0) / d);
    let predicted = ipd / d * pixels_per_unit();
    println!(
        "torus: disparity {disparity:.3} px (tan θ alone gives {predicted:.3} px; the outline's centre sits a little outside)"
    );
    assert!(disparity > 10.0, "the disparity should be clearly visible");
    // Twice the eye distance, twice the disparity (flat space is linear).
    let doubled = measured_disparity(&space, d, 2.0 * ipd, ipd / d);
    assert!((doubled / disparity - 2.0).abs() < 0.05);
}

#[test]
fn disparity_in_hyperbolic_space_follows_the_hyperbolic_right_triangle() {
    let space = seed_space("seifert-weber").expect("seed");
    let (d, ipd): (f64, f64) = (0.9, 0.2);
    // Right angle at the head between the eye axis and the view axis: the angle A at the eye
    // opposite the leg d has tan A = tanh d / sinh(b/2), so tan θ = tan(90° − A) =
    // sinh(b/2) / tanh d.
    let hyperbolic = (ipd / 2.0).sinh() / d.tanh();
    let flat = (ipd / 2.0) / d;
    let disparity = measured_disparity(&space, d, ipd, hyperbolic);
    let flat_px = 2.0 * flat * pixels_per_unit();
    println!(
        "seifert-weber: disparity {disparity:.3} px; the flat formula would give {flat_px:.3} px"
    );
    // A chart offset or the flat formula would be off by several pixels here.
    assert!(disparity - flat_px > 5.0);
}

#[test]
fn disparity_in_spherical_space_follows_the_spherical_right_triangle() {
    let space = seed_space("poincare").expect("seed");
    let (d, ipd): (f64, f64) = (0.5, 0.1);
    // tan A = tan d / sin(b/2) at the eye, so tan θ = sin(b/2) / tan d.
    let spherical = (ipd / 2.0).sin() / d.tan();
    let disparity = measured_disparity(&space, d, ipd, spherical);
    let flat_px = ipd / d * pixels_per_unit();
    println!("poincare: disparity {disparity:.3} px; flat formula {flat_px:.3} px");
    assert!(flat_px - disparity > 0.5);
}

#[test]
fn rolling_the_head_by_90_degrees_turns_the_eye_axis_vertical() {
    let space = seed_space("torus").expect("seed");
    let g = space.geometry();
    let (d, ipd) = (0.6, 0.06);
    let (head, scene) = head_and_ball(&space, d, 0.08);
    // Roll 90° about the view axis (back): the head's right now points along chart +y.
    let rolled = head * g.rotation(DVec3::Z, std::f64::consts::FRAC_PI_2);
    let eyes = eye_frames(&space, rolled, ipd);
    let gap = g.to_chart(eyes[1].frame.w_axis) - g.to_chart(eyes[0].frame.w_axis);
    assert!(
        (gap - DVec3::new(0.0, ipd, 0.0)).length() < 1e-12,
        "the eyes should be stacked vertically after the roll, gap {gap:?}"
    );
    // In each eye's own picture the disparity stays along the eye axis (horizontal in the
    // picture), which in the world is now vertical.
    let frames = eyes.map(|e| e.frame);
    let layout = ViewLayout::new(StereoMode::SideBySide, false, frames, FOV, WIDTH, HEIGHT);
    let [left, right] = ball_centroids(&space, &scene, &layout, WIDTH, HEIGHT);
    let px = pixels_per_unit();
    let picture = (left - right).truncate() * px;
    assert!(picture.x > 10.0 && picture.y.abs() < 0.25, "{picture:?}");
    let world = picture.x * rolled.x_axis.truncate() + picture.y * rolled.y_axis.truncate();
    assert!(
        world.x.abs() < 0.25 && (world.y - picture.x).abs() < 0.25,
        "the disparity in the world should be vertical, got {world:?}"
    );
}

#[test]
fn eyes_near_a_face_are_wrapped_with_their_own_pairings() {
    let space = seed_space("torus").expect("seed");
    let g = space.geometry();
    let ipd = 0.06;
    // The head 0.01 inside the +x face: the right eye is 0.02 past it.
    let head = g.translation(DVec3::X, 0.49) * g.rotation(DVec3::Y, 0.3);
    let eyes = eye_frames(&space, head, ipd);
    assert!(
        eyes[0].crossed.is_empty(),
        "the left eye is inside the cell"
    );
    assert_eq!(eyes[1].crossed.len(), 1, "the right eye crosses one face");
    for eye in &eyes {
        assert!(space.outside_by(eye.frame.w_axis) <= 0.0);
    }
    let face = eyes[1].crossed[0];
    assert!(space.faces()[face].covector.x > 0.5, "it is the +x face");

    // The right eye's picture equals a mono picture from the same point computed without
    // the stereo code: the head's right tangent in the torus is a chart direction, and the
    // +x face's pairing is the translation by −1 in x.
    let walker_start = head.w_axis.truncate() + head.x_axis.truncate() * (ipd / 2.0);
    let independent = DMat4::from_cols(
        head.x_axis,
        head.y_axis,
        head.z_axis,
        (walker_start - DVec3::X).extend(1.0),
    );
    // Lit by the nearest copy of its lamp (which depends on where in the cell a point is),
    // a picture seen from outside the cell is wrong, and the test below can tell.
    let mut scene = CurvedScene::default_for(&space, Shading::default_fog_distance(&space));
    scene
        .set_lighting(&space, Lighting::NEAREST)
        .expect("the nearest-copy lighting");
    let (w, h) = (160, 90);
    let settings = RenderSettings {
        width: w,
        height: h,
        max_crossings: 24,
    };
    let frames = eyes.map(|e| e.frame);
    let stereo = render_view(
        &space,
        &scene,
        &ViewLayout::new(StereoMode::SideBySide, false, frames, 70.0, w, h),
        &settings,
        |_, _| {},
    );
    let half_lens = Lens::symmetric(70.0, (f64::from(w) / 2.0) / f64::from(h));
    let mono = |frame| {
        render_view(
            &space,
            &scene,
            &ViewLayout::mono(frame, half_lens, w / 2, h),
            &RenderSettings {
                width: w / 2,
                ..settings
            },
            |_, _| {},
        )
    };
    let right_half = image::imageops::crop_imm(&stereo, w / 2, 0, w / 2, h).to_image();
    let differing = |a: &image::RgbImage, b: &image::RgbImage| differing_fraction(a, b, 2);
    let same = differing(&right_half, &mono(independent));
    assert!(
        same < 0.002,
        "{:.2} % of the right eye's pixels differ",
        100.0 * same
    );
    // Seen from the unwrapped point (outside the cell), the picture is wrong: the test can
    // tell.
    let unwrapped = head * g.translation(DVec3::X, ipd / 2.0);
    let wrong = differing(&right_half, &mono(unwrapped));
    assert!(
        wrong > 0.02,
        "only {:.2} % differ from outside",
        100.0 * wrong
    );
}

/// In every space, eyes of random heads near faces, edges and vertices are inside the cell,
/// and in the universal cover (undoing each eye's pairing) they are `ipd/2` from the head on
/// opposite sides along its right tangent.
#[test]
fn both_eyes_are_always_inside_the_cell_and_ipd_apart_in_the_cover() {
    let mut rng = SplitMix64(7);
    for id in [
        "torus",
        "hantzsche-wendt",
        "seifert-weber",
        "mirrored-dodecahedron",
        "poincare",
    ] {
        let space = seed_space(id).expect("seed");
        let g = space.geometry();
        let r = inradius(&space);
        let ipd = 0.3 * r;
        let mut wrapped = 0;
        for _ in 0..500 {
            // From the centre along a random direction to the boundary (bisection), then back
            // in by less than half the eye distance, turned at random.
            let dir = rng.direction();
            let (mut inside, mut outside) = (0.0, 4.0 * r);
            for _ in 0..60 {
                let mid = 0.5 * (inside + outside);
                if space.outside_by(g.translation(dir, mid) * ORIGIN) > 0.0 {
                    outside = mid;
                } else {
                    inside = mid;
                }
            }
            let depth = inside - rng.unit() * 0.5 * ipd;
            let head = g.translation(dir, depth) * g.rotation(rng.direction(), 6.0 * rng.unit());
            let eyes = eye_frames(&space, head, ipd);
            for (eye, sign) in eyes.iter().zip([-1.0, 1.0]) {
                assert!(
                    space.outside_by(eye.frame.w_axis) <= 1e-12,
                    "{id}: an eye is outside the cell"
                );
                wrapped += usize::from(!eye.crossed.is_empty());
                let unwrapped = g.inverse(eye.pairing) * eye.frame;
                let expected = head * g.translation(DVec3::X, sign * ipd / 2.0);
                let gap = g.distance(unwrapped.w_axis, expected.w_axis);
                assert!(gap < 1e-9, "{id}: eye {gap:e} from where it belongs");
                assert!((g.distance(unwrapped.w_axis, head.w_axis) - ipd / 2.0).abs() < 1e-9);
            }
        }
        println!("{id}: {wrapped} of 1000 eyes were wrapped");
        assert!(
            wrapped > 20,
            "{id}: the heads should often put an eye past a face"
        );
    }
}

#[test]
fn swapping_the_eyes_swaps_the_halves() {
    let space = seed_space("seifert-weber").expect("seed");
    let camera = bevy_curved_spaces::view::TraceCamera::default_for(&space);
    let scene = CurvedScene::default_for(&space, Shading::default_fog_distance(&space));
    let eyes = eye_frames(&space, camera.frame, 0.05).map(|e| e.frame);
    let settings = RenderSettings {
        width: 128,
        height: 48,
        max_crossings: 24,
    };
    let picture = |mode, swap| {
        let layout = ViewLayout::new(mode, swap, eyes, 70.0, 128, 48);
        render_view(&space, &scene, &layout, &settings, |_, _| {})
    };
    for (mode, halves) in [
        (StereoMode::SideBySide, [(0, 0), (64, 0)]),
        (StereoMode::TopBottom, [(0, 0), (0, 24)]),
    ] {
        let (w, h) = if halves[1].0 > 0 { (64, 48) } else { (128, 24) };
        let plain = picture(mode, false);
        let swapped = picture(mode, true);
        let half = |img: &image::RgbImage, (x, y): (u32, u32)| {
            image::imageops::crop_imm(img, x, y, w, h).to_image()
        };
        assert_eq!(half(&plain, halves[0]), half(&swapped, halves[1]), "{mode}");
        assert_eq!(half(&plain, halves[1]), half(&swapped, halves[0]), "{mode}");
        assert_ne!(
            half(&plain, halves[0]),
            half(&plain, halves[1]),
            "{mode}: eyes differ"
        );
    }
}

#[test]
fn anaglyphs_put_the_left_eye_in_red_and_keep_grey_grey() {
    let space = seed_space("torus").expect("seed");
    let (head, scene) = head_and_ball(&space, 0.6, 0.08);
    let eyes = eye_frames(&space, head, 0.06).map(|e| e.frame);
    let (w, h) = (96, 54);
    let settings = RenderSettings {
        width: w,
        height: h,
        max_crossings: 24,
    };
    let mono = |frame| {
        render_view(
            &space,
            &scene,
            &ViewLayout::new(StereoMode::Mono, false, [frame; 2], 70.0, w, h),
            &settings,
            |_, _| {},
        )
    };
    let (left, right) = (mono(eyes[0]), mono(eyes[1]));
    let layout = ViewLayout::new(StereoMode::AnaglyphRedCyan, false, eyes, 70.0, w, h);
    assert_eq!(layout.kind, ViewKind::Anaglyph);
    let plain = render_view(&space, &scene, &layout, &settings, |_, _| {});
    for ((a, l), r) in plain.pixels().zip(left.pixels()).zip(right.pixels()) {
        // Channel selection commutes with the sRGB curve: up to 1 level of rounding.
        assert!(a[0].abs_diff(l[0]) <= 1 && a[1].abs_diff(r[1]) <= 1 && a[2].abs_diff(r[2]) <= 1);
    }
    assert_ne!(left, right, "the eyes see different pictures");

    // Dubois' matrices map a grey seen by both eyes to (nearly) the same grey.
    for mode in [StereoMode::AnaglyphDubois, StereoMode::AnaglyphOptimized] {
        let layout = ViewLayout::new(mode, false, eyes, 70.0, w, h);
        for grey in [0.1, 0.5, 0.9] {
            let c = layout.mix_anaglyph(DVec3::splat(grey), DVec3::splat(grey));
            assert!(
                (c - DVec3::splat(grey)).abs().max_element() < 0.01,
                "{mode}: grey {grey} became {c:?}"
            );
        }
    }
}

#[test]
fn stereo_modes_parse_by_name_and_bad_settings_are_named() {
    for mode in StereoMode::ALL {
        assert_eq!(mode.name().parse::<StereoMode>(), Ok(mode));
    }
    let err = "sideways".parse::<StereoMode>().unwrap_err().to_string();
    assert!(
        err.contains("sideways") && err.contains("top-bottom"),
        "{err}"
    );
    assert_eq!(check_ipd(-1.0, 1.0), Err(StereoError::BadIpd(-1.0)));
    assert!(matches!(
        check_ipd(f64::NAN, 1.0),
        Err(StereoError::BadIpd(_))
    ));
    assert!(matches!(
        check_ipd(2.0, 1.0),
        Err(StereoError::IpdTooLarge { .. })
    ));
    assert_eq!(check_ipd(0.05, 1.0), Ok(()));
    // A zero offset is the head itself.
    let space = seed_space("poincare").expect("seed");
    let head = Geometry::Spherical.translation(DVec3::Y, 0.1);
    assert_eq!(offset_eye(&space, head, 0.0).frame, head);
}
