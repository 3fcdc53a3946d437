//! Views: the camera and how pixels map to rays, for one eye or two.
//!
//! The pixel mapping of every layout (mono, side-by-side, top-bottom, anaglyph) is defined
//! here once, in [`ViewLayout`]; the CPU reference renders through it and the GPU packer
//! writes it into the shader's uniform, where `shaders/curved_space.wgsl` mirrors it.

pub mod headset;
pub mod stereo;

pub use stereo::StereoMode;

use crate::colour::{linear_to_srgb, srgb_to_linear};
use crate::geometry::{Geometry, GeometryError, Ray};
use crate::space::Space;
use glam::{DMat3, DMat4, DVec3, DVec4};

/// A pinhole camera: a frame (columns right, up, back, position) and a vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TraceCamera {
    /// Columns right, up, back, position.
    pub frame: DMat4,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

impl TraceCamera {
    /// A camera at chart point `eye` looking at chart point `target`, chart y up.
    pub fn looking_at(
        geometry: Geometry,
        eye: DVec3,
        target: DVec3,
        fov_y_degrees: f64,
    ) -> Result<Self, GeometryError> {
        Ok(Self {
            frame: geometry.look_at(eye, target, DVec3::Y)?,
            fov_y_degrees,
        })
    }

    /// The default view of a space: from 60 % of the inradius out, looking past the centre
    /// ball so that its copies through the faces show.
    #[must_use]
    pub fn default_for(space: &Space) -> Self {
        let g = space.geometry;
        // The 3-sphere's inradius is π: stay within the chart's hemisphere (S³ only: a flat
        // cell has no length of its own).
        let r = crate::space::invariants::inradius_at_most(space, std::f64::consts::FRAC_PI_2);
        let chart = |dir: DVec3, t: f64| g.to_chart(g.translation(dir, t) * space.centre());
        let eye = chart(DVec3::new(0.3, 0.22, 1.0), 0.75 * r);
        let target = chart(DVec3::new(-0.5, -0.1, -0.3), 0.5 * r);
        Self::looking_at(g, eye, target, 70.0)
            .expect("a point inside the cell is a valid chart point")
    }

    /// The unit tangent of the ray through pixel `(i, j)` of a `width × height` image:
    /// `normalize(px·right + py·up − back)` (the mono case of [`ViewLayout`]).
    #[must_use]
    pub fn ray(&self, geometry: Geometry, i: u32, j: u32, width: u32, height: u32) -> Ray<DVec4> {
        self.layout(width, height).ray_at(geometry, i, j)
    }

    /// The mono pixel mapping of a `width × height` image.
    #[must_use]
    pub fn layout(&self, width: u32, height: u32) -> ViewLayout {
        ViewLayout::new(
            StereoMode::Mono,
            false,
            [self.frame; 2],
            self.fov_y_degrees,
            width,
            height,
        )
    }
}

/// What the shader is specialised on for a view: one eye, two eyes in two parts of the
/// image, or two eyes traced per pixel and mixed.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ViewKind {
    /// One eye.
    #[default]
    Mono,
    /// Two eyes in two parts of the picture.
    Split,
    /// Two eyes per pixel, mixed.
    Anaglyph,
}

/// A view frustum as the tangents of its four half-angles: a camera ray through image point
/// `(u, v)` ∈ [0, 1]² (v down) has direction `x·right + y·up − back` with
/// `x = left·(1−u) + right·u` and `y = top·(1−v) + bottom·v`. `left` and `bottom` are
/// negative for a frustum around the view axis; XR views are asymmetric.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// Tangent of the left half-angle (negative left of the axis).
    pub left: f64,
    /// Tangent of the right half-angle.
    pub right: f64,
    /// Tangent of the lower half-angle (negative below the axis).
    pub bottom: f64,
    /// Tangent of the upper half-angle.
    pub top: f64,
}

