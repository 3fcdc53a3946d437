//! Rendering one picture through the real plugin without a window: a Bevy app whose
//! curved-space camera draws into an image, captured once the tracer has drawn it.
//! Used by the CLI's GPU `render`, the headless example and the GPU-vs-CPU tests.

use crate::plugin::CurvedSpacesPlugin;
use crate::plugin::components::PlayerFrame;
use crate::plugin::components::StereoSettings;
use crate::plugin::components::{
    ActiveSpace, BaseProductScene, BaseScene, CurvedSpaceCamera, SceneObjects, TracerSettings,
};
use crate::plugin::render::FramesTraced;
use crate::plugin::screenshot::image_to_rgb;
use crate::scene::{Object, SceneParts};
use crate::view::TraceCamera;
use bevy::app::{PluginsState, ScheduleRunnerPlugin};
use bevy::camera::{ImageRenderTarget, RenderTarget};
use bevy::prelude::*;
use bevy::render::render_resource::{TextureFormat, TextureUsages};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured};
use bevy::window::ExitCondition;
use glam::DMat4;
use image::RgbImage;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// What to render.
#[derive(Clone, Debug)]
pub struct OffscreenRender {
    /// The space.
    pub space: ActiveSpace,
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// The camera frame (columns right, up, back, position).
    pub frame: DMat4,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
    /// Fog distance scale λ; `None` for the space's default.
    pub fog_distance: Option<f64>,
    /// Crossing budget per ray.
    pub max_crossings: u32,
    /// Which default scene parts show.
    pub parts: SceneParts,
    /// Objects added to the scene (see [`SceneObjects`]).
    pub objects: Vec<Object>,
    /// Fraction of the resolution that is traced (then scaled up), in (0, 1].
    pub resolution_scale: f32,
    /// Stereo mode, eye distance and eye swap (the frame is the head's).
    pub stereo: StereoSettings,
    /// A whole scene (a scene file's) instead of the default parts, for its space.
    pub base: BaseScene,
    /// The scene's clock in seconds (the globes' spin).
    pub time: f64,
    /// Entities to spawn for the picture ([`crate::plugin::objects`]): objects at their frames,
    /// drawn the way a game's are (padded lists, shared scene data).
    pub entities: Vec<(crate::plugin::objects::CurvedObject, DMat4)>,
    /// The teaching view ([`crate::scene::ColourBy`]).
    pub colour_by: crate::scene::ColourBy,
    /// The cell's walls with windows.
    pub walls: Option<crate::scene::WallStyle>,
    /// The lighting ([`TracerSettings::lighting`]); `None`: the base scene's own, else the
    /// default.
    pub lighting: Option<crate::scene::lighting::Lighting>,
}

impl OffscreenRender {
    /// A mono picture of the space's default scene parts from `camera` at `width × height`,
    /// with the space's own fog, full resolution, no objects of your own and the clock at 0.
    /// Change the other fields with struct update syntax.
    #[must_use]
    pub fn new(
        space: ActiveSpace,
        camera: TraceCamera,
        (width, height): (u32, u32),
        max_crossings: u32,
    ) -> Self {
        Self {
            space,
            width,
            height,
            frame: camera.frame,
            fov_y_degrees: camera.fov_y_degrees,
            fog_distance: None,
            max_crossings,
            parts: SceneParts::default(),
            objects: Vec::new(),
            resolution_scale: 1.0,
            stereo: StereoSettings::default(),
            base: BaseScene::default(),
            time: 0.0,
            entities: Vec::new(),
            colour_by: crate::scene::ColourBy::Shading,
            walls: None,
            lighting: None,
        }
    }
}

/// Why no picture came back.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OffscreenError {
    /// No GPU adapter was found (no GPU and no software Vulkan driver).
    #[error(
        "no GPU adapter was found (no GPU and no software Vulkan driver): on Debian install one with `apt-get install mesa-vulkan-drivers libvulkan1`, or use --cpu"
    )]
    NoAdapter,
    /// The image size (width, height attached) is not supported: each must be 1 to 8192.
    #[error("image size {0}×{1} is not supported: width and height must be 1 to 8192")]
    BadSize(u32, u32),
    /// The GPU tracer did not produce a picture within the time limit (attached).
    #[error(
        "the GPU tracer did not produce a picture within {0:?} (is the GPU busy or the scene too heavy?)"
    )]
    Timeout(Duration),
    /// The scene cannot be drawn on the GPU (the reason is attached).
    #[error("the scene cannot be drawn on the GPU: {0}")]
    Scene(String),
    /// The tracer's shader did not build for this scene (the compiler's message attached).
    #[error("the GPU tracer's shader did not build: {0}")]
    Shader(String),
    /// A request of one family's renderer was given a space of another (the space's id and
    /// the renderer to use attached).
    #[error("{0} is not a space this renderer draws: use {1}")]
    WrongFamily(String, &'static str),
    /// The captured picture has an unexpected format (described in the message).
    #[error("the captured picture has an unexpected format: {0}")]
    Format(String),
}

