//! The benchmark's GPU harness: the tracer's WGSL with the plugin's shader defs and uniform
//! packing, drawn as one fullscreen triangle into a texture with plain wgpu, so that a frame
//! is timed by itself (GPU timestamps around the pass where the adapter has them, else wall
//! time from submission to completion) and its pixels can be read back.

use crate::plugin::render::gpu::{
    GpuScene, ShaderKey, TEXTURE_SLOTS, TRACER_WGSL, compose_wgsl, view_shader_defs,
};
use crate::view::ViewKind;
use bevy::shader::ShaderDefVal;
use std::collections::HashMap;
use std::time::Instant;
use wgpu::util::DeviceExt;

/// WGSL of the baseline: a trivial fullscreen material (one colour from the pixel position)
/// of the same size, so that tracer timings can be given as ratios to it.
pub const BASELINE_WGSL: &str = include_str!("../../../shaders/bench_baseline.wgsl");

/// The GPU harness could not start or run.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum HarnessError {
    /// No GPU adapter was found (no GPU and no software Vulkan driver).
    #[error(
        "no GPU adapter was found (no GPU and no software Vulkan driver): on Debian install one with `apt-get install mesa-vulkan-drivers libvulkan1`"
    )]
    NoAdapter,
    /// The GPU device could not be opened (the reason is attached).
    #[error("the GPU device could not be opened: {0}")]
    Device(String),
    /// The shader did not compile (the compiler's message is attached).
    #[error("the shader did not compile: {0}")]
    Shader(String),
    /// The GPU failed while rendering (the reason is attached).
    #[error("the GPU failed while rendering: {0}")]
    Gpu(String),
}

/// What the results were measured on.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct DeviceInfo {
    /// The adapter's name.
    pub name: String,
    /// The graphics API (Vulkan, Metal, …).
    pub backend: String,
    /// Discrete, integrated, CPU, …
    pub device_type: String,
    /// The driver and its version.
    pub driver: String,
    /// Whether frame times come from GPU timestamps (else wall time around a synchronised
    /// submission).
    pub timestamps: bool,
}

/// Which pixels a pipeline writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Output {
    /// sRGB colour, the bytes the plugin's target holds.
    Colour,
    /// `HIT_ID`: what each ray met (`[u32; 4]` per pixel).
    HitId,
}

impl Output {
    fn format(self) -> wgpu::TextureFormat {
        match self {
            Output::Colour => wgpu::TextureFormat::Rgba8UnormSrgb,
            Output::HitId => wgpu::TextureFormat::Rgba32Uint,
        }
    }

    fn bytes_per_pixel(self) -> u32 {
        match self {
            Output::Colour => 4,
            Output::HitId => 16,
        }
    }
}

/// Which shader a pipeline runs.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum Program {
    /// The tracer with these shader defs, for this kind of view.
    Tracer(ShaderKey, ViewKind, Output),
    /// The trivial fullscreen material.
    Baseline,
}

/// A wgpu device with the pipelines compiled so far.
pub struct Harness {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: DeviceInfo,
    layout: wgpu::BindGroupLayout,
    pipelines: HashMap<Program, wgpu::RenderPipeline>,
    timestamp_period_ns: f64,
}

/// One drawn frame's texture and uniform, reused while the size and data stay the same.
pub struct Frame {
    width: u32,
    height: u32,
    output: Output,
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    bind_group: wgpu::BindGroup,
}

