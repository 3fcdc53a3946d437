//! The GPU side: the scene packed for the WGSL tracer ([`gpu`]) and a small render node that
//! draws it over every camera carrying [`CurvedSpaceCamera`](crate::CurvedSpaceCamera).
//!
//! Modelled on Bevy 0.19's `FullscreenMaterial`, which specialises only on the target
//! format: the tracer is also specialised on the geometry, the face count and the object
//! kinds present (shader defs, [`gpu::ShaderKey`]), and its uniform is sized to the scene.

pub mod gpu;
pub mod offscreen;

use crate::player::PlayerFrame;
use crate::plugin::CurvedSpaceCamera;
use bevy::asset::{load_internal_asset, uuid_handle};
use bevy::core_pipeline::{Core3d, Core3dSystems, tonemapping::tonemapping};
use bevy::prelude::*;
use bevy::render::{
    Extract, ExtractSchedule, Render, RenderApp, RenderStartup, RenderSystems,
    render_resource::{
        BindGroup, BindGroupEntries, BindGroupLayoutDescriptor, BindGroupLayoutEntries, Buffer,
        BufferInitDescriptor, BufferUsages, CachedRenderPipelineId, ColorTargetState,
        ColorWrites, FragmentState, Operations, PipelineCache, RenderPassColorAttachment,
        RenderPassDescriptor, RenderPipelineDescriptor, ShaderStages, SpecializedRenderPipeline,
        SpecializedRenderPipelines, TextureFormat, VertexState, binding_types::uniform_buffer_sized,
    },
    renderer::{RenderContext, RenderDevice, RenderQueue, ViewQuery},
    sync_component::{SyncComponent, SyncComponentPlugin},
    sync_world::RenderEntity,
    view::{ExtractedView, ViewTarget},
};
use bevy::shader::Shader;
use gpu::{GpuScene, ShaderKey, view_words};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

/// The tracer's shader, loaded once as an internal asset.
pub const TRACER_SHADER: Handle<Shader> = uuid_handle!("4c2f8a7e-1d53-4b0e-9e61-2a7c3f9d8b15");

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

/// A curved-space view in the render world.
#[derive(Component, Clone, Debug)]
pub struct ExtractedCurvedView {
    pub frame: glam::DMat4,
    pub fov_y_degrees: f64,
    pub scene: Arc<GpuScene>,
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
            "../../shaders/curved_space.wgsl",
            Shader::from_wgsl
        );
        let frames = FramesTraced::default();
        app.insert_resource(frames.clone())
            .add_plugins(SyncComponentPlugin::<CurvedSpaceCamera>::default());
        let Some(render_app) = app.get_sub_app_mut(RenderApp) else {
            return;
        };
        render_app
            .insert_resource(frames)
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

fn extract_curved_views(
    mut commands: Commands,
    scene: Extract<Option<Res<PreparedScene>>>,
    views: Extract<Query<(RenderEntity, &CurvedSpaceCamera, &PlayerFrame)>>,
) {
    let Some(scene) = scene.as_ref() else {
        return;
    };
    for (entity, camera, frame) in &views {
        commands.entity(entity).insert(ExtractedCurvedView {
            frame: frame.0,
            fov_y_degrees: camera.fov_y_degrees,
            scene: scene.0.clone(),
        });
    }
}

/// The tracer's layout and shader.
#[derive(Resource)]
pub struct TracerPipeline {
    layout: BindGroupLayoutDescriptor,
}

/// One pipeline per shader key and target format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TracerPipelineKey {
    pub shader: ShaderKey,
    pub format: TextureFormat,
}

impl SpecializedRenderPipeline for TracerPipeline {
    type Key = TracerPipelineKey;

