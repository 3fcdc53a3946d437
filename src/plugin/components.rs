//! The ECS state the plugin shares: the components on curved-space cameras and the
//! resources that configure and report on the tracer. Everything Bevy-facing that more than
//! one of the player, render and UI systems reads lives here, so those modules depend on this
//! one and not on each other.

use crate::scene::{CurvedScene, Object, SceneParts, Shading};
use crate::space::product::ProductSpace;
use crate::space::{AnySpace, Family, Holonomy, Space, SpaceError, seed_space};
use crate::trace::BudgetChoice;
use crate::view::stereo::{HUMAN_IPD_METRES, StereoMode, check_ipd, default_ipd};
use crate::view::{Lens, TraceCamera};
use bevy::ecs::component::{Mutable, StorageType};
use bevy::prelude::*;
use glam::{DMat4, DVec3};
use std::sync::Arc;

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

    /// The fraction of sampled rays the crossing budget may leave short at the least, when
    /// a frame-rate target lowers it ([`crate::plugin::frame_rate::BudgetShare`]) after the
    /// resolution scale reached its floor: the next lower quality's fraction (5 % for
    /// `Low`).
    #[must_use]
    pub fn floor_miss_fraction(self) -> f64 {
        match self {
            Quality::Low => 0.05,
            Quality::Medium => Quality::Low.miss_fraction(),
            Quality::High => Quality::Medium.miss_fraction(),
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

    /// The most lamp images walked for shadows per lit point and lamp: a scene's or the
    /// settings' `shadows` above it is lowered to it, and the images past it are lit
    /// unshadowed. The first shadowed image costs the most (a shadow walk per lit pixel:
    /// 10–30 times the frame with four of them, in `bench --lighting`), so `Low` walks
    /// none; `Medium` walks 4, which leaves the Poincaré space's default view 0.9/255 of
    /// mean error more than 16 do; `High` keeps what was asked for.
    #[must_use]
    pub fn max_shadows(self) -> u32 {
        match self {
            Quality::Low => 0,
            Quality::Medium => 4,
            Quality::High => crate::scene::lighting::Lighting::MAX_SHADOWS,
        }
    }

    /// Every preset, lowest first.
    pub const ALL: [Quality; 3] = [Quality::Low, Quality::Medium, Quality::High];
}

/// Rays sampled to choose the automatic crossing budget (a few ms to 0.1 s of CPU time when
/// the space, the fog or the scene changes).
pub const AUTO_BUDGET_SAMPLES: usize = 2048;

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

/// The space every curved-space camera shows, of whichever geometry family: a
/// constant-curvature space (E³, S³, H³) or a product space (H²×R, S²×R). Replace it (or use
/// [`ActiveSpace::seed`], [`ActiveSpace::named`]) to switch spaces at run time: the players
/// are put back at the space's start view. The plugin's systems for each family run while it
/// holds a space of that family ([`ActiveSpace::shows`]).
#[derive(Resource, Clone, Debug)]
pub struct ActiveSpace {
    /// The seed id or the file the space came from.
    pub id: String,
    /// The validated space.
    pub space: AnySpace,
    /// Its volume.
    pub volume: f64,
    /// A length of the cell's size ([`AnySpace::scale`]: the cell's inradius; a product's
    /// smaller of its polygon's inradius and half its circle): the default fog, the walking
    /// speed and the eye distance scale with it.
    pub inradius: f64,
    /// `None` where the group was too large to enumerate.
    pub injectivity_radius: Option<f64>,
}

impl ActiveSpace {
    /// A space of any family with its read-outs computed.
    #[must_use]
    pub fn new(id: impl Into<String>, space: impl Into<AnySpace>) -> Self {
        let space = space.into();
        Self {
            id: id.into(),
            volume: space.volume(),
            inradius: space.scale(),
            injectivity_radius: space.injectivity_radius(),
            space,
        }
    }

    /// One of the seed spaces by id.
    pub fn seed(id: &str) -> Result<Self, SpaceError> {
        Ok(Self::new(id, seed_space(id)?))
    }

    /// A space by name, as the command line takes it, of any family: a seed space, a library
    /// family member (`lens-7-2`, `weeks`), a product space (`bitorus-circle`,
    /// `surface-abABcdCD-circle-2`) or a path to a space file (`.gen` or JSON). Slow for spaces
    /// from large groups (a census manifold takes a fraction of a second in a release build).
    pub fn named(id: &str) -> Result<Self, String> {
        let space = AnySpace::named(id)?;
        // The plugin shows only the families it can draw.
        space
            .supports(crate::space::Feature::Pictures)
            .map_err(|e| format!("{id}: {e}"))?;
        Ok(Self::new(id, space))
    }

    /// The space's family.
    #[must_use]
    pub fn family(&self) -> Family {
        self.space.family()
    }

    /// The constant-curvature space shown, if the space is one.
    #[must_use]
    pub fn constant(&self) -> Option<&Arc<Space>> {
        self.space.constant()
    }

    /// The product space shown, if the space is one.
    #[must_use]
    pub fn product(&self) -> Option<&Arc<ProductSpace>> {
        self.space.product()
    }

    /// Where players start in this space: the base scene's start view where it was made for
    /// this space ([`BaseScenes::start_frame`]), else the space's default view.
    #[must_use]
    pub fn start_frame(&self, bases: &BaseScenes) -> DMat4 {
        bases.start_frame(self)
    }

    /// A run condition: whether the active space is of `family` (the plugin's systems of a
    /// family run under it).
    pub fn shows(family: Family) -> impl Fn(Option<Res<ActiveSpace>>) -> bool + Clone {
        move |active: Option<Res<ActiveSpace>>| active.is_some_and(|a| a.family() == family)
    }
}

/// The base scenes of every family, as one system parameter: where players start and with
/// which field of view, for whichever family the active space is of.
#[derive(bevy::ecs::system::SystemParam)]
pub struct BaseScenes<'w> {
    /// The constant-curvature base scene.
    pub constant: Res<'w, BaseScene>,
    /// The product spaces' base scene, where a game set one.
    pub product: Option<Res<'w, BaseProductScene>>,
    /// The Nil spaces' base scene, where a game set one.
    pub nil: Option<Res<'w, BaseNilScene>>,
    /// The SL̃(2,R) spaces' base scene, where a game set one.
    pub sl2r: Option<Res<'w, BaseSl2rScene>>,
}

