//! Stereo in the curved space: the two eyes are geodesic offsets of the head, each wrapped
//! into the cell, traced by the same shader.
//!
//! ```text
//! cargo run --release --example stereo [SPACE]
//! ```
//!
//! Starts in the red–cyan anaglyph (put on red–cyan glasses, red on the left eye). Keys:
//! **1** mono, **2** side by side, **3** top and bottom, **4** anaglyph (Dubois), **5**
//! anaglyph (plain red/cyan), **[** and **]** halve or double the eye distance (the world
//! scale: how big the cell feels), **X** swaps the eyes (for cross-eyed viewing). Walk with
//! the usual controls (click, WASD, Q/E roll: the eye axis rolls with the head).

use bevy::prelude::*;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::view::stereo::default_ipd;

fn main() {
    let space = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "seifert-weber".into());
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(CurvedSpacesPlugin {
            space,
            stereo: StereoSettings {
                mode: StereoMode::AnaglyphDubois,
                ..default()
            },
            ..default()
        })
        .add_systems(Startup, |mut commands: Commands| {
            commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
        })
        .add_systems(Update, stereo_keys.before(CurvedSpacesSystems::Upload))
        .run();
}

fn stereo_keys(
    keys: Res<ButtonInput<KeyCode>>,
    active: Res<ActiveSpace>,
    mut stereo: ResMut<StereoSettings>,
) {
    for (key, mode) in [
        (KeyCode::Digit1, StereoMode::Mono),
        (KeyCode::Digit2, StereoMode::SideBySide),
        (KeyCode::Digit3, StereoMode::TopBottom),
        (KeyCode::Digit4, StereoMode::AnaglyphDubois),
        (KeyCode::Digit5, StereoMode::AnaglyphRedCyan),
    ] {
        if keys.just_pressed(key) {
            stereo.mode = mode;
            info!("stereo: {}", mode.label());
        }
    }
    let ipd = stereo.ipd_for(active.inradius);
    let scaled = if keys.just_pressed(KeyCode::BracketLeft) {
        Some(ipd / 2.0)
    } else if keys.just_pressed(KeyCode::BracketRight) {
        Some((ipd * 2.0).min(active.inradius))
    } else {
        None
    };
    if let Some(ipd) = scaled {
        stereo.ipd = Some(ipd);
        info!(
            "eye distance {ipd:.4} ({:.2}× the default): the inradius feels like {:.2} m",
            ipd / default_ipd(active.inradius),
            active.inradius / stereo.units_per_metre(active.inradius)
        );
    }
    if keys.just_pressed(KeyCode::KeyX) {
        stereo.swap_eyes = !stereo.swap_eyes;
    }
}
