//! The player: a frame `F` inside the cell (columns right, up, back, position) that moves by
//! local translations and rotations, and wraps through a face (`F ← g_f F`) once it is past
//! the face by a margin, recording the crossing ([`Holonomy`]). `docs/design.md` §6.
//!
//! All motion is local (`F ← F M`): the picture depends on `F` only through its columns, so
//! after a mirror crossing (a left-handed frame) the view and the controls continue exactly
//! as they would have without the wrap.

use crate::plugin::components::{
    ActiveSpace, BaseScenes, KeyBindings, MouseLook, PlayerFrame, PlayerMotion, PlayerSettings,
};

use crate::geometry::Geometry;
use crate::space::contract::step_constant_frame;
use crate::space::{FamilySpace, FrameMotion, Holonomy};
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;
use bevy::window::{CursorGrabMode, CursorOptions, PrimaryWindow};
use glam::{DMat4, DVec3};

/// The frame after a local motion: translate along the local direction, then turn.
/// Rotations are applied about right, up and back in that order, each by its angle.
#[must_use]
pub fn step_frame(geometry: Geometry, frame: DMat4, motion: &PlayerMotion) -> DMat4 {
    step_constant_frame(geometry, frame, motion.translation, motion.rotation)
}

/// Applies each player's motion to its frame, in the family `F` of the space shown (the
/// fibre kept up in a product space while [`PlayerSettings::fibre_up`] is on).
pub(crate) fn move_players<F: FamilySpace>(
    active: Res<ActiveSpace>,
    settings: Res<PlayerSettings>,
    mut players: Query<(&mut PlayerFrame, &PlayerMotion)>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    for (mut frame, motion) in &mut players {
        if *motion != PlayerMotion::default() {
            frame.0 = space.step_frame(
                frame.0,
                &FrameMotion {
                    translation: motion.translation,
                    rotation: motion.rotation,
                    level: settings.fibre_up,
                },
            );
        }
    }
}

/// Wraps players that left the cell of the family `F`'s space back in (past the margin),
/// recording each crossing in their [`Holonomy`], and puts every frame back on the model.
pub(crate) fn wrap_players<F: FamilySpace>(
    active: Res<ActiveSpace>,
    settings: Res<PlayerSettings>,
    mut players: Query<(&mut PlayerFrame, &mut Holonomy)>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    for (mut frame, mut holonomy) in &mut players {
        let (wrapped, crossed) = space.wrap_frame(frame.0, settings.wrap_margin);
        for c in crossed {
            holonomy.record_crossing(&c);
        }
        frame.0 = wrapped;
    }
}

/// Reads keys, mouse and scroll into each player's [`PlayerMotion`].
#[allow(clippy::too_many_arguments)]
pub(crate) fn read_input(
    keys: Res<ButtonInput<KeyCode>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    bindings: Res<KeyBindings>,
    mut settings: ResMut<PlayerSettings>,
    look: Res<MouseLook>,
    time: Res<Time>,
    active: Option<Res<ActiveSpace>>,
    mut players: Query<&mut PlayerMotion>,
) {
    let Some(inradius) = active.map(|a| a.inradius) else {
        return;
    };
    let dt = time.delta_secs_f64();
    let axis = |plus: KeyCode, minus: KeyCode| {
        f64::from(u8::from(keys.pressed(plus))) - f64::from(u8::from(keys.pressed(minus)))
    };
    let b = &*bindings;
    let mut factor = 1.0;
    if keys.just_pressed(b.faster) {
        factor *= 1.25;
    }
    if keys.just_pressed(b.slower) {
        factor /= 1.25;
    }
    let notches = match scroll.unit {
        MouseScrollUnit::Line => f64::from(scroll.delta.y),
        MouseScrollUnit::Pixel => f64::from(scroll.delta.y) / 40.0,
    };
    factor *= 1.25f64.powf(notches);
    if factor != 1.0 {
        settings.speed = (settings.speed * factor).clamp(0.01, 20.0);
    }
    let direction = DVec3::new(
        axis(b.right, b.left),
        axis(b.up, b.down),
        axis(b.backward, b.forward),
    );
    let direction = direction.normalize_or_zero();
    let step = settings.speed * inradius * dt;
    let looking = look.grabbed || settings.look_without_grab;
    let mouse = if looking {
        motion.delta.as_dvec2() * settings.mouse_sensitivity
    } else {
        glam::DVec2::ZERO
    };
    let roll = axis(b.roll_left, b.roll_right) * settings.roll_speed * dt;
    for mut m in &mut players {
        *m = PlayerMotion {
            translation: direction * step,
            // Mouse right turns right (negative yaw about up); mouse down looks down.
            rotation: DVec3::new(-mouse.y, -mouse.x, roll),
        };
    }
}

/// Grabs the cursor on a click in the window, releases it with the release key.
pub(crate) fn grab_cursor(
    mouse: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    bindings: Res<KeyBindings>,
    mut look: ResMut<MouseLook>,
    mut windows: Query<&mut CursorOptions, With<PrimaryWindow>>,
    pointer_over_ui: Option<Res<crate::plugin::components::PointerOverUi>>,
) {
    let over_ui = pointer_over_ui.is_some_and(|p| p.0);
    let grab = if mouse.just_pressed(MouseButton::Left) && !over_ui {
        true
    } else if keys.just_pressed(bindings.release_mouse) {
        false
    } else {
        return;
    };
    look.grabbed = grab;
    for mut cursor in &mut windows {
        cursor.grab_mode = if grab {
            CursorGrabMode::Locked
        } else {
            CursorGrabMode::None
        };
        cursor.visible = !grab;
    }
}

/// Puts every player at the new space's start view when the space shown changes (either
/// kind, either way); not on the first frame, which keeps frames set before it.
pub(crate) fn reset_players_on_switch(
    active: Option<Res<ActiveSpace>>,
    bases: BaseScenes,
    mut started: Local<bool>,
    mut players: Query<(&mut PlayerFrame, &mut Holonomy)>,
) {
    if !*started {
        *started = true;
        return;
    }
    let Some(active) = active.filter(|a| a.is_changed()) else {
        return;
    };
    let start = active.start_frame(&bases);
    for (mut frame, mut holonomy) in &mut players {
        frame.0 = start;
        *holonomy = Holonomy::default();
    }
}
