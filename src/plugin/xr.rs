//! OpenXR headsets (cargo feature `xr`), through the Bevy OpenXR crates (`bevy_mod_openxr`,
//! `bevy_mod_xr`).
//!
//! The headset's two views become two curved-space cameras ([`CurvedSpaceEye`], each with
//! the view's own asymmetric frustum). Their frames come from [`HeadTracker`]: the head's
//! motion in the room is applied as local motion in the space (walking in the room walks
//! through faces, with holonomy), and each eye is the head's frame moved by the eye's pose
//! relative to the head, wrapped into the cell on its own. The world scale is the stereo
//! settings' (eye distance / 64 mm). Controllers: the left thumbstick walks (along where the
//! head looks), the right one turns smoothly about the head's up axis. The desktop window
//! mirrors the head's view.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::prelude::*;
//! use bevy_curved_spaces::plugin::xr::{CurvedSpacesXrPlugin, add_xr_plugins};
//!
//! App::new()
//!     .add_plugins(add_xr_plugins(DefaultPlugins))
//!     .add_plugins((CurvedSpacesPlugin::default(), CurvedSpacesXrPlugin::default()))
//!     .run();
//! ```

use crate::plugin::components::CurvedSpaceEye;
use crate::plugin::components::StereoSettings;
use crate::plugin::components::{ActiveSpace, CurvedSpaceCamera, CurvedSpacesSystems};
use crate::plugin::components::{PlayerFrame, PlayerSettings};
use crate::view::Lens;
use crate::view::TraceCamera;
use crate::view::headset::{HeadTracker, RoomPose};
use bevy::prelude::*;
use bevy_mod_openxr::action_binding::{OxrSendActionBindings, OxrSuggestActionBinding};
use bevy_mod_openxr::action_set_attaching::OxrAttachActionSet;
use bevy_mod_openxr::action_set_syncing::{OxrActionSetSyncSet, OxrSyncActionSet};
use bevy_mod_openxr::openxr_session_running;
use bevy_mod_openxr::resources::{OxrInstance, OxrViews};
use bevy_mod_openxr::session::OxrSession;
use bevy_mod_xr::camera::XrCamera;
use bevy_mod_xr::session::{XrSessionCreated, XrState, session_available};
use glam::{DQuat, DVec3};

pub use bevy_mod_openxr::add_xr_plugins;

/// Why no headset can be used.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum XrUnavailable {
    /// No OpenXR loader was found (the loader's error is attached).
    #[error(
        "no OpenXR loader was found ({0}); install one (Debian: `apt-get install libopenxr-dev`, which provides libopenxr_loader.so) and a runtime (SteamVR, Monado or your headset's)"
    )]
    NoLoader(String),
    /// No OpenXR runtime was found (its error is attached): start SteamVR, Monado or your headset's runtime (or point XR_RUNTIME_JSON at its manifest).
    #[error(
        "no OpenXR runtime was found ({0}): start SteamVR, Monado or your headset's runtime (or point XR_RUNTIME_JSON at its manifest)"
    )]
    NoRuntime(String),
}

/// Checks, without starting a session, that an OpenXR loader and an active runtime exist.
pub fn probe_runtime() -> Result<(), XrUnavailable> {
    // SAFETY: loading the system's OpenXR loader library runs its initialisers; that is
    // what every OpenXR application does, and nothing else is loaded by it here.
    let entry =
        unsafe { openxr::Entry::load() }.map_err(|e| XrUnavailable::NoLoader(e.to_string()))?;
    entry
        .enumerate_extensions()
        .map(|_| ())
        .map_err(|e| XrUnavailable::NoRuntime(e.to_string()))
}

/// Drives curved-space cameras from an OpenXR headset. Add it after
/// [`add_xr_plugins`]`(DefaultPlugins)` and [`CurvedSpacesPlugin`](crate::plugin::CurvedSpacesPlugin).
#[derive(Clone, Debug)]
pub struct CurvedSpacesXrPlugin {
    /// Walking speed of the thumbstick in cell inradii per second.
    pub speed: f64,
    /// Turning speed of the thumbstick in radians per second.
    pub turn_speed: f64,
    /// A desktop window camera that shows the head's view.
    pub mirror: bool,
}

impl Default for CurvedSpacesXrPlugin {
    fn default() -> Self {
        Self {
            speed: 0.5,
            turn_speed: 1.5,
            mirror: true,
        }
    }
}

/// The wearer's head in the space.
#[derive(Resource, Clone, Debug)]
pub struct XrHead(pub HeadTracker);

