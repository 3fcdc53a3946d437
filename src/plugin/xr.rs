//! OpenXR headsets (cargo feature `xr`), through the Bevy OpenXR crates (`bevy_mod_openxr`,
//! `bevy_mod_xr`).
//!
//! The headset's two views become two curved-space cameras ([`CurvedSpaceEye`], each with
//! the view's own asymmetric frustum). Their frames come from [`HeadTracker`]: the head's
//! motion in the room is applied as local motion in the space (walking in the room walks
//! through faces, with holonomy), and each eye is the head's frame moved by the eye's pose
//! relative to the head, wrapped into the cell on its own.
//!
//! - **World scale.** The stereo settings' eye distance in the space (by default
//!   [`default_ipd`](crate::view::stereo::default_ipd): 64 mm where the cell's inradius is
//!   the size of a room) is the wearer's real eye distance, 64 mm: one metre in the room is
//!   `ipd / 0.064` space units.
//! - **Controllers.** The left thumbstick walks (along where the head looks), the right one
//!   turns about the head's up axis, smoothly or in snaps ([`TurnStyle`]). The sticks'
//!   values are in [`XrSticks`] each frame, so a game may drive them too.
//! - **Play area.** [`PlayArea`] chooses the OpenXR reference space the head is tracked in
//!   (the standing stage, with its floor at the room's `y = 0`, or the seated local space
//!   centred on the head); pass it to [`xr_plugins`].
//! - **Frame rate.** The tracer's frame-rate target follows the headset's display period,
//!   so the per-eye resolution (the runtime's recommended size × the quality's scale) drops
//!   where the headset's refresh rate cannot be held.
//!
//! The desktop window mirrors the head's view.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::prelude::*;
//! use bevy_curved_spaces::plugin::xr::{CurvedSpacesXrPlugin, PlayArea, xr_plugins};
//!
//! App::new()
//!     .add_plugins(xr_plugins(DefaultPlugins, PlayArea::Standing))
//!     .add_plugins((CurvedSpacesPlugin::default(), CurvedSpacesXrPlugin::default()))
//!     .run();
//! ```

use crate::plugin::components::CurvedSpaceEye;
use crate::plugin::components::StereoSettings;
use crate::plugin::components::{ActiveSpace, BaseScenes, CurvedSpaceCamera, CurvedSpacesSystems};
use crate::plugin::components::{PlayerFrame, PlayerSettings};
use crate::plugin::frame_rate::FrameRateTarget;
use crate::space::FamilySpace;
use crate::view::Lens;
pub use crate::view::headset::TurnStyle;
use crate::view::headset::{DEAD_ZONE, HeadTracker, RoomPose, turn_yaw};
use bevy::app::PluginGroupBuilder;
use bevy::prelude::*;
use bevy_mod_openxr::action_binding::{OxrSendActionBindings, OxrSuggestActionBinding};
use bevy_mod_openxr::action_set_attaching::OxrAttachActionSet;
use bevy_mod_openxr::action_set_syncing::{OxrActionSetSyncSet, OxrSyncActionSet};
use bevy_mod_openxr::openxr_session_running;
use bevy_mod_openxr::poll_events::{OxrEventHandlerExt, OxrEventIn};
use bevy_mod_openxr::reference_space::OxrReferenceSpacePlugin;
use bevy_mod_openxr::resources::{OxrFrameState, OxrInstance, OxrViews};
use bevy_mod_openxr::session::OxrSession;
use bevy_mod_xr::camera::XrCamera;
use bevy_mod_xr::session::{XrSessionCreated, XrState, session_available};
use glam::{DQuat, DVec3};

pub use bevy_mod_openxr::add_xr_plugins;