impl BaseScenes<'_> {
    /// Where players start in `active`: the base scene's start view where it was made for
    /// this family ([`BaseScene::start_frame`], [`BaseProductScene::start_frame`],
    /// [`BaseNilScene::start_frame`]), else the space's default view.
    #[must_use]
    pub fn start_frame(&self, active: &ActiveSpace) -> DMat4 {
        match &active.space {
            AnySpace::Constant(s) => self.constant.start_frame(active, s),
            AnySpace::Product(p) => BaseProductScene::start_frame(self.product.as_deref(), p),
            AnySpace::Nil(n) => BaseNilScene::start_frame(self.nil.as_deref(), n),
            AnySpace::Sl2r(s) => BaseSl2rScene::start_frame(self.sl2r.as_deref(), s),
        }
    }

    /// The start view's field of view, where the base scene of the active family sets one.
    #[must_use]
    pub fn start_fov(&self, active: &ActiveSpace) -> Option<f64> {
        match &active.space {
            AnySpace::Constant(_) => self
                .constant
                .fov
                .filter(|_| active.id == self.constant.space_id),
            AnySpace::Product(_) => self
                .product
                .as_ref()
                .and_then(|b| b.start)
                .map(|c| c.fov_y_degrees),
            AnySpace::Nil(_) => self
                .nil
                .as_ref()
                .and_then(|b| b.start)
                .map(|c| c.fov_y_degrees),
            AnySpace::Sl2r(_) => self
                .sl2r
                .as_ref()
                .and_then(|b| b.start)
                .map(|c| c.fov_y_degrees),
        }
    }
}

/// The scene shown in an SL̃(2,R) space instead of its default one, and where players start.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct BaseSl2rScene {
    /// The scene.
    pub scene: crate::trace::sl2r::Sl2rScene,
    /// The start view (`None`: the space's default camera).
    pub start: Option<crate::trace::sl2r::Sl2rCamera>,
}

