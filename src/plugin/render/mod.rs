//! The GPU side: the scene packed for the WGSL tracer ([`gpu`]) and a small render node that
//! draws it over every camera carrying [`CurvedSpaceCamera`].
//!
//! Modelled on Bevy 0.19's `FullscreenMaterial`, which specialises only on the target
//! format: the tracer is also specialised on the geometry, the face count and the object
//! kinds present (shader defs, [`gpu::ShaderKey`]), and its uniform is sized to the scene.

pub mod gpu;
pub mod layout;
pub mod upload;

use crate::plugin::components::StereoSettings;
use crate::plugin::components::{CurvedSpaceCamera, CurvedSpaceEye, PlayerFrame};
use crate::space::AnySpace;
use crate::view::StereoMode;
use crate::view::{Lens, ViewKind, ViewLayout};
use bevy::asset::{load_internal_asset, uuid_handle};
use bevy::core_pipeline::{Core3d, Core3dSystems, tonemapping::tonemapping};
use bevy::prelude::*;
use bevy::render::{
    Extract, ExtractSchedule, Render, RenderApp, RenderStartup, RenderSystems,
    render_resource::{
        BindGroup, BindGroupEntries, BindGroupLayoutDescriptor, BindGroupLayoutEntries, Buffer,
        BufferInitDescriptor, BufferUsages, CachedPipelineState, CachedRenderPipelineId,
        ColorTargetState, ColorWrites, CommandEncoder, Extent3d, FilterMode, FragmentState,
        Operations, PipelineCache, RenderPassColorAttachment, RenderPassDescriptor, RenderPipeline,
        RenderPipelineDescriptor, Sampler, SamplerBindingType, SamplerDescriptor, ShaderStages,
        SpecializedRenderPipeline, SpecializedRenderPipelines, TextureDataOrder, TextureDescriptor,
        TextureDimension, TextureFormat, TextureSampleType, TextureUsages, TextureView,
        VertexState,
        binding_types::{
            sampler, storage_buffer_read_only_sized, texture_2d, uniform_buffer_sized,
        },
    },
    renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery},
    sync_component::{SyncComponent, SyncComponentPlugin},
    sync_world::RenderEntity,
    texture::{CachedTexture, TextureCache},
    view::{ExtractedView, ViewTarget},
};
use bevy::shader::Shader;
use gpu::{GpuScene, ShaderKey, TEXTURE_SLOTS, ViewExtras, view_shader_defs, view_words};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// The tracer's shader, loaded once as an internal asset.
pub(crate) const TRACER_SHADER: Handle<Shader> =
    uuid_handle!("4c2f8a7e-1d53-4b0e-9e61-2a7c3f9d8b15");

/// The shader that scales a reduced-resolution trace up to the view.
pub(crate) const UPSCALE_SHADER: Handle<Shader> =
    uuid_handle!("9a1e3b52-7c0d-4f86-b2a4-5d3e6f708192");

/// The first of the ids the tracer's modules are registered under (one after another).
const SHADER_MODULE_IDS: u128 = 0x6d1f_0c3a_52b8_4e27_a9c4_1b7e_0000_0000;

/// The scene the GPU draws, shared by all curved-space cameras (rebuilt when the space or
/// the tracer settings change).
#[derive(Resource, Clone, Debug)]
pub struct PreparedScene(pub Arc<GpuScene>);

/// Frames the tracer has drawn so far (all views), readable from the main world: headless
/// renders wait for it before they capture a picture.
#[derive(Resource, Clone, Debug, Default)]
pub struct FramesTraced(pub Arc<AtomicU64>);

impl FramesTraced {
    /// The count so far.
    #[must_use]
    pub fn get(&self) -> u64 {
        self.0.load(Ordering::Acquire)
    }
}

