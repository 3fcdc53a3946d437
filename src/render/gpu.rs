//! What the WGSL tracer needs, packed for its uniform: the shader key (geometry, face count,
//! object kinds and counts → shader defs) and the words of `SpaceUniform` in
//! `shaders/curved_space.wgsl`, in the same order and layout.
//!
//! Every member of the WGSL struct is a `vec4` or a `mat4x4` (or an array of them), so the
//! layout has no padding: the buffer is the members' components one after another.

use crate::geometry::Geometry;
use crate::space::Space;
use crate::stereo::{ViewKind, ViewLayout};
use crate::trace::{Object, Scene};
use bevy::shader::ShaderDefVal;
use glam::{DMat4, DVec4};

/// The WGSL source of the tracer.
pub const TRACER_WGSL: &str = include_str!("../../shaders/curved_space.wgsl");

/// The WGSL source of the upscaling pass (the resolution scale).
pub const UPSCALE_WGSL: &str = include_str!("../../shaders/upscale.wgsl");

/// wgpu's default `max_uniform_buffer_binding_size`: the tracer's data must fit in it.
pub const MAX_UNIFORM_BYTES: usize = 64 << 10;

/// The largest crossing budget the GPU tracer takes: every loop of the shader is bounded by
/// it (and by the face and object counts), so no frame can run away.
pub const MAX_GPU_BUDGET: u32 = 4096;

/// Words of the per-view part at the start of the uniform (`View`: two eye frames, three
/// vec4 and the two anaglyph matrices).
pub const VIEW_WORDS: usize = 76;

/// What the shader is specialised on: one compiled pipeline per key.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ShaderKey {
    pub geometry: Geometry,
    pub faces: u32,
    pub balls: u32,
    pub tubes: u32,
    /// The unspecialised variant (the benchmark's comparison): all geometries' formulas,
    /// arrays of [`GENERAL_CAPACITY`], geometry and counts read from the uniform.
    pub general: bool,
}

/// Array sizes of the unspecialised variant: faces, balls, tubes.
pub const GENERAL_CAPACITY: (u32, u32, u32) = (crate::space::MAX_FACES as u32, 256, 256);

impl ShaderKey {
    /// The shader defs of this key (see the header of `shaders/curved_space.wgsl`).
    #[must_use]
    pub fn shader_defs(&self) -> Vec<ShaderDefVal> {
        let (faces, balls, tubes) = self.array_sizes();
        let mut defs: Vec<ShaderDefVal> = if self.general {
            ["SPHERICAL", "EUCLIDEAN", "HYPERBOLIC", "CURVED", "GENERAL"]
                .map(ShaderDefVal::from)
                .into()
        } else {
            match self.geometry {
                Geometry::Spherical => vec!["SPHERICAL".into(), "CURVED".into()],
                Geometry::Euclidean => vec!["EUCLIDEAN".into()],
                Geometry::Hyperbolic => vec!["HYPERBOLIC".into(), "CURVED".into()],
            }
        };
        defs.push(ShaderDefVal::UInt("FACE_COUNT".into(), faces));
        defs.push(ShaderDefVal::UInt("PARTNER_VECS".into(), faces.div_ceil(4)));
        if balls > 0 {
            defs.push("BALLS".into());
            defs.push(ShaderDefVal::UInt("BALL_COUNT".into(), balls));
        }
        if tubes > 0 {
            defs.push("TUBES".into());
            defs.push(ShaderDefVal::UInt("TUBE_COUNT".into(), tubes));
        }
        defs
    }

    /// The sizes of the uniform's face, ball and tube arrays.
    #[must_use]
    pub fn array_sizes(&self) -> (u32, u32, u32) {
        if self.general {
            GENERAL_CAPACITY
        } else {
            (self.faces, self.balls, self.tubes)
        }
    }

    /// Size in bytes of `SpaceUniform` for this key.
    #[must_use]
    pub fn uniform_bytes(&self) -> usize {
        let vec4 = 16;
        let (faces, balls, tubes) = self.array_sizes();
        let view = VIEW_WORDS * 4;
        let shading_and_light = 4 * vec4;
        let partners = faces.div_ceil(4) as usize * vec4;
        let faces = faces as usize * (vec4 + 4 * vec4);
        let balls = balls as usize * 2 * vec4;
        let tubes = tubes as usize * 4 * vec4;
        let general = if self.general { vec4 } else { 0 };
        view + shading_and_light + faces + partners + balls + tubes + general
    }
}

