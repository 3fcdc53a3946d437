//! Stereo on the GPU: every layout against the CPU reference, the disparity the geometry
//! gives, and the split between scaled-up halves.

use super::*;

/// Stereo on the GPU: both eyes traced by the same shader agree with the CPU reference in
/// every layout and in all three geometries, with the eyes' own frames (one of them wrapped
/// through a face where the head is near one).
#[test]
fn stereo_layouts_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::StereoSettings;
    use bevy_curved_spaces::space::invariants::inradius;
    use bevy_curved_spaces::trace::render_view;
    use bevy_curved_spaces::view::StereoMode;
    use bevy_curved_spaces::view::ViewLayout;
    use bevy_curved_spaces::view::stereo::eye_frames;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    // The torus head 0.01 inside its +x face: the right eye is wrapped through it.
    let torus = bevy_curved_spaces::space::seed_space("torus").expect("builds");
    let near_face = torus.geometry().translation(glam::DVec3::X, 0.49)
        * torus.geometry().rotation(glam::DVec3::Y, 0.3);
    for (id, mode, head, wrapped) in [
        ("torus", StereoMode::SideBySide, None, false),
        ("torus", StereoMode::SideBySide, Some(near_face), true),
        ("seifert-weber", StereoMode::TopBottomHalf, None, false),
        ("poincare", StereoMode::AnaglyphDubois, None, false),
        (
            "mirrored-dodecahedron",
            StereoMode::AnaglyphRedCyan,
            None,
            false,
        ),
        ("half-turn", StereoMode::SideBySideHalf, None, false),
    ] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let mut camera = TraceCamera::default_for(&space);
        if let Some(frame) = head {
            camera.frame = frame;
        }
        let stereo = StereoSettings {
            mode,
            ipd: Some(0.12 * inradius(&space)),
            swap_eyes: false,
        };
        let eyes = eye_frames(&space, camera.frame, stereo.ipd_for(inradius(&space)));
        assert_eq!(
            !eyes[1].crossed.is_empty(),
            wrapped,
            "{id}: the right eye's wrap"
        );
        let layout = ViewLayout::new(
            mode,
            false,
            eyes.map(|e| e.frame),
            camera.fov_y_degrees,
            WIDTH,
            HEIGHT,
        );
        let fog = Shading::default_fog_distance(&space);
        let scene = CurvedScene::with_parts(&space, fog, SceneParts::default());
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 24,
        };
        let cpu = render_view(&space, &scene, &layout, &settings, |_, _| {});
        let gpu = renderer
            .render(&OffscreenRender {
                fog_distance: Some(fog),
                stereo,
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    24,
                )
            })
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        let (c, diff) = compare(&gpu, &cpu, TOLERANCE);
        let id = if wrapped { "torus-eye-wrapped" } else { id };
        println!(
            "{id:<22} {mode:<18} differing {:.3} %, mean error {:.3}/255, max {}",
            100.0 * c.differing,
            c.mean_error,
            c.max_error
        );
        if c.differing > MAX_DIFFERING {
            std::fs::create_dir_all(&out).expect("create output folder");
            for (name, img) in [("gpu", &gpu), ("cpu", &cpu), ("diff", &diff)] {
                img.save(out.join(format!("{id}-{mode}-{name}.png")))
                    .expect("write image");
            }
        }
        assert!(
            c.differing <= MAX_DIFFERING,
            "{id} {mode}: {:.2} % of pixels differ (images in {})",
            100.0 * c.differing,
            out.display()
        );
        // The stereo picture is not the mono one: the test sees the eyes.
        let mono = render(&space, &scene, &camera, &settings);
        assert!(
            compare(&gpu, &mono, TOLERANCE).0.differing > 0.05,
            "{id} {mode}"
        );
    }
}