/// Why the tracer's pipeline could not be built (a shader that does not compile, with the
/// compiler's words), readable from the main world: headless renders stop waiting and say
/// so, and the panel shows it.
#[derive(Resource, Clone, Debug, Default)]
pub struct TracerFailure(pub Arc<std::sync::Mutex<Option<String>>>);

impl TracerFailure {
    /// The failure, if the pipeline of a view failed to build.
    #[must_use]
    pub fn get(&self) -> Option<String> {
        self.0.lock().ok().and_then(|f| f.clone())
    }

    /// Forgets it (before a new picture is waited for).
    pub fn clear(&self) {
        if let Ok(mut f) = self.0.lock() {
            *f = None;
        }
    }

    fn set(&self, why: String) {
        if let Ok(mut f) = self.0.lock() {
            *f = Some(why);
        }
    }
}

/// Shows a failed pipeline in the tracer's status (the panel's error line).
fn report_tracer_failure(
    failure: Res<TracerFailure>,
    status: Option<ResMut<crate::plugin::components::TracerStatus>>,
) {
    if let (Some(why), Some(mut status)) = (failure.get(), status) {
        let message = format!("the tracer's shader did not build: {why}");
        if status.error.as_ref() != Some(&message) {
            status.error = Some(message);
        }
    }
}

/// A curved-space view in the render world.
#[derive(Component, Clone, Debug)]
pub struct ExtractedCurvedView {
    /// The eyes' frames `[left, right]`, each inside the cell (both the head's in mono).
    pub eyes: [glam::DMat4; 2],
    /// How the eyes share the picture.
    pub stereo: StereoMode,
    /// Whether the eyes' pictures are swapped.
    pub swap_eyes: bool,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
    /// The frustum of a [`CurvedSpaceEye`] (an XR view); `None` for the symmetric one of
    /// `fov_y_degrees` and the view's aspect.
    pub lens: Option<Lens>,
    /// Fraction of the view's resolution that is traced, in (0, 1].
    pub resolution_scale: f32,
    /// The packed scene.
    pub scene: Arc<GpuScene>,
    /// The scene's time and the avatar at the head's frame.
    pub extras: ViewExtras,
}

impl SyncComponent for CurvedSpaceCamera {
    type Target = ExtractedCurvedView;
}

/// Registers the tracer's shader and render-world systems.
pub(crate) struct TracerRenderPlugin;

impl Plugin for TracerRenderPlugin {
    fn build(&self, app: &mut App) {
        load_internal_asset!(
            app,
            TRACER_SHADER,
            "../../../shaders/curved_space.wgsl",
            Shader::from_wgsl
        );
        load_internal_asset!(
            app,
            UPSCALE_SHADER,
            "../../../shaders/upscale.wgsl",
            Shader::from_wgsl
        );
        // The modules the tracer `#import`s, registered under fixed ids so that Bevy's
        // shader cache resolves them by their import paths.
        let mut shaders = app.world_mut().resource_mut::<Assets<Shader>>();
        for (i, (path, source)) in gpu::SHADER_MODULES.iter().enumerate() {
            let id = bevy::asset::uuid::Uuid::from_u128(SHADER_MODULE_IDS + i as u128);
            let handle: Handle<Shader> = Handle::Uuid(id, std::marker::PhantomData);
            shaders
                .insert(handle.id(), Shader::from_wgsl(*source, *path))
                .expect("an internal shader id is free");
        }
        let frames = FramesTraced::default();
        let failure = TracerFailure::default();
        app.insert_resource(frames.clone())
            .insert_resource(failure.clone())
            .add_systems(Update, report_tracer_failure)
            .add_plugins(SyncComponentPlugin::<CurvedSpaceCamera>::default());
        let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
            return;
        };
        render_app
            .insert_resource(frames)
            .insert_resource(failure)
            .init_resource::<SpecializedRenderPipelines<TracerPipeline>>()
            .add_systems(RenderStartup, init_tracer_pipeline)
            .add_systems(ExtractSchedule, extract_curved_views)
            .add_systems(
                Render,
                prepare_tracer_views.in_set(RenderSystems::PrepareBindGroups),
            )
            .add_systems(
                Core3d,
                trace_views
                    .in_set(Core3dSystems::PostProcess)
                    .before(tonemapping),
            );
    }
}

