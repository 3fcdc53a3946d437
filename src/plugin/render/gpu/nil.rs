//! A Nil space and its scene packed for the WGSL tracer's `NIL` variant
//! (`shaders/nil.wgsl`): the shading, empty face arrays (the box is the shader's own), the
//! box's half height and the lamp, the objects with their chart boxes, and the lamp's
//! images.

use super::VIEW_WORDS;
use super::key::NIL_OBJECT_VEC4S;
use super::{DataSources, GpuScene, GpuSceneError, MAX_UNIFORM_BYTES, ShaderKey};
use crate::geometry::Geometry;
use crate::plugin::render::layout::{GpuShading, UniformWriter, colour, vec4};
use crate::scene::lighting::LightPaths;
use crate::scene::lighting::open_tail_fluence;
use crate::space::nil::NIL_FACES;
use crate::space::nil::NilSpace;
use crate::trace::nil::walls::NilWalls;
use crate::trace::nil::{NilScene, NilShape};
use glam::DVec4;
use std::sync::Arc;

/// A chart coordinate for the shader: `f32`, with infinities (a fibre's height) as the
/// largest finite values.
fn finite(x: f64) -> f64 {
    x.clamp(-f64::from(f32::MAX), f64::from(f32::MAX))
}

impl GpuScene {
    /// Packs a Nil space and its scene with a crossing budget per ray. Drawn by
    /// [`crate::plugin::offscreen::OffscreenRenderer::render_nil`] (the command line's
    /// `render`) and by the plugin's render node while a Nil space is shown.
    pub fn nil(
        space: &NilSpace,
        scene: &NilScene,
        max_crossings: u32,
    ) -> Result<Self, GpuSceneError> {
        super::check_budget(max_crossings)?;
        let images = match scene.lighting.paths {
            LightPaths::Images => &scene.lamp.images[..],
            LightPaths::Nearest => &[],
        };
        let shadows = (scene.lighting.shadows as usize).min(images.len());
        let walls = scene
            .walls
            .and_then(|style| NilWalls::new(space, style, crate::scene::DEFAULT_CUTOFF_WEIGHT));
        // Walls need a slot per face for their colours (the face arrays stay unused).
        let faces = if walls.is_some() { NIL_FACES } else { 0 };
        let key = ShaderKey {
            nil: true,
            walls: walls.is_some(),
            faces: faces as u32,
            colour_by: scene.colour_by.index(),
            nil_objects: scene.objects.len() as u32,
            nil_images: images.len() as u32,
            nil_shadows: shadows > 0,
            ..ShaderKey::empty(Geometry::Euclidean)
        };
        let bytes = key.uniform_bytes();
        if bytes > MAX_UNIFORM_BYTES {
            return Err(GpuSceneError::TooLarge {
                bytes,
                limit: MAX_UNIFORM_BYTES,
                faces: 0,
                objects: scene.objects.len(),
                lights: 1,
            });
        }
        let mut out = UniformWriter::with_capacity(bytes);
        out.push(&GpuShading::of_fog(
            scene.fog_colour,
            scene.ambient,
            (scene.fog_distance, scene.cutoff_distance()),
            max_crossings,
        ));
        // No scene data, and the unused face slots (one, or a face's with walls): covectors,
        // pairings and their rests, partners.
        out.push(&[0u32; 4]);
        let slots = faces.max(1);
        for _ in 0..slots {
            out.push(&[0.0f32; 4]);
        }
        for _ in 0..2 * slots {
            out.push(&[[0.0f32; 4]; 4]);
        }
        for _ in 0..slots.div_ceil(4) {
            out.push(&[0u32; 4]);
        }
        out.push(&vec4(DVec4::new(
            space.half_height(),
            f64::from(space.k()),
            scene.objects.len() as f64,
            scene.power,
        )));
        let [x, y, z] = scene.light;
        out.push(&vec4(DVec4::new(
            x,
            y,
            z,
            scene.near_light * scene.near_light,
        )));
        for o in &scene.objects {
            let (shape, info, height) = match o.shape {
                NilShape::Ball(c) => (c, [0.0, o.radius, 0.0, 0.0], 0.0),
                NilShape::Fibre(b) => ([b[0], b[1], 0.0], [1.0, o.radius, 0.0, 0.0], 0.0),
                NilShape::Edge {
                    image,
                    along,
                    offset,
                    height,
                } => (image, [2.0, o.radius, along as f64, offset], height),
            };
            let (lo, hi) = o.chart_box();
            out.push(&vec4(DVec4::new(shape[0], shape[1], shape[2], 0.0)));
            out.push(&vec4(DVec4::from_array(info)));
            out.push(&colour(o.colour, height));
            out.push(&vec4(DVec4::new(
                finite(lo[0]),
                finite(lo[1]),
                finite(lo[2]),
                0.0,
            )));
            out.push(&vec4(DVec4::new(
                finite(hi[0]),
                finite(hi[1]),
                finite(hi[2]),
                0.0,
            )));
        }
        if scene.objects.is_empty() {
            out.push(&[[0.0f32; 4]; NIL_OBJECT_VEC4S]);
        }
        if !images.is_empty() {
            let tail = if scene.lighting.tail {
                0.25 * open_tail_fluence(scene.lamp.reach, scene.fog_distance, scene.lamp.volume)
            } else {
                0.0
            };
            out.push(&vec4(DVec4::new(
                images.len() as f64,
                tail,
                scene.lamp.reach,
                shadows as f64,
            )));
            for q in images {
                out.push(&vec4(DVec4::new(q[0], q[1], q[2], 0.0)));
            }
        }
        // The walls: per face an unused slot, the colour and margin (a huge number for a
        // solid wall), the opacity; then the share of light below which a ray stops.
        if let Some(walls) = &walls {
            for _ in 0..NIL_FACES {
                out.push(&[0.0f32; 4]);
            }
            for face in 0..NIL_FACES {
                let margin = walls.margins[usize::from(face >= 4)];
                out.push(&colour(walls.colours[face], margin.min(1e30)));
            }
            for _ in 0..NIL_FACES {
                out.push(&vec4(DVec4::new(walls.opacity, 0.0, 0.0, 0.0)));
            }
            out.push(&vec4(DVec4::new(walls.stop_below, 0.0, 0.0, 0.0)));
        }
        let words = out.words;
        debug_assert_eq!(words.len() * 4 + VIEW_WORDS * 4, bytes);
        Ok(Self {
            key,
            words,
            data: Arc::new(vec![0; 4]),
            textures: Arc::new(Vec::new()),
            avatar: None,
            sources: DataSources::empty(),
        })
    }
}