impl Lens {
    /// A symmetric frustum of vertical field of view `fov_y_degrees` and aspect ratio
    /// (width / height) `aspect`.
    #[must_use]
    pub fn symmetric(fov_y_degrees: f64, aspect: f64) -> Self {
        let half = (fov_y_degrees.to_radians() / 2.0).tan();
        Self {
            left: -half * aspect,
            right: half * aspect,
            bottom: -half,
            top: half,
        }
    }

    /// From the four half-angles in radians (OpenXR's `Fovf`: left and down negative).
    #[must_use]
    pub fn from_angles(left: f64, right: f64, down: f64, up: f64) -> Self {
        Self {
            left: left.tan(),
            right: right.tan(),
            bottom: down.tan(),
            top: up.tan(),
        }
    }

    /// The direction coefficients `(x, y)` of image point `(u, v)`.
    #[must_use]
    pub fn at(&self, u: f64, v: f64) -> (f64, f64) {
        (
            self.left * (1.0 - u) + self.right * u,
            self.top * (1.0 - v) + self.bottom * v,
        )
    }
}

/// How a view's pixels map to eyes and camera rays: what the CPU reference renders and the
/// GPU packer writes into the shader's `View` (the shader mirrors [`ViewLayout::rays_at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewLayout {
    /// The eyes' frames `[left, right]` (both the head's frame in mono).
    pub frames: [DMat4; 2],
    /// The frustum of each eye's picture.
    pub lens: Lens,
    /// The view's size in pixels.
    pub size: [f64; 2],
    /// Where the second half of the image starts (pixels, in x for side-by-side, in y for
    /// top-bottom; 0 for none).
    pub split: [f64; 2],
    /// Whether the left half shows the right eye.
    pub swap_eyes: bool,
    /// What the shader is specialised on.
    pub kind: ViewKind,
    /// The anaglyph's matrices (identity and zero otherwise).
    pub anaglyph: (DMat3, DMat3),
}

/// The camera rays of one pixel: one, or two for an anaglyph (left eye first).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PixelRays {
    /// One eye's ray.
    One(Ray<DVec4>),
    /// The left and the right eye's rays.
    Two(Ray<DVec4>, Ray<DVec4>),
}

impl ViewLayout {
    /// A layout for a view of `width × height` pixels with vertical field of view
    /// `fov_y_degrees` (each eye's picture has it).
    #[must_use]
    pub fn new(
        stereo: StereoMode,
        swap_eyes: bool,
        eyes: [DMat4; 2],
        fov_y_degrees: f64,
        width: u32,
        height: u32,
    ) -> Self {
        let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
        let [split_x, split_y] = stereo.split_axes();
        let split = [
            if split_x { w / 2.0 } else { 0.0 },
            if split_y { h / 2.0 } else { 0.0 },
        ];
        // Each eye's picture keeps its own aspect, unless squeezed into its half (3D TVs).
        let aspect = match stereo {
            StereoMode::SideBySideHalf | StereoMode::TopBottomHalf => w / h,
            _ if split_x => (w / 2.0) / h,
            _ if split_y => w / (h / 2.0),
            _ => w / h,
        };
        Self {
            frames: eyes,
            lens: Lens::symmetric(fov_y_degrees, aspect),
            size: [w, h],
            split,
            swap_eyes,
            kind: stereo.kind(),
            anaglyph: stereo
                .anaglyph_matrices()
                .unwrap_or((DMat3::IDENTITY, DMat3::ZERO)),
        }
    }

    /// A mono view from one camera `frame` with a vertical field of view of `fov_y_degrees`
    /// (the default lens): what a still picture or a flight's frame draws.
    #[must_use]
    pub fn camera(frame: DMat4, fov_y_degrees: f64, width: u32, height: u32) -> Self {
        Self::new(
            StereoMode::Mono,
            false,
            [frame; 2],
            fov_y_degrees,
            width,
            height,
        )
    }

