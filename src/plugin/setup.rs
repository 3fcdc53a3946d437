//! [`CurvedSpacesPlugin`]: one line to add curved spaces to a Bevy app; its `build` only
//! registers the resources, systems and render plugin of the modules beside it.
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

use crate::plugin::components::{
    ActiveSpace, BaseScene, BaseScenes, CurvedSpaceCamera, CurvedSpacesSystems, KeyBindings,
    MouseLook, PlayerFrame, PlayerSettings, Quality, SceneObjects, StereoSettings, TracerSettings,
    TracerStatus,
};
use crate::plugin::family::FamilyPlugin;
use crate::plugin::frame_rate::{BudgetShare, FrameRateTarget, hold_frame_rate};
use crate::plugin::player;
use crate::plugin::render::TracerRenderPlugin;
use crate::plugin::render::upload::upload_scene;
use crate::scene::SceneParts;
use crate::space::{DEFAULT_SPACE, Family};
use bevy::core_pipeline::tonemapping::{DebandDither, Tonemapping};
use bevy::prelude::*;

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
    /// What the automatic budget and the traced resolution aim for.
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
    /// Frames a second to hold by adapting the resolution scale within the quality's range
    /// ([`crate::plugin::frame_rate`]); `None` keeps the quality's scale (changeable at run time in
    /// [`FrameRateTarget`]).
    pub target_fps: Option<f64>,
    /// The teaching view to start with (changeable at run time in
    /// [`TracerSettings::colour_by`]).
    pub colour_by: crate::scene::ColourBy,
    /// The cell's walls to start with (changeable at run time in [`TracerSettings::walls`]).
    pub walls: Option<crate::scene::WallStyle>,
    /// The lighting to start with (changeable at run time in [`TracerSettings::lighting`]);
    /// `None`: the base scene's own, else the default.
    pub lighting: Option<crate::scene::lighting::Lighting>,
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
            target_fps: None,
            colour_by: crate::scene::ColourBy::Shading,
            walls: None,
            lighting: None,
        }
    }
}

impl Plugin for CurvedSpacesPlugin {
    fn build(&self, app: &mut App) {
        // A space inserted before the plugin (e.g. from a file) wins over `self.space`.
        if !app.world().contains_resource::<ActiveSpace>() {
            let active = ActiveSpace::named(&self.space).unwrap_or_else(|e| {
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
            colour_by: self.colour_by,
            walls: self.walls,
            lighting: self.lighting,
        })
        .insert_resource(self.stereo)
        .insert_resource(FrameRateTarget::fps(self.target_fps))
        .init_resource::<BudgetShare>()
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
                player::reset_players_on_switch.in_set(CurvedSpacesSystems::Move),
                #[cfg(feature = "scene-files")]
                (
                    (
                        crate::plugin::flight::replay_flight::<crate::scene::flight::Flight>,
                        crate::plugin::flight::replay_flight::<
                            crate::trace::product::flight::ProductFlight,
                        >,
                        crate::plugin::flight::replay_flight::<crate::trace::nil::flight::NilFlight>,
                        crate::plugin::flight::replay_flight::<
                            crate::trace::sl2r::flight::Sl2rFlight,
                        >,
                    ),
                    crate::plugin::flight::record_flight,
                )
                    .chain()
                    .after(CurvedSpacesSystems::Wrap)
                    .before(CurvedSpacesSystems::Upload),
                (
                    upload_scene
                        .after(crate::plugin::objects::collect_objects)
                        .run_if(ActiveSpace::shows(Family::Constant)),
                    crate::plugin::product::upload_product_scene
                        .after(
                            crate::plugin::objects::gather::collect_entity_objects::<
                                crate::space::product::ProductSpace,
                            >,
                        )
                        .run_if(ActiveSpace::shows(Family::Product)),
                    crate::plugin::sl2r::upload_sl2r_scene
                        .run_if(ActiveSpace::shows(Family::Sl2r)),
                    crate::plugin::nil::upload_nil_scene
                        .after(
                            crate::plugin::objects::gather::collect_entity_objects::<
                                crate::space::nil::NilSpace,
                            >,
                        )
                        .run_if(ActiveSpace::shows(Family::Nil)),
                    check_stereo_settings,
                )
                    .in_set(CurvedSpacesSystems::Upload),
                hold_frame_rate.before(CurvedSpacesSystems::Upload),
            ),
        )
        .add_observer(start_camera)
        // The systems written once over the geometry contract, one set per family.
        .add_plugins((
            FamilyPlugin::<crate::space::Space>::default(),
            FamilyPlugin::<crate::space::product::ProductSpace>::default(),
            FamilyPlugin::<crate::space::nil::NilSpace>::default(),
            FamilyPlugin::<crate::space::sl2r::UnitTangentSpace>::default(),
        ));
        #[cfg(feature = "scene-files")]
        app.add_systems(Last, crate::plugin::flight::finish_recording);
        crate::plugin::objects::add_systems(app);
        if self.controls {
            app.add_systems(
                Update,
                (player::grab_cursor, player::read_input)
                    .chain()
                    .in_set(CurvedSpacesSystems::Input),
            );
        }
        if self.ui {
            #[cfg(feature = "ui")]
            app.add_plugins(crate::plugin::ui::CurvedSpacesUiPlugin);
            #[cfg(not(feature = "ui"))]
            warn!(
                "CurvedSpacesPlugin::ui is set, but bevy_curved_spaces was built without its `ui` feature: no panel"
            );
        }
        if app.is_plugin_added::<bevy::render::RenderPlugin>() {
            app.add_plugins(TracerRenderPlugin);
        }
    }

    fn finish(&self, app: &mut App) {
        crate::plugin::objects::finish(app);
    }
}

/// A new curved-space camera starts at the space's default view and draws only the tracer.
fn start_camera(
    add: On<Add, CurvedSpaceCamera>,
    active: Option<Res<ActiveSpace>>,
    bases: BaseScenes,
    mut commands: Commands,
    frames: Query<&PlayerFrame>,
) {
    let mut entity = commands.entity(add.entity);
    let start = active.as_ref().map(|a| a.start_frame(&bases));
    if let Some(start) = start
        && frames
            .get(add.entity)
            .is_ok_and(|f| *f == PlayerFrame::default())
    {
        entity.insert(PlayerFrame(start));
    }
    // The scene's start view includes its field of view.
    if let Some(fov) = active.as_ref().and_then(|a| bases.start_fov(a)) {
        entity.insert(CurvedSpaceCamera { fov_y_degrees: fov });
    }
    // The tracer writes final colours: no anti-aliasing, tonemapping or dithering on top.
    entity.insert((Msaa::Off, Tonemapping::None, DebandDither::Disabled));
}

/// Reports an eye distance that cannot be used (the tracer falls back to the default).
fn check_stereo_settings(
    stereo: Res<StereoSettings>,
    active: Option<Res<ActiveSpace>>,
    mut status: ResMut<TracerStatus>,
) {
    let Some((inradius, changed)) = active.map(|a| (a.inradius, a.is_changed())) else {
        return;
    };
    if !stereo.is_changed() && !changed {
        return;
    }
    let problem = stereo
        .ipd
        .and_then(|ipd| crate::view::stereo::check_ipd(ipd, inradius).err())
        .map(|e| format!("{e}; using the default eye distance"));
    if let Some(p) = &problem {
        warn!("{p}");
    }
    status.stereo_error = problem;
}