/// Composes WGSL with shader defs through naga_oil (as Bevy does) into a naga module; the
/// error names the file and what went wrong.
pub fn compose_wgsl(
    source: &str,
    file_path: &str,
    defs: &[ShaderDefVal],
) -> Result<naga::Module, String> {
    use naga_oil::compose::{Composer, NagaModuleDescriptor, ShaderDefValue, ShaderType};
    let shader_defs = defs
        .iter()
        .map(|d| match d {
            ShaderDefVal::Bool(k, v) => (k.clone(), ShaderDefValue::Bool(*v)),
            ShaderDefVal::Int(k, v) => (k.clone(), ShaderDefValue::Int(*v)),
            ShaderDefVal::UInt(k, v) => (k.clone(), ShaderDefValue::UInt(*v)),
        })
        .collect();
    Composer::default()
        .make_naga_module(NagaModuleDescriptor {
            source,
            file_path,
            shader_type: ShaderType::Wgsl,
            shader_defs,
            additional_imports: &[],
        })
        .map_err(|e| format!("{file_path}: {e:?}"))
}

/// The scene cannot be given to the GPU tracer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GpuSceneError {
    #[error(
        "the scene needs {bytes} bytes of uniform data ({faces} faces, {balls} balls, {tubes} tubes), more than the {limit} bytes a GPU is guaranteed to bind; show fewer objects"
    )]
    TooLarge {
        bytes: usize,
        limit: usize,
        faces: u32,
        balls: u32,
        tubes: u32,
    },
    #[error("the crossing budget must be at least 1, got {0}")]
    NoCrossings(u32),
    #[error(
        "a crossing budget of {0} is more than the GPU tracer takes ({MAX_GPU_BUDGET}): a frame could run for seconds; the fog ends rays long before"
    )]
    BudgetTooLarge(u32),
}

/// The index each scene object has in the shader's lists, which [`GpuScene::new`] fills with
/// the balls first, then the tubes, each in scene order (the `HIT_ID` output reports it).
#[must_use]
pub fn gpu_object_indices(scene: &Scene) -> Vec<u32> {
    let balls = scene
        .objects
        .iter()
        .filter(|o| matches!(o, Object::Ball(_)))
        .count() as u32;
    let (mut ball, mut tube) = (0u32, balls);
    scene
        .objects
        .iter()
        .map(|o| {
            let counter = match o {
                Object::Ball(_) => &mut ball,
                Object::Tube(_) => &mut tube,
            };
            *counter += 1;
            *counter - 1
        })
        .collect()
}

/// A space and its scene, packed for the GPU (everything but the per-view camera part).
#[derive(Clone, Debug, PartialEq)]
pub struct GpuScene {
    pub key: ShaderKey,
    /// The words of `SpaceUniform` after `view`.
    pub words: Vec<u32>,
}

fn push_vec4(words: &mut Vec<u32>, v: DVec4) {
    words.extend(v.to_array().map(|x| (x as f32).to_bits()));
}

fn push_mat4(words: &mut Vec<u32>, m: DMat4) {
    for column in [m.x_axis, m.y_axis, m.z_axis, m.w_axis] {
        push_vec4(words, column);
    }
}

impl GpuScene {
    /// Packs a space and a scene with a crossing budget per ray.
    pub fn new(space: &Space, scene: &Scene, max_crossings: u32) -> Result<Self, GpuSceneError> {
        if max_crossings == 0 {
            return Err(GpuSceneError::NoCrossings(max_crossings));
        }
        if max_crossings > MAX_GPU_BUDGET {
            return Err(GpuSceneError::BudgetTooLarge(max_crossings));
        }
        let g = space.geometry;
        let balls: Vec<_> = scene
            .objects
            .iter()
            .filter_map(|o| match o {
                Object::Ball(b) => Some(b),
                Object::Tube(_) => None,
            })
            .collect();
        let tubes: Vec<_> = scene
            .objects
            .iter()
            .filter_map(|o| match o {
                Object::Tube(t) => Some(t),
                Object::Ball(_) => None,
            })
            .collect();
        let key = ShaderKey {
            geometry: g,
            faces: space.faces.len() as u32,
            balls: balls.len() as u32,
            tubes: tubes.len() as u32,
            general: false,
        };
        let bytes = key.uniform_bytes();
        if bytes > MAX_UNIFORM_BYTES {
            return Err(GpuSceneError::TooLarge {
                bytes,
                limit: MAX_UNIFORM_BYTES,
                faces: key.faces,
                balls: key.balls,
                tubes: key.tubes,
            });
        }
        let shading = &scene.shading;
        let light = &scene.light;
        let mut words = Vec::with_capacity(bytes / 4);
        push_vec4(&mut words, shading.fog_colour.extend(shading.ambient));
        push_vec4(
            &mut words,
            DVec4::new(
                shading.fog_distance,
                shading.cutoff_distance(),
                g.s(shading.near_light),
                f64::from(max_crossings),
            ),
        );
        push_vec4(&mut words, light.position);
        push_vec4(&mut words, (light.colour * light.power).extend(0.0));
        for face in &space.faces {
            push_vec4(&mut words, face.covector);
        }
        for face in &space.faces {
            push_mat4(&mut words, face.pairing);
        }
        let mut partners: Vec<u32> = space.faces.iter().map(|f| f.partner as u32).collect();
        partners.resize(4 * space.faces.len().div_ceil(4), 0);
        words.extend(partners);
        for ball in &balls {
            push_vec4(&mut words, ball.centre);
            let size = match g {
                Geometry::Euclidean => ball.radius,
                _ => g.cs(ball.radius).0,
            };
            push_vec4(&mut words, ball.colour.extend(size));
        }
        for tube in &tubes {
            push_vec4(&mut words, tube.a);
            push_vec4(&mut words, tube.towards_b());
            let size = match g {
                Geometry::Euclidean => tube.radius * tube.radius,
                _ => g.cs(tube.radius).0.powi(2),
            };
            push_vec4(&mut words, tube.colour.extend(size));
            let (c, s) = tube.cs_length();
            push_vec4(&mut words, DVec4::new(c, s, 0.0, 0.0));
        }
        debug_assert_eq!(words.len() * 4 + VIEW_WORDS * 4, bytes);
        Ok(Self { key, words })
    }
}

