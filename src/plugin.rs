//! [`CurvedSpacesPlugin`]: one line to add curved spaces to a Bevy app.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::prelude::*;
//!
//! App::new()
//!     .add_plugins((DefaultPlugins, CurvedSpacesPlugin::default()))
//!     .add_systems(Startup, |mut commands: Commands| {
//!         // An ordinary 3D camera that shows the curved space.
//!         commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
//!     })
//!     .run();
//! ```

use crate::player::{
    self, Holonomy, KeyBindings, MouseLook, PlayerFrame, PlayerMotion, PlayerSettings,
};
use crate::render::{PreparedScene, TracerRenderPlugin, gpu::GpuScene};
use crate::space::{Space, SpaceError, invariants, seed_space};
use crate::stereo::StereoSettings;
use crate::trace::{
    BudgetChoice, Camera as TraceCamera, Object, Scene, SceneParts, Shading, auto_budget,
};
use bevy::core_pipeline::tonemapping::{DebandDither, Tonemapping};
use bevy::prelude::*;
use glam::DMat4;
use std::sync::Arc;

/// The seed space shown when nothing else is chosen.
pub const DEFAULT_SPACE: &str = "seifert-weber";

/// Speed against accuracy presets: how many rays the automatic crossing budget may leave
/// short (shown as fog instead of a far object) and the fraction of the window's resolution
/// that is traced.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Quality {
    /// Budget short for at most 2 % of rays, half resolution.
    Low,
    /// Budget short for at most 0.5 % of rays, three quarters of the resolution.
    #[default]
    Medium,
    /// Budget enough for every sampled ray, full resolution.
    High,
}

impl Quality {
    /// The fraction of sampled rays the automatic budget may leave short. Such a ray shows
    /// the fog colour instead of an object seen at distance `d`, an error of at most its fog
    /// weight `e^(−d/λ)`.
    #[must_use]
    pub fn miss_fraction(self) -> f64 {
        match self {
            Quality::Low => 0.02,
            Quality::Medium => 0.005,
            Quality::High => 0.0,
        }
    }

    /// The fraction of the view's resolution that is traced.
    #[must_use]
    pub fn resolution_scale(self) -> f32 {
        match self {
            Quality::Low => 0.5,
            Quality::Medium => 0.75,
            Quality::High => 1.0,
        }
    }

    pub const ALL: [Quality; 3] = [Quality::Low, Quality::Medium, Quality::High];
}

/// Rays sampled to choose the automatic crossing budget (a few ms to 0.1 s of CPU time when
/// the space, the fog or the scene changes).
pub const AUTO_BUDGET_SAMPLES: usize = 2048;

/// Adds curved spaces to an app: the GPU tracer behind every [`CurvedSpaceCamera`], the
/// first-person controls and (optionally) the egui panel.
#[derive(Clone, Debug)]
pub struct CurvedSpacesPlugin {
    /// The seed space to start in (see [`crate::space::SEED_SPACES`]).
    pub space: String,
    /// Fog distance scale λ; `None` for the space's default (three inradii).
    pub fog_distance: Option<f64>,
    /// Crossing budget per ray; `None` to choose it from the fog distance and the scene
    /// (see [`Quality::miss_fraction`]).
    pub max_crossings: Option<u32>,
    pub quality: Quality,
    /// Built-in first-person controls (WASD, mouse look, Q/E roll, Space/Shift, scroll).
    pub controls: bool,
    /// The egui panel (toggled with F1; needs a window).
    pub ui: bool,
    /// Stereo mode and eye distance at start ([`StereoSettings`], changeable at run time).
    pub stereo: StereoSettings,
    /// Draw the player's ship where rays come back round the space (toggle it at run time
    /// in [`TracerSettings::parts`]).
    pub avatar: bool,
}

impl Default for CurvedSpacesPlugin {
    fn default() -> Self {
        Self {
            space: DEFAULT_SPACE.into(),
            fog_distance: None,
            max_crossings: None,
            quality: Quality::default(),
            controls: true,
            ui: false,
            stereo: StereoSettings::default(),
            avatar: true,
        }
    }
}

