//! Put your own objects in a curved space: a ball placed over a vertex of the cell is drawn
//! whole, through its images under the face pairings (`CurvedScene::place`), in a picture rendered
//! by the GPU tracer without a window.
//!
//! ```text
//! cargo run --release --example place_objects -- seifert-weber
//! ```
//!
//! Writes `place-objects.png` to the working directory. In an app, put the objects in the
//! `SceneObjects` resource instead; the plugin places them the same way.

use bevy_curved_spaces::plugin::components::ActiveSpace;
use bevy_curved_spaces::plugin::offscreen::{OffscreenRender, render_offscreen};
use bevy_curved_spaces::scene::Centrepiece;
use bevy_curved_spaces::scene::{Ball, Object, SceneParts};
use bevy_curved_spaces::space::invariants::inradius;
use bevy_curved_spaces::space::seed_space;
use bevy_curved_spaces::view::TraceCamera;
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
    let g = space.geometry();
    // A ball a little inside the cell from vertex 0, big enough to stick out through the
    // faces that meet there: its images complete it in every copy of the cell.
    let r = inradius(&space);
    let vertex = space.vertices()[0];
    let centre = match g.from_chart(vertex * 0.9) {
        Ok(p) => p,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let ball = Object::Ball(Ball::new(g, centre, 0.45 * r, DVec3::new(0.35, 0.85, 0.55)));
    let camera = TraceCamera::default_for(&space);
    let picture = render_offscreen(&OffscreenRender {
        parts: SceneParts {
            edges: true,
            centrepiece: Centrepiece::None,
            avatar: false,
            clifford: false,
        },
        objects: vec![ball],
        ..OffscreenRender::new(ActiveSpace::new(&id, space.clone()), camera, (640, 360), 32)
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