/// The main world's view of a curved-space camera.
type CurvedCameras<'w, 's> = Query<
    'w,
    's,
    (
        RenderEntity,
        &'static CurvedSpaceCamera,
        &'static PlayerFrame,
        Option<&'static CurvedSpaceEye>,
    ),
>;

fn extract_curved_views(
    mut commands: Commands,
    scene: Extract<Option<Res<PreparedScene>>>,
    settings: Extract<Option<Res<crate::plugin::components::TracerSettings>>>,
    stereo: Extract<Option<Res<StereoSettings>>>,
    active: Extract<Option<Res<crate::plugin::components::ActiveSpace>>>,
    time: Extract<Option<Res<Time>>>,
    views: Extract<CurvedCameras>,
) {
    let seconds = settings
        .as_ref()
        .and_then(|s| s.time)
        .unwrap_or_else(|| time.as_ref().map_or(0.0, |t| t.elapsed_secs_f64()));
    let resolution_scale = settings
        .as_ref()
        .map_or(1.0, |s| s.resolution_scale)
        .clamp(0.05, 1.0);
    let Some(scene) = scene.as_ref() else {
        return;
    };
    let Some(active) = active.as_deref() else {
        return;
    };
    let stereo = stereo.as_deref().copied().unwrap_or_default();
    let ipd = stereo.ipd_for(active.inradius);
    for (entity, camera, frame, eye) in &views {
        // An XR eye is one view with its own frustum; other cameras show the stereo mode.
        let mode = if eye.is_some() {
            StereoMode::Mono
        } else {
            stereo.mode
        };
        let eyes = if mode.is_stereo() {
            active.space.frames().eye_frames(frame.0, ipd)
        } else {
            [frame.0; 2]
        };
        let extras = match &active.space {
            AnySpace::Constant(s) => ViewExtras::new(s, &scene.0, frame.0, seconds),
            // No avatar in the other families.
            AnySpace::Product(_) | AnySpace::Nil(_) | AnySpace::Sl2r(_) => ViewExtras {
                time: seconds,
                ..ViewExtras::default()
            },
        };
        commands.entity(entity).insert(ExtractedCurvedView {
            eyes,
            stereo: mode,
            swap_eyes: stereo.swap_eyes,
            fov_y_degrees: camera.fov_y_degrees,
            lens: eye.map(|e| e.lens),
            resolution_scale,
            scene: scene.0.clone(),
            extras,
        });
    }
}

/// The tracer's layout and shader.
#[derive(Resource)]
pub(crate) struct TracerPipeline {
    layout: BindGroupLayoutDescriptor,
    upscale_layout: BindGroupLayoutDescriptor,
    sampler: Sampler,
    /// A 1×1 texture for the texture slots a scene leaves empty.
    blank: TextureView,
}

/// One pipeline per shader key, view kind and target format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct TracerPipelineKey {
    /// `None` for the upscaling pass.
    pub shader: Option<ShaderKey>,
    pub view: ViewKind,
    /// The upscaling pass of a split view: whether the halves are side by side (x) or on
    /// top of each other (y).
    pub split: [bool; 2],
    pub format: TextureFormat,
}

impl SpecializedRenderPipeline for TracerPipeline {
    type Key = TracerPipelineKey;