impl BaseSl2rScene {
    /// Where players start in `space`: the base scene's start view, else the default one.
    #[must_use]
    pub fn start_frame(base: Option<&Self>, space: &crate::space::sl2r::UnitTangentSpace) -> DMat4 {
        base.and_then(|b| b.start)
            .unwrap_or_else(|| crate::trace::sl2r::default_camera(space))
            .frame
    }
}

/// The scene shown in a Nil space instead of its default one, and where players start.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct BaseNilScene {
    /// The scene.
    pub scene: crate::trace::nil::NilScene,
    /// The start view (`None`: the space's default camera).
    pub start: Option<crate::trace::nil::NilCamera>,
    /// Balls that move (placed at the app's clock each frame, with their lattice images).
    pub moving: Vec<crate::trace::nil::moving::NilMover>,
}

impl BaseNilScene {
    /// A Nil scene file's scene, start view and moving balls.
    #[cfg(feature = "scene-files")]
    #[must_use]
    pub fn from_file(file: &crate::trace::nil::file::NilSceneFile) -> Self {
        Self {
            scene: file.scene.clone(),
            start: file.start,
            moving: file.moving.clone(),
        }
    }

    /// Where players start in `space`: the base scene's start view, else the default one.
    #[must_use]
    pub fn start_frame(base: Option<&Self>, space: &crate::space::nil::NilSpace) -> DMat4 {
        base.and_then(|b| b.start)
            .unwrap_or_else(|| crate::trace::nil::default_camera(space))
            .frame
    }
}

/// The scene shown in a product space instead of its default one
/// ([`crate::trace::product::default_scene`]), and where players start; the fog of
/// [`TracerSettings::fog_distance`] still applies where it is set.
#[derive(Resource, Clone, Debug, PartialEq)]
pub struct BaseProductScene {
    /// The scene.
    pub scene: crate::trace::product::ProductScene,
    /// The start view (`None`: the space's default camera).
    pub start: Option<crate::trace::product::ProductCamera>,
    /// Balls that move (a product scene file's balls with a `velocity`): while the scene is
    /// shown the plugin spawns each as an entity that flies from its start through the
    /// faces.
    pub moving: Vec<crate::trace::product::moving::ProductMover>,
}

impl BaseProductScene {
    /// A scene, players starting at the space's default view.
    #[must_use]
    pub fn new(scene: crate::trace::product::ProductScene) -> Self {
        Self {
            scene,
            start: None,
            moving: Vec::new(),
        }
    }

    /// A product scene file's scene, start view and moving balls.
    #[cfg(feature = "scene-files")]
    #[must_use]
    pub fn from_file(file: &crate::trace::product::file::ProductSceneFile) -> Self {
        Self {
            scene: file.scene.clone(),
            start: file.start,
            moving: file.moving.clone(),
        }
    }

    /// This base scene with its moving balls fixed where they are at `time` seconds (a
    /// still picture, or a flight's frame): no entities are spawned for them.
    pub fn at_time(
        &self,
        space: &ProductSpace,
        time: f64,
    ) -> Result<Self, crate::space::motion::MotionError> {
        let mut scene = self.scene.clone();
        scene
            .objects
            .extend(crate::trace::product::moving::movers_at(
                space,
                &self.moving,
                time,
            )?);
        Ok(Self {
            scene,
            start: self.start,
            moving: Vec::new(),
        })
    }