/// Where the wearer is, which decides the OpenXR reference space the head is tracked in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PlayArea {
    /// Standing (room scale): the runtime's stage, with the floor at the room's `y = 0` and
    /// the play area's centre at its origin; walking in the room walks in the space.
    #[default]
    Standing,
    /// Seated: the runtime's local space, its origin where the head was when the session
    /// began (moved by the runtime's recentre); the thumbsticks do the walking.
    Seated,
}

impl PlayArea {
    /// The OpenXR reference space of this play area.
    #[must_use]
    pub fn reference_space(self) -> openxr::ReferenceSpaceType {
        match self {
            PlayArea::Standing => openxr::ReferenceSpaceType::STAGE,
            PlayArea::Seated => openxr::ReferenceSpaceType::LOCAL,
        }
    }

    /// Its name on the command line: `standing` or `seated`.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            PlayArea::Standing => "standing",
            PlayArea::Seated => "seated",
        }
    }
}

/// [`add_xr_plugins`] with the head tracked in `play_area`'s reference space.
pub fn xr_plugins<G: PluginGroup>(plugins: G, play_area: PlayArea) -> PluginGroupBuilder {
    add_xr_plugins(plugins).set(OxrReferenceSpacePlugin {
        default_primary_ref_space: play_area.reference_space(),
    })
}

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
/// [`xr_plugins`]`(DefaultPlugins, …)` and [`CurvedSpacesPlugin`](crate::plugin::CurvedSpacesPlugin).
/// Its locomotion and comfort fields start the [`XrComfort`] resource.
#[derive(Clone, Debug)]
pub struct CurvedSpacesXrPlugin {
    /// Walking speed of the thumbstick in cell inradii per second.
    pub speed: f64,
    /// Turning speed of the thumbstick in radians per second ([`TurnStyle::Smooth`]).
    pub turn_speed: f64,
    /// Smooth or snap turning.
    pub turn: TurnStyle,
    /// A desktop window camera that shows the head's view.
    pub mirror: bool,
    /// Sets the tracer's [`FrameRateTarget`] to the headset's display rate.
    pub display_rate_target: bool,
}

impl Default for CurvedSpacesXrPlugin {
    fn default() -> Self {
        Self {
            speed: 0.5,
            turn_speed: 1.5,
            turn: TurnStyle::default(),
            mirror: true,
            display_rate_target: true,
        }
    }
}

/// The wearer's head in the space.
#[derive(Resource, Clone, Debug)]
pub struct XrHead(pub HeadTracker);

/// The thumbsticks this frame, each axis in `[-1, 1]` (x right, y forward), read from the
/// runtime's actions in `PreUpdate`; a system before [`CurvedSpacesSystems::Move`] may set
/// them instead (a game's own input, a test).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct XrSticks {
    /// The left stick: walking.
    pub walk: Vec2,
    /// The right stick: turning (its x).
    pub turn: Vec2,
    /// Whether the runtime reported the sticks as bound to a controller this frame.
    pub bound: bool,
}

/// The headset's locomotion and comfort settings (a resource, changeable at run time; the
/// plugin's fields give its start).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct XrComfort {
    /// Walking speed of the thumbstick in cell inradii per second.
    pub speed: f64,
    /// Turning speed of the thumbstick in radians per second ([`TurnStyle::Smooth`]).
    pub turn_speed: f64,
    /// Smooth or snap turning.
    pub turn: TurnStyle,
    /// Sets the tracer's [`FrameRateTarget`] to the headset's display rate (off: the target
    /// is left as it is).
    pub display_rate_target: bool,
}