    fn specialize(&self, key: Self::Key) -> RenderPipelineDescriptor {
        let (label, shader, layout, defs) = match key.shader {
            Some(k) => (
                "curved_space_tracer",
                TRACER_SHADER,
                &self.layout,
                [k.shader_defs(), view_shader_defs(key.view)].concat(),
            ),
            None => (
                "curved_space_upscale",
                UPSCALE_SHADER,
                &self.upscale_layout,
                key.split
                    .iter()
                    .zip(["SPLIT_X", "SPLIT_Y"])
                    .filter(|(split, _)| **split)
                    .map(|(_, def)| def.into())
                    .collect(),
            ),
        };
        RenderPipelineDescriptor {
            label: Some(label.into()),
            layout: vec![layout.clone()],
            vertex: VertexState {
                shader: shader.clone(),
                shader_defs: defs.clone(),
                entry_point: Some("vertex".into()),
                buffers: vec![],
            },
            fragment: Some(FragmentState {
                shader,
                shader_defs: defs,
                entry_point: Some("fragment".into()),
                targets: vec![Some(ColorTargetState {
                    format: key.format,
                    blend: None,
                    write_mask: ColorWrites::ALL,
                })],
            }),
            ..default()
        }
    }
}

fn init_tracer_pipeline(mut commands: Commands, device: Res<RenderDevice>) {
    // The scene's textures, read texel by texel (TEXTURE_SLOTS of them).
    let slot = texture_2d(TextureSampleType::Float { filterable: false });
    let layout = BindGroupLayoutDescriptor::new(
        "curved_space_tracer_layout",
        &BindGroupLayoutEntries::sequential(
            ShaderStages::VERTEX_FRAGMENT,
            (
                uniform_buffer_sized(false, None),
                storage_buffer_read_only_sized(false, None),
                slot,
                slot,
                slot,
                slot,
                slot,
                slot,
                slot,
                slot,
            ),
        ),
    );
    let upscale_layout = BindGroupLayoutDescriptor::new(
        "curved_space_upscale_layout",
        &BindGroupLayoutEntries::sequential(
            ShaderStages::FRAGMENT,
            (
                texture_2d(TextureSampleType::Float { filterable: true }),
                sampler(SamplerBindingType::Filtering),
            ),
        ),
    );
    let sampler = device.create_sampler(&SamplerDescriptor {
        mag_filter: FilterMode::Linear,
        min_filter: FilterMode::Linear,
        ..default()
    });
    let blank = device
        .create_texture(&TextureDescriptor {
            label: Some("curved_space_blank_texture"),
            size: Extent3d {
                width: 1,
                height: 1,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: TextureDimension::D2,
            format: TextureFormat::Rgba8Unorm,
            usage: TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        })
        .create_view(&default());
    commands.insert_resource(TracerPipeline {
        layout,
        upscale_layout,
        sampler,
        blank,
    });
}

/// The uniform buffer, its bind group and the pipeline of one view.
#[derive(Component)]
pub(crate) struct TracerBindings {
    buffer: Buffer,
    bytes: usize,
    /// The scene whose words the uniform holds.
    scene: Arc<GpuScene>,
    /// The scene data buffer and textures and what they hold: kept while only objects move.
    scene_data: SceneDataGpu,
    bind_group: BindGroup,
    pipeline: CachedRenderPipelineId,
    /// The reduced-resolution target, its upscaling bind group and pipeline.
    reduced: Option<(CachedTexture, BindGroup, CachedRenderPipelineId)>,
}

/// The scene data buffer, and the GPU textures of the scene's first [`TEXTURE_SLOTS`]
/// textures (the rest of the slots blank), made from `data` and `textures`.
#[derive(Clone)]
struct SceneDataGpu {
    buffer: Buffer,
    data: Arc<Vec<u32>>,
    textures: Vec<TextureView>,
}

impl SceneDataGpu {
    fn new(
        device: &RenderDevice,
        queue: &RenderQueue,
        scene: &GpuScene,
        blank: &TextureView,
    ) -> Self {
        let buffer = device.create_buffer_with_data(&BufferInitDescriptor {
            label: Some("curved_space_scene_data"),
            contents: bytemuck::cast_slice(&scene.data),
            usage: BufferUsages::STORAGE,
        });
        let mut textures: Vec<TextureView> = scene
            .textures
            .iter()
            .map(|t| {
                device
                    .create_texture_with_data(
                        queue,
                        &TextureDescriptor {
                            label: Some("curved_space_scene_texture"),
                            size: Extent3d {
                                width: t.width,
                                height: t.height,
                                depth_or_array_layers: 1,
                            },
                            mip_level_count: 1,
                            sample_count: 1,
                            dimension: TextureDimension::D2,
                            format: TextureFormat::Rgba8Unorm,
                            usage: TextureUsages::TEXTURE_BINDING,
                            view_formats: &[],
                        },
                        TextureDataOrder::LayerMajor,
                        bytemuck::cast_slice(&t.texels),
                    )
                    .create_view(&default())
            })
            .collect();
        textures.resize(TEXTURE_SLOTS, blank.clone());
        Self {
            buffer,
            data: scene.data.clone(),
            textures,
        }
    }
}

/// The views the tracer may draw, with what it knows of them so far.
type TracerViews<'w, 's> = Query<
    'w,
    's,
    (
        Entity,
        &'static ExtractedView,
        &'static ViewTarget,
        Option<&'static ExtractedCurvedView>,
        Option<&'static mut TracerBindings>,
    ),
>;

// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
fn prepare_tracer_views(
    mut commands: Commands,
    views: TracerViews,
    tracer: Res<TracerPipeline>,
    mut pipelines: ResMut<SpecializedRenderPipelines<TracerPipeline>>,
    cache: Res<PipelineCache>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
    mut textures: ResMut<TextureCache>,
) {
    for (entity, view, target, curved, bindings) in views {
        let Some(curved) = curved else {
            if bindings.is_some() {
                commands.entity(entity).remove::<TracerBindings>();
            }
            continue;
        };
        let format = target.main_texture_format();
        let pipeline = pipelines.specialize(
            &cache,
            &tracer,
            TracerPipelineKey {
                shader: Some(curved.scene.key),
                view: curved.stereo.kind(),
                split: [false; 2],
                format,
            },
        );
        let viewport = view.viewport;
        let full = [viewport.z.max(1), viewport.w.max(1)];
        let scaled = full.map(|n| ((n as f32 * curved.resolution_scale).ceil() as u32).clamp(1, n));
        let reduced = (scaled != full).then(|| {
            let texture = textures.get(
                &device,
                TextureDescriptor {
                    label: Some("curved_space_reduced"),
                    size: Extent3d {
                        width: scaled[0],
                        height: scaled[1],
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: TextureDimension::D2,
                    format,
                    usage: TextureUsages::RENDER_ATTACHMENT | TextureUsages::TEXTURE_BINDING,
                    view_formats: &[],
                },
            );
            let bind_group = device.create_bind_group(
                "curved_space_upscale_bind_group",
                &cache.get_bind_group_layout(&tracer.upscale_layout),
                &BindGroupEntries::sequential((&texture.default_view, &tracer.sampler)),
            );
            let upscale = pipelines.specialize(
                &cache,
                &tracer,
                TracerPipelineKey {
                    shader: None,
                    view: ViewKind::Mono,
                    split: curved.stereo.split_axes(),
                    format,
                },
            );
            (texture, bind_group, upscale)
        });
        // The reduced target is drawn whole, from its own origin.
        let (origin, size) = match reduced {
            Some(_) => ([0, 0], scaled),
            None => ([viewport.x, viewport.y], full),
        };
        let layout = match curved.lens {
            Some(lens) => ViewLayout::mono(curved.eyes[0], lens, size[0], size[1]),
            None => ViewLayout::new(
                curved.stereo,
                curved.swap_eyes,
                curved.eyes,
                curved.fov_y_degrees,
                size[0],
                size[1],
            ),
        };
        let head = view_words(&layout, origin, &curved.extras);
        let words: Vec<u32> = head.iter().chain(&curved.scene.words).copied().collect();
        let data: &[u8] = bytemuck::cast_slice(&words);
        match bindings {
            // The same scene, or only its objects moved: the same mesh data, a uniform of
            // the same size.
            Some(mut b)
                if b.bytes == data.len() && Arc::ptr_eq(&b.scene_data.data, &curved.scene.data) =>
            {
                queue.write_buffer(&b.buffer, 0, data);
                b.scene = curved.scene.clone();
                b.pipeline = pipeline;
                b.reduced = reduced;
            }
            b => {
                let buffer = device.create_buffer_with_data(&BufferInitDescriptor {
                    label: Some("curved_space_uniform"),
                    contents: data,
                    usage: BufferUsages::UNIFORM | BufferUsages::COPY_DST,
                });
                let scene_data = match b {
                    Some(b) if Arc::ptr_eq(&b.scene_data.data, &curved.scene.data) => {
                        b.scene_data.clone()
                    }
                    _ => SceneDataGpu::new(&device, &queue, &curved.scene, &tracer.blank),
                };
                let t = &scene_data.textures;
                let bind_group = device.create_bind_group(
                    "curved_space_bind_group",
                    &cache.get_bind_group_layout(&tracer.layout),
                    &BindGroupEntries::sequential((
                        buffer.as_entire_binding(),
                        scene_data.buffer.as_entire_binding(),
                        &t[0],
                        &t[1],
                        &t[2],
                        &t[3],
                        &t[4],
                        &t[5],
                        &t[6],
                        &t[7],
                    )),
                );
                commands.entity(entity).insert(TracerBindings {
                    buffer,
                    bytes: data.len(),
                    scene: curved.scene.clone(),
                    scene_data,
                    bind_group,
                    pipeline,
                    reduced,
                });
            }
        }
    }
}

fn trace_views(
    view: ViewQuery<(&ViewTarget, &TracerBindings)>,
    cache: Res<PipelineCache>,
    frames: Res<FramesTraced>,
    failure: Res<TracerFailure>,
    mut ctx: RenderContext,
) {
    let (target, bindings) = view.into_inner();
    // A pipeline still building draws nothing yet; one that failed says why.
    let failed = |id: CachedRenderPipelineId| {
        if let CachedPipelineState::Err(e) = cache.get_render_pipeline_state(id) {
            failure.set(e.to_string());
        }
    };
    let Some(pipeline) = cache.get_render_pipeline(bindings.pipeline) else {
        failed(bindings.pipeline);
        return;
    };
    let upscale = match &bindings.reduced {
        Some((texture, bind_group, id)) => match cache.get_render_pipeline(*id) {
            Some(p) => Some((texture, bind_group, p)),
            None => {
                failed(*id);
                return;
            }
        },
        None => None,
    };
    let traced_into = upscale.map_or(target.main_texture_view(), |(t, _, _)| &t.default_view);
    let encoder = ctx.command_encoder();
    draw_fullscreen(
        encoder,
        traced_into,
        "curved_space_tracer_pass",
        pipeline,
        &bindings.bind_group,
    );
    if let Some((_, bind_group, upscale)) = upscale {
        draw_fullscreen(
            encoder,
            target.main_texture_view(),
            "curved_space_upscale_pass",
            upscale,
            bind_group,
        );
    }
    frames.0.fetch_add(1, Ordering::AcqRel);
}

/// One triangle over the whole of `view` (every pixel is written: nothing to load).
fn draw_fullscreen(
    encoder: &mut CommandEncoder,
    view: &TextureView,
    label: &'static str,
    pipeline: &RenderPipeline,
    bind_group: &BindGroup,
) {
    let mut pass = encoder.begin_render_pass(&RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target: None,
            ops: Operations::default(),
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.draw(0..3, 0..1);
}