/// The graphics APIs the app, the offscreen renderer and the benchmark ask wgpu for: the
/// primary ones (Vulkan, Metal, DX12), or those `WGPU_BACKEND` names.
///
/// wgpu is built with its GL backend too (the OpenXR backend asks for it), and a machine
/// with no GPU has a software driver for both Vulkan (lavapipe) and GL (llvmpipe): this
/// keeps the choice on the API the tracer is tested on.
#[must_use]
pub fn gpu_backends() -> wgpu::Backends {
    wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY)
}

/// Bevy's render plugin asking for [`gpu_backends`]: `DefaultPlugins.set(render_plugin())`.
#[must_use]
pub fn render_plugin() -> bevy::render::RenderPlugin {
    bevy::render::RenderPlugin {
        render_creation: bevy::render::settings::WgpuSettings {
            backends: Some(gpu_backends()),
            ..default()
        }
        .into(),
        ..default()
    }
}

/// wgpu's instance options asking for [`gpu_backends`].
#[must_use]
pub fn instance_descriptor() -> wgpu::InstanceDescriptor {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle();
    descriptor.backends = gpu_backends();
    descriptor
}

/// Whether wgpu finds any adapter (a GPU or a software driver such as lavapipe).
///
/// The instance it asks is kept for the rest of the process, and with it the Vulkan driver
/// it loaded. Were it dropped, the Vulkan loader would unload the driver with the last
/// instance (after Bevy's renderer is gone too), and a driver that registered an exit
/// handler (lavapipe does, through LLVM) would then crash the process at exit with
/// SIGSEGV, after a refusal had been printed and its exit code chosen.
#[must_use]
pub fn gpu_available() -> bool {
    use std::sync::OnceLock;
    use wgpu::{Instance, RequestAdapterOptions};
    static INSTANCE: OnceLock<Instance> = OnceLock::new();
    let instance = INSTANCE.get_or_init(|| Instance::new(instance_descriptor()));
    bevy::tasks::block_on(instance.request_adapter(&RequestAdapterOptions::default())).is_ok()
}

/// How long a picture may take before [`render_offscreen`] gives up.
pub const OFFSCREEN_TIMEOUT: Duration = Duration::from_secs(120);

/// Renders one picture with the GPU tracer and returns it (8-bit RGB, the same encoding as
/// the CPU reference's PNGs). To render several, keep an [`OffscreenRenderer`].
pub fn render_offscreen(request: &OffscreenRender) -> Result<RgbImage, OffscreenError> {
    OffscreenRenderer::new()?.render(request)
}

/// A windowless Bevy app with the plugin, reused for any number of pictures.
pub struct OffscreenRenderer {
    app: App,
    frames: FramesTraced,
}

impl OffscreenRenderer {
    /// Starts the app (and the GPU device).
    pub fn new() -> Result<Self, OffscreenError> {
        if !gpu_available() {
            return Err(OffscreenError::NoAdapter);
        }
        let mut app = App::new();
        let plugins = DefaultPlugins
            .set(WindowPlugin {
                primary_window: None,
                exit_condition: ExitCondition::DontExit,
                ..default()
            })
            .set(render_plugin());
        // No window and no event loop: the app is driven by `update` below.
        #[cfg(feature = "window")]
        let plugins = plugins.disable::<bevy::winit::WinitPlugin>();
        app.add_plugins(plugins.set(bevy::log::LogPlugin {
            level: bevy::log::Level::WARN,
            // "software rendering is slow" is expected on lavapipe, not news.
            filter: "wgpu=error,wgpu_hal::gles=off,naga=warn,bevy_render::renderer=error".into(),
            ..default()
        }))
        .add_plugins(ScheduleRunnerPlugin::run_loop(Duration::ZERO))
        .add_plugins(CurvedSpacesPlugin {
            controls: false,
            ..default()
        });
        // Wait for the renderer to initialise (it may do so asynchronously).
        while app.plugins_state() == PluginsState::Adding {
            bevy::tasks::tick_global_task_pools_on_main_thread();
        }
        app.finish();
        app.cleanup();
        let frames = app.world().resource::<FramesTraced>().clone();
        Ok(Self { app, frames })
    }

