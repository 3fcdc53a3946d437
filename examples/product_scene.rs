//! A scene of your own in a product space (H²×R or S²×R), built in code: the default
//! scene's edges and ball, a floor (a horizontal disc) under them and a red disc above,
//! rendered through the GPU tracer without a window and with the f64 CPU reference.
//!
//! ```text
//! cargo run --release --example product_scene -- bitorus-circle
//! ```
//!
//! Writes `product-gpu.png` and `product-cpu.png` to the working directory. In a game, put
//! the same scene in a `BaseProductScene` resource beside `CurvedSpacesPlugin { space:
//! "bitorus-circle".into(), .. }`.

use bevy_curved_spaces::plugin::offscreen::OffscreenRenderer;
use bevy_curved_spaces::space::product::{ProductOrFlat, product_space};
use bevy_curved_spaces::trace::product::{
    ProductObject, ProductShape, default_camera, default_scene, render_product,
};
use glam::{DVec3, DVec4};
use std::process::ExitCode;

fn main() -> ExitCode {
    let id = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "bitorus-circle".into());
    let space = match product_space(&id) {
        Some(Ok(ProductOrFlat::Product(space))) => *space,
        Some(Ok(ProductOrFlat::Flat(_))) => {
            eprintln!("error: {id} is a flat space; try bitorus-circle or sphere-circle-turn");
            return ExitCode::FAILURE;
        }
        Some(Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
        None => {
            eprintln!("error: {id} is not a product space (see `curved-spaces list`)");
            return ExitCode::FAILURE;
        }
    };
    let mut scene = default_scene(&space);
    let size = space.base_inradius().min(1.2);
    let l = space.length();
    // Discs are centred on a surface point (x, y, w) at the slice's height z.
    scene.objects.push(ProductObject {
        shape: ProductShape::Disc(DVec4::new(0.0, 0.0, -0.3 * l, 1.0)),
        radius: 0.8 * size,
        colour: DVec3::new(0.3, 0.8, 0.4),
    });
    scene.objects.push(ProductObject {
        shape: ProductShape::Disc(DVec4::new(0.0, 0.0, 0.45 * l, 1.0)),
        radius: 0.4 * size,
        colour: DVec3::new(0.9, 0.3, 0.3),
    });
    let camera = default_camera(&space);
    let (width, height, crossings) = (320, 180, 24);
    let gpu = match OffscreenRenderer::new()
        .and_then(|mut r| r.render_product(&space, &scene, &camera, (width, height), crossings))
    {
        Ok(image) => image,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let cpu = render_product(&space, &scene, &camera, width, height, crossings as usize);
    let differing = gpu
        .pixels()
        .zip(cpu.pixels())
        .filter(|(g, c)| (0..3).any(|k| g.0[k].abs_diff(c.0[k]) > 10))
        .count();
    for (image, path) in [(&gpu, "product-gpu.png"), (&cpu, "product-cpu.png")] {
        if let Err(e) = image.save(path) {
            eprintln!("error: cannot write {path}: {e}");
            return ExitCode::FAILURE;
        }
    }
    println!(
        "{} ({}): wrote product-gpu.png and product-cpu.png ({width}×{height}); {:.2} % of pixels differ by more than 10/255",
        space.name(),
        space.geometry_name(),
        100.0 * differing as f64 / f64::from(width * height)
    );
    ExitCode::SUCCESS
}
