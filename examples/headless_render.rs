//! Render a picture through the GPU tracer without a window, and the same picture with the
//! f64 CPU reference, then report how far they differ.
//!
//! ```text
//! cargo run --release --example headless_render -- poincare
//! ```
//!
//! Writes `headless-gpu.png` and `headless-cpu.png` to the working directory. Without a GPU
//! it runs on Mesa's lavapipe (`apt-get install mesa-vulkan-drivers libvulkan1`).

use bevy_curved_spaces::plugin::components::ActiveSpace;
use bevy_curved_spaces::plugin::offscreen::{OffscreenRender, render_offscreen};
use bevy_curved_spaces::scene::{CurvedScene, Shading};
use bevy_curved_spaces::space::seed_space;
use bevy_curved_spaces::trace::{RenderSettings, render};
use bevy_curved_spaces::view::TraceCamera;
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
    let camera = TraceCamera::default_for(&space);
    let gpu = match render_offscreen(&OffscreenRender {
        fog_distance: Some(fog),
        ..OffscreenRender::new(
            ActiveSpace::new(&id, space.clone()),
            camera,
            (width, height),
            crossings,
        )
    }) {
        Ok(image) => image,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let scene = CurvedScene::default_for(&space, fog);
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