    /// Where players start in `space`: the scene's start view, else the default camera of
    /// the space's default scene ([`crate::trace::product::default_camera`]).
    #[must_use]
    pub fn start_frame(base: Option<&Self>, space: &ProductSpace) -> DMat4 {
        let camera = base
            .and_then(|b| b.start)
            .unwrap_or_else(|| crate::trace::product::default_camera(space));
        crate::space::product::motion::camera_frame(camera.point, camera.frame)
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
    /// Which parts of the default scene show (edges, centre ball, your ship).
    pub parts: SceneParts,
    /// The scene's clock in seconds (spinning globes); `None` follows the app's [`Time`].
    /// Fixed for still pictures that must match a CPU render.
    pub time: Option<f64>,
    /// What surfaces are coloured by over their shading (the teaching views).
    pub colour_by: crate::scene::ColourBy,
    /// The cell's walls with windows ([`crate::scene::walls`]); `None`: the base scene's
    /// own (a scene file's `walls`; none in the default scene). An opening of 1 shows no
    /// walls, whatever the base scene says.
    pub walls: Option<crate::scene::WallStyle>,
    /// How the lamps light the scene ([`crate::scene::lighting`]: every image or the nearest
    /// copy, how far, the tail, how many shadows); `None`: the base scene's own (a scene
    /// file's `[lighting]`), else [`Lighting::default`](crate::scene::lighting::Lighting).
    /// The product spaces light by the nearest copy whatever this says.
    pub lighting: Option<crate::scene::lighting::Lighting>,
}

impl TracerSettings {
    /// The fog distance in use: the one set here, else the base scene's own (a scene file's
    /// `fog`), else the space's default ([`Shading::default_fog_distance`]). The one rule for
    /// it: the tracer, the panel and offscreen renders all ask here.
    #[must_use]
    pub fn fog_for(&self, space: &Space, base: Option<&CurvedScene>) -> f64 {
        self.fog_distance
            .or(base.map(|b| b.shading.fog_distance))
            .unwrap_or_else(|| Shading::default_fog_distance(space))
    }
}

/// Your own objects in the curved space, added to the default scene parts: metric balls and
/// geodesic tubes with their centres inside the cell (`trace::Ball::new`, `trace::Tube::new`
/// in model coordinates). One that sticks out through faces is drawn through its images
/// under the pairings that meet the cell ([`CurvedScene::place`]), so it looks whole from every
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
    /// The id of the space the scene was made for.
    pub space_id: String,
    /// Its objects, lights and shading, without the default parts.
    pub scene: Option<Arc<CurvedScene>>,
    /// Where players start (a frame), if the scene says.
    pub start: Option<DMat4>,
    /// The start view's vertical field of view (degrees), if the scene says: new
    /// [`CurvedSpaceCamera`]s take it.
    pub fov: Option<f64>,
    /// The parts the plugin starts [`TracerSettings::parts`] with, if the scene says.
    pub parts: Option<SceneParts>,
    /// Objects that move (a scene file's objects with a `velocity`): while the scene is in
    /// use the plugin spawns each as an entity ([`crate::plugin::objects`]) that flies from its
    /// start through the faces.
    pub moving: Vec<crate::scene::MovingObject>,
}

impl BaseScene {
    /// A loaded scene file as the base scene.
    #[cfg(feature = "scene-files")]
    #[must_use]
    pub fn from_file(file: &crate::scene::file::SceneFile) -> Self {
        Self {
            space_id: file.space_id.clone(),
            scene: Some(Arc::new(file.base.clone())),
            start: file.start,
            fov: file.start_fov,
            parts: Some(file.parts),
            moving: file.moving.clone(),
        }
    }

    /// This base scene with its moving objects fixed where they are at `time` seconds (a
    /// still picture, or a flight's frame): no entities are spawned for them.
    pub fn at_time(&self, space: &Space, time: f64) -> Result<Self, crate::scene::MovingError> {
        if self.moving.is_empty() {
            return Ok(self.clone());
        }
        let scene = match &self.scene {
            Some(s) => Some(Arc::new(s.with_moving_at(space, &self.moving, time)?)),
            None => None,
        };
        Ok(Self {
            scene,
            moving: Vec::new(),
            ..self.clone()
        })
    }

    /// The base scene for the active space, if it is the one the scene was made for.
    #[must_use]
    pub fn for_space(&self, active: &ActiveSpace) -> Option<&CurvedScene> {
        self.scene.as_deref().filter(|_| active.id == self.space_id)
    }

    /// Where players start in the active constant-curvature space `space`.
    #[must_use]
    pub fn start_frame(&self, active: &ActiveSpace, space: &Space) -> DMat4 {
        self.start
            .filter(|_| active.id == self.space_id)
            .unwrap_or_else(|| TraceCamera::default_for(space).frame)
    }
}