impl GpuScene {
    /// The same scene for the unspecialised shader variant: arrays padded to
    /// [`GENERAL_CAPACITY`] and the geometry and counts appended. `None` if the scene has
    /// more faces or objects than that.
    #[must_use]
    pub fn generalised(&self) -> Option<GpuScene> {
        let k = self.key;
        let (cap_faces, cap_balls, cap_tubes) = GENERAL_CAPACITY;
        if k.general || k.faces > cap_faces || k.balls > cap_balls || k.tubes > cap_tubes {
            return None;
        }
        let faces = k.faces as usize;
        // (words per element, elements, capacity) of each array, in uniform order.
        let arrays = [
            (4, faces, cap_faces as usize),
            (16, faces, cap_faces as usize),
            (4, faces.div_ceil(4), (cap_faces as usize).div_ceil(4)),
            (8, k.balls as usize, cap_balls as usize),
            (16, k.tubes as usize, cap_tubes as usize),
        ];
        let header = 16;
        let mut words = self.words[..header].to_vec();
        let mut at = header;
        for (size, count, capacity) in arrays {
            words.extend_from_slice(&self.words[at..at + size * count]);
            words.resize(words.len() + size * (capacity - count), 0);
            at += size * count;
        }
        debug_assert_eq!(at, self.words.len());
        let general = [
            self.key.geometry.kappa() as f32,
            k.faces as f32,
            k.balls as f32,
            k.tubes as f32,
        ];
        words.extend(general.map(f32::to_bits));
        Some(GpuScene {
            key: ShaderKey { general: true, ..k },
            words,
        })
    }
}

/// The per-view part of the uniform (`View` in the shader): the eyes' frames (columns
/// right, up, back, position), the frustum tangents, the viewport (origin and size in
/// pixels), the stereo split and eye swap, and the anaglyph matrices.
#[must_use]
pub fn view_words(layout: &ViewLayout, origin: [u32; 2]) -> [u32; VIEW_WORDS] {
    let mut words = Vec::with_capacity(VIEW_WORDS);
    for frame in layout.frames {
        push_mat4(&mut words, frame);
    }
    let lens = layout.lens;
    push_vec4(
        &mut words,
        DVec4::new(lens.left, lens.right, lens.bottom, lens.top),
    );
    push_vec4(
        &mut words,
        DVec4::new(
            f64::from(origin[0]),
            f64::from(origin[1]),
            layout.size[0],
            layout.size[1],
        ),
    );
    push_vec4(
        &mut words,
        DVec4::new(
            layout.split[0],
            layout.split[1],
            f64::from(u8::from(layout.swap_eyes)),
            0.0,
        ),
    );
    for m in [layout.anaglyph.0, layout.anaglyph.1] {
        push_mat4(&mut words, DMat4::from_mat3(m));
    }
    words
        .try_into()
        .expect("four mat4 and three vec4 are 76 words")
}

/// The shader defs of a view kind (added to the scene's, [`ShaderKey::shader_defs`]).
#[must_use]
pub fn view_shader_defs(kind: ViewKind) -> Vec<ShaderDefVal> {
    match kind {
        ViewKind::Mono => vec![],
        ViewKind::Split => vec!["STEREO_SPLIT".into()],
        ViewKind::Anaglyph => vec!["ANAGLYPH".into()],
    }
}
