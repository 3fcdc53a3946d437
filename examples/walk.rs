//! Walk inside any space in a window, with the panel.
//!
//! ```text
//! cargo run --release --example walk -- poincare
//! cargo run --release --example walk -- my-space.json
//! ```
//!
//! The argument is a seed space id (`cargo run -- list`) or a space file; the default is
//! the Seifert–Weber space. Click to look around, WASD/Space/Shift to move, Q/E to roll,
//! scroll for speed, Esc to release the mouse, F1 for the panel, F12 for a screenshot.

use bevy::prelude::*;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::space::file::load_space_file;
use std::process::ExitCode;

fn main() -> ExitCode {
    let arg = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "seifert-weber".into());
    let loaded = if arg.ends_with(".json") {
        load_space_file(std::path::Path::new(&arg)).map_err(|e| e.to_string())
    } else {
        seed_space(&arg).map_err(|e| e.to_string())
    };
    let space = match loaded {
        Ok(space) => space,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    App::new()
        .add_plugins(DefaultPlugins)
        // A space inserted before the plugin is the one it starts in.
        .insert_resource(ActiveSpace::new(arg, space))
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