/// Our systems, in the order they run in `Update`; order your own around them.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CurvedSpacesSystems {
    /// Keys, mouse and scroll become each player's [`PlayerMotion`].
    Input,
    /// Motions are applied to the frames (and a space switch resets them).
    Move,
    /// Frames that left the cell are wrapped through faces ([`Holonomy`]).
    Wrap,
    /// The space and scene are packed for the GPU when they changed.
    Upload,
}

/// A camera that shows the curved space: add it to an ordinary `Camera3d`.
///
/// Its position and orientation in the space are its [`PlayerFrame`]; the camera's
/// `Transform` is not used.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
#[require(PlayerFrame, Holonomy, PlayerMotion)]
pub struct CurvedSpaceCamera {
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

impl Default for CurvedSpaceCamera {
    fn default() -> Self {
        Self {
            fov_y_degrees: 70.0,
        }
    }
}

/// The space every curved-space camera shows. Replace it (or use [`ActiveSpace::seed`]) to
/// switch spaces at run time: the players are put back at the space's start view.
#[derive(Resource, Clone, Debug)]
pub struct ActiveSpace {
    /// The seed id or the file the space came from.
    pub id: String,
    pub space: Arc<Space>,
    pub volume: f64,
    pub inradius: f64,
    /// `None` where the group was too large to enumerate.
    pub injectivity_radius: Option<f64>,
}

impl ActiveSpace {
    /// A space with its read-outs computed.
    #[must_use]
    pub fn new(id: impl Into<String>, space: Space) -> Self {
        Self {
            id: id.into(),
            volume: invariants::volume(&space),
            inradius: invariants::inradius(&space),
            injectivity_radius: invariants::injectivity_radius(&space),
            space: Arc::new(space),
        }
    }

    /// One of the seed spaces by id.
    pub fn seed(id: &str) -> Result<Self, SpaceError> {
        Ok(Self::new(id, seed_space(id)?))
    }
}

/// The tracer's knobs, changeable at run time.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct TracerSettings {
    /// Fog distance scale λ; `None` for the space's default.
    pub fog_distance: Option<f64>,
    /// Crossing budget per ray; `None` for the automatic budget of `quality`.
    pub max_crossings: Option<u32>,
    /// What the automatic budget aims for.
    pub quality: Quality,
    /// Fraction of the view's resolution that is traced (then scaled up), in (0, 1].
    pub resolution_scale: f32,
    pub parts: SceneParts,
    /// The scene's clock in seconds (spinning globes); `None` follows the app's [`Time`].
    /// Fixed for still pictures that must match a CPU render.
    pub time: Option<f64>,
}

impl TracerSettings {
    /// The fog distance in use for a space.
    #[must_use]
    pub fn fog_for(&self, space: &Space) -> f64 {
        self.fog_distance
            .unwrap_or_else(|| Shading::default_fog_distance(space))
    }
}

/// Your own objects in the curved space, added to the default scene parts: metric balls and
/// geodesic tubes with their centres inside the cell (`trace::Ball::new`, `trace::Tube::new`
/// in model coordinates). One that sticks out through faces is drawn through its images
/// under the pairings that meet the cell ([`Scene::place`]), so it looks whole from every
/// side. A misplaced object is reported in [`TracerStatus::error`] and left out.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct SceneObjects(pub Vec<Object>);

/// A scene to show instead of the default one, such as a loaded scene file
/// ([`crate::scene::file::load_scene_file`], [`BaseScene::from_file`]): used while the
/// active space's id is `space_id`, with the default parts of [`TracerSettings::parts`] and
/// the [`SceneObjects`] added to it. Its start view is where players start, and `parts` is
/// what the plugin starts [`TracerSettings::parts`] with.
#[derive(Resource, Clone, Debug, Default)]
pub struct BaseScene {
    pub space_id: String,
    /// Its objects, lights and shading, without the default parts.
    pub scene: Option<Arc<Scene>>,
    pub start: Option<DMat4>,
    pub parts: Option<SceneParts>,
}

impl BaseScene {
    /// A loaded scene file as the base scene.
    #[must_use]
    pub fn from_file(file: &crate::scene::file::SceneFile) -> Self {
        Self {
            space_id: file.space_id.clone(),
            scene: Some(Arc::new(file.base.clone())),
            start: file.start,
            parts: Some(file.parts),
        }
    }
}

