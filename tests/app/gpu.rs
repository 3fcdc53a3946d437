//! The GPU tracer against the f64 CPU reference, through the real plugin rendering offscreen
//! (on lavapipe where there is no GPU: `scripts/setup-system.sh` installs it).
//!
//! Both images use the same camera, scene, fog and crossing budget. f32 and f64 differ where
//! a ray grazes an object's silhouette or, in H³, after many crossings (docs/design.md §3), so the
//! assertion is on the fraction of pixels that differ visibly. On failure the GPU, CPU and
//! difference images are written to `target/gpu-vs-cpu/`.

use crate::common::{compare, gpu_lock};
use bevy_curved_spaces::plugin::components::ActiveSpace;
use bevy_curved_spaces::plugin::offscreen::{OffscreenRender, OffscreenRenderer};
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::{CurvedScene, SceneParts, Shading};
use bevy_curved_spaces::space::{SEED_SPACES, Space};
use bevy_curved_spaces::trace::{RenderSettings, render};
use bevy_curved_spaces::view::TraceCamera;
use image::RgbImage;
use std::path::{Path, PathBuf};

const WIDTH: u32 = 160;
const HEIGHT: u32 = 90;
/// A pixel "differs" when a channel is off by more than this (of 255).
const TOLERANCE: u8 = 10;
/// At most this fraction of the pixels may differ.
const MAX_DIFFERING: f64 = 0.01;

#[test]
fn every_seed_space_renders_on_the_gpu_like_the_cpu_reference() {
    let spaces: Vec<(String, Space)> = SEED_SPACES
        .iter()
        .map(|seed| {
            (
                seed.id.to_string(),
                seed.build().expect("seed space builds"),
            )
        })
        .collect();
    spaces_render_alike(&spaces);
}

/// Spaces from groups (spherical, flat non-orientable, hyperbolic census) render alike.
#[test]
fn library_spaces_render_on_the_gpu_like_the_cpu_reference() {
    let spaces: Vec<(String, Space)> = [
        "three-sphere",
        "projective-space",
        "lens-7-1",
        "lens-7-2",
        "prism-5",
        "binary-octahedral",
        "second-amphidicosm",
        "weeks",
    ]
    .iter()
    .map(|id| {
        let space = bevy_curved_spaces::space::resolve_space(
            id,
            std::path::Path::new(""),
            &Default::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        (id.to_string(), space)
    })
    .collect();
    spaces_render_alike(&spaces);
}

/// Each space's default view on the GPU against the CPU reference.
/// Compares a GPU picture with its CPU reference: prints the figures and, where more than
/// [`MAX_DIFFERING`] of the pixels differ or the GPU picture is nearly flat, writes the
/// three images to `out` and adds a failure. A blank or constant picture would also
/// "agree" with a blank reference: the reference must show structure, and so must the GPU
/// image.
/// Notes a failure where `what` (the difference between two pictures of the same tracer)
/// changes fewer than `at_least` of the pixels: a feature that must be there to see.
fn changes(
    what: &str,
    (with, without): (&RgbImage, &RgbImage),
    at_least: f64,
    failures: &mut Vec<String>,
) {
    let (c, _) = compare(with, without, TOLERANCE);
    println!("{what} change {:.2} % of the pixels", 100.0 * c.differing);
    if c.differing < at_least {
        failures.push(format!(
            "{what} change only {:.2} % of the pixels",
            100.0 * c.differing
        ));
    }
}

fn judge(id: &str, gpu: &RgbImage, cpu: &RgbImage, out: &Path, failures: &mut Vec<String>) {
    let (c, diff) = compare(gpu, cpu, TOLERANCE);
    println!(
        "{:<24} differing {:.3} %, mean error {:.3}/255, max {}",
        id,
        100.0 * c.differing,
        c.mean_error,
        c.max_error
    );
    let distinct = |img: &RgbImage| {
        let mut v: Vec<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        v.sort_unstable();
        v.dedup();
        v.len()
    };
    assert!(
        distinct(cpu) > 50,
        "{id}: the reference image is nearly flat"
    );
    if c.differing > MAX_DIFFERING || distinct(gpu) < 50 {
        std::fs::create_dir_all(out).expect("create output folder");
        for (name, img) in [("gpu", gpu), ("cpu", cpu), ("diff", &diff)] {
            img.save(out.join(format!("{id}-{name}.png")))
                .expect("write image");
        }
        failures.push(format!(
            "{id}: {:.2} % of pixels differ by more than {TOLERANCE}/255 (bound {:.0} %)",
            100.0 * c.differing,
            100.0 * MAX_DIFFERING
        ));
    }
}

fn spaces_render_alike(spaces: &[(String, Space)]) {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| {
        panic!("{e}\n(the GPU tests need a Vulkan driver: run scripts/setup-system.sh)")
    });
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let mut failures = Vec::new();
    let crossings = 24;
    for (id, space) in spaces {
        let fog = Shading::default_fog_distance(space);
        let camera = TraceCamera::default_for(space);
        let scene = CurvedScene::with_parts(space, fog, SceneParts::default());
        let cpu = render(
            space,
            &scene,
            &camera,
            &RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                max_crossings: crossings,
            },
        );
        let gpu = renderer
            .render(&OffscreenRender {
                fog_distance: Some(fog),
                ..OffscreenRender::new(
                    ActiveSpace::new(id.as_str(), space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    crossings as u32,
                )
            })
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        judge(id, &gpu, &cpu, &out, &mut failures);
    }
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

#[test]
fn a_reduced_resolution_is_traced_and_scaled_up() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = SEED_SPACES[0].build().expect("seed space builds");
    let camera = TraceCamera::default_for(&space);
    let mut request = OffscreenRender::new(
        ActiveSpace::new("torus", space.clone()),
        camera,
        (WIDTH, HEIGHT),
        24,
    );
    let full = renderer.render(&request).expect("full resolution");
    request.resolution_scale = 0.25;
    let reduced = renderer.render(&request).expect("quarter resolution");
    let (c, _) = compare(&reduced, &full, TOLERANCE);
    println!(
        "quarter resolution vs full: {:.1} % of pixels differ, mean error {:.2}/255",
        100.0 * c.differing,
        c.mean_error
    );
    // Scaled up from 40×23, the picture is the same scene (a small mean error; another view
    // of the scene errs by tens of levels) but blurred at every edge: visibly not the
    // full-resolution trace.
    assert!(
        c.mean_error < 15.0,
        "the reduced picture shows another scene"
    );
    assert!(c.differing > 0.02, "the resolution scale had no effect");
}