    /// Renders one picture.
    pub fn render(&mut self, request: &OffscreenRender) -> Result<RgbImage, OffscreenError> {
        let (w, h) = (request.width, request.height);
        if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
            return Err(OffscreenError::BadSize(w, h));
        }
        let settings = TracerSettings {
            fog_distance: request.fog_distance,
            max_crossings: Some(request.max_crossings.max(1)),
            quality: crate::plugin::components::Quality::High,
            resolution_scale: request.resolution_scale,
            parts: request.parts,
            time: Some(request.time),
            colour_by: request.colour_by,
            walls: request.walls,
            lighting: request.lighting,
        };
        // A scene the GPU cannot take would only time out below: say why now.
        let Some(space) = request.space.constant() else {
            return Err(OffscreenError::WrongFamily(
                request.space.id.clone(),
                "OffscreenRenderer::render_product",
            ));
        };
        let (scene, _) = crate::plugin::render::upload::build_scene(
            space,
            &settings,
            &request.objects,
            request.base.for_space(&request.space),
        );
        crate::plugin::render::gpu::GpuScene::new(
            space,
            &scene,
            settings.max_crossings.unwrap_or(1),
        )
        .map_err(|e| OffscreenError::Scene(e.to_string()))?;
        let world = self.app.world_mut();
        // The same space again (a flight's frames) is not inserted anew: that would count as
        // a change of space.
        let same_space = world.get_resource::<ActiveSpace>().is_some_and(|a| {
            a.id == request.space.id && a.constant().is_some_and(|s| Arc::ptr_eq(s, space))
        });
        if !same_space {
            world.insert_resource(request.space.clone());
        }
        world.insert_resource(settings);
        world.insert_resource(request.base.clone());
        world.insert_resource(SceneObjects(request.objects.clone()));
        world.insert_resource(request.stereo);
        let spawned: Vec<Entity> = request
            .entities
            .iter()
            .map(|(object, frame)| {
                world
                    .spawn((
                        object.clone(),
                        crate::plugin::objects::CurvedTransform(*frame),
                    ))
                    .id()
            })
            .collect();
        // A changed space puts every player back at its start view in the next update:
        // let that happen before the camera exists, so the requested frame is kept.
        self.app.update();
        let (handle, camera) = spawn_camera(
            self.app.world_mut(),
            (w, h),
            request.fov_y_degrees,
            request.frame,
        );
        let result = self.capture(&handle);
        self.app.world_mut().despawn(camera);
        for e in spawned {
            self.app.world_mut().despawn(e);
        }
        self.app
            .world_mut()
            .resource_mut::<Assets<Image>>()
            .remove(&handle);
        result
    }

    /// Renders a product space (H²×R, S²×R) and its scene from a product camera with the
    /// GPU tracer's `PRODUCT` variant, through the plugin's own product systems (the space
    /// becomes the [`ActiveSpace`], the scene its [`BaseProductScene`]). Traced at full
    /// resolution; the picture matches the CPU reference
    /// ([`crate::trace::product::render_product`]) but for f32 rounding at silhouettes.
    pub fn render_product(
        &mut self,
        space: &crate::space::product::ProductSpace,
        scene: &crate::trace::product::ProductScene,
        camera: &crate::trace::product::ProductCamera,
        size: (u32, u32),
        max_crossings: u32,
    ) -> Result<RgbImage, OffscreenError> {
        self.render_product_stereo(
            space,
            scene,
            camera,
            size,
            max_crossings,
            StereoSettings::default(),
        )
    }

    /// [`OffscreenRenderer::render_product`] in a stereo mode: the eyes half the eye
    /// distance either side of the camera along its right
    /// ([`crate::space::product::motion::product_eye_frames`]), as the CPU reference's
    /// [`crate::trace::product::render_product_view`] places them.
    pub fn render_product_stereo(
        &mut self,
        space: &crate::space::product::ProductSpace,
        scene: &crate::trace::product::ProductScene,
        camera: &crate::trace::product::ProductCamera,
        (w, h): (u32, u32),
        max_crossings: u32,
        stereo: StereoSettings,
    ) -> Result<RgbImage, OffscreenError> {
        let frame = crate::space::product::motion::camera_frame(camera.point, camera.frame);
        self.render_family(
            (space, space.name()),
            || crate::plugin::render::gpu::GpuScene::product(space, scene, max_crossings),
            BaseProductScene::new(scene.clone()),
            ((w, h), max_crossings, scene.colour_by, stereo),
            (camera.fov_y_degrees, frame),
        )
    }

    /// Shows `space` (named `name`) with `base` as its family's base scene and draws the
    /// picture from a camera of `fov` degrees at `frame`, once the size is one a picture can
    /// have and `pack` (the scene as the GPU would take it) packs: a scene the GPU cannot take
    /// would only time out later, so its error is said now. The space is inserted only when
    /// another is shown, so the renderer keeps its pipeline from picture to picture.
    fn render_family<F: crate::space::FamilySpace + Clone>(
        &mut self,
        (space, name): (&F, &str),
        pack: impl FnOnce() -> Result<
            crate::plugin::render::gpu::GpuScene,
            crate::plugin::render::gpu::GpuSceneError,
        >,
        base: impl Resource,
        ((w, h), max_crossings, colour_by, stereo): (
            (u32, u32),
            u32,
            crate::scene::ColourBy,
            StereoSettings,
        ),
        view: (f64, DMat4),
    ) -> Result<RgbImage, OffscreenError>
    where
        crate::space::AnySpace: From<F>,
    {
        if !(1..=8192).contains(&w) || !(1..=8192).contains(&h) {
            return Err(OffscreenError::BadSize(w, h));
        }
        pack().map_err(|e| OffscreenError::Scene(e.to_string()))?;
        let world = self.app.world_mut();
        let same_space = world
            .get_resource::<ActiveSpace>()
            .is_some_and(|a| a.space.get::<F>().is_some() && a.space.name() == name);
        if !same_space {
            world.insert_resource(ActiveSpace::new(name, space.clone()));
        }
        world.insert_resource(base);
        self.picture((w, h), (max_crossings, colour_by, stereo), view)
    }

    /// The picture of the space and scene now in the world from a camera of `fov` degrees at
    /// `frame`: every pixel traced, none scaled up (the picture the CPU reference draws),
    /// with the budget, colouring and stereo mode given.
    fn picture(
        &mut self,
        (w, h): (u32, u32),
        (max_crossings, colour_by, stereo): (u32, crate::scene::ColourBy, StereoSettings),
        (fov, frame): (f64, DMat4),
    ) -> Result<RgbImage, OffscreenError> {
        let world = self.app.world_mut();
        world.insert_resource(stereo);
        world.insert_resource(TracerSettings {
            fog_distance: None,
            max_crossings: Some(max_crossings.max(1)),
            quality: crate::plugin::components::Quality::High,
            resolution_scale: 1.0,
            parts: SceneParts::default(),
            time: Some(0.0),
            colour_by,
            walls: None,
            lighting: None,
        });
        // The switch puts players at the start view in this update, before the camera.
        self.app.update();
        let (handle, entity) = spawn_camera(self.app.world_mut(), (w, h), fov, frame);
        let result = self.capture(&handle);
        let world = self.app.world_mut();
        world.despawn(entity);
        world.resource_mut::<Assets<Image>>().remove(&handle);
        result
    }

    /// Renders a Nil space's scene from `camera` on the GPU (mono or stereo), as the plugin
    /// draws it while the space is shown.
    pub fn render_nil(
        &mut self,
        space: &crate::space::nil::NilSpace,
        scene: &crate::trace::nil::NilScene,
        camera: &crate::trace::nil::NilCamera,
        (w, h): (u32, u32),
        max_crossings: u32,
        stereo: StereoSettings,
    ) -> Result<RgbImage, OffscreenError> {
        self.render_family(
            (space, space.name()),
            || crate::plugin::render::gpu::GpuScene::nil(space, scene, max_crossings),
            crate::plugin::nil::BaseNilScene {
                scene: scene.clone(),
                start: Some(*camera),
                moving: Vec::new(),
            },
            ((w, h), max_crossings, scene.colour_by, stereo),
            (camera.fov_y_degrees, camera.frame),
        )
    }

    /// Renders an SL̃(2,R) space's scene from `camera` on the GPU (mono or stereo), as the
    /// plugin draws it while the space is shown.
    pub fn render_sl2r(
        &mut self,
        space: &crate::space::sl2r::UnitTangentSpace,
        scene: &crate::trace::sl2r::Sl2rScene,
        camera: &crate::trace::sl2r::Sl2rCamera,
        (w, h): (u32, u32),
        max_crossings: u32,
        stereo: StereoSettings,
    ) -> Result<RgbImage, OffscreenError> {
        self.render_family(
            (space, space.name()),
            || crate::plugin::render::gpu::GpuScene::sl2r(space, scene, max_crossings),
            crate::plugin::sl2r::BaseSl2rScene {
                scene: scene.clone(),
                start: Some(*camera),
            },
            ((w, h), max_crossings, scene.colour_by, stereo),
            (camera.fov_y_degrees, camera.frame),
        )
    }

    fn capture(&mut self, handle: &Handle<Image>) -> Result<RgbImage, OffscreenError> {
        let failure = self
            .app
            .world()
            .resource::<crate::plugin::render::TracerFailure>()
            .clone();
        failure.clear();
        let drawn_before = self.frames.get();
        let captured: Arc<Mutex<Option<Image>>> = Arc::default();
        let start = Instant::now();
        let mut requested = false;
        loop {
            self.app.update();
            if let Some(image) = captured.lock().expect("capture lock").take() {
                return image_to_rgb(&image).map_err(OffscreenError::Format);
            }
            if let Some(why) = failure.get() {
                return Err(OffscreenError::Shader(why));
            }
            if start.elapsed() > OFFSCREEN_TIMEOUT {
                return Err(OffscreenError::Timeout(OFFSCREEN_TIMEOUT));
            }
            // The pipeline compiles asynchronously: capture once the tracer has drawn
            // this camera (two frames, as the previous camera's last frame may still have
            // been in flight in the pipelined renderer).
            if !requested && self.frames.get() >= drawn_before + 2 {
                requested = true;
                let sink = captured.clone();
                self.app
                    .world_mut()
                    .spawn(Screenshot::image(handle.clone()))
                    .observe(move |shot: On<ScreenshotCaptured>| {
                        *sink.lock().expect("capture lock") = Some(shot.image.clone());
                    });
            }
        }
    }
}

