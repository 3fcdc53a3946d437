//! Rendering a picture with the f64 reference: a camera ray per pixel walks the cell,
//! nearest object hit against exit face, crossing by pairings until the fog cut-off or the
//! crossing budget.

use super::{CellWalker, Ray, Scene, scene::Hit};
use crate::geometry::{Geometry, GeometryError};
use crate::space::Space;
use glam::{DMat4, DVec3, DVec4};
use image::RgbImage;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// A pinhole camera: a frame (columns right, up, back, position) and a vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub frame: DMat4,
    pub fov_y_degrees: f64,
}

impl Camera {
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
        let r = crate::space::invariants::inradius(space);
        let chart = |dir: DVec3, t: f64| g.to_chart(g.translation(dir, t) * space.centre());
        let eye = chart(DVec3::new(0.3, 0.22, 1.0), 0.75 * r);
        let target = chart(DVec3::new(-0.5, -0.1, -0.3), 0.5 * r);
        Self::looking_at(g, eye, target, 70.0)
            .expect("a point inside the cell is a valid chart point")
    }

    /// The unit tangent of the ray through pixel `(i, j)` of a `width × height` image:
    /// `normalize(px·right + py·up − back)`.
    #[must_use]
    pub fn ray(&self, geometry: Geometry, i: u32, j: u32, width: u32, height: u32) -> Ray<DVec4> {
        let half = (self.fov_y_degrees.to_radians() / 2.0).tan();
        let aspect = width as f64 / height as f64;
        let px = (2.0 * (i as f64 + 0.5) / width as f64 - 1.0) * half * aspect;
        let py = (1.0 - 2.0 * (j as f64 + 0.5) / height as f64) * half;
        let f = self.frame;
        let v = px * f.x_axis + py * f.y_axis - f.z_axis;
        let point = f.w_axis;
        Ray {
            point,
            tangent: geometry.unit_tangent(point, v),
        }
    }
}

/// Image size and the speed/error knobs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Crossing budget per ray; a ray that uses it up shows the fog colour.
    pub max_crossings: usize,
}

/// What a camera ray meets first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneHit {
    /// Index into [`Scene::objects`].
    pub object: usize,
    pub hit: Hit,
    /// Geodesic distance from the camera.
    pub distance: f64,
    /// Face crossings before the hit.
    pub crossings: usize,
}

/// How a camera ray ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RayEnd {
    /// It hit an object before the cut-off.
    Hit(SceneHit),
    /// It reached the fog cut-off distance after this many crossings.
    Fog(usize),
    /// It used up the crossing budget.
    Budget,
}

/// Walks a camera ray through the cell: nearest object hit against the exit face, crossing
/// by pairings, until a hit, the fog cut-off or the crossing budget.
#[must_use]
pub fn first_hit(
    walker: &CellWalker<DVec4>,
    scene: &Scene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> RayEnd {
    let g = walker.geometry;
    let cutoff = scene.shading.cutoff_distance();
    let mut ray = start;
    let mut distance = 0.0;
    let mut skip = None;
    for crossings in 0..=max_crossings {
        let Some(exit) = walker.exit(&ray, skip) else {
            break;
        };
        let s_exit = exit.ratio();
        let nearest = scene
            .objects
            .iter()
            .enumerate()
            .filter_map(|(i, o)| {
                o.intersect(g, ray.point, ray.tangent, s_exit)
                    .map(|h| (i, h))
            })
            .min_by(|a, b| a.1.s.total_cmp(&b.1.s));
        if let Some((object, hit)) = nearest {
            let d = distance + g.distance_from_ratio(hit.s, 1.0);
            if d >= cutoff {
                return RayEnd::Fog(crossings);
            }
            return RayEnd::Hit(SceneHit {
                object,
                hit,
                distance: d,
                crossings,
            });
        }
        if crossings == max_crossings {
            break;
        }
        let (next, length) = walker.cross(&ray, &exit);
        distance += length;
        if distance >= cutoff {
            return RayEnd::Fog(crossings + 1);
        }
        ray = next;
        skip = Some(walker.partners[exit.face]);
    }
    RayEnd::Budget
}

/// The colour seen along one camera ray (fog where it meets nothing).
#[must_use]
pub fn trace_pixel(
    walker: &CellWalker<DVec4>,
    scene: &Scene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> DVec3 {
    match first_hit(walker, scene, start, max_crossings) {
        RayEnd::Hit(h) => scene
            .shading
            .shade(walker.geometry, &scene.light, &h.hit, h.distance),
        RayEnd::Fog(_) | RayEnd::Budget => scene.shading.fog_colour,
    }
}

/// Renders a picture (rows in parallel with rayon). Colours are written as they are
/// computed (no gamma curve), so the fog cut-off bound holds in 8-bit steps.
#[must_use]
pub fn render(
    space: &Space,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
) -> RgbImage {
    render_with_progress(space, scene, camera, settings, |_, _| {})
}

/// [`render`], calling `progress(rows_done, rows)` as rows complete (from worker threads).
#[must_use]
pub fn render_with_progress(
    space: &Space,
    scene: &Scene,
    camera: &Camera,
    settings: &RenderSettings,
    progress: impl Fn(u32, u32) + Sync,
) -> RgbImage {
    let walker = CellWalker::<DVec4>::new(space);
    let (w, h) = (settings.width, settings.height);
    let done = AtomicU32::new(0);
    let rows: Vec<Vec<u8>> = (0..h)
        .into_par_iter()
        .map(|j| {
            let mut row = Vec::with_capacity(3 * w as usize);
            for i in 0..w {
                let ray = camera.ray(space.geometry, i, j, w, h);
                let c = trace_pixel(&walker, scene, ray, settings.max_crossings);
                row.extend(
                    c.to_array()
                        .map(|x| (x.clamp(0.0, 1.0) * 255.0).round() as u8),
                );
            }
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, h);
            row
        })
        .collect();
    RgbImage::from_raw(w, h, rows.concat()).expect("buffer has width × height pixels")
}