/// Your own objects through the plugin (`SceneObjects`): a ball over a corner of the torus
/// cell and one sticking out of a Seifert–Weber face are drawn through their images on the
/// GPU exactly as the CPU reference draws the same placed scene, and a ball outside the cell
/// is left out with a message.
#[test]
fn placed_objects_straddling_faces_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::TracerSettings;
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::{Ball, Object};
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for (id, at, radius) in [
        ("torus", DVec3::new(0.45, 0.45, 0.4), 0.25),
        ("seifert-weber", DVec3::new(0.0, 0.3, 0.55), 0.35),
    ] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let centre = g.from_chart(at).expect("chart point");
        let ball = Object::Ball(Ball::new(g, centre, radius, DVec3::new(0.3, 0.9, 0.5)));
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let settings = TracerSettings {
            fog_distance: None,
            max_crossings: Some(24),
            quality: bevy_curved_spaces::plugin::components::Quality::High,
            resolution_scale: 1.0,
            parts,
            time: None,
            colour_by: Default::default(),
            walls: None,
            lighting: None,
        };
        let (scene, problems) = build_scene(&space, &settings, &[ball], None);
        assert_eq!(problems, None, "{id}");
        let defaults = CurvedScene::with_parts(&space, settings.fog_for(&space, None), parts);
        assert!(
            scene.objects.len() >= defaults.objects.len() + 2,
            "{id}: the ball needs at least one image"
        );
        let camera = TraceCamera::default_for(&space);
        let cpu = render(
            &space,
            &scene,
            &camera,
            &RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                max_crossings: 24,
            },
        );
        let request = OffscreenRender {
            parts,
            objects: vec![ball],
            ..OffscreenRender::new(
                ActiveSpace::new(id, space.clone()),
                camera,
                (WIDTH, HEIGHT),
                24,
            )
        };
        let gpu = renderer.render(&request).expect("renders");
        let (c, _) = compare(&gpu, &cpu, TOLERANCE);
        println!(
            "{id} with a straddling ball: differing {:.3} %, mean error {:.3}/255",
            100.0 * c.differing,
            c.mean_error
        );
        assert!(
            c.differing <= MAX_DIFFERING,
            "{id}: {:.2} %",
            100.0 * c.differing
        );
        // Without the ball the picture changes: the test sees the objects.
        let mut plain = request.clone();
        plain.objects.clear();
        let (without, _) = compare(&renderer.render(&plain).expect("renders"), &gpu, TOLERANCE);
        assert!(without.differing > 0.02, "{id}: the ball is not visible");
    }
    let space = SEED_SPACES[0].build().expect("builds");
    let far = space
        .geometry()
        .from_chart(DVec3::new(2.0, 0.0, 0.0))
        .expect("chart point");
    let settings = TracerSettings {
        fog_distance: None,
        max_crossings: None,
        quality: bevy_curved_spaces::plugin::components::Quality::Medium,
        resolution_scale: 1.0,
        parts: SceneParts::default(),
        time: None,
        colour_by: Default::default(),
        walls: None,
        lighting: None,
    };
    let outside = Object::Ball(Ball::new(space.geometry(), far, 0.1, DVec3::ONE));
    let (scene, problems) = build_scene(&space, &settings, &[outside], None);
    assert!(
        problems.is_some_and(|p| p.contains("scene object 0") && p.contains("not inside the cell")),
        "a misplaced object is named"
    );
    assert_eq!(
        scene.objects.len(),
        CurvedScene::with_parts(&space, settings.fog_for(&space, None), settings.parts)
            .objects
            .len()
    );
}

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

/// Renders `scene` (a base scene for space `id`) on the GPU and the CPU with the same
/// camera, budget and clock; when more than `MAX_DIFFERING` of the pixels differ, saves the
/// pictures under `name` and returns what failed.
fn compare_scene(
    renderer: &mut OffscreenRenderer,
    id: &str,
    space: &bevy_curved_spaces::space::Space,
    scene: &CurvedScene,
    frame: glam::DMat4,
    time: f64,
    name: &str,
) -> Option<String> {
    use bevy_curved_spaces::plugin::components::BaseScene;
    let crossings = 24;
    let mut cpu_scene = scene.clone();
    cpu_scene.time = time;
    cpu_scene.set_avatar_frame(space, frame);
    let camera = TraceCamera {
        frame,
        fov_y_degrees: 70.0,
    };
    let cpu = render(
        space,
        &cpu_scene,
        &camera,
        &RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: crossings,
        },
    );
    let gpu = renderer
        .render(&OffscreenRender {
            fog_distance: Some(scene.shading.fog_distance),
            // The scene holds its edges already: add no parts but the avatar.
            parts: SceneParts {
                edges: false,
                centrepiece: Centrepiece::None,
                avatar: scene.avatar.is_some(),
                clifford: false,
            },
            base: BaseScene {
                space_id: id.to_string(),
                scene: Some(std::sync::Arc::new(scene.clone())),
                start: None,
                parts: None,
                fov: None,
                moving: Vec::new(),
            },
            time,
            ..OffscreenRender::new(
                ActiveSpace::new(id, space.clone()),
                TraceCamera {
                    frame,
                    fov_y_degrees: 70.0,
                },
                (WIDTH, HEIGHT),
                crossings as u32,
            )
        })
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let (c, diff) = compare(&gpu, &cpu, TOLERANCE);
    println!(
        "{name:<28} differing {:.3} %, mean error {:.3}/255, max {}",
        100.0 * c.differing,
        c.mean_error,
        c.max_error
    );
    if c.differing > MAX_DIFFERING {
        let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
        std::fs::create_dir_all(&out).expect("create output folder");
        for (kind, img) in [("gpu", &gpu), ("cpu", &cpu), ("diff", &diff)] {
            img.save(out.join(format!("{name}-{kind}.png")))
                .expect("write image");
        }
    }
    (c.differing > MAX_DIFFERING)
        .then(|| format!("{name}: {:.2} % of pixels differ", 100.0 * c.differing))
}

