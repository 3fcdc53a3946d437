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

mod laws;
mod light;
mod nil;
mod scenes;
mod sl2r;
mod spaces;
mod stereo;
mod views;

const WIDTH: u32 = 160;

const HEIGHT: u32 = 90;

/// A pixel "differs" when a channel is off by more than this (of 255).
const TOLERANCE: u8 = 10;

/// At most this fraction of the pixels may differ.
const MAX_DIFFERING: f64 = 0.01;

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