impl Harness {
    /// Opens the first adapter wgpu finds (a GPU, or lavapipe).
    pub fn new() -> Result<Self, HarnessError> {
        let instance = wgpu::Instance::new(crate::plugin::offscreen::instance_descriptor());
        let adapter = pollster_block(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            ..Default::default()
        }))
        .map_err(|_| HarnessError::NoAdapter)?;
        let timestamps = adapter.features().contains(wgpu::Features::TIMESTAMP_QUERY);
        let features = if timestamps {
            wgpu::Features::TIMESTAMP_QUERY
        } else {
            wgpu::Features::empty()
        };
        let (device, queue) = pollster_block(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("curved-spaces bench"),
            required_features: features,
            required_limits: wgpu::Limits::default(),
            ..Default::default()
        }))
        .map_err(|e| HarnessError::Device(e.to_string()))?;
        let a = adapter.get_info();
        let info = DeviceInfo {
            name: a.name.clone(),
            backend: format!("{:?}", a.backend),
            device_type: format!("{:?}", a.device_type),
            driver: format!("{} {}", a.driver, a.driver_info).trim().to_string(),
            timestamps,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("space uniform"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ]
            .into_iter()
            .chain(
                (0..TEXTURE_SLOTS as u32).map(|i| wgpu::BindGroupLayoutEntry {
                    binding: 2 + i,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                }),
            )
            .collect::<Vec<_>>(),
        });
        let timestamp_period_ns = f64::from(queue.get_timestamp_period());
        Ok(Self {
            device,
            queue,
            info,
            layout,
            pipelines: HashMap::new(),
            timestamp_period_ns,
        })
    }

    /// The device the harness runs on.
    #[must_use]
    pub fn info(&self) -> &DeviceInfo {
        &self.info
    }

    fn pipeline(&mut self, program: &Program) -> Result<&wgpu::RenderPipeline, HarnessError> {
        if !self.pipelines.contains_key(program) {
            let (source, path, defs, output) = match program {
                Program::Tracer(key, view, output) => {
                    let mut defs = [key.shader_defs(), view_shader_defs(*view)].concat();
                    if *output == Output::HitId {
                        defs.push(ShaderDefVal::from("HIT_ID"));
                    }
                    (TRACER_WGSL, "shaders/curved_space.wgsl", defs, *output)
                }
                Program::Baseline => (
                    BASELINE_WGSL,
                    "shaders/bench_baseline.wgsl",
                    Vec::new(),
                    Output::Colour,
                ),
            };
            let module = compose_wgsl(source, path, &defs).map_err(HarnessError::Shader)?;
            let device = &self.device;
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(path),
                source: wgpu::ShaderSource::Naga(std::borrow::Cow::Owned(module)),
            });
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: None,
                bind_group_layouts: &[Some(&self.layout)],
                immediate_size: 0,
            });
            let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(path),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vertex"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fragment"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: output.format(),
                        blend: None,
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            });
            self.pipelines.insert(program.clone(), pipeline);
        }
        Ok(&self.pipelines[program])
    }

    /// A target of `width × height` with `words` as the shader's uniform, and the scene
    /// data and textures of `scene` (none for the baseline).
    #[must_use]
    pub fn frame(
        &self,
        width: u32,
        height: u32,
        output: Output,
        words: &[u32],
        scene: Option<&GpuScene>,
    ) -> Frame {
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("bench target"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: output.format(),
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        // The baseline has no uniform; a one-vec4 buffer keeps one bind group layout.
        let contents: &[u32] = if words.is_empty() { &[0; 4] } else { words };
        let buffer = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("space uniform"),
                contents: bytemuck::cast_slice(contents),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        let data: &[u32] = match scene {
            Some(s) if !s.data.is_empty() => &s.data,
            _ => &[0; 4],
        };
        let data = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("scene data"),
                contents: bytemuck::cast_slice(data),
                usage: wgpu::BufferUsages::STORAGE,
            });
        let textures = self.scene_textures(scene);
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: data.as_entire_binding(),
                },
            ]
            .into_iter()
            .chain(
                textures
                    .iter()
                    .enumerate()
                    .map(|(i, view)| wgpu::BindGroupEntry {
                        binding: 2 + i as u32,
                        resource: wgpu::BindingResource::TextureView(view),
                    }),
            )
            .collect::<Vec<_>>(),
        });
        Frame {
            width,
            height,
            output,
            texture,
            view,
            bind_group,
        }
    }

    /// The views of `scene`'s GPU textures, slot by slot; 1×1 textures fill the slots it
    /// leaves empty.
    fn scene_textures(&self, scene: Option<&GpuScene>) -> Vec<wgpu::TextureView> {
        let texture = |width: u32, height: u32, texels: &[u32]| {
            self.device
                .create_texture_with_data(
                    &self.queue,
                    &wgpu::TextureDescriptor {
                        label: Some("scene texture"),
                        size: wgpu::Extent3d {
                            width,
                            height,
                            depth_or_array_layers: 1,
                        },
                        mip_level_count: 1,
                        sample_count: 1,
                        dimension: wgpu::TextureDimension::D2,
                        format: wgpu::TextureFormat::Rgba8Unorm,
                        usage: wgpu::TextureUsages::TEXTURE_BINDING,
                        view_formats: &[],
                    },
                    wgpu::util::TextureDataOrder::LayerMajor,
                    bytemuck::cast_slice(texels),
                )
                .create_view(&wgpu::TextureViewDescriptor::default())
        };
        let mut views: Vec<wgpu::TextureView> = scene
            .map(|s| s.textures.as_slice())
            .unwrap_or_default()
            .iter()
            .map(|t| texture(t.width, t.height, &t.texels))
            .collect();
        if views.len() < TEXTURE_SLOTS {
            let blank = texture(1, 1, &[0]);
            views.resize(TEXTURE_SLOTS, blank);
        }
        views
    }

    /// Draws the frame once with `program`; returns the frame time in milliseconds.
    pub fn draw(&mut self, program: &Program, frame: &Frame) -> Result<f64, HarnessError> {
        let timestamps = self.info.timestamps;
        let queries = timestamps.then(|| {
            let set = self.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: None,
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            });
            let resolve = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let read = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: None,
                size: 16,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            (set, resolve, read)
        });
        let pipeline = self.pipeline(program)?.clone();
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("bench pass"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &frame.view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: queries.as_ref().map(|(set, _, _)| {
                    wgpu::RenderPassTimestampWrites {
                        query_set: set,
                        beginning_of_pass_write_index: Some(0),
                        end_of_pass_write_index: Some(1),
                    }
                }),
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &frame.bind_group, &[]);
            pass.draw(0..3, 0..1);
        }
        if let Some((set, resolve, read)) = &queries {
            encoder.resolve_query_set(set, 0..2, resolve, 0);
            encoder.copy_buffer_to_buffer(resolve, 0, read, 0, 16);
        }
        let start = Instant::now();
        self.queue.submit([encoder.finish()]);
        self.wait()?;
        let wall_ms = start.elapsed().as_secs_f64() * 1e3;
        let Some((_, _, read)) = &queries else {
            return Ok(wall_ms);
        };
        let bytes = self.read_buffer(read)?;
        let t: &[u64] = bytemuck::cast_slice(&bytes);
        let ticks = t[1].saturating_sub(t[0]);
        if ticks == 0 {
            // Some drivers report zero for a pass; the wall time is then the measurement.
            return Ok(wall_ms);
        }
        Ok(ticks as f64 * self.timestamp_period_ns * 1e-6)
    }

    /// The frame's pixels, row by row without padding (`width × height × bytes per pixel`).
    pub fn read_pixels(&self, frame: &Frame) -> Result<Vec<u8>, HarnessError> {
        let bpp = frame.output.bytes_per_pixel();
        let row = frame.width * bpp;
        let padded =
            row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: u64::from(padded) * u64::from(frame.height),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut encoder = self
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
        encoder.copy_texture_to_buffer(
            wgpu::TexelCopyTextureInfo {
                texture: &frame.texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            wgpu::TexelCopyBufferInfo {
                buffer: &buffer,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(padded),
                    rows_per_image: Some(frame.height),
                },
            },
            wgpu::Extent3d {
                width: frame.width,
                height: frame.height,
                depth_or_array_layers: 1,
            },
        );
        self.queue.submit([encoder.finish()]);
        self.wait()?;
        let bytes = self.read_buffer(&buffer)?;
        Ok(bytes
            .chunks(padded as usize)
            .flat_map(|r| &r[..row as usize])
            .copied()
            .collect())
    }

    fn wait(&self) -> Result<(), HarnessError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map(|_| ())
            .map_err(|e| HarnessError::Gpu(e.to_string()))
    }

    fn read_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, HarnessError> {
        let slice = buffer.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.wait()?;
        rx.recv()
            .map_err(|e| HarnessError::Gpu(e.to_string()))?
            .map_err(|e| HarnessError::Gpu(e.to_string()))?;
        let bytes = slice.get_mapped_range().to_vec();
        buffer.unmap();
        Ok(bytes)
    }
}

fn pollster_block<F: std::future::Future>(future: F) -> F::Output {
    bevy::tasks::block_on(future)
}
