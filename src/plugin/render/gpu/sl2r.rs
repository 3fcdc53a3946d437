//! An SL̃(2,R) space and its scene packed for the WGSL tracer's `SL2R` variant
//! (`shaders/sl2r.wgsl`): the shading, the polygon's sides as the face arrays (covectors,
//! 3×3 pairings in a mat4 with what rounding to f32 left out, partners), then the tubes
//! (base point and radius; colour and `cosh` of the radius) and the balls (the centre's
//! base point and radius; its `e` and `cosh` of the radius; colour and `sinh` of the radius;
//! in a fibre cover its sheet and fibre angle), then the lamp (power, the falloff's floor,
//! the reach, the images shadowed; the images' count and the tail's light) and its images
//! (`f` and the sheet; the base point `q`). A cover's side turns
//! ([`UnitTangentSpace::side_turn_reference`]) ride in the covectors' fourth entries (the raw
//! turn at the midpoint) and the rests' unused corner (its lift); the header's third entry is
//! the number of sheets. With walls, the layout's wall arrays follow: per side its direction
//! at the midpoint, its colour and the window's reach, its opacity and normal.

use super::VIEW_WORDS;
use super::{DataSources, GpuScene, GpuSceneError, MAX_UNIFORM_BYTES, ShaderKey};
use crate::geometry::{DoubleDouble, Geometry};
use crate::plugin::render::layout::{GpuShading, UniformWriter, colour, vec4};
use crate::scene::lighting::{LightPaths, open_tail_fluence};
use crate::space::sl2r::UnitTangentSpace;
use crate::trace::sl2r::Sl2rScene;
use crate::trace::sl2r::light::{LampImage, MAX_LIGHT_REACH};
use glam::DVec4;
use std::sync::Arc;

/// A double-double as the nearest `f32` and the `f32` nearest what that leaves out.
fn split(x: DoubleDouble) -> (f32, f32) {
    let hi = x.round_f32();
    let rest = (x - DoubleDouble::new(f64::from(hi))).hi;
    (hi, rest as f32)
}

