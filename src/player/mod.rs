//! The player: a frame `F` inside the cell (columns right, up, back, position) that moves by
//! local translations and rotations, and wraps through a face (`F ← g_f F`) once it is past
//! the face by a margin, recording the crossing ([`Holonomy`]). `DESIGN.md` §4.
//!
//! All motion is local (`F ← F M`): the picture depends on `F` only through its columns, so
//! after a mirror crossing (a left-handed frame) the view and the controls continue exactly
//! as they would have without the wrap.

use crate::geometry::Geometry;
use crate::space::Space;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll, MouseScrollUnit};
use bevy::prelude::*;
use bevy::window::{CursorGrabMode, CursorOptions, PrimaryWindow};
use glam::{DMat4, DVec3};

/// The player's frame: an isometry of the model whose columns are the right, up and back
/// unit tangents and the position (the camera looks along `−back`).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PlayerFrame(pub DMat4);

impl Default for PlayerFrame {
    fn default() -> Self {
        Self(DMat4::IDENTITY)
    }
}

/// The face crossings of a player since the space was entered.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Holonomy {
    /// Faces crossed so far.
    pub crossings: u64,
    /// The product of the pairings applied, latest on the left: `F_now = matrix · F_unwrapped`.
    pub matrix: DMat4,
    /// The face crossed last.
    pub last_face: Option<usize>,
}

impl Default for Holonomy {
    fn default() -> Self {
        Self {
            crossings: 0,
            matrix: DMat4::IDENTITY,
            last_face: None,
        }
    }
}

impl Holonomy {
    /// Records a crossing through `face` with pairing `g`.
    pub fn record(&mut self, face: usize, g: DMat4) {
        self.crossings += 1;
        self.matrix = g * self.matrix;
        self.last_face = Some(face);
    }
}

/// What the controls ask for this frame, in the player's own axes.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct PlayerMotion {
    /// Distance to move along right, up, back (geodesic units).
    pub translation: DVec3,
    /// Angles (radians) to turn about right (pitch), up (yaw) and back (roll).
    pub rotation: DVec3,
}

/// Rebindable keys of the first-person controls.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct KeyBindings {
    pub forward: KeyCode,
    pub backward: KeyCode,
    pub left: KeyCode,
    pub right: KeyCode,
    pub up: KeyCode,
    pub down: KeyCode,
    pub roll_left: KeyCode,
    pub roll_right: KeyCode,
    pub faster: KeyCode,
    pub slower: KeyCode,
    pub release_mouse: KeyCode,
}

impl Default for KeyBindings {
    fn default() -> Self {
        Self {
            forward: KeyCode::KeyW,
            backward: KeyCode::KeyS,
            left: KeyCode::KeyA,
            right: KeyCode::KeyD,
            up: KeyCode::Space,
            down: KeyCode::ShiftLeft,
            roll_left: KeyCode::KeyQ,
            roll_right: KeyCode::KeyE,
            faster: KeyCode::Equal,
            slower: KeyCode::Minus,
            release_mouse: KeyCode::Escape,
        }
    }
}

/// How the controls feel.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct PlayerSettings {
    /// Walking speed in cell inradii per second.
    pub speed: f64,
    /// Radians per pixel of mouse motion.
    pub mouse_sensitivity: f64,
    /// Roll speed in radians per second.
    pub roll_speed: f64,
    /// How far past a face (in `N·X/X.w`, chart units) the position may go before it wraps:
    /// the hysteresis that keeps a player standing on a face from flickering between sides.
    pub wrap_margin: f64,
    /// Whether mouse motion turns the view without a grabbed cursor (tests, touchpads).
    pub look_without_grab: bool,
}

impl Default for PlayerSettings {
    fn default() -> Self {
        Self {
            speed: 0.6,
            mouse_sensitivity: 0.003,
            roll_speed: 1.2,
            wrap_margin: 1e-4,
            look_without_grab: false,
        }
    }
}