/// The last problem the tracer had with the scene (shown in the UI), if any.
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct TracerStatus {
    /// What is wrong with the scene or its objects, if anything.
    pub error: Option<String>,
    /// The crossing budget in use.
    pub budget: u32,
    /// The fog distance λ in use ([`TracerSettings::fog_for`]).
    pub fog_distance: f64,
    /// How the automatic budget was chosen (`None` when the budget is fixed).
    pub auto_budget: Option<BudgetChoice>,
    /// What is wrong with the [`StereoSettings`], if anything (the default eye distance is
    /// used meanwhile).
    pub stereo_error: Option<String>,
}

/// The player's frame: an isometry of the model whose columns are the right, up and back
/// unit tangents and the position (the camera looks along `−back`).
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct PlayerFrame(pub DMat4);

impl Default for PlayerFrame {
    fn default() -> Self {
        Self(DMat4::IDENTITY)
    }
}

// `Holonomy` is plain data of the space layer (the headset tracks it without Bevy); as a
// component it lives in the table storage like the others.
impl Component for Holonomy {
    const STORAGE_TYPE: StorageType = StorageType::Table;
    type Mutability = Mutable;
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
    /// Move forward.
    pub forward: KeyCode,
    /// Move backward.
    pub backward: KeyCode,
    /// Move left.
    pub left: KeyCode,
    /// Move right.
    pub right: KeyCode,
    /// Move up.
    pub up: KeyCode,
    /// Move down.
    pub down: KeyCode,
    /// Roll to the left.
    pub roll_left: KeyCode,
    /// Roll to the right.
    pub roll_right: KeyCode,
    /// Speed up.
    pub faster: KeyCode,
    /// Slow down.
    pub slower: KeyCode,
    /// Release the grabbed mouse.
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
    /// In a product space (H²×R, S²×R): the fibre stays up, so walking is horizontal and
    /// turning left and right is about the fibre (Space and Shift climb along it). `false`
    /// flies freely, as in the constant-curvature spaces.
    pub fibre_up: bool,
}

impl Default for PlayerSettings {
    fn default() -> Self {
        Self {
            speed: 0.6,
            mouse_sensitivity: 0.003,
            roll_speed: 1.2,
            wrap_margin: 1e-4,
            look_without_grab: false,
            fibre_up: true,
        }
    }
}

/// Whether the primary window's cursor is grabbed for mouse look.
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct MouseLook {
    /// Whether the cursor is grabbed now.
    pub grabbed: bool,
}

/// Whether the pointer is over the panel (then a click does not grab the cursor).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PointerOverUi(pub bool);

/// The stereo options of the curved-space cameras (a resource; changeable at run time).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct StereoSettings {
    /// How the two eyes share the picture.
    pub mode: StereoMode,
    /// Distance between the eyes in the space's units (geodesic); `None` for
    /// [`default_ipd`] of the cell. It sets the world scale: how big the cell feels.
    pub ipd: Option<f64>,
    /// Show the right eye where the left one belongs and vice versa (cross-eyed viewing of
    /// side-by-side pictures).
    pub swap_eyes: bool,
}

impl StereoSettings {
    /// The eye distance in use for a cell of this inradius: the chosen one, or the default
    /// where none is chosen or the chosen one fails [`check_ipd`].
    #[must_use]
    pub fn ipd_for(&self, inradius: f64) -> f64 {
        self.ipd
            .filter(|&ipd| check_ipd(ipd, inradius).is_ok())
            .unwrap_or_else(|| default_ipd(inradius))
    }

    /// Space units per metre at this eye distance (the "world scale").
    #[must_use]
    pub fn units_per_metre(&self, inradius: f64) -> f64 {
        self.ipd_for(inradius) / HUMAN_IPD_METRES
    }
}

/// Marks a curved-space camera that is one eye of a head-mounted display: it is drawn as
/// one view with its own (asymmetric) frustum, and the [`StereoSettings`] do not apply to
/// it. Its [`PlayerFrame`] is the eye's frame, kept inside the cell by its owner.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct CurvedSpaceEye {
    /// The eye's frustum.
    pub lens: Lens,
}
