//! Put your own objects in a curved space: a ball placed over a vertex of the cell is drawn
//! whole, through its images under the face pairings (`Scene::place`), in a picture rendered
//! by the GPU tracer without a window.
//!
//! ```text
//! cargo run --release --example place_objects -- seifert-weber
//! ```
//!
//! Writes `place-objects.png` to the working directory. In an app, put the objects in the
//! `SceneObjects` resource instead; the plugin places them the same way.

use bevy_curved_spaces::ActiveSpace;
use bevy_curved_spaces::render::offscreen::{OffscreenRender, render_offscreen};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::seed_space;
use bevy_curved_spaces::trace::{Ball, Camera, Object, SceneParts};
use glam::DVec3;
use std::process::ExitCode;

fn main() -> ExitCode {
    let id = std::env::args().nth(1).unwrap_or_else(|| "torus".into());
    let space = match seed_space(&id) {
        Ok(space) => space,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let g = space.geometry;
    // A ball a little inside the cell from vertex 0, big enough to stick out through the
    // faces that meet there: its images complete it in every copy of the cell.
    let r = inradius(&space);
    let vertex = space.vertices[0];
    let centre = match g.from_chart(vertex * 0.9) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let ball = Object::Ball(Ball::new(g, centre, 0.45 * r, DVec3::new(0.35, 0.85, 0.55)));
    let camera = Camera::default_for(&space);
    let picture = render_offscreen(&OffscreenRender {
        space: ActiveSpace::new(&id, space.clone()),
        width: 640,
        height: 360,
        frame: camera.frame,
        fov_y_degrees: camera.fov_y_degrees,
        fog_distance: None,
        max_crossings: 32,
        parts: SceneParts {
            edges: true,
            centre_ball: false,
            avatar: false,
        },
        objects: vec![ball],
        resolution_scale: 1.0,
        base: Default::default(),
        time: 0.0,
        stereo: Default::default(),
    });
    match picture.map(|image| image.save("place-objects.png")) {
        Ok(Ok(())) => {
            println!("wrote place-objects.png");
            ExitCode::SUCCESS
        }
        Ok(Err(e)) => {
            eprintln!("error: cannot write place-objects.png: {e}");
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
