//! The tracer's uniform as typed structs: each one is the Rust twin of a struct of
//! `shaders/curved_space.wgsl` (same name without `Gpu`, same members in the same order), so
//! the packer writes fields, not word offsets. Every member is a `vec4` or a `mat4x4` of f32
//! (or u32), so the WGSL layout has no padding and `#[repr(C)]` matches it; `tests/app/
//! shaders.rs` checks each struct's size and the uniform's against what naga computes from the
//! WGSL for every shader variant.

use bytemuck::{Pod, Zeroable};
use glam::{DMat4, DVec3, DVec4};

/// A `vec4<f32>`.
pub type Vec4F = [f32; 4];
/// A `mat4x4<f32>`, column by column.
pub type Mat4F = [[f32; 4]; 4];

/// A 4-vector rounded to f32.
#[must_use]
pub(crate) fn vec4(v: DVec4) -> Vec4F {
    v.to_array().map(|x| x as f32)
}

/// A colour and a fourth value rounded to f32.
#[must_use]
pub(crate) fn colour(rgb: DVec3, w: f64) -> Vec4F {
    vec4(rgb.extend(w))
}

/// A 4×4 matrix rounded to f32, column by column.
#[must_use]
pub(crate) fn mat4(m: DMat4) -> Mat4F {
    [m.x_axis, m.y_axis, m.z_axis, m.w_axis].map(vec4)
}

/// Images of the avatar the view carries (frame and inverse each).
pub const AVATAR_SLOTS: usize = crate::scene::MAX_AVATAR_IMAGES;

/// `View`: the per-view part at the start of the uniform.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuView {
    /// The eyes' frames, left then right.
    pub frames: [Mat4F; 2],
    /// Frustum tangents left, right, bottom, top.
    pub lens: Vec4F,
    /// Viewport origin and size in pixels.
    pub viewport: Vec4F,
    /// Split point (x, y), eye swap (0 or 1), the scene's time.
    pub split: Vec4F,
    /// Anaglyph matrices, left and right (upper 3×3).
    pub anaglyph: [Mat4F; 2],
    /// The avatar's images: frame and inverse, one pair each.
    pub avatar: [Mat4F; 2 * AVATAR_SLOTS],
    /// Images in use, pass-through distance, root node, unused.
    pub avatar_info: Vec4F,
}

/// `Shading` followed by the scene data offsets (`data: vec4<u32>`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuShading {
    /// Fog colour and ambient fraction.
    pub fog: Vec4F,
    /// Fog distance, cut-off distance, S(near light), crossing budget.
    pub params: Vec4F,
    /// `(1, 0, 0, 0)`: a one the shader compiler cannot see through, so that the compensated
    /// pairing's error-free transforms are not simplified away (`transform_compensated`).
    pub exact: Vec4F,
}

impl GpuShading {
    /// The shading of a family's own scene: fog colour and ambient share, fog distance λ and
    /// its cut-off, the crossing budget (no near light).
    #[must_use]
    pub fn of_fog(
        fog_colour: glam::DVec3,
        ambient: f64,
        (fog_distance, cutoff): (f64, f64),
        max_crossings: u32,
    ) -> Self {
        Self {
            fog: colour(fog_colour, ambient),
            params: vec4(glam::DVec4::new(
                fog_distance,
                cutoff,
                0.0,
                f64::from(max_crossings),
            )),
            exact: vec4(glam::DVec4::X),
        }
    }
}

/// `Ball` (plain balls).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuBall {
    /// The centre.
    pub centre: Vec4F,
    /// Albedo and C(ρ) (ρ in E³).
    pub colour: Vec4F,
    /// Emission, unused.
    pub emission: Vec4F,
}

/// `Tube`: an equidistant tube around a geodesic segment.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuTube {
    /// One end.
    pub a: Vec4F,
    /// Unit tangent at `a` towards the other end.
    pub towards_b: Vec4F,
    /// Albedo and C(ρ)² (ρ² in E³).
    pub colour: Vec4F,
    /// C(L), S(L) of the length L, unused ×2.
    pub length: Vec4F,
    /// Emission, unused.
    pub emission: Vec4F,
}

/// `Globe`: a textured, spinning ball.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuGlobe {
    /// The centre.
    pub centre: Vec4F,
    /// Albedo and C(ρ) (ρ in E³).
    pub colour: Vec4F,
    /// Emission and texture index.
    pub emission: Vec4F,
    /// Spin in radians per second, unused ×3.
    pub spin: Vec4F,
    /// The inverse of the globe's orientation frame.
    pub inverse: Mat4F,
}

/// `Disc`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuDisc {
    /// The centre.
    pub centre: Vec4F,
    /// Unit normal tangent at the centre.
    pub normal: Vec4F,
    /// The plane's covector.
    pub covector: Vec4F,
    /// Albedo and radius.
    pub colour: Vec4F,
    /// Emission, unused.
    pub emission: Vec4F,
}

/// `Instance`: a placed mesh.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuInstance {
    /// The mesh's frame.
    pub frame: Mat4F,
    /// Its inverse.
    pub inverse: Mat4F,
    /// Root node, material override (or `u32::MAX`), material base, unused.
    pub info: [u32; 4],
}

/// `Face` data as the uniform holds it: per face a covector, its pairing rounded to f32
/// and what that rounding left out (three arrays).
pub(crate) const FACE_BYTES: usize = size_of::<Vec4F>() + 2 * size_of::<Mat4F>();

/// The uniform's words so far, with typed pushes.
#[derive(Clone, Debug, Default)]
pub(crate) struct UniformWriter {
    /// The words written.
    pub(crate) words: Vec<u32>,
}

impl UniformWriter {
    /// An empty writer with room for `bytes`.
    #[must_use]
    pub(crate) fn with_capacity(bytes: usize) -> Self {
        Self {
            words: Vec::with_capacity(bytes / 4),
        }
    }

    /// Appends a struct's bytes.
    pub(crate) fn push<T: Pod>(&mut self, value: &T) {
        self.words
            .extend_from_slice(bytemuck::cast_slice::<T, u32>(std::slice::from_ref(value)));
    }
}