    fn specialize(&self, key: Self::Key) -> RenderPipelineDescriptor {
        let defs = key.shader.shader_defs();
        RenderPipelineDescriptor {
            label: Some("curved_space_tracer".into()),
            layout: vec![self.layout.clone()],
            vertex: VertexState {
                shader: TRACER_SHADER,
                shader_defs: defs.clone(),
                entry_point: Some("vertex".into()),
                buffers: vec![],
            },
            fragment: Some(FragmentState {
                shader: TRACER_SHADER,
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

fn init_tracer_pipeline(mut commands: Commands) {
    let layout = BindGroupLayoutDescriptor::new(
        "curved_space_tracer_layout",
        &BindGroupLayoutEntries::single(
            ShaderStages::VERTEX_FRAGMENT,
            uniform_buffer_sized(false, None),
        ),
    );
    commands.insert_resource(TracerPipeline { layout });
}

/// The uniform buffer, its bind group and the pipeline of one view.
#[derive(Component)]
pub struct TracerBindings {
    buffer: Buffer,
    bytes: usize,
    bind_group: BindGroup,
    pipeline: CachedRenderPipelineId,
}

fn prepare_tracer_views(
    mut commands: Commands,
    views: Query<(
        Entity,
        &ExtractedView,
        &ViewTarget,
        Option<&ExtractedCurvedView>,
        Option<&mut TracerBindings>,
    )>,
    tracer: Res<TracerPipeline>,
    mut pipelines: ResMut<SpecializedRenderPipelines<TracerPipeline>>,
    cache: Res<PipelineCache>,
    device: Res<RenderDevice>,
    queue: Res<RenderQueue>,
) {
    for (entity, view, target, curved, bindings) in views {
        let Some(curved) = curved else {
            if bindings.is_some() {
                commands.entity(entity).remove::<TracerBindings>();
            }
            continue;
        };
        let pipeline = pipelines.specialize(
            &cache,
            &tracer,
            TracerPipelineKey {
                shader: curved.scene.key,
                format: target.main_texture_format(),
            },
        );
        let viewport = view.viewport;
        let head = view_words(
            curved.frame,
            curved.fov_y_degrees,
            [viewport.x, viewport.y],
            [viewport.z, viewport.w],
        );
        let words: Vec<u32> = head.iter().chain(&curved.scene.words).copied().collect();
        let data: &[u8] = bytemuck::cast_slice(&words);
        match bindings {
            Some(mut b) if b.bytes == data.len() => {
                queue.write_buffer(&b.buffer, 0, data);
                b.pipeline = pipeline;
            }
            _ => {
                let buffer = device.create_buffer_with_data(&BufferInitDescriptor {
                    label: Some("curved_space_uniform"),
                    contents: data,
                    usage: BufferUsages::UNIFORM | BufferUsages::COPY_DST,
                });
                let bind_group = device.create_bind_group(
                    "curved_space_bind_group",
                    &cache.get_bind_group_layout(&tracer.layout),
                    &BindGroupEntries::single(buffer.as_entire_binding()),
                );
                commands.entity(entity).insert(TracerBindings {
                    buffer,
                    bytes: data.len(),
                    bind_group,
                    pipeline,
                });
            }
        }
    }
}

fn trace_views(
    view: ViewQuery<(&ViewTarget, &TracerBindings)>,
    cache: Res<PipelineCache>,
    frames: Res<FramesTraced>,
    mut ctx: RenderContext,
) {
    let (target, bindings) = view.into_inner();
    let Some(pipeline) = cache.get_render_pipeline(bindings.pipeline) else {
        return;
    };
    let pass = RenderPassDescriptor {
        label: Some("curved_space_tracer_pass"),
        color_attachments: &[Some(RenderPassColorAttachment {
            view: target.main_texture_view(),
            depth_slice: None,
            resolve_target: None,
            ops: Operations::default(),
        })],
        depth_stencil_attachment: None,
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    };
    {
        let mut render_pass = ctx.command_encoder().begin_render_pass(&pass);
        render_pass.set_pipeline(pipeline);
        render_pass.set_bind_group(0, &bindings.bind_group, &[]);
        render_pass.draw(0..3, 0..1);
    }
    frames.0.fetch_add(1, Ordering::AcqRel);
}

