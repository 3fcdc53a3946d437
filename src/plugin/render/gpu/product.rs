//! A product space (H²×R, S²×R) and its scene packed for the WGSL tracer's `PRODUCT`
//! variant (`shaders/product_walk.wgsl`, `product_objects.wgsl`, `product.wgsl`): the
//! shading, the side faces' covectors, every face's pairing (the sides', then the top's
//! `R⁻¹` and the bottom's `R`) with what rounding left out, the partners, the circle, the
//! light and the objects.

use super::VIEW_WORDS;
use super::key::PRODUCT_OBJECT_VEC4S;
use super::{DataSources, GpuScene, GpuSceneError, MAX_UNIFORM_BYTES, ShaderKey};
use crate::plugin::render::layout::{GpuShading, UniformWriter, Vec4F, colour, vec4};
use crate::scene::lighting::LightPaths;
use crate::space::product::{ProductSpace, ProductWalker};
use crate::trace::product::lighting::product_tail_fluence;
use crate::trace::product::triangle::ProductTriangle;
use crate::trace::product::walls::ProductWalls;
use crate::trace::product::{ProductScene, ProductShape};
use glam::{DVec4, Mat4, Vec4};
use std::sync::Arc;

impl GpuScene {
    /// Packs a product space and its scene with a crossing budget per ray. Drawn by
    /// [`crate::plugin::offscreen::OffscreenRenderer::render_product`] (the command line's
    /// `render`) and by the plugin's render node while a product space is shown (a player
    /// walks it as in any space).
    pub fn product(
        space: &ProductSpace,
        scene: &ProductScene,
        max_crossings: u32,
    ) -> Result<Self, GpuSceneError> {
        super::check_budget(max_crossings)?;
        let walker = ProductWalker::<Vec4>::new(space);
        let sides = walker.covectors.len();
        let walls = scene
            .walls
            .and_then(|style| ProductWalls::new(space, style, crate::scene::DEFAULT_CUTOFF_WEIGHT));
        // The lamp's images (none in the older model), the shadowed ones among them.
        let images = match scene.lighting.paths {
            LightPaths::Images => &scene.lamp.images[..],
            LightPaths::Nearest => &[],
        };
        let shadows = (scene.lighting.shadows as usize).min(images.len());
        let key = ShaderKey {
            walls: walls.is_some(),
            faces: sides as u32,
            step_cap: walker.step_cap,
            product: true,
            product_objects: scene.objects.len() as u32,
            colour_by: scene.colour_by.index(),
            product_images: images.len() as u32,
            product_shadows: shadows > 0,
            ..ShaderKey::empty(space.base())
        };
        let bytes = key.uniform_bytes();
        if bytes > MAX_UNIFORM_BYTES {
            return Err(GpuSceneError::TooLarge {
                bytes,
                limit: MAX_UNIFORM_BYTES,
                faces: key.faces,
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
        // No scene data: the offsets are unused.
        out.push(&[0u32; 4]);
        let slots = sides + 2;
        let mut covectors: Vec<Vec4F> = walker.covectors.iter().map(|c| c.to_array()).collect();
        covectors.resize(slots, [0.0; 4]);
        let hi: Vec<Mat4> = walker
            .pairings
            .iter()
            .copied()
            .chain([walker.up.0, walker.down.0])
            .collect();
        let lo: Vec<Mat4> = walker
            .pairings_lo
            .iter()
            .copied()
            .chain([walker.up.1, walker.down.1])
            .collect();
        for c in &covectors {
            out.push(c);
        }
        for m in hi.iter().chain(&lo) {
            out.push(&m.to_cols_array_2d());
        }
        let mut partners: Vec<u32> = walker.partners.iter().map(|&p| p as u32).collect();
        partners.resize(4 * slots.div_ceil(4), 0);
        out.words.extend(partners);
        out.push(&vec4(DVec4::new(
            0.5 * space.length(),
            scene.objects.len() as f64,
            0.0,
            0.0,
        )));
        out.push(&vec4(scene.light));
        for o in &scene.objects {
            let mut more = [DVec4::ZERO; 3];
            let mut info_zw = [0.0, 0.0];
            let (shape, kind, height) = match o.shape {
                ProductShape::Point(c) => (c, 0.0, 0.0),
                ProductShape::Fibre(c) => (c, 1.0, 0.0),
                ProductShape::Geodesic { covector, height } => (covector, 2.0, height),
                ProductShape::Disc(c) => (c, 3.0, c.z),
                ProductShape::Triangle(ProductTriangle::Horizontal { edges, height }) => {
                    more[0] = edges[1];
                    more[1] = edges[2];
                    (edges[0], 4.0, height)
                }
                ProductShape::Triangle(ProductTriangle::Vertical {
                    covector,
                    origin,
                    along,
                    corner,
                    to_barycentric: m,
                }) => {
                    more = [origin, along, DVec4::new(corner[0], corner[1], m[0], m[1])];
                    info_zw = [m[2], m[3]];
                    (covector, 5.0, 0.0)
                }
            };
            let height = if kind == 5.0 { info_zw[0] } else { height };
            out.push(&vec4(shape));
            out.push(&vec4(DVec4::new(kind, o.radius, height, info_zw[1])));
            out.push(&colour(o.colour, 0.0));
            for m in more {
                out.push(&vec4(m));
            }
        }
        if scene.objects.is_empty() {
            out.push(&[[0.0f32; 4]; PRODUCT_OBJECT_VEC4S]);
        }
        if !images.is_empty() {
            let tail = if scene.lighting.tail {
                0.25 * product_tail_fluence(scene.lamp.reach, scene.fog_distance, scene.lamp.volume)
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
                out.push(&vec4(*q));
            }
        }
        // The walls: per face slot the side's midpoint, the colour and margin (a huge
        // number for a solid wall), the opacity and half the side's length; then the share
        // of light below which a ray stops.
        if let Some(walls) = &walls {
            for w in &walls.faces {
                out.push(&vec4(w.midpoint));
            }
            for w in &walls.faces {
                out.push(&colour(w.colour, w.margin.min(1e30)));
            }
            for w in &walls.faces {
                out.push(&vec4(DVec4::new(walls.opacity, 0.0, w.half_side, 0.0)));
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