/// The textured cube of `assets/models/cube.glb`, loaded with the glTF reader and placed
/// turned at the cell's centre with two lights, draws alike on the GPU and the CPU in a
/// flat, a hyperbolic and a spherical space: same hierarchy, triangles, texture sampling
/// and shading.
#[test]
fn a_gltf_from_assets_renders_alike_on_gpu_and_cpu_in_three_geometries() {
    use bevy_curved_spaces::scene::gltf;
    use bevy_curved_spaces::scene::{Light, MeshInstance, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let model =
        gltf::load(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/models/cube.glb"))
            .expect("the asset loads");
    assert!(!model.textures.is_empty(), "the cube carries its texture");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("seed");
        let g = space.geometry();
        let r = inradius(&space);
        let mut scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts {
                edges: true,
                centrepiece: Centrepiece::None,
                avatar: false,
                clifford: false,
            },
        );
        let mesh = scene
            .add_model(g, &model, 0.3 * r / 3f64.sqrt())
            .expect("places");
        let frame = g.rotation(DVec3::new(1.0, 2.0, 0.5), 0.7);
        let radius = scene.meshes[mesh as usize].radius;
        scene
            .place(
                &space,
                Object::Mesh(MeshInstance::new(g, mesh, frame, radius)),
            )
            .expect("inside");
        let at = |v: DVec3| g.translation(v, v.length() * r) * space.centre();
        scene.lights.push(Light::new(
            &space,
            at(DVec3::new(-0.5, 0.4, 0.6)),
            DVec3::new(0.4, 0.5, 1.0),
            g.s(r).powi(2) * 0.5,
        ));
        let camera = TraceCamera::default_for(&space);
        failures.extend(compare_scene(
            &mut renderer,
            id,
            &space,
            &scene,
            camera.frame,
            0.0,
            &format!("cube-{id}"),
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every example scene in `assets/scenes/` (globes at a spun time, glTF meshes, discs,
/// emission, several lights, the avatar) draws alike on the GPU and the CPU.
#[test]
fn the_example_scene_files_render_alike_on_gpu_and_cpu() {
    use bevy_curved_spaces::scene::file::load_scene_file;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("assets/scenes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 2, "the examples ship");
    let mut failures = Vec::new();
    for path in &files {
        // Product scene files are compared in products.rs (their own renderer).
        if bevy_curved_spaces::trace::product::file::load_product_scene_file(path)
            .unwrap_or_else(|e| panic!("{e}"))
            .is_some()
        {
            continue;
        }
        let file = load_scene_file(path).unwrap_or_else(|e| panic!("{e}"));
        let frame = file
            .start
            .unwrap_or_else(|| TraceCamera::default_for(&file.space).frame);
        let name = path
            .file_stem()
            .expect("name")
            .to_string_lossy()
            .to_string();
        failures.extend(compare_scene(
            &mut renderer,
            &file.space_id,
            &file.space,
            &file.scene(),
            frame,
            2.5,
            &name,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The globe of `assets/scenes/torus_globe.toml` with its picture scaled up to 8192×8192
/// texels (256 MiB, past the 128 MiB a storage binding is guaranteed: the GPU reads it from
/// a texture of its own), and with its picture as the scene's tenth texture (past the
/// texture slots: its texels go in the scene data buffer), draws alike on the GPU and the
/// CPU.
#[test]
fn a_globe_texture_of_8192_texels_a_side_and_one_past_the_slots_render_alike() {
    use bevy_curved_spaces::plugin::render::gpu::TEXTURE_SLOTS;
    use bevy_curved_spaces::scene::Object;
    use bevy_curved_spaces::scene::file::load_scene_file;
    use bevy_curved_spaces::scene::texture::{MAX_TEXTURE_SIDE, Texture};
    use std::sync::Arc;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("assets/scenes/torus_globe.toml");
    let file = load_scene_file(&path).unwrap_or_else(|e| panic!("{e}"));
    let scene = file.scene();
    let globe = scene
        .objects
        .iter()
        .find_map(|o| match o {
            Object::Ball(b) => b.texture.map(|t| t.texture as usize),
            _ => None,
        })
        .expect("the scene has a globe");
    let picture = scene.textures[globe].clone();
    // Nearest-texel scaling: the same picture, each texel read from the large texture.
    let side = MAX_TEXTURE_SIDE;
    let texels = (0..side * side)
        .map(|i| {
            let (x, y) = (i % side, i / side);
            let (u, v) = (
                (u64::from(x) * u64::from(picture.width) / u64::from(side)) as u32,
                (u64::from(y) * u64::from(picture.height) / u64::from(side)) as u32,
            );
            picture.texels[(v * picture.width + u) as usize]
        })
        .collect();
    let large = Arc::new(Texture {
        width: side,
        height: side,
        texels,
    });
    assert!(4 * large.texels.len() > 128 << 20, "past a storage binding");
    let retextured = |texture: usize| {
        let mut s = scene.clone();
        for o in &mut s.objects {
            if let Object::Ball(b) = o
                && let Some(t) = &mut b.texture
            {
                t.texture = texture as u32;
            }
        }
        s
    };
    let mut with_large = retextured(globe);
    with_large.textures[globe] = large;
    let mut past_the_slots = retextured(TEXTURE_SLOTS + 1);
    while past_the_slots.textures.len() <= TEXTURE_SLOTS {
        past_the_slots.textures.push(Arc::new(Texture {
            width: 1,
            height: 1,
            texels: vec![0xff00_ff00],
        }));
    }
    past_the_slots.textures.push(picture);
    let frame = file
        .start
        .unwrap_or_else(|| TraceCamera::default_for(&file.space).frame);
    let mut failures = Vec::new();
    for (name, s) in [
        ("globe-8192", &with_large),
        ("globe-past-the-slots", &past_the_slots),
    ] {
        failures.extend(compare_scene(
            &mut renderer,
            &file.space_id,
            &file.space,
            s,
            frame,
            2.5,
            name,
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// A scene the GPU cannot take (scene data past what a GPU is guaranteed to bind) is
/// refused at once with the reason, not after waiting for a picture: a 6000×6000 texture
/// past the texture slots puts 137 MiB of texels in the scene data buffer.
#[test]
fn an_offscreen_render_of_a_scene_too_large_for_the_gpu_says_why() {
    use bevy_curved_spaces::plugin::components::BaseScene;
    use bevy_curved_spaces::plugin::offscreen::OffscreenError;
    use bevy_curved_spaces::plugin::render::gpu::TEXTURE_SLOTS;
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let space = bevy_curved_spaces::space::seed_space("torus").expect("seed");
    let mut scene = CurvedScene::default_for(&space, 1.5);
    while scene.textures.len() < TEXTURE_SLOTS {
        scene.textures.push(std::sync::Arc::new(
            bevy_curved_spaces::scene::texture::Texture {
                width: 1,
                height: 1,
                texels: vec![0],
            },
        ));
    }
    scene.textures.push(std::sync::Arc::new(
        bevy_curved_spaces::scene::texture::Texture {
            width: 6000,
            height: 6000,
            texels: vec![0; 6000 * 6000],
        },
    ));
    let started = std::time::Instant::now();
    let result = renderer.render(&OffscreenRender {
        base: BaseScene {
            space_id: "torus".into(),
            scene: Some(std::sync::Arc::new(scene)),
            start: None,
            parts: None,
            fov: None,
            moving: Vec::new(),
        },
        ..OffscreenRender::new(
            ActiveSpace::new("torus", space.clone()),
            TraceCamera {
                frame: TraceCamera::default_for(&space).frame,
                fov_y_degrees: 70.0,
            },
            (WIDTH, HEIGHT),
            16,
        )
    });
    match result {
        Err(OffscreenError::Scene(why)) => assert!(why.contains("meshes and textures"), "{why}"),
        other => panic!("{:?}", other.map(|i| i.dimensions())),
    }
    assert!(started.elapsed().as_secs() < 30);
}

/// Entities ([`bevy_curved_spaces::plugin::objects`]) as a game spawns them: balls, a tube, a disc and
/// two meshes (shared traced models, so material bases and padded lists are exercised) in
/// Seifert–Weber with its edges (culled lists) and in the torus, one ball straddling a face.
/// The GPU draws them as the CPU reference draws the same objects.
#[test]
fn entities_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::objects::{
        CurvedObject, CurvedTransform, ReadyObject, ReadyShape, add_entity_objects,
    };
    use bevy_curved_spaces::scene::mesh::cube_source;
    use bevy_curved_spaces::scene::{Model, SurfaceMaterial, TracedModel};
    use glam::DVec3;
    use std::sync::Arc;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["seifert-weber", "torus"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = bevy_curved_spaces::space::invariants::inradius(&space);
        let model = |colour: DVec3| {
            Arc::new(
                TracedModel::new(
                    g,
                    &Model {
                        source: cube_source(0.5, 0),
                        materials: vec![SurfaceMaterial {
                            colour,
                            ..SurfaceMaterial::default()
                        }],
                        textures: Vec::new(),
                    },
                    0.2 * r,
                )
                .expect("cube"),
            )
        };
        let (green, blue) = (
            model(DVec3::new(0.2, 0.9, 0.3)),
            model(DVec3::new(0.2, 0.3, 0.9)),
        );
        let at = |x: f64, y: f64, z: f64| {
            CurvedTransform::from_geodesic(&space, DVec3::new(x, y, z) * r).0
        };
        let objects: Vec<(CurvedObject, glam::DMat4)> = vec![
            (
                CurvedObject::ball(0.15 * r, DVec3::new(0.9, 0.3, 0.2)),
                at(0.3, 0.1, -0.6),
            ),
            // Over a face: drawn through its images too.
            (
                CurvedObject::ball(0.3 * r, DVec3::new(0.9, 0.8, 0.2)),
                at(0.0, 0.3, -0.9),
            ),
            (
                CurvedObject::tube(0.6 * r, 0.05 * r, DVec3::new(0.8, 0.2, 0.8)),
                at(-0.4, 0.0, -0.5),
            ),
            // A half mirror: an entity's reflectance reaches both tracers.
            (
                CurvedObject::disc(0.2 * r, DVec3::new(0.3, 0.8, 0.8)).with_reflectance(0.5),
                at(0.0, -0.4, -0.5),
            ),
            (CurvedObject::traced(green.clone()), at(0.4, -0.3, -0.4)),
            (CurvedObject::traced(blue.clone()), at(-0.4, 0.35, -0.45)),
            (CurvedObject::traced(green), at(-0.2, -0.35, -0.7)),
        ];
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let mut scene =
            CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), parts);
        let ready: Vec<ReadyObject> = objects
            .iter()
            .enumerate()
            .map(|(i, (o, frame))| ReadyObject {
                entity: bevy::prelude::Entity::from_raw_u32(i as u32 + 1).unwrap(),
                shape: match &o.shape {
                    bevy_curved_spaces::plugin::objects::CurvedShape::Ball { radius } => {
                        ReadyShape::Ball(*radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Tube { length, radius } => {
                        ReadyShape::Tube(*length, *radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Disc { radius } => {
                        ReadyShape::Disc(*radius)
                    }
                    bevy_curved_spaces::plugin::objects::CurvedShape::Traced(m) => {
                        ReadyShape::Mesh(m.clone())
                    }
                    other => panic!("{other:?}"),
                },
                frame: *frame,
                colour: o.colour,
                emission: o.emission,
                reflectance: o.reflectance,
            })
            .collect();
        let problems = add_entity_objects(&mut scene, &space, &ready);
        assert!(problems.is_empty(), "{id}: {problems:?}");
        assert!(scene.has_mirrors(), "{id}: the mirror disc is drawn as one");
        let camera = TraceCamera::default_for(&space);
        let cpu = render(
            &space,
            &scene,
            &camera,
            &RenderSettings {
                width: WIDTH,
                height: HEIGHT,
                max_crossings: 16,
            },
        );
        let gpu = renderer
            .render(&OffscreenRender {
                parts,
                entities: objects,
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    16,
                )
            })
            .expect("renders");
        let (c, _) = compare(&gpu, &cpu, TOLERANCE);
        println!(
            "{id} with entities: differing {:.3} %, mean error {:.3}/255",
            100.0 * c.differing,
            c.mean_error
        );
        let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
        let _ = std::fs::create_dir_all(&out);
        let _ = gpu.save(out.join(format!("entities-{id}-gpu.png")));
        let _ = cpu.save(out.join(format!("entities-{id}-cpu.png")));
        assert!(
            c.differing <= MAX_DIFFERING,
            "{id}: {:.3} % differ",
            100.0 * c.differing
        );
    }
}

/// The teaching views (`--colour-by crossings|face|holonomy`) on the GPU as on the CPU
/// reference, in a space of each geometry (a flat one with rotations, a spherical one and
/// the twisted hyperbolic Seifert–Weber space), and each differs from the plain picture.
#[test]
fn colour_by_views_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::scene::ColourBy;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["quarter-turn", "poincare", "seifert-weber"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let camera = TraceCamera::default_for(&space);
        let plain_scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 12,
        };
        let plain = render(&space, &plain_scene, &camera, &settings);
        for by in [ColourBy::Crossings, ColourBy::Face, ColourBy::Holonomy] {
            let mut scene = plain_scene.clone();
            scene.shading.colour_by = by;
            let cpu = render(&space, &scene, &camera, &settings);
            let gpu = renderer
                .render(&OffscreenRender {
                    colour_by: by,
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        12,
                    )
                })
                .expect("renders");
            let (c, _) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id} coloured by {}: differing {:.3} %, mean error {:.3}/255",
                by.name(),
                100.0 * c.differing,
                c.mean_error
            );
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            let _ = std::fs::create_dir_all(&out);
            let _ = gpu.save(out.join(format!("colour-by-{}-{id}-gpu.png", by.name())));
            let _ = cpu.save(out.join(format!("colour-by-{}-{id}-cpu.png", by.name())));
            assert!(
                c.differing <= MAX_DIFFERING,
                "{id} by {}: {:.3} % differ",
                by.name(),
                100.0 * c.differing
            );
            let (d, _) = compare(&cpu, &plain, TOLERANCE);
            assert!(
                d.differing > 0.05,
                "{id} by {}: like the plain picture",
                by.name()
            );
        }
    }
}

/// The default scene with `parts` in `space`, GPU against CPU (12 crossings): the
/// fraction of pixels differing.
fn parts_render_alike(
    renderer: &mut OffscreenRenderer,
    id: &str,
    space: &Space,
    parts: SceneParts,
) -> f64 {
    let scene = CurvedScene::with_parts(space, Shading::default_fog_distance(space), parts);
    let camera = TraceCamera::default_for(space);
    let cpu = render(
        space,
        &scene,
        &camera,
        &RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 12,
        },
    );
    let gpu = renderer
        .render(&OffscreenRender {
            parts,
            ..OffscreenRender::new(
                ActiveSpace::new(id, space.clone()),
                camera,
                (WIDTH, HEIGHT),
                12,
            )
        })
        .expect("renders");
    compare(&gpu, &cpu, TOLERANCE).0.differing
}

/// Clifford parallels (spherical spaces; absent elsewhere) and the gyroscope on the GPU as
/// on the CPU.
#[test]
fn clifford_parallels_and_the_gyroscope_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let clifford = SceneParts {
        clifford: true,
        ..SceneParts::default()
    };
    let gyroscope = SceneParts {
        centrepiece: Centrepiece::Gyroscope,
        ..SceneParts::default()
    };
    for (id, parts) in [
        ("poincare", clifford),
        ("lens-7-1", clifford),
        ("seifert-weber", gyroscope),
        ("mirrored-cube", gyroscope),
    ] {
        let space = bevy_curved_spaces::space::resolve_space(
            id,
            std::path::Path::new(""),
            &Default::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let plain = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let with = CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), parts);
        assert!(
            with.objects.len() >= plain.objects.len() + 6,
            "{id}: the parts are there"
        );
        let differing = parts_render_alike(&mut renderer, id, &space, parts);
        println!("{id} with {parts:?}: differing {:.3} %", 100.0 * differing);
        assert!(
            differing <= MAX_DIFFERING,
            "{id}: {:.3} % differ",
            100.0 * differing
        );
    }
    let torus = bevy_curved_spaces::space::seed_space("torus").unwrap();
    assert!(bevy_curved_spaces::scene::clifford_parallels(&torus).is_empty());
}

/// The walls with windows, closed and half open, on the GPU as on the CPU reference, in a
/// space of each geometry and one with mirrors; each differs from the plain picture.
#[test]
fn walls_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::scene::WallStyle;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["half-turn", "poincare", "seifert-weber", "mirrored-cube"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let camera = TraceCamera::default_for(&space);
        let plain_scene = CurvedScene::with_parts(
            &space,
            Shading::default_fog_distance(&space),
            SceneParts::default(),
        );
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 12,
        };
        let plain = render(&space, &plain_scene, &camera, &settings);
        for opening in [0.0, 0.5] {
            let walls = WallStyle::new(opening).expect("in range");
            let mut scene = plain_scene.clone();
            scene.shading.walls = Some(walls);
            let cpu = render(&space, &scene, &camera, &settings);
            let gpu = renderer
                .render(&OffscreenRender {
                    walls: Some(walls),
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        12,
                    )
                })
                .expect("renders");
            let (c, _) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id} with walls {opening} open: differing {:.3} %, mean error {:.3}/255",
                100.0 * c.differing,
                c.mean_error
            );
            let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
            let _ = std::fs::create_dir_all(&out);
            let _ = gpu.save(out.join(format!("walls-{opening}-{id}-gpu.png")));
            let _ = cpu.save(out.join(format!("walls-{opening}-{id}-cpu.png")));
            assert!(
                c.differing <= MAX_DIFFERING,
                "{id} walls {opening}: {:.3} % differ",
                100.0 * c.differing
            );
            let (d, _) = compare(&cpu, &plain, TOLERANCE);
            assert!(
                d.differing > 0.3,
                "{id} walls {opening}: like the plain picture"
            );
        }
    }
}

/// Glued faces share a colour, read off the GPU's picture: with solid, opaque walls, no
/// objects and black fog, each pixel shows the wall of the first face its ray leaves by
/// (known from the CPU walker), in that panel's colour times its light. Pixels of a face and
/// of its partner have the same hue; pixels of different pairs do not; mirrors are silver.
#[test]
fn walls_of_glued_faces_share_a_colour_in_the_picture() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::components::BaseScene;
    use bevy_curved_spaces::scene::walls::MIRROR_COLOUR;
    use bevy_curved_spaces::scene::{WallPanels, WallStyle};
    use bevy_curved_spaces::space::CellWalker;
    use bevy_curved_spaces::view::PixelRays;
    use glam::{DVec3, DVec4};
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let nothing = SceneParts {
        edges: false,
        centrepiece: Centrepiece::None,
        avatar: false,
        clifford: false,
    };
    let walls = WallStyle::with_opacity(0.0, 1.0).expect("in range");
    for id in ["seifert-weber", "quarter-turn", "poincare", "mirrored-cube"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let mut base =
            CurvedScene::with_parts(&space, Shading::default_fog_distance(&space), nothing);
        base.shading.fog_colour = DVec3::ZERO;
        let camera = TraceCamera::default_for(&space);
        let gpu = renderer
            .render(&OffscreenRender {
                walls: Some(walls),
                parts: nothing,
                base: BaseScene {
                    space_id: id.into(),
                    scene: Some(std::sync::Arc::new(base.clone())),
                    parts: Some(nothing),
                    ..Default::default()
                },
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    12,
                )
            })
            .expect("renders");
        let panels = WallPanels::new(&space, walls, &base.shading).expect("walls");
        let walker = CellWalker::<DVec4>::new(&space);
        let layout = camera.layout(WIDTH, HEIGHT);
        let g = space.geometry();
        // Per face: the sum of its pixels' unit colours, and how many.
        let mut hues = vec![(DVec3::ZERO, 0usize); space.faces().len()];
        for j in 0..HEIGHT {
            for i in 0..WIDTH {
                let PixelRays::One(ray) = layout.rays_at(g, i, j) else {
                    unreachable!("a mono view")
                };
                let ray = walker.normalized(ray);
                let face = walker.exit(&ray, None).expect("a face ahead").face;
                let p = gpu.get_pixel(i, j).0.map(f64::from);
                let rgb = DVec3::new(p[0], p[1], p[2]);
                // Dark pixels (far walls, faint in the fog) carry little hue.
                if rgb.max_element() < 60.0 {
                    continue;
                }
                let hue = rgb.normalize();
                let expected = panels.faces[face].colour.normalize();
                assert!(
                    hue.distance(expected) < 0.08,
                    "{id} pixel ({i}, {j}) over face {face}: hue {hue} against the panel's {expected}"
                );
                hues[face].0 += hue;
                hues[face].1 += 1;
            }
        }
        let seen: Vec<(usize, DVec3)> = hues
            .iter()
            .enumerate()
            .filter(|(_, (_, n))| *n > 0)
            .map(|(f, (sum, n))| (f, *sum / *n as f64))
            .collect();
        assert!(seen.len() >= 2, "{id}: walls of several faces in view");
        for &(f, a) in &seen {
            for &(h, b) in &seen {
                let glued = space.faces()[f].partner == h || f == h;
                let same_hue = a.distance(b) < 0.08;
                if glued {
                    assert!(
                        same_hue,
                        "{id}: faces {f} and {h} are glued, hues {a} and {b}"
                    );
                } else if !(space.faces()[f].is_mirror(f) && space.faces()[h].is_mirror(h)) {
                    assert!(
                        !same_hue,
                        "{id}: faces {f} and {h} are not glued, hues {a} and {b}"
                    );
                }
            }
            if space.faces()[f].is_mirror(f) {
                assert!(
                    a.distance(MIRROR_COLOUR.normalize()) < 0.05,
                    "{id}: mirror {f} is silver"
                );
            }
        }
        println!("{id}: walls of {} faces seen, glued ones alike", seen.len());
    }
}

