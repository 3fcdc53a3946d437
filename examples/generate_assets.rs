//! Writes the project's generated assets: `cargo run --example generate_assets`.
//!
//! - `assets/textures/globe.png`: an invented planet, equirectangular, 1024×512;
//! - `assets/models/cube.glb`: a cube of half-size 1 with a crate texture (12 triangles);
//! - `assets/models/torus_knot.glb`: a smooth (3, 2) torus knot (4 608 triangles).
//!
//! They are made here from code, so they carry the project's licence (MIT OR Apache-2.0).

use bevy_curved_spaces::scene::assets::{
    crate_texture, globe_texture, png_bytes, torus_knot, write_source_glb,
};
use bevy_curved_spaces::scene::mesh::cube_source;
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    std::fs::create_dir_all(root.join("textures"))?;
    std::fs::create_dir_all(root.join("models"))?;
    let globe = root.join("textures/globe.png");
    globe_texture(1024, 512).save(&globe)?;
    println!("wrote {}", globe.display());
    let cube = root.join("models/cube.glb");
    let crate_png = png_bytes(&crate_texture(128));
    write_source_glb(&cube, &cube_source(1.0, 0), [1.0; 4], Some(&crate_png))?;
    println!("wrote {}", cube.display());
    let knot = root.join("models/torus_knot.glb");
    write_source_glb(
        &knot,
        &torus_knot(3, 2, 192, 12),
        [0.9, 0.55, 0.2, 1.0],
        None,
    )?;
    println!("wrote {}", knot.display());
    Ok(())
}