/// The parallax measured on the GPU's side-by-side picture of a ball straight ahead in the
/// torus is what flat geometry predicts: the centre of the ball's outline in each eye is at
/// `(tan(θ+α) + tan(θ−α))/2` with `tan θ = (b/2)/d` and `sin α = r/D`.
#[test]
fn gpu_disparity_in_the_torus_matches_the_geometry() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::geometry::ORIGIN;
    use bevy_curved_spaces::plugin::components::StereoSettings;
    use bevy_curved_spaces::scene::{Ball, Object};
    use bevy_curved_spaces::view::StereoMode;
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = bevy_curved_spaces::space::seed_space("torus").expect("builds");
    let g = space.geometry();
    let (d, ipd, radius, fov) = (0.6, 0.06, 0.08, 40.0_f64);
    let head = g.translation(DVec3::Z, d / 2.0);
    let centre = g.translation(DVec3::Z, -d / 2.0) * ORIGIN;
    let ball = Object::Ball(Ball::new(g, centre, radius, DVec3::ONE));
    let picture = renderer
        .render(&OffscreenRender {
            parts: SceneParts {
                edges: false,
                centrepiece: Centrepiece::None,
                avatar: false,
                clifford: false,
            },
            objects: vec![ball],
            stereo: StereoSettings {
                mode: StereoMode::SideBySide,
                ipd: Some(ipd),
                swap_eyes: false,
            },
            ..OffscreenRender::new(
                ActiveSpace::new("torus", space.clone()),
                TraceCamera {
                    frame: head,
                    fov_y_degrees: fov,
                },
                (WIDTH, HEIGHT),
                8,
            )
        })
        .expect("renders");
    let fog = Shading::default_fog_distance(&space);
    let fog_colour = CurvedScene::default_for(&space, fog).shading.fog_colour * 255.0;
    // Pixels per unit of tan(angle), the same in x and y (square pixels).
    let f = f64::from(HEIGHT) / 2.0 / (fov.to_radians() / 2.0).tan();
    let eye_width = f64::from(WIDTH) / 2.0;
    let mut measured = [0.0; 2];
    for (eye, sign) in [(0u32, 1.0), (1u32, -1.0)] {
        let theta = sign * (ipd / 2.0 / d).atan();
        let distance = (d * d + ipd * ipd / 4.0).sqrt();
        let alpha = (radius / distance).asin();
        let want = ((theta + alpha).tan() + (theta - alpha).tan()) / 2.0;
        // The ball's pixels near where it should be (its copies are smaller and far off).
        let (cx, cy) = (eye_width / 2.0 + want * f, f64::from(HEIGHT) / 2.0);
        let window = 1.5 * alpha.tan() * f;
        let (mut sx, mut sy, mut n) = (0.0, 0.0, 0.0);
        for j in 0..HEIGHT {
            for i in 0..WIDTH / 2 {
                let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
                if (x - cx).hypot(y - cy) > window {
                    continue;
                }
                let p = picture.get_pixel(i + eye * WIDTH / 2, j);
                let off = (0..3).any(|k| (f64::from(p[k]) - fog_colour[k]).abs() > 25.0);
                if off {
                    sx += x;
                    sy += y;
                    n += 1.0;
                }
            }
        }
        assert!(n > 100.0, "eye {eye}: the ball covers {n} pixels");
        let (mx, my) = (sx / n, sy / n);
        println!(
            "eye {eye}: ball centre at {mx:.3}, {my:.3} px; the geometry predicts {cx:.3}, {cy:.3}"
        );
        assert!((mx - cx).abs() < 0.3 && (my - cy).abs() < 0.3);
        measured[eye as usize] = mx;
    }
    println!(
        "GPU disparity {:.3} px (tan θ alone gives {:.3} px)",
        measured[0] - measured[1],
        ipd / d * f
    );
}

/// At a reduced resolution the picture is scaled up, but the two eyes of a side-by-side or
/// top-bottom view are not blended where their halves meet: the first row or column of the
/// second eye continues that eye's picture (it is as close to its neighbour inside the
/// half as the picture's rows and columns are on average), instead of being a mix of the
/// two eyes.
#[test]
fn scaled_up_stereo_halves_do_not_mix_at_the_split() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::StereoSettings;
    use bevy_curved_spaces::view::StereoMode;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = bevy_curved_spaces::space::seed_space("seifert-weber").expect("builds");
    let camera = TraceCamera::default_for(&space);
    for (mode, vertical) in [
        (StereoMode::SideBySide, false),
        (StereoMode::TopBottom, true),
    ] {
        let picture = renderer
            .render(&OffscreenRender {
                resolution_scale: 0.5,
                stereo: StereoSettings {
                    mode,
                    ..Default::default()
                },
                ..OffscreenRender::new(
                    ActiveSpace::new("seifert-weber", space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    24,
                )
            })
            .expect("renders");
        // Mean absolute difference between line k and line k + 1 (columns, or rows).
        let (lines, length) = if vertical {
            (HEIGHT, WIDTH)
        } else {
            (WIDTH, HEIGHT)
        };
        let pixel = |line: u32, at: u32| {
            let (x, y) = if vertical { (at, line) } else { (line, at) };
            picture.get_pixel(x, y).0.map(f64::from)
        };
        let step = |k: u32| {
            (0..length)
                .map(|at| {
                    let (a, b) = (pixel(k, at), pixel(k + 1, at));
                    (0..3).map(|c| (a[c] - b[c]).abs()).sum::<f64>() / 3.0
                })
                .sum::<f64>()
                / f64::from(length)
        };
        let split = lines / 2;
        let typical = (1..lines - 2).map(step).sum::<f64>() / f64::from(lines - 3);
        let inside_second = step(split);
        println!(
            "{mode}: first line of the second eye vs its neighbour {inside_second:.2} levels; typical step {typical:.2}"
        );
        assert!(
            inside_second < 2.0 * typical,
            "{mode}: the second eye's first line is mixed with the first eye"
        );
    }
}