/// The globe and the galaxy centrepieces on the GPU as on the CPU reference, in a space of
/// each geometry.
#[test]
fn the_globe_and_the_galaxy_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    for id in ["quarter-turn", "poincare", "seifert-weber"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        for centrepiece in [Centrepiece::Globe, Centrepiece::Galaxy] {
            let parts = SceneParts {
                centrepiece,
                ..SceneParts::default()
            };
            let differing = parts_render_alike(&mut renderer, id, &space, parts);
            println!(
                "{id} with the {}: differing {:.3} %",
                centrepiece.name(),
                100.0 * differing
            );
            assert!(
                differing <= MAX_DIFFERING,
                "{id} {}: {:.3} % differ",
                centrepiece.name(),
                100.0 * differing
            );
        }
    }
}

/// The product spaces (H²×R, S²×R) on the GPU's `PRODUCT` variant against the f64 CPU
/// reference, default scene and view, 96×54 (the CPU reference's bracketed search is
/// slower than the constant-curvature tracer's closed forms).
/// The hard case of the product spaces' object search: rays that graze a ball, a fibre's
/// tube and a horizontal geodesic's tube, seen at their limbs through a narrow field of view
/// so that most pixels of the picture are nearly tangent. The GPU's searches (Newton's steps
/// in H²×R, a golden section and a bisection on S²) must find the same silhouettes as the
/// f64 reference: only the pixels the limb passes through may differ.
#[test]
fn grazing_rays_meet_product_objects_on_the_gpu_where_the_cpu_reference_does() {
    use bevy_curved_spaces::trace::product::{
        ProductCamera, ProductObject, ProductShape, default_scene, render_product,
    };
    use glam::{DVec3, DVec4};
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let (w, h) = (96, 54);
    // Two crossings: the object in the cell and its nearest copies, the rest fog (far copies
    // a pixel wide differ between f32 and f64 by aliasing, not by the search).
    const BUDGET: usize = 2;
    let mut failures = Vec::new();
    for id in ["bitorus-circle", "sphere-circle-turn"] {
        let space = crate::common::product(id);
        let g = space.base();
        // A point at surface distance d from the centre in direction θ, at height z.
        let at = |d: f64, theta: f64, z: f64| {
            let (c, s) = g.cs(d);
            DVec4::new(s * theta.cos(), s * theta.sin(), z, c)
        };
        let size = (0.25 * space.length()).min(0.3);
        let eye = at(1.1, 0.0, 0.1 * size);
        let views = [
            (
                "ball",
                ProductShape::Point(DVec4::W),
                size,
                at(size, 0.5 * std::f64::consts::PI, 0.05 * size),
            ),
            (
                "fibre",
                ProductShape::Fibre(DVec4::W),
                0.7 * size,
                at(0.7 * size, 0.5 * std::f64::consts::PI, 0.3 * size),
            ),
            (
                "geodesic",
                ProductShape::Geodesic {
                    covector: DVec4::X,
                    height: -0.5 * size,
                },
                0.5 * size,
                at(0.2, 0.5 * std::f64::consts::PI, 0.0),
            ),
        ];
        for (name, shape, radius, target) in views {
            let mut scene = default_scene(&space);
            scene.objects = vec![ProductObject {
                shape,
                radius,
                colour: DVec3::new(0.9, 0.6, 0.3),
            }];
            let camera = ProductCamera::looking_at(g, eye, target, 4.0);
            let cpu = render_product(&space, &scene, &camera, w, h, BUDGET);
            let gpu = renderer
                .render_product(&space, &scene, &camera, (w, h), BUDGET as u32)
                .unwrap_or_else(|e| panic!("{id} {name}: {e}"));
            // What the view shows without the object: the pixels alike are its misses.
            let mut empty = scene.clone();
            empty.objects.clear();
            let background = render_product(&space, &empty, &camera, w, h, BUDGET);
            let (hit, missed) =
                cpu.pixels()
                    .zip(background.pixels())
                    .fold((0, 0), |(a, b), (p, q)| {
                        if p.0.iter().zip(q.0).all(|(x, y)| x.abs_diff(y) <= 2) {
                            (a, b + 1)
                        } else {
                            (a + 1, b)
                        }
                    });
            // The limb crosses the picture: both sides of it are in view.
            assert!(
                hit > 200 && missed > 200,
                "{id} {name}: the view shows {hit} pixels of the object and {missed} of fog"
            );
            let (c, diff) = compare(&gpu, &cpu, TOLERANCE);
            println!(
                "{id:<20} {name:<8} object {hit} px, fog {missed} px, differing {} px",
                c.differing_pixels
            );
            // At most an eighth of the pixels along the limb: a search that misses grazing
            // rays, or stops short of the root, moves the whole silhouette.
            if c.differing_pixels > w.max(h) as usize / 8 {
                std::fs::create_dir_all(&out).expect("create output folder");
                for (kind, img) in [("gpu", &gpu), ("cpu", &cpu), ("diff", &diff)] {
                    img.save(out.join(format!("{id}-grazing-{name}-{kind}.png")))
                        .expect("write image");
                }
                failures.push(format!(
                    "{id} {name}: {} pixels differ by more than {TOLERANCE}/255",
                    c.differing_pixels
                ));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree at the limbs (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

#[test]
fn product_spaces_render_on_the_gpu_like_the_cpu_reference() {
    use bevy_curved_spaces::trace::product::{
        ProductObject, ProductShape, default_camera, default_scene, render_product,
    };
    let _gpu = gpu_lock();
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let (w, h) = (96, 54);
    let mut failures = Vec::new();
    for id in [
        "bitorus-circle",
        "projective-plane-circle",
        "sphere-circle-turn",
        "crosscaps-circle",
    ] {
        let space = crate::common::product(id);
        let scene = default_scene(&space);
        let camera = default_camera(&space);
        let plain = render_product(&space, &scene, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &scene, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id}: {e}"));
        judge(id, &gpu, &plain, &out, &mut failures);
        // Horizontal discs: a floor below the view and a smaller one above, met where the
        // ray's height reaches their slice (and through the faces, in the next cells).
        let mut floors = scene.clone();
        let r = space.base_inradius().min(1.2);
        for (height, radius, colour) in [
            (-0.3, 0.8 * r, [0.3, 0.8, 0.4]),
            (0.45, 0.4 * r, [0.9, 0.3, 0.3]),
        ] {
            floors.objects.push(ProductObject {
                shape: ProductShape::Disc(glam::DVec4::new(0.0, 0.0, height * space.length(), 1.0)),
                radius,
                colour: glam::DVec3::from_array(colour),
            });
        }
        let cpu = render_product(&space, &floors, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &floors, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id} with discs: {e}"));
        let shown = cpu
            .pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| p != q)
            .count();
        assert!(shown > 20, "{id}: the discs change {shown} pixels");
        judge(&format!("{id}-discs"), &gpu, &cpu, &out, &mut failures);
        // Every image shadowed by the discs and the ball, walked through the faces; and the
        // older model, the lamp in the cell only.
        for (name, lighting) in [
            (
                "shadows",
                bevy_curved_spaces::scene::lighting::Lighting {
                    shadows: 8,
                    ..Default::default()
                },
            ),
            (
                "nearest",
                bevy_curved_spaces::scene::lighting::Lighting::NEAREST,
            ),
        ] {
            let mut lit = floors.clone();
            lit.set_lighting(&space, floors.light, lighting)
                .unwrap_or_else(|e| panic!("{e}"));
            let cpu_lit = render_product(&space, &lit, &camera, w, h, 24);
            let gpu = renderer
                .render_product(&space, &lit, &camera, (w, h), 24)
                .unwrap_or_else(|e| panic!("{id} with {name}: {e}"));
            let changed = cpu_lit
                .pixels()
                .zip(cpu.pixels())
                .filter(|(p, q)| p != q)
                .count();
            assert!(changed > 20, "{id}: {name} changes {changed} pixels");
            judge(&format!("{id}-{name}"), &gpu, &cpu_lit, &out, &mut failures);
        }
        // Walls with windows half open: panels met where the ray crosses a face.
        let mut walled = scene.clone();
        walled.walls = Some(bevy_curved_spaces::scene::WallStyle::new(0.5).expect("style"));
        let cpu = render_product(&space, &walled, &camera, w, h, 24);
        let gpu = renderer
            .render_product(&space, &walled, &camera, (w, h), 24)
            .unwrap_or_else(|e| panic!("{id} with walls: {e}"));
        let shown = cpu
            .pixels()
            .zip(plain.pixels())
            .filter(|(p, q)| p != q)
            .count();
        assert!(shown > 200, "{id}: the walls change {shown} pixels");
        judge(&format!("{id}-walls"), &gpu, &cpu, &out, &mut failures);
    }
    // The renderer goes back to constant curvature afterwards.
    let space = bevy_curved_spaces::space::seed_space("torus").expect("seed");
    let back = renderer.render(&OffscreenRender::new(
        ActiveSpace::new("torus", space.clone()),
        TraceCamera::default_for(&space),
        (32, 18),
        8,
    ));
    assert!(back.is_ok(), "after a product render: {back:?}");
    assert!(
        failures.is_empty(),
        "GPU and CPU disagree (images in {}):\n{}",
        out.display(),
        failures.join("\n")
    );
}

/// Shadows walked through the faces: a ball between the lamp and the centre ball shadows it
/// (and its images shadow the lamp's other images), on the GPU as on the CPU, in the three
/// geometries; the shadows are there to see (turned off, the picture changes). A lamp with a
/// radius casts soft ones (a few shadow rays over its disc), alike on both and unlike the
/// hard ones.
#[test]
fn shadows_through_the_faces_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::lighting::Lighting;
    use bevy_curved_spaces::scene::{Ball, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = inradius(&space);
        // On the way from the default lamp to the centre.
        let towards_lamp = DVec3::new(0.45, 0.8, 0.4);
        let centre = g.translation(towards_lamp, 0.4 * r) * space.centre();
        let ball = Object::Ball(Ball::new(g, centre, 0.12 * r, DVec3::new(0.9, 0.6, 0.3)));
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::Ball,
            avatar: false,
            clifford: false,
        };
        let hard = Lighting {
            shadows: 8,
            ..Lighting::default()
        };
        let soft = Lighting {
            lamp_radius_inradii: 0.4,
            soft_samples: 4,
            ..hard
        };
        let picture = |lighting: Lighting, gpu: bool, renderer: &mut OffscreenRenderer| {
            let camera = TraceCamera::default_for(&space);
            if gpu {
                let request = OffscreenRender {
                    parts,
                    objects: vec![ball],
                    lighting: Some(lighting),
                    ..OffscreenRender::new(
                        ActiveSpace::new(id, space.clone()),
                        camera,
                        (WIDTH, HEIGHT),
                        24,
                    )
                };
                return renderer.render(&request).expect("renders");
            }
            let settings = still(parts, Some(lighting));
            let (scene, problems) = build_scene(&space, &settings, &[ball], None);
            assert_eq!(problems, None, "{id}");
            assert_eq!(scene.shading.lighting, lighting);
            render(
                &space,
                &scene,
                &camera,
                &RenderSettings {
                    width: WIDTH,
                    height: HEIGHT,
                    max_crossings: 24,
                },
            )
        };
        let shadowed = picture(hard, false, &mut renderer);
        let none = Lighting { shadows: 0, ..hard };
        let unshadowed = picture(none, false, &mut renderer);
        changes(
            &format!("{id}: the shadows"),
            (&shadowed, &unshadowed),
            0.005,
            &mut failures,
        );
        let gpu = picture(hard, true, &mut renderer);
        judge(
            &format!("{id}-shadows"),
            &gpu,
            &shadowed,
            &out,
            &mut failures,
        );
        let softened = picture(soft, false, &mut renderer);
        changes(
            &format!("{id}: a lamp of 0.4 inradii's soft shadows"),
            (&softened, &shadowed),
            0.002,
            &mut failures,
        );
        let gpu = picture(soft, true, &mut renderer);
        judge(
            &format!("{id}-soft-shadows"),
            &gpu,
            &softened,
            &out,
            &mut failures,
        );
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Mirrors: a mirror ball at the centre reflects the tiling (and a half mirror a mix), a
/// mirror disc beside it, on the GPU as on the CPU in the three geometries.
#[test]
fn mirrors_render_alike_on_gpu_and_cpu() {
    let _gpu = gpu_lock();
    use bevy_curved_spaces::plugin::render::upload::build_scene;
    use bevy_curved_spaces::scene::{Ball, Disc, Object};
    use bevy_curved_spaces::space::invariants::inradius;
    use glam::DVec3;
    let mut renderer = OffscreenRenderer::new().unwrap_or_else(|e| panic!("{e}"));
    let out = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("gpu-vs-cpu");
    let mut failures = Vec::new();
    for id in ["torus", "seifert-weber", "poincare"] {
        let space = bevy_curved_spaces::space::seed_space(id).expect("builds");
        let g = space.geometry();
        let r = inradius(&space);
        let centre = space.centre();
        let mirror = Object::Ball(
            Ball::new(g, centre, 0.45 * r, DVec3::new(0.9, 0.9, 1.0)).with_reflectance(0.85),
        );
        let at = g.translation(DVec3::new(-0.6, -0.5, 0.3), 0.6 * r) * centre;
        let normal = g.unit_tangent(at, g.translation(DVec3::Y, 0.1) * at - at);
        let disc = Object::Disc(
            Disc::new(g, at, normal, 0.25 * r, DVec3::new(0.3, 0.8, 0.5)).with_reflectance(0.5),
        );
        let objects = vec![mirror, disc];
        let parts = SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        };
        let camera = TraceCamera::default_for(&space);
        let (scene, problems) = build_scene(&space, &still(parts, None), &objects, None);
        assert_eq!(problems, None, "{id}");
        assert!(scene.has_mirrors());
        let settings = RenderSettings {
            width: WIDTH,
            height: HEIGHT,
            max_crossings: 24,
        };
        let cpu = render(&space, &scene, &camera, &settings);
        // The same scene with plain surfaces: the mirrors change the picture.
        let (plain, _) = build_scene(
            &space,
            &still(parts, None),
            &objects
                .iter()
                .map(|o| match o {
                    Object::Ball(b) => Object::Ball(b.with_reflectance(0.0)),
                    Object::Disc(d) => Object::Disc(d.with_reflectance(0.0)),
                    o => *o,
                })
                .collect::<Vec<_>>(),
            None,
        );
        let (changed, _) = compare(&render(&space, &plain, &camera, &settings), &cpu, TOLERANCE);
        println!(
            "{id}: the mirrors change {:.2} % of the pixels",
            100.0 * changed.differing
        );
        if changed.differing < 0.05 {
            failures.push(format!("{id}: the mirrors change too little"));
        }
        let gpu = renderer
            .render(&OffscreenRender {
                parts,
                objects: objects.clone(),
                ..OffscreenRender::new(
                    ActiveSpace::new(id, space.clone()),
                    camera,
                    (WIDTH, HEIGHT),
                    24,
                )
            })
            .expect("renders");
        judge(&format!("{id}-mirrors"), &gpu, &cpu, &out, &mut failures);
        if id == "seifert-weber" {
            let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
            gpu.save(dir.join("mirrors-gpu.png")).expect("write");
            cpu.save(dir.join("mirrors-cpu.png")).expect("write");
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The settings of a still picture that a CPU reference can match: every pixel traced, 24
/// crossings, the clock at 0, these parts and this lighting.
fn still(
    parts: SceneParts,
    lighting: Option<bevy_curved_spaces::scene::lighting::Lighting>,
) -> bevy_curved_spaces::plugin::components::TracerSettings {
    bevy_curved_spaces::plugin::components::TracerSettings {
        fog_distance: None,
        max_crossings: Some(24),
        quality: bevy_curved_spaces::plugin::components::Quality::High,
        resolution_scale: 1.0,
        parts,
        time: Some(0.0),
        colour_by: Default::default(),
        walls: None,
        lighting,
    }
}