/// A snap turn was made and the stick has not come back yet.
#[derive(Resource, Default)]
struct SnapHeld(bool);

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
        app.insert_resource(XrComfort {
            speed: self.speed,
            turn_speed: self.turn_speed,
            turn: self.turn,
            display_rate_target: self.display_rate_target,
        })
        .init_resource::<SnapHeld>()
        .init_resource::<XrSticks>()
        .add_systems(Startup, create_actions.run_if(session_available))
        .add_systems(XrSessionCreated, attach_actions)
        .add_systems(OxrSendActionBindings, suggest_bindings)
        .add_systems(
            PreUpdate,
            (
                sync_actions.before(OxrActionSetSyncSet),
                read_thumbsticks.after(OxrActionSetSyncSet),
            )
                .run_if(openxr_session_running),
        )
        .add_systems(
            Update,
            reset_head_on_switch
                .in_set(CurvedSpacesSystems::Move)
                .run_if(openxr_session_running)
                .run_if(resource_exists::<ActiveSpace>),
        )
        .init_resource::<XrDisplayPeriod>()
        .add_observer(mark_xr_camera)
        .configure_sets(
            PostUpdate,
            DriveEyes.after(bevy_mod_openxr::render::update_views),
        );
        // The head's systems, written once over the geometry contract, per family.
        add_head_systems::<crate::space::Space>(app);
        add_head_systems::<crate::space::product::ProductSpace>(app);
        add_head_systems::<crate::space::nil::NilSpace>(app);
        add_head_systems::<crate::space::sl2r::UnitTangentSpace>(app);
        app.add_systems(
            Update,
            follow_display_rate
                .before(CurvedSpacesSystems::Move)
                .run_if(openxr_session_running),
        );
        app.add_oxr_event_handler(reanchor_on_recentre);
        if self.mirror {
            app.add_systems(Startup, spawn_mirror)
                .add_systems(PostUpdate, mirror_head.after(DriveEyes));
        }
    }
}

/// Where the eye cameras get their frames (after the runtime's views are read).
#[derive(SystemSet, Clone, Debug, PartialEq, Eq, Hash)]
struct DriveEyes;

