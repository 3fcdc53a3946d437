//! The plugin in an ordinary Bevy game: the code to copy into yours.
//!
//! ```text
//! cargo run --release --example embed
//! ```
//!
//! One plugin, one marker component on a `Camera3d`, and your own systems ordered around
//! ours with [`CurvedSpacesSystems`]. Here a system of the game switches the space with the
//! number keys 1–9 and 0, and another one prints every face crossing.

use bevy::prelude::*;
use bevy_curved_spaces::prelude::*;

fn main() {
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(CurvedSpacesPlugin {
            space: "poincare".into(),
            quality: Quality::Medium,
            ..default()
        })
        .add_systems(Startup, spawn_camera)
        .add_systems(Update, switch_space.before(CurvedSpacesSystems::Move))
        .add_systems(Update, report_crossings.after(CurvedSpacesSystems::Wrap))
        .run();
}

fn spawn_camera(mut commands: Commands) {
    commands.spawn((
        Camera3d::default(),
        CurvedSpaceCamera {
            fov_y_degrees: 75.0,
        },
    ));
}

fn switch_space(keys: Res<ButtonInput<KeyCode>>, mut active: ResMut<ActiveSpace>) {
    let digits = [
        KeyCode::Digit1,
        KeyCode::Digit2,
        KeyCode::Digit3,
        KeyCode::Digit4,
        KeyCode::Digit5,
        KeyCode::Digit6,
        KeyCode::Digit7,
        KeyCode::Digit8,
        KeyCode::Digit9,
        KeyCode::Digit0,
    ];
    for (key, seed) in digits.iter().zip(SEED_SPACES) {
        if keys.just_pressed(*key) {
            match ActiveSpace::seed(seed.id) {
                Ok(space) => *active = space,
                Err(e) => error!("{e}"),
            }
        }
    }
}

fn report_crossings(players: Query<&Holonomy, Changed<Holonomy>>) {
    for h in &players {
        if let Some(face) = h.last_face {
            info!("crossed face {face} ({} crossings so far)", h.crossings);
        }
    }
}
