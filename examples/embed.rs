//! The plugin in an ordinary Bevy game: the code to copy into yours.
//!
//! ```text
//! cargo run --release --example embed
//! ```
//!
//! One plugin, one marker component on a `Camera3d`, and your own systems ordered around
//! ours with [`CurvedSpacesSystems`]. Here a system of the game switches the space with the
//! number keys 1–9 and 0, another one prints every face crossing, and a spawned entity (a
//! small glowing companion, a `CurvedObject`) follows the player a little ahead and to the
//! right: through the faces with you, and seen again wherever rays come back round.

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
        .add_systems(Startup, (spawn_camera, spawn_companion))
        .add_systems(Update, switch_space.before(CurvedSpacesSystems::Move))
        .add_systems(Update, report_crossings.after(CurvedSpacesSystems::Wrap))
        .add_systems(
            Update,
            follow_player
                .after(CurvedSpacesSystems::Wrap)
                .before(CurvedSpacesSystems::Upload),
        )
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

/// The companion: marks the entity that follows the player.
#[derive(Component)]
struct Companion;

fn spawn_companion(mut commands: Commands) {
    commands.spawn((
        Companion,
        // Sized in follow_player, where the space (and its scale) is known.
        CurvedObject::ball(0.01, glam::DVec3::new(0.3, 0.9, 1.0))
            .with_emission(glam::DVec3::new(0.1, 0.4, 0.5)),
    ));
}

/// Keeps the companion a little ahead, right and below the player's eye, sized to the cell.
fn follow_player(
    active: Res<ActiveSpace>,
    players: Query<&PlayerFrame, With<CurvedSpaceCamera>>,
    mut companions: Query<(&mut CurvedTransform, &mut CurvedObject), With<Companion>>,
) {
    let Some(player) = players.iter().next() else {
        return;
    };
    let r = active.inradius as f32;
    let offset = Transform::from_xyz(0.25 * r, -0.15 * r, -0.6 * r);
    for (mut at, mut object) in &mut companions {
        *at = CurvedTransform::relative_to(active.space.model_geometry(), player.0, &offset);
        let radius = 0.06 * active.inradius;
        if object.shape != (CurvedShape::Ball { radius }) {
            object.shape = CurvedShape::Ball { radius };
        }
    }
}