impl BaseScene {
    /// The base scene for the active space, if it is the one the scene was made for.
    #[must_use]
    pub fn for_space(&self, active: &ActiveSpace) -> Option<&Scene> {
        self.scene.as_deref().filter(|_| active.id == self.space_id)
    }

    /// Where players start in the active space.
    #[must_use]
    pub fn start_frame(&self, active: &ActiveSpace) -> DMat4 {
        self.start
            .filter(|_| active.id == self.space_id)
            .unwrap_or_else(|| TraceCamera::default_for(&active.space).frame)
    }
}

/// The last problem the tracer had with the scene (shown in the UI), if any.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct TracerStatus {
    pub error: Option<String>,
    /// The crossing budget in use.
    pub budget: u32,
    /// How the automatic budget was chosen (`None` when the budget is fixed).
    pub auto_budget: Option<BudgetChoice>,
    /// What is wrong with the [`StereoSettings`], if anything (the default eye distance is
    /// used meanwhile).
    pub stereo_error: Option<String>,
}

impl Plugin for CurvedSpacesPlugin {
    fn build(&self, app: &mut App) {
        // A space inserted before the plugin (e.g. from a file) wins over `self.space`.
        if !app.world().contains_resource::<ActiveSpace>() {
            let active = ActiveSpace::seed(&self.space).unwrap_or_else(|e| {
                error!("{e}; starting in {DEFAULT_SPACE} instead");
                ActiveSpace::seed(DEFAULT_SPACE).expect("the default seed space is valid")
            });
            app.insert_resource(active);
        }
        app.insert_resource(TracerSettings {
            fog_distance: self.fog_distance,
            max_crossings: self.max_crossings.map(|b| b.max(1)),
            quality: self.quality,
            resolution_scale: self.quality.resolution_scale(),
            parts: app
                .world()
                .get_resource::<BaseScene>()
                .and_then(|b| b.parts)
                .map_or(
                    SceneParts {
                        avatar: self.avatar,
                        ..SceneParts::default()
                    },
                    |p| SceneParts {
                        avatar: p.avatar && self.avatar,
                        ..p
                    },
                ),
            time: None,
        })
        .insert_resource(self.stereo)
        .init_resource::<TracerStatus>()
        .init_resource::<SceneObjects>()
        .init_resource::<BaseScene>()
        .init_resource::<PlayerSettings>()
        .init_resource::<KeyBindings>()
        .init_resource::<MouseLook>()
        .configure_sets(
            Update,
            (
                CurvedSpacesSystems::Input,
                CurvedSpacesSystems::Move,
                CurvedSpacesSystems::Wrap,
                CurvedSpacesSystems::Upload,
            )
                .chain(),
        )
        .add_systems(
            Update,
            (
                (reset_players_on_switch, player::move_players)
                    .chain()
                    .in_set(CurvedSpacesSystems::Move),
                player::wrap_players.in_set(CurvedSpacesSystems::Wrap),
                (upload_scene, check_stereo_settings).in_set(CurvedSpacesSystems::Upload),
            ),
        )
        .add_observer(start_camera);
        if self.controls {
            app.add_systems(
                Update,
                (player::grab_cursor, player::read_input)
                    .chain()
                    .in_set(CurvedSpacesSystems::Input),
            );
        }
        if self.ui {
            app.add_plugins(crate::ui::CurvedSpacesUiPlugin);
        }
        if app.is_plugin_added::<bevy::render::RenderPlugin>() {
            app.add_plugins(TracerRenderPlugin);
        }
    }
}

/// A new curved-space camera starts at the space's default view and draws only the tracer.
fn start_camera(
    add: On<Add, CurvedSpaceCamera>,
    active: Res<ActiveSpace>,
    base: Res<BaseScene>,
    mut commands: Commands,
    frames: Query<&PlayerFrame>,
) {
    let mut entity = commands.entity(add.entity);
    if frames
        .get(add.entity)
        .is_ok_and(|f| *f == PlayerFrame::default())
    {
        entity.insert(PlayerFrame(base.start_frame(&active)));
    }
    // The tracer writes final colours: no anti-aliasing, tonemapping or dithering on top.
    entity.insert((Msaa::Off, Tonemapping::None, DebandDither::Disabled));
}