impl GpuScene {
    /// Packs an SL̃(2,R) space and its scene with a crossing budget per ray. Drawn by
    /// [`crate::plugin::offscreen::OffscreenRenderer::render_sl2r`] (the command line's
    /// `render`).
    pub fn sl2r(
        space: &UnitTangentSpace,
        scene: &Sl2rScene,
        max_crossings: u32,
    ) -> Result<Self, GpuSceneError> {
        super::check_budget(max_crossings)?;
        let sides = space.sides();
        let walls = scene.walls.and_then(|style| {
            crate::trace::sl2r::walls::Sl2rWalls::new(
                space,
                style,
                crate::scene::DEFAULT_CUTOFF_WEIGHT,
            )
        });
        // The lamp's images within the reach, or the lamp itself for the nearest path
        // (unshadowed, no tail, within the longest reach).
        let lighting = &scene.lighting;
        let lamp = LampImage {
            frame: scene.light,
            sheet: scene.light_sheet,
        };
        let (images, reach, shadows, tail) = match lighting.paths {
            LightPaths::Images => (
                scene.lamp.images.clone(),
                scene.lamp.reach,
                (lighting.shadows as usize).min(scene.lamp.images.len()),
                if lighting.tail {
                    0.25 * open_tail_fluence(
                        scene.lamp.reach,
                        scene.fog_distance,
                        scene.lamp.volume,
                    )
                } else {
                    0.0
                },
            ),
            LightPaths::Nearest => (vec![lamp], MAX_LIGHT_REACH, 0, 0.0),
        };
        let key = ShaderKey {
            sl2r: true,
            walls: walls.is_some(),
            sl2r_tubes: scene.tubes.len() as u32,
            sl2r_balls: scene.balls.len() as u32,
            sl2r_cover: space.sheets() > 1,
            faces: sides.len() as u32,
            colour_by: scene.colour_by.index(),
            sl2r_images: images.len() as u32,
            sl2r_shadows: shadows > 0,
            ..ShaderKey::empty(Geometry::Hyperbolic)
        };
        let bytes = key.uniform_bytes();
        if bytes > MAX_UNIFORM_BYTES {
            return Err(GpuSceneError::TooLarge {
                bytes,
                limit: MAX_UNIFORM_BYTES,
                faces: sides.len() as u32,
                objects: scene.tubes.len() + scene.balls.len(),
                lights: 0,
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
        // A cover's side turns: the raw turn at the side's midpoint beside the covector,
        // its lift in the rests' unused corner.
        let turns: Vec<(f64, f64)> = (0..sides.len())
            .map(|f| {
                if key.sl2r_cover {
                    space.side_turn_reference(f)
                } else {
                    (0.0, 0.0)
                }
            })
            .collect();
        for (s, turn) in sides.iter().zip(&turns) {
            let n = s.normal.map(|x| split(x).0);
            out.push(&[n[0], n[1], n[2], turn.0 as f32]);
        }
        // The pairings as mat4 columns (column j holds the 3×3's column j), then the rests.
        for part in [0usize, 1] {
            for (s, turn) in sides.iter().zip(&turns) {
                let mut m = [[0.0f32; 4]; 4];
                for (j, column) in m.iter_mut().enumerate().take(3) {
                    for (r, x) in column.iter_mut().enumerate().take(3) {
                        let (hi, lo) = split(s.pairing[r][j]);
                        *x = if part == 0 { hi } else { lo };
                    }
                }
                m[3][3] = if part == 0 { 1.0 } else { turn.1 as f32 };
                out.push(&m);
            }
        }
        let mut partners: Vec<u32> = sides.iter().map(|s| s.partner as u32).collect();
        partners.resize(4 * sides.len().div_ceil(4), 0);
        out.words.extend(partners);
        out.push(&vec4(DVec4::new(
            scene.tubes.len() as f64,
            scene.balls.len() as f64,
            f64::from(space.sheets()),
            0.0,
        )));
        for t in &scene.tubes {
            out.push(&vec4(DVec4::new(t.base[0], t.base[1], t.base[2], t.radius)));
            out.push(&colour(t.colour, t.radius.cosh()));
        }
        for b in &scene.balls {
            let [e, _, p] = b.centre;
            out.push(&vec4(DVec4::new(p[0], p[1], p[2], b.radius)));
            out.push(&vec4(DVec4::new(e[0], e[1], e[2], b.radius.cosh())));
            out.push(&colour(b.colour, b.radius.sinh()));
            if key.sl2r_cover {
                let angle = crate::space::sl2r::cover::fibre_angle(&b.centre);
                out.push(&vec4(DVec4::new(f64::from(b.sheet), angle, 0.0, 0.0)));
            }
        }
        if scene.tubes.is_empty() && scene.balls.is_empty() {
            out.push(&[[0.0f32; 4]; 2]);
        }
        out.push(&vec4(DVec4::new(
            scene.power,
            scene.near_light * scene.near_light,
            reach,
            shadows as f64,
        )));
        out.push(&vec4(DVec4::new(images.len() as f64, tail, 0.0, 0.0)));
        for image in &images {
            let [f, _, q] = image.frame;
            out.push(&vec4(DVec4::new(f[0], f[1], f[2], f64::from(image.sheet))));
            out.push(&vec4(DVec4::new(q[0], q[1], q[2], 0.0)));
        }
        if images.is_empty() {
            out.push(&[[0.0f32; 4]; 2]);
        }
        // The walls: per side its direction at the midpoint; its pair's colour and how far
        // along it the window reaches (−1: solid); the opacity and the side's normal; then
        // the share of light below which a ray stops.
        if let Some(walls) = &walls {
            for t in &walls.along {
                out.push(&vec4(DVec4::new(t[0], t[1], t[2], 0.0)));
            }
            for c in &walls.colours {
                out.push(&colour(*c, walls.window));
            }
            for n in &walls.normals {
                out.push(&vec4(DVec4::new(walls.opacity, n[0], n[1], n[2])));
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