/// Thumbstick speeds.
#[derive(Resource, Clone, Copy, Debug)]
struct XrControls {
    speed: f64,
    turn_speed: f64,
}

/// The desktop camera that mirrors the head.
#[derive(Component, Clone, Copy, Debug)]
pub struct XrMirror;

#[derive(Resource)]
struct LocomotionActions {
    set: openxr::ActionSet,
    walk: openxr::Action<openxr::Vector2f>,
    turn: openxr::Action<openxr::Vector2f>,
}

impl Plugin for CurvedSpacesXrPlugin {
    fn build(&self, app: &mut App) {
        app.insert_resource(XrControls {
            speed: self.speed,
            turn_speed: self.turn_speed,
        })
        .add_systems(Startup, create_actions.run_if(session_available))
        .add_systems(XrSessionCreated, attach_actions)
        .add_systems(OxrSendActionBindings, suggest_bindings)
        .add_systems(
            PreUpdate,
            sync_actions
                .before(OxrActionSetSyncSet)
                .run_if(openxr_session_running),
        )
        .add_systems(
            Update,
            (reset_head_on_switch, thumbstick_locomotion)
                .chain()
                .in_set(CurvedSpacesSystems::Move)
                .run_if(openxr_session_running)
                .run_if(resource_exists::<ActiveSpace>),
        )
        .add_systems(
            PostUpdate,
            (mark_xr_cameras, drive_eyes)
                .chain()
                .after(bevy_mod_openxr::render::update_views)
                .run_if(openxr_session_running)
                .run_if(resource_exists::<ActiveSpace>),
        );
        if self.mirror {
            app.add_systems(Startup, spawn_mirror)
                .add_systems(PostUpdate, mirror_head.after(drive_eyes));
        }
    }
}

fn spawn_mirror(mut commands: Commands) {
    commands.spawn((Camera3d::default(), CurvedSpaceCamera::default(), XrMirror));
}

fn create_actions(instance: Res<OxrInstance>, mut commands: Commands) {
    let created = instance
        .create_action_set("curved_spaces", "Curved spaces locomotion", 0)
        .and_then(|set| {
            let walk = set.create_action("walk", "Walk", &[])?;
            let turn = set.create_action("turn", "Turn", &[])?;
            Ok(LocomotionActions { set, walk, turn })
        });
    match created {
        Ok(actions) => commands.insert_resource(actions),
        Err(e) => error!("cannot create the OpenXR locomotion actions: {e}"),
    }
}

fn attach_actions(
    actions: Option<Res<LocomotionActions>>,
    mut attach: MessageWriter<OxrAttachActionSet>,
) {
    if let Some(actions) = actions {
        attach.write(OxrAttachActionSet(actions.set.clone()));
    }
}

fn sync_actions(
    actions: Option<Res<LocomotionActions>>,
    mut sync: MessageWriter<OxrSyncActionSet>,
) {
    if let Some(actions) = actions {
        sync.write(OxrSyncActionSet(actions.set.clone()));
    }
}

/// Thumbsticks (or trackpads) of the common controllers: left walks, right turns.
fn suggest_bindings(
    actions: Option<Res<LocomotionActions>>,
    mut bindings: MessageWriter<OxrSuggestActionBinding>,
) {
    let Some(actions) = actions else {
        return;
    };
    for (profile, stick) in [
        (
            "/interaction_profiles/oculus/touch_controller",
            "thumbstick",
        ),
        ("/interaction_profiles/valve/index_controller", "thumbstick"),
        (
            "/interaction_profiles/microsoft/motion_controller",
            "thumbstick",
        ),
        ("/interaction_profiles/htc/vive_controller", "trackpad"),
    ] {
        for (action, hand) in [(&actions.walk, "left"), (&actions.turn, "right")] {
            bindings.write(OxrSuggestActionBinding {
                action: action.as_raw(),
                interaction_profile: profile.into(),
                bindings: vec![format!("/user/hand/{hand}/input/{stick}").into()],
            });
        }
    }
}

/// A new space starts the head at its default view.
fn reset_head_on_switch(active: Res<ActiveSpace>, head: Option<ResMut<XrHead>>) {
    if let Some(mut head) = head
        && active.is_changed()
        && !active.is_added()
    {
        head.0.frame = TraceCamera::default_for(&active.space).frame;
        head.0.holonomy = default();
    }
}