fn reset_players_on_switch(
    active: Res<ActiveSpace>,
    base: Res<BaseScene>,
    mut players: Query<(&mut PlayerFrame, &mut Holonomy)>,
) {
    if !active.is_changed() || active.is_added() {
        return;
    }
    let start = base.start_frame(&active);
    for (mut frame, mut holonomy) in &mut players {
        frame.0 = start;
        *holonomy = Holonomy::default();
    }
}

/// Reports an eye distance that cannot be used (the tracer falls back to the default).
fn check_stereo_settings(
    stereo: Res<StereoSettings>,
    active: Res<ActiveSpace>,
    mut status: ResMut<TracerStatus>,
) {
    if !stereo.is_changed() && !active.is_changed() {
        return;
    }
    let problem = stereo
        .ipd
        .and_then(|ipd| crate::stereo::check_ipd(ipd, active.inradius).err())
        .map(|e| format!("{e}; using the default eye distance"));
    if let Some(p) = &problem {
        warn!("{p}");
    }
    status.stereo_error = problem;
}

/// The scene the tracer shows: the base scene (or the default parts) and the user's objects
/// with their images; the avatar as [`SceneParts::avatar`] says. Objects that cannot be
/// placed are left out and described in the returned message.
#[must_use]
pub fn build_scene(
    space: &Space,
    settings: &TracerSettings,
    objects: &[Object],
    base: Option<&Scene>,
) -> (Scene, Option<String>) {
    let mut scene = match base {
        Some(b) => {
            let mut scene = b.adding_parts(space, settings.parts);
            if let Some(fog) = settings.fog_distance {
                scene.shading.fog_distance = fog;
            }
            scene
        }
        None => Scene::with_parts(space, settings.fog_for(space), settings.parts),
    };
    let problems: Vec<String> = objects
        .iter()
        .enumerate()
        .filter_map(|(i, o)| {
            scene
                .place(space, *o)
                .err()
                .map(|e| format!("scene object {i}: {e}"))
        })
        .collect();
    for p in &problems {
        warn!("{p}");
    }
    (scene, (!problems.is_empty()).then(|| problems.join("; ")))
}

/// The automatic budget last chosen and what it was chosen for.
struct BudgetCache {
    space: Arc<Space>,
    scene: Scene,
    quality: Quality,
    choice: BudgetChoice,
}

/// Packs the scene for the GPU when the space, the settings or the objects changed.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
fn upload_scene(
    active: Res<ActiveSpace>,
    settings: Res<TracerSettings>,
    objects: Res<SceneObjects>,
    base: Res<BaseScene>,
    mut status: ResMut<TracerStatus>,
    prepared: Option<Res<PreparedScene>>,
    mut last_choice: Local<Option<BudgetCache>>,
    mut commands: Commands,
) {
    if prepared.is_some()
        && !active.is_changed()
        && !settings.is_changed()
        && !objects.is_changed()
        && !base.is_changed()
    {
        return;
    }
    let space = &active.space;
    let (scene, problems) = build_scene(space, &settings, &objects.0, base.for_space(&active));
    // The automatic budget depends on the space, the scene and the quality only: a change
    // of the resolution scale or a fixed budget's toggling does not sample rays again.
    let auto = settings.max_crossings.is_none().then(|| {
        let quality = settings.quality;
        match last_choice.as_ref() {
            Some(c) if Arc::ptr_eq(&c.space, space) && c.scene == scene && c.quality == quality => {
                c.choice
            }
            _ => {
                let choice =
                    auto_budget(space, &scene, quality.miss_fraction(), AUTO_BUDGET_SAMPLES);
                *last_choice = Some(BudgetCache {
                    space: space.clone(),
                    scene: scene.clone(),
                    quality,
                    choice,
                });
                choice
            }
        }
    });
    let budget = settings
        .max_crossings
        .or(auto.map(|a| a.budget))
        .unwrap_or(1);
    match GpuScene::new(space, &scene, budget) {
        Ok(gpu) => {
            commands.insert_resource(PreparedScene(Arc::new(gpu)));
            status.error = problems;
            status.budget = budget;
            status.auto_budget = auto;
        }
        Err(e) => {
            error!("{e}");
            status.error = Some(e.to_string());
        }
    }
}