    /// A mono view with its own frustum (an XR eye).
    #[must_use]
    pub fn mono(frame: DMat4, lens: Lens, width: u32, height: u32) -> Self {
        Self {
            frames: [frame; 2],
            lens,
            size: [f64::from(width.max(1)), f64::from(height.max(1))],
            split: [0.0, 0.0],
            swap_eyes: false,
            kind: ViewKind::Mono,
            anaglyph: (DMat3::IDENTITY, DMat3::ZERO),
        }
    }

    /// Which eye (0 left, 1 right) a pixel centre `(x, y)` shows, and its point `(u, v)`
    /// in that eye's picture. Anaglyph and mono views answer eye 0 over the whole view.
    #[must_use]
    pub fn eye_at(&self, x: f64, y: f64) -> (usize, [f64; 2]) {
        let [sx, sy] = self.split;
        let second = (sx > 0.0 && x >= sx) || (sy > 0.0 && y >= sy);
        let half = usize::from(self.kind == ViewKind::Split && second);
        let (x, y) = (x - half as f64 * sx, y - half as f64 * sy);
        let eye_w = if sx > 0.0 { sx } else { self.size[0] };
        let eye_h = if sy > 0.0 { sy } else { self.size[1] };
        let eye = if self.kind == ViewKind::Split {
            half ^ usize::from(self.swap_eyes)
        } else {
            0
        };
        (eye, [x / eye_w, y / eye_h])
    }

    /// The camera ray of eye `eye` through image point `(u, v)` as the frame gives it: from
    /// the frame's fourth column along `x·right + y·up − back`, not yet a unit tangent
    /// (each family makes it one in its own model).
    #[must_use]
    pub fn frame_ray(&self, eye: usize, u: f64, v: f64) -> Ray<DVec4> {
        let f = self.frames[eye];
        let (x, y) = self.lens.at(u, v);
        Ray {
            point: f.w_axis,
            tangent: x * f.x_axis + y * f.y_axis - f.z_axis,
        }
    }

    /// The unit camera ray of eye `eye` through image point `(u, v)`.
    #[must_use]
    pub fn ray(&self, geometry: Geometry, eye: usize, u: f64, v: f64) -> Ray<DVec4> {
        let ray = self.frame_ray(eye, u, v);
        Ray {
            point: ray.point,
            tangent: geometry.unit_tangent(ray.point, ray.tangent),
        }
    }

    /// The camera ray through the centre of pixel `(i, j)`: the left eye's for an anaglyph.
    #[must_use]
    pub fn ray_at(&self, geometry: Geometry, i: u32, j: u32) -> Ray<DVec4> {
        match self.rays_at(geometry, i, j) {
            PixelRays::One(ray) | PixelRays::Two(ray, _) => ray,
        }
    }

    /// The camera rays through the centre of pixel `(i, j)`.
    #[must_use]
    pub fn rays_at(&self, geometry: Geometry, i: u32, j: u32) -> PixelRays {
        let (x, y) = (f64::from(i) + 0.5, f64::from(j) + 0.5);
        let (eye, [u, v]) = self.eye_at(x, y);
        match self.kind {
            ViewKind::Anaglyph => {
                PixelRays::Two(self.ray(geometry, 0, u, v), self.ray(geometry, 1, u, v))
            }
            _ => PixelRays::One(self.ray(geometry, eye, u, v)),
        }
    }

    /// The anaglyph's colour (8-bit-encoded values in [0, 1], as the tracer's colours are)
    /// from the two eyes' colours: decoded to linear RGB, mixed, clamped and encoded again.
    #[must_use]
    pub fn mix_anaglyph(&self, left: DVec3, right: DVec3) -> DVec3 {
        let (ml, mr) = self.anaglyph;
        let linear = ml * srgb_to_linear(left) + mr * srgb_to_linear(right);
        linear_to_srgb(linear.clamp(DVec3::ZERO, DVec3::ONE))
    }
}