/// The head's locomotion and eyes for the family `F`, run while its space is shown.
fn add_head_systems<F: FamilySpace>(app: &mut App) {
    let shown = ActiveSpace::shows(F::FAMILY);
    app.add_systems(
        Update,
        thumbstick_locomotion::<F>
            .after(reset_head_on_switch)
            .in_set(CurvedSpacesSystems::Move)
            .run_if(openxr_session_running)
            .run_if(shown.clone()),
    )
    .add_systems(
        PostUpdate,
        drive_eyes::<F>
            .in_set(DriveEyes)
            .run_if(openxr_session_running)
            .run_if(shown),
    );
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
fn reset_head_on_switch(active: Res<ActiveSpace>, bases: BaseScenes, head: Option<ResMut<XrHead>>) {
    if let Some(mut head) = head
        && active.is_changed()
        && !active.is_added()
    {
        head.0.frame = active.start_frame(&bases);
        head.0.holonomy = default();
    }
}

fn read_thumbsticks(
    actions: Option<Res<LocomotionActions>>,
    session: Option<Res<OxrSession>>,
    mut sticks: ResMut<XrSticks>,
) {
    let (Some(actions), Some(session)) = (actions, session) else {
        return;
    };
    let stick = |action: &openxr::Action<openxr::Vector2f>| {
        action
            .state(&session, openxr::Path::NULL)
            .ok()
            .filter(|s| s.is_active)
            .map(|s| Vec2::new(s.current_state.x, s.current_state.y))
    };
    let (walk, turn) = (stick(&actions.walk), stick(&actions.turn));
    *sticks = XrSticks {
        bound: walk.is_some() || turn.is_some(),
        walk: walk.unwrap_or_default(),
        turn: turn.unwrap_or_default(),
    };
}

fn thumbstick_locomotion<F: FamilySpace>(
    sticks: Res<XrSticks>,
    comfort: Res<XrComfort>,
    mut snap: ResMut<SnapHeld>,
    active: Res<ActiveSpace>,
    time: Res<Time>,
    head: Option<ResMut<XrHead>>,
) {
    let (Some(space), Some(mut head)) = (active.space.get::<F>(), head) else {
        return;
    };
    let dt = time.delta_secs_f64();
    // Stick up walks forward (−back), right strafes.
    let dead = |v: f32| {
        let v = f64::from(v);
        if v.abs() < DEAD_ZONE { 0.0 } else { v }
    };
    let step = DVec3::new(dead(sticks.walk.x), 0.0, -dead(sticks.walk.y))
        * comfort.speed
        * active.inradius
        * dt;
    let (yaw, snapped) = turn_yaw(
        comfort.turn,
        f64::from(sticks.turn.x),
        comfort.turn_speed,
        dt,
        snap.0,
    );
    if snap.0 != snapped {
        snap.0 = snapped;
    }
    if step != DVec3::ZERO || yaw != 0.0 {
        head.0.locomote(&**space, step, yaw);
    }
}

/// The headset display's period: the shortest frame period the runtime has predicted this
/// session. A runtime lengthens its prediction while the app misses frames (Monado to a
/// multiple of its display's period), so the latest one would let a slow app set its own
/// target; the shortest is the display's.
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct XrDisplayPeriod {
    /// Milliseconds; `None` before the first frame.
    pub ms: Option<f64>,
}

/// The frame-rate target at the headset's display rate.
fn follow_display_rate(
    frame: Option<Res<OxrFrameState>>,
    comfort: Res<XrComfort>,
    mut period: ResMut<XrDisplayPeriod>,
    mut target: ResMut<FrameRateTarget>,
) {
    let Some(frame) = frame else {
        return;
    };
    let predicted = frame.predicted_display_period.as_nanos() as f64 / 1e6;
    if !(predicted > 0.0 && predicted.is_finite()) {
        return;
    }
    let shortest = period.ms.map_or(predicted, |p| p.min(predicted));
    if period.ms != Some(shortest) {
        period.ms = Some(shortest);
    }
    if comfort.display_rate_target && target.target_ms != Some(shortest) {
        target.target_ms = Some(shortest);
    }
}

/// A recentre (or a change of the play area's bounds) moves the room's reference: the head
/// keeps its place in the space and continues from its next pose.
fn reanchor_on_recentre(event: OxrEventIn, head: Option<ResMut<XrHead>>) {
    if let openxr::Event::ReferenceSpaceChangePending(_) = *event
        && let Some(mut head) = head
    {
        head.0.reanchor();
    }
}

/// The headset's cameras become curved-space eyes as the OpenXR backend spawns them (before
/// any frame draws them as plain cameras).
fn mark_xr_camera(added: On<Add, XrCamera>, mut commands: Commands) {
    commands.entity(added.entity).insert((
        CurvedSpaceCamera::default(),
        CurvedSpaceEye {
            lens: Lens::symmetric(90.0, 1.0),
        },
    ));
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
#[allow(clippy::too_many_arguments)]
fn drive_eyes<F: FamilySpace>(
    views: Res<OxrViews>,
    active: Res<ActiveSpace>,
    bases: BaseScenes,
    stereo: Res<StereoSettings>,
    player: Res<PlayerSettings>,
    mut existing: Option<ResMut<XrHead>>,
    mut commands: Commands,
    mut eyes: Query<(&XrCamera, &mut PlayerFrame, &mut CurvedSpaceEye)>,
) {
    let Some(space) = active.space.get::<F>() else {
        return;
    };
    let space = &**space;
    let [left, right] = views.as_slice() else {
        return;
    };
    let poses = [room_pose(&left.pose), room_pose(&right.pose)];
    let head_pose = RoomPose::between(&poses[0], &poses[1]);
    let scale = stereo.units_per_metre(active.inradius);
    // The head is tracked in place; the first frame creates it at the space's start view.
    let mut created = None;
    let head = match existing.as_deref_mut() {
        Some(XrHead(tracker)) => tracker,
        None => {
            &mut created
                .insert(XrHead(HeadTracker::new(
                    active.start_frame(&bases),
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