fn thumbstick_locomotion(
    actions: Option<Res<LocomotionActions>>,
    session: Option<Res<OxrSession>>,
    controls: Res<XrControls>,
    active: Res<ActiveSpace>,
    time: Res<Time>,
    head: Option<ResMut<XrHead>>,
) {
    let (Some(actions), Some(session), Some(mut head)) = (actions, session, head) else {
        return;
    };
    let stick = |action: &openxr::Action<openxr::Vector2f>| {
        action
            .state(&session, openxr::Path::NULL)
            .ok()
            .filter(|s| s.is_active)
            .map_or(DVec3::ZERO, |s| {
                DVec3::new(
                    f64::from(s.current_state.x),
                    f64::from(s.current_state.y),
                    0.0,
                )
            })
    };
    let (walk, turn) = (stick(&actions.walk), stick(&actions.turn));
    let dt = time.delta_secs_f64();
    // Stick up walks forward (−back), right strafes; a dead zone ignores resting drift.
    let dead = |v: f64| if v.abs() < 0.15 { 0.0 } else { v };
    let step = DVec3::new(dead(walk.x), 0.0, -dead(walk.y)) * controls.speed * active.inradius * dt;
    let yaw = -dead(turn.x) * controls.turn_speed * dt;
    if step != DVec3::ZERO || yaw != 0.0 {
        head.0.locomote(&active.space, step, yaw);
    }
}

/// The headset's cameras (spawned by the OpenXR backend) become curved-space eyes.
fn mark_xr_cameras(
    mut commands: Commands,
    cameras: Query<Entity, (With<XrCamera>, Without<CurvedSpaceEye>)>,
) {
    for entity in &cameras {
        commands.entity(entity).insert((
            CurvedSpaceCamera::default(),
            CurvedSpaceEye {
                lens: Lens::symmetric(90.0, 1.0),
            },
        ));
    }
}

fn room_pose(pose: &openxr::Posef) -> RoomPose {
    let q = pose.orientation;
    let p = pose.position;
    RoomPose::new(
        DVec3::new(f64::from(p.x), f64::from(p.y), f64::from(p.z)),
        DQuat::from_xyzw(
            f64::from(q.x),
            f64::from(q.y),
            f64::from(q.z),
            f64::from(q.w),
        ),
    )
}

/// Moves the head by the headset's motion and gives each eye camera its frame and frustum.
fn drive_eyes(
    views: Res<OxrViews>,
    active: Res<ActiveSpace>,
    stereo: Res<StereoSettings>,
    player: Res<PlayerSettings>,
    mut existing: Option<ResMut<XrHead>>,
    mut commands: Commands,
    mut eyes: Query<(&XrCamera, &mut PlayerFrame, &mut CurvedSpaceEye)>,
) {
    let [left, right] = views.as_slice() else {
        return;
    };
    let poses = [room_pose(&left.pose), room_pose(&right.pose)];
    let head_pose = RoomPose::between(&poses[0], &poses[1]);
    let space = &active.space;
    let scale = stereo.units_per_metre(active.inradius);
    // The head is tracked in place; the first frame creates it at the space's start view.
    let mut created = None;
    let head = match existing.as_deref_mut() {
        Some(XrHead(tracker)) => tracker,
        None => {
            &mut created
                .insert(XrHead(HeadTracker::new(
                    TraceCamera::default_for(space).frame,
                    scale,
                    player.wrap_margin,
                )))
                .0
        }
    };
    head.units_per_metre = scale;
    head.track(space, head_pose);
    for (camera, mut frame, mut eye) in &mut eyes {
        let Some(view) = views.get(camera.0 as usize) else {
            continue;
        };
        let pose = poses.get(camera.0 as usize).copied().unwrap_or(head_pose);
        frame.0 = head.eye(space, &head_pose, &pose).frame;
        let f = view.fov;
        eye.lens = Lens::from_angles(
            f64::from(f.angle_left),
            f64::from(f.angle_right),
            f64::from(f.angle_down),
            f64::from(f.angle_up),
        );
    }
    if let Some(head) = created {
        commands.insert_resource(head);
    }
}

fn mirror_head(
    head: Option<Res<XrHead>>,
    mut mirrors: Query<&mut PlayerFrame, (With<XrMirror>, Without<XrCamera>)>,
) {
    let Some(head) = head else {
        return;
    };
    for mut frame in &mut mirrors {
        frame.0 = head.0.frame;
    }
}

/// Whether the OpenXR backend found a runtime when the plugins were built.
#[must_use]
pub fn xr_available(world: &World) -> bool {
    world
        .get_resource::<XrState>()
        .is_some_and(|s| *s != XrState::Unavailable)
}
