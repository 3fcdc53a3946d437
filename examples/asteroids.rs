//! Asteroids drifting through the Seifert–Weber space: a small game on the plugin's entities.
//!
//! ```text
//! cargo run --release --example asteroids
//! ```
//!
//! Rocks (cubes and balls) fly along geodesics and tumble; each leaves through a face and
//! comes back through its partner, turned by the pairing — three tenths of a turn in this
//! space. The window's title counts how often each came round. Fly with WASD and the mouse
//! (click to grab it), press F to fire: a shot flies straight ahead, and a rock within its
//! reach along the shortest geodesic through the faces breaks up. Shots fade after four
//! seconds. Every rock is a spawned entity with a `CurvedObject`, a `CurvedTransform` and a
//! `CurvedVelocity`; shots and hits spawn and despawn them.

use bevy::prelude::*;
use bevy::window::PrimaryWindow;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::scene::mesh::cube_source;
use bevy_curved_spaces::scene::{Model, TracedModel};
use glam::DVec3;
use std::collections::HashMap;
use std::sync::Arc;

fn main() {
    App::new()
        .add_plugins(DefaultPlugins)
        .add_plugins(CurvedSpacesPlugin {
            space: "seifert-weber".into(),
            quality: Quality::Low,
            ..default()
        })
        .init_resource::<Score>()
        .add_systems(Startup, (spawn_camera, spawn_rocks))
        .add_systems(
            Update,
            (fire, hit_rocks, count_rounds, show_score)
                .chain()
                .after(CurvedSpacesSystems::Wrap)
                .before(CurvedSpacesSystems::Upload),
        )
        .run();
}

/// A rock and how often it came round (crossed a face).
#[derive(Component)]
struct Rock {
    size: f64,
}

/// A shot and when it was fired.
#[derive(Component)]
struct Shot {
    fired: f64,
}

#[derive(Resource, Default)]
struct Score {
    rounds: HashMap<Entity, u64>,
    broken: u32,
}

fn spawn_camera(mut commands: Commands) {
    commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
}

fn spawn_rocks(mut commands: Commands, active: Res<ActiveSpace>) {
    let r = active.inradius;
    let g = active.space.model_geometry();
    let cube = Arc::new(
        TracedModel::new(
            g,
            &Model {
                source: cube_source(0.5, 0),
                materials: vec![SurfaceMaterial {
                    colour: DVec3::new(0.55, 0.45, 0.4),
                    ..SurfaceMaterial::default()
                }],
                textures: Vec::new(),
            },
            0.12 * r,
        )
        .expect("a cube is a mesh"),
    );
    let mut rng = SplitMix64(7);
    for i in 0..10 {
        let at = rng.direction() * (0.3 + 0.5 * rng.unit()) * r;
        let object = if i % 2 == 0 {
            CurvedObject::traced(cube.clone())
        } else {
            CurvedObject::ball(0.1 * r, DVec3::new(0.5 + 0.4 * rng.unit(), 0.4, 0.3))
        };
        commands.spawn((
            Rock { size: 0.12 * r },
            object,
            CurvedTransform::from_geodesic(&active.space, at),
            CurvedVelocity::linear(rng.direction() * (0.2 + 0.3 * rng.unit()) * r)
                .with_angular(rng.direction() * 0.8),
        ));
    }
}

/// F fires a glowing shot straight ahead from the player.
fn fire(
    keys: Res<ButtonInput<KeyCode>>,
    time: Res<Time>,
    active: Res<ActiveSpace>,
    players: Query<&PlayerFrame, With<CurvedSpaceCamera>>,
    shots: Query<(Entity, &Shot)>,
    mut commands: Commands,
) {
    let now = time.elapsed_secs_f64();
    for (e, shot) in &shots {
        if now - shot.fired > 4.0 {
            commands.entity(e).despawn();
        }
    }
    if !keys.just_pressed(KeyCode::KeyF) {
        return;
    }
    let r = active.inradius;
    for player in &players {
        let g = active.space.model_geometry();
        // Just ahead of the eye, flying forward (−back) at two inradii a second.
        let start = CurvedTransform::relative_to(
            g,
            player.0,
            &Transform::from_xyz(0.0, -0.05 * r as f32, -0.2 * r as f32),
        );
        commands.spawn((
            Shot { fired: now },
            CurvedObject::ball(0.03 * r, DVec3::ONE).with_emission(DVec3::new(1.0, 0.8, 0.3)),
            start,
            CurvedVelocity::linear(DVec3::new(0.0, 0.0, -2.0 * r)),
        ));
    }
}

/// A shot within reach of a rock (along the shortest geodesic between them, through any
/// faces) breaks it.
fn hit_rocks(
    sightlines: Res<ActiveSightlines>,
    shots: Query<(Entity, &CurvedTransform), With<Shot>>,
    rocks: Query<(Entity, &CurvedTransform, &Rock)>,
    mut score: ResMut<Score>,
    mut commands: Commands,
) {
    for (shot, at) in &shots {
        for (rock, rock_at, size) in &rocks {
            let Some(line) = sightlines.between(at, rock_at) else {
                return;
            };
            if line.distance < size.size {
                commands.entity(rock).despawn();
                commands.entity(shot).despawn();
                score.rounds.remove(&rock);
                score.broken += 1;
                info!("rock {rock} broken at {:.2}", line.distance);
                return;
            }
        }
    }
}

fn count_rounds(
    mut crossings: MessageReader<ObjectCrossedFace>,
    rocks: Query<(), With<Rock>>,
    mut score: ResMut<Score>,
) {
    for c in crossings.read() {
        if rocks.contains(c.entity) {
            *score.rounds.entry(c.entity).or_default() += 1;
        }
    }
}

fn show_score(score: Res<Score>, mut window: Query<&mut Window, With<PrimaryWindow>>) {
    if !score.is_changed() {
        return;
    }
    let mut rounds: Vec<u64> = score.rounds.values().copied().collect();
    rounds.sort_unstable_by(|a, b| b.cmp(a));
    if let Ok(mut w) = window.single_mut() {
        w.title = format!(
            "asteroids in the Seifert–Weber space: {} broken, rounds per rock {:?} (F fires)",
            score.broken, rounds
        );
    }
}