/// A curved-space camera at `frame` drawing into a new `width × height` image that can be
/// captured: the image's handle and the camera.
fn spawn_camera(
    world: &mut World,
    (w, h): (u32, u32),
    fov_y_degrees: f64,
    frame: DMat4,
) -> (Handle<Image>, Entity) {
    let mut target = Image::new_target_texture(w, h, TextureFormat::Rgba8UnormSrgb, None);
    target.texture_descriptor.usage |= TextureUsages::COPY_SRC;
    let handle = world.resource_mut::<Assets<Image>>().add(target);
    let camera = world
        .spawn((
            Camera3d::default(),
            RenderTarget::Image(ImageRenderTarget {
                handle: handle.clone(),
                scale_factor: 1.0,
            }),
            CurvedSpaceCamera { fov_y_degrees },
            PlayerFrame(frame),
        ))
        .id();
    (handle, camera)
}

/// Gives the process a private runtime directory when `XDG_RUNTIME_DIR` is unset or not a
/// folder, so that the Vulkan loader's Wayland client does not print
/// `error: XDG_RUNTIME_DIR is invalid or not set` for every GPU render in a headless session.
/// Genuine errors are unaffected. Does nothing where the variable names a folder already.
///
/// # Safety
/// Changes the process environment: call it before any other thread is started (first thing
/// in `main`), as [`std::env::set_var`] requires.
pub unsafe fn quiet_runtime_dir() {
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| std::path::Path::new(&d).is_dir()) {
        return;
    }
    let user = std::env::var("USER").unwrap_or_else(|_| "user".into());
    let dir = std::env::temp_dir().join(format!("curved-spaces-runtime-{user}"));
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    #[cfg(unix)]
    std::os::unix::fs::DirBuilderExt::mode(&mut builder, 0o700);
    if builder.create(&dir).is_ok() {
        // SAFETY: the caller guarantees no other thread reads the environment now.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", &dir) };
    }
}