/// The frame moved by `t` in its own axes (right, up, back): along the geodesic in that
/// direction by `|t|`. A zero or non-finite `t` leaves it where it is.
#[must_use]
pub fn translate_local(geometry: Geometry, frame: DMat4, t: DVec3) -> DMat4 {
    let distance = t.length();
    if distance > 0.0 && distance.is_finite() {
        frame * geometry.translation(t / distance, distance)
    } else {
        frame
    }
}

/// The frame after a local motion: translate along the local direction, then turn.
/// Rotations are applied about right, up and back in that order, each by its angle.
#[must_use]
pub fn step_frame(geometry: Geometry, frame: DMat4, motion: &PlayerMotion) -> DMat4 {
    let mut f = translate_local(geometry, frame, motion.translation);
    for (axis, angle) in [
        (DVec3::X, motion.rotation.x),
        (DVec3::Y, motion.rotation.y),
        (DVec3::Z, motion.rotation.z),
    ] {
        if angle != 0.0 && angle.is_finite() {
            f *= geometry.rotation(axis, angle);
        }
    }
    f
}

/// Most faces a single wrap may cross (through an edge or a vertex a few are needed).
pub const MAX_WRAPS_PER_STEP: usize = 32;

/// Brings a frame back into the cell: while its position is past a face by more than
/// `margin`, applies the pairing of the face it is farthest past. Returns the new frame
/// (re-orthonormalized) and the faces crossed, in order.
#[must_use]
pub fn wrap_into_cell(space: &Space, frame: DMat4, margin: f64) -> (DMat4, Vec<usize>) {
    let g = space.geometry;
    let mut f = frame;
    let mut crossed = Vec::new();
    for _ in 0..MAX_WRAPS_PER_STEP {
        let p = f.w_axis / f.w_axis.w;
        let (face, outside) = space
            .faces
            .iter()
            .enumerate()
            .map(|(i, face)| (i, face.covector.dot(p)))
            .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
        if !(outside > margin) {
            break;
        }
        f = space.faces[face].pairing * f;
        crossed.push(face);
    }
    (g.orthonormalize_frame(f), crossed)
}

/// Whether the primary window's cursor is grabbed for mouse look.
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MouseLook {
    pub grabbed: bool,
}

/// Reads keys, mouse and scroll into each player's [`PlayerMotion`].
#[allow(clippy::too_many_arguments)]
pub fn read_input(
    keys: Res<ButtonInput<KeyCode>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    bindings: Res<KeyBindings>,
    mut settings: ResMut<PlayerSettings>,
    look: Res<MouseLook>,
    time: Res<Time>,
    active: Res<crate::plugin::ActiveSpace>,
    mut players: Query<&mut PlayerMotion>,
) {
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
    let step = settings.speed * active.inradius * dt;
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
pub fn grab_cursor(
    mouse: Res<ButtonInput<MouseButton>>,
    keys: Res<ButtonInput<KeyCode>>,
    bindings: Res<KeyBindings>,
    mut look: ResMut<MouseLook>,
    mut windows: Query<&mut CursorOptions, With<PrimaryWindow>>,
    pointer_over_ui: Option<Res<crate::ui::PointerOverUi>>,
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

/// Applies each player's motion to its frame.
pub fn move_players(
    active: Res<crate::plugin::ActiveSpace>,
    mut players: Query<(&mut PlayerFrame, &PlayerMotion)>,
) {
    let g = active.space.geometry;
    for (mut frame, motion) in &mut players {
        if *motion != PlayerMotion::default() {
            frame.0 = step_frame(g, frame.0, motion);
        }
    }
}

/// Wraps players that left the cell and re-orthonormalizes every frame.
pub fn wrap_players(
    active: Res<crate::plugin::ActiveSpace>,
    settings: Res<PlayerSettings>,
    mut players: Query<(&mut PlayerFrame, &mut Holonomy)>,
) {
    let space = &active.space;
    for (mut frame, mut holonomy) in &mut players {
        let (wrapped, crossed) = wrap_into_cell(space, frame.0, settings.wrap_margin);
        for face in crossed {
            holonomy.record(face, space.faces[face].pairing);
        }
        frame.0 = wrapped;
    }
}
