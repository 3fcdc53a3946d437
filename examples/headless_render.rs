//! Render a picture through the GPU tracer without a window, and the same picture with the
//! f64 CPU reference, then report how far they differ.
//!
//! ```text
//! cargo run --release --example headless_render -- poincare
//! ```
//!
//! Writes `headless-gpu.png` and `headless-cpu.png` to the working directory. Without a GPU
//! it runs on Mesa's lavapipe (`apt-get install mesa-vulkan-drivers libvulkan1`).

use bevy_curved_spaces::ActiveSpace;
use bevy_curved_spaces::render::offscreen::{OffscreenRender, render_offscreen};
use bevy_curved_spaces::space::seed_space;
use bevy_curved_spaces::trace::{Camera, RenderSettings, Scene, SceneParts, Shading, render};
use std::process::ExitCode;

fn main() -> ExitCode {
    let id = std::env::args().nth(1).unwrap_or_else(|| "poincare".into());
    let space = match seed_space(&id) {
        Ok(space) => space,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let (width, height, crossings) = (320, 180, 24);
    let fog = Shading::default_fog_distance(&space);
    let camera = Camera::default_for(&space);
    let gpu = match render_offscreen(&OffscreenRender {
        space: ActiveSpace::new(&id, space.clone()),
        width,
        height,
        frame: camera.frame,
        fov_y_degrees: camera.fov_y_degrees,
        fog_distance: Some(fog),
        max_crossings: crossings,
        parts: SceneParts::default(),
        objects: Vec::new(),
        resolution_scale: 1.0,
        base: Default::default(),
        time: 0.0,
        stereo: Default::default(),
    }) {
        Ok(image) => image,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let scene = Scene::default_for(&space, fog);
    let cpu = render(
        &space,
        &scene,
        &camera,
        &RenderSettings {
            width,
            height,
            max_crossings: crossings as usize,
        },
    );
    let worst: Vec<u8> = gpu
        .pixels()
        .zip(cpu.pixels())
        .map(|(g, c)| (0..3).map(|k| g.0[k].abs_diff(c.0[k])).max().unwrap_or(0))
        .collect();
    let differing = worst.iter().filter(|&&e| e > 10).count();
    for (name, img) in [("headless-gpu.png", &gpu), ("headless-cpu.png", &cpu)] {
        if let Err(e) = img.save(name) {
            eprintln!("error: cannot write {name}: {e}");
            return ExitCode::FAILURE;
        }
    }
    println!(
        "{id}: wrote headless-gpu.png and headless-cpu.png ({width}×{height}); {:.2} % of pixels differ by more than 10/255",
        100.0 * differing as f64 / worst.len() as f64
    );
    ExitCode::SUCCESS
}
