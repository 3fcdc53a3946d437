//! Walk a scene file in your own app: the file's space, objects, lights and start view
//! become the plugin's [`BaseScene`]; a globe of your own is added through `SceneObjects`.
//!
//! ```text
//! cargo run --release --example scene_file -- assets/scenes/seifert_weber_knot.toml
//! ```
//!
//! The default file is `assets/scenes/torus_globe.toml`. F4 shows or hides your ship, F1 the
//! panel.

use bevy::prelude::*;
use bevy_curved_spaces::plugin::components::BaseScene;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::scene::file::load_scene_file;
use bevy_curved_spaces::scene::{Ball, Object};
use glam::DVec3;
use std::process::ExitCode;

fn main() -> ExitCode {
    let path = std::env::args().nth(1).unwrap_or_else(|| {
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/assets/scenes/torus_globe.toml"
        )
        .into()
    });
    let file = match load_scene_file(std::path::Path::new(&path)) {
        Ok(file) => file,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    // One more object from code: a small red ball a third of the way to the +x face.
    let g = file.space.geometry();
    let r = bevy_curved_spaces::space::invariants::inradius(&file.space);
    let ball = Ball::new(
        g,
        g.translation(DVec3::X, r / 3.0) * file.space.centre(),
        0.08 * r,
        DVec3::new(0.9, 0.15, 0.1),
    );
    App::new()
        .add_plugins(DefaultPlugins)
        // The space and the base scene go in before the plugin: it starts with them (the
        // file's parts: edges, centre ball, ship).
        .insert_resource(ActiveSpace::new(file.space_id.clone(), file.space.clone()))
        .insert_resource(BaseScene::from_file(&file))
        .insert_resource(SceneObjects(vec![Object::Ball(ball)]))
        .add_plugins(CurvedSpacesPlugin {
            ui: true,
            ..default()
        })
        .add_systems(Startup, |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        })
        .run();
    ExitCode::SUCCESS
}
