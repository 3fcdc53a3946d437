//! Rendering a picture with the f64 reference: a camera ray per pixel walks the cell,
//! nearest object hit against exit face, crossing by pairings until the fog cut-off or the
//! crossing budget.

use crate::geometry::Ray;
use crate::scene::{ColourBy, CurvedScene, FaceCulling, Hit, Veil, WallPanels};
use crate::space::{CellWalker, Space};
use crate::view::{PixelRays, TraceCamera, ViewLayout};
use glam::{DVec3, DVec4};
use image::RgbImage;
use rayon::prelude::*;
use std::sync::atomic::{AtomicU32, Ordering};

/// Image size and the speed/error knobs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderSettings {
    /// Picture width in pixels.
    pub width: u32,
    /// Picture height in pixels.
    pub height: u32,
    /// Crossing budget per ray; a ray that uses it up shows the fog colour.
    pub max_crossings: usize,
}

/// What a camera ray meets first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneHit {
    /// Index into [`CurvedScene::objects`] (`objects.len() + k` for the avatar's `k`-th image).
    pub object: usize,
    /// Where and what it hit.
    pub hit: Hit,
    /// Geodesic distance from the camera.
    pub distance: f64,
    /// Face crossings before the hit.
    pub crossings: usize,
    /// The ray's unit tangent at the hit (where a mirror reflects it).
    pub tangent: DVec4,
}

/// How a camera ray ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RayEnd {
    /// It hit an object before the cut-off.
    Hit(SceneHit),
    /// It reached the fog cut-off distance after this many crossings.
    Fog(usize),
    /// It used up the crossing budget (or found no exit: a degenerate ray) after this many
    /// crossings.
    Budget(usize),
}

/// Walks a camera ray through the cell: nearest object hit against the exit face, crossing
/// by pairings, until a hit, the fog cut-off or the crossing budget.
#[must_use]
pub fn first_hit(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> RayEnd {
    first_hit_traced(walker, scene, start, max_crossings).end
}

/// How a camera ray ended and the faces it crossed on the way (as a hash).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracedRay {
    /// How the ray ended.
    pub end: RayEnd,
    /// FNV-1a-style hash of the crossed faces' indices + 1, in order (see [`path_hash`]).
    pub path: u32,
    /// The face it crossed last, if any.
    pub last_face: Option<usize>,
    /// The product of the pairings applied to it, latest on the left (kept only where the
    /// scene is coloured by holonomy, [`ColourBy::Holonomy`]; the identity otherwise).
    pub holonomy: glam::DMat4,
    /// What the walls it crossed added and let through ([`first_hit_walled`]; clear
    /// without walls).
    pub veil: Veil,
}

/// The start of a face path hash.
pub const PATH_HASH_START: u32 = 2_166_136_261;

/// The path hash after crossing `face`: the shader's `HIT_ID` output computes the same, so
/// GPU and CPU rays can be compared by what they met, not only by colour.
#[must_use]
pub fn path_hash(path: u32, face: usize) -> u32 {
    (path ^ (face as u32 + 1)).wrapping_mul(16_777_619)
}

impl TracedRay {
    /// What the shader's `HIT_ID` output writes for this ray: `[object + 1 (0 for none),
    /// crossings, path hash, end]` with end 1 hit, 2 fog, 3 budget. `gpu_index` maps a scene
    /// object to its index in the GPU's lists (balls first, then tubes).
    #[must_use]
    pub fn id(&self, gpu_index: impl Fn(usize) -> u32) -> [u32; 4] {
        match self.end {
            RayEnd::Hit(h) => [gpu_index(h.object) + 1, h.crossings as u32, self.path, 1],
            RayEnd::Fog(c) => [0, c as u32, self.path, 2],
            RayEnd::Budget(c) => [0, c as u32, self.path, 3],
        }
    }
}

/// [`first_hit`] with the hash of the crossed faces.
#[must_use]
pub fn first_hit_traced(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> TracedRay {
    first_hit_culled(walker, scene, None, start, max_crossings)
}

/// [`first_hit_traced`] testing in each cell only the objects the segment can come near
/// ([`FaceCulling`], built once per scene with [`FaceCulling::new`]): the same result, sooner
/// where the scene draws the cell's edges.
#[must_use]
pub fn first_hit_culled(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    culling: Option<&FaceCulling>,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> TracedRay {
    first_hit_walled(walker, scene, culling, None, start, max_crossings)
}

/// Most mirror bounces a camera ray makes ([`colour_along`]); each also takes a step of the
/// crossing budget.
pub const MAX_BOUNCES: usize = 8;

/// How far along the reflected geodesic a ray leaving a mirror starts, so that it does not
/// meet the mirror again where it left it.
pub const MIRROR_OFFSET: f64 = 1e-3;

/// The ray that leaves a mirror at the hit `h`: the tangent turned about the normal,
/// `v − 2⟨v, n⟩ n`, started [`MIRROR_OFFSET`] along its geodesic.
#[must_use]
pub fn reflected_ray(g: crate::geometry::Geometry, h: &SceneHit) -> Ray<DVec4> {
    let n = h.hit.normal;
    let reflected = h.tangent - 2.0 * g.form(h.tangent, n) * n;
    let (point, along) = g.geodesic(h.hit.point, reflected, MIRROR_OFFSET);
    let point = g.project_point(point);
    Ray {
        point,
        tangent: g.unit_tangent(point, along),
    }
}

/// The colour seen along a camera ray, mirrors followed: where the ray meets a surface that
/// reflects a share `r`, it shows `1 − r` of the lit surface and `r` of what the reflected
/// ray sees, the walk going on from the hit with the tangent turned about the normal
/// (`v − 2⟨v, n⟩ n`), the fog counted along the whole path, the walls' veils along each
/// part, every bounce a step of the same crossing budget, at most [`MAX_BOUNCES`]. Without
/// mirrors this is [`colour_of_traced`] of [`first_hit_walled`].
#[must_use]
pub fn colour_along(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    culling: Option<&FaceCulling>,
    walls: Option<&WallPanels>,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> DVec3 {
    let g = walker.geometry;
    let walk = ShadowWalk::new(walker, culling, max_crossings);
    let (mut sum, mut weight) = (DVec3::ZERO, 1.0);
    let (mut ray, mut from, mut left) = (start, 0.0, max_crossings);
    for bounce in 0..=MAX_BOUNCES {
        let traced = trace_ray(walker, scene, culling, walls, (ray, from), left, |_, _| {});
        let h = match traced.end {
            RayEnd::Hit(h)
                if h.hit.reflectance > 0.0 && bounce < MAX_BOUNCES && h.crossings < left =>
            {
                h
            }
            _ => return sum + weight * colour_of_traced(walk, scene, &traced),
        };
        let r = h.hit.reflectance;
        let here = colour_of_traced(
            walk,
            scene,
            &TracedRay {
                veil: Veil::CLEAR,
                ..traced
            },
        );
        sum += weight * traced.veil.over((1.0 - r) * here);
        weight *= traced.veil.through * r;
        ray = reflected_ray(g, &h);
        from = h.distance + MIRROR_OFFSET;
        left -= h.crossings + 1;
    }
    sum
}

/// [`first_hit_culled`] through the cell's walls ([`WallPanels`], built once per scene with
/// [`WallPanels::new`]): the ray's [`TracedRay::veil`] holds what the walls it crossed add,
/// and a ray stops (as fog) once the walls let too little light through to matter.
#[must_use]
pub fn first_hit_walled(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    culling: Option<&FaceCulling>,
    walls: Option<&WallPanels>,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> TracedRay {
    trace_ray(
        walker,
        scene,
        culling,
        walls,
        (start, 0.0),
        max_crossings,
        |_, _| {},
    )
}

/// The walls of the walker's cell in the scene's wall style, if it has walls.
#[must_use]
pub fn walls_of(walker: &CellWalker<DVec4>, scene: &CurvedScene) -> Option<WallPanels> {
    let style = scene.shading.walls?;
    let reflections: Vec<bool> = walker
        .pairings
        .iter()
        .map(|m| m.determinant() < 0.0)
        .collect();
    WallPanels::in_cells(
        walker.geometry,
        &walker.covectors,
        &walker.partners,
        &reflections,
        (!walker.face_cells.is_empty()).then_some((&walker.face_cells[..], &walker.seams[..])),
        style,
        &scene.shading,
    )
}

/// The one walk of the CPU tracer: [`first_hit_walled`], calling `crossed(face, distance)`
/// at each face crossed (the distance travelled to it), the ray having come `from` already.
fn trace_ray(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    culling: Option<&FaceCulling>,
    walls: Option<&WallPanels>,
    (start, from): (Ray<DVec4>, f64),
    max_crossings: usize,
    mut crossed: impl FnMut(usize, f64),
) -> TracedRay {
    let g = walker.geometry;
    let cutoff = scene.shading.cutoff_distance();
    let mut ray = walker.normalized(start);
    let mut distance = from;
    let mut skip = None;
    let mut path = PATH_HASH_START;
    let mut last_face = None;
    let mut holonomy = glam::DMat4::IDENTITY;
    let keep_holonomy = scene.shading.colour_by == ColourBy::Holonomy;
    let mut veil = Veil::CLEAR;
    for crossings in 0..=max_crossings {
        let Some(exit) = walker.exit(&ray, skip) else {
            return TracedRay {
                end: RayEnd::Budget(crossings),
                path,
                last_face,
                holonomy,
                veil,
            };
        };
        let s_exit = exit.ratio();
        let nearest = scene.intersect_culled(g, ray.point, ray.tangent, s_exit, distance, culling);
        if let Some((object, hit)) = nearest {
            let d = distance + g.distance_from_ratio(hit.s, 1.0);
            let end = if d >= cutoff {
                RayEnd::Fog(crossings)
            } else {
                RayEnd::Hit(SceneHit {
                    object,
                    hit,
                    distance: d,
                    crossings,
                    tangent: g.unit_tangent(hit.point, ray.tangent),
                })
            };
            return TracedRay {
                end,
                path,
                last_face,
                holonomy,
                veil,
            };
        }
        if crossings == max_crossings {
            break;
        }
        let (next, length) = walker.cross(&ray, &exit);
        distance += length;
        if exit.face != crate::space::walk::NO_FACE {
            path = path_hash(path, exit.face);
            last_face = Some(exit.face);
            crossed(exit.face, distance);
            if keep_holonomy {
                holonomy = walker.pairings[exit.face] * holonomy;
            }
            if let Some(walls) = walls {
                // The exit point and tangent there, as `CellWalker::cross` forms them.
                let at_face = ray.point * exit.den + ray.tangent * exit.num;
                let along = ray.point * (-g.kappa() * exit.num) + ray.tangent * exit.den;
                let seen = walls.cross(
                    &mut veil,
                    &scene.shading,
                    exit.face,
                    at_face,
                    along,
                    distance,
                );
                if !seen {
                    return TracedRay {
                        end: RayEnd::Fog(crossings + 1),
                        path,
                        last_face,
                        holonomy,
                        veil,
                    };
                }
            }
        }
        if distance >= cutoff {
            return TracedRay {
                end: RayEnd::Fog(crossings + 1),
                path,
                last_face,
                holonomy,
                veil,
            };
        }
        ray = next;
        skip = walker.entered(&exit);
    }
    TracedRay {
        end: RayEnd::Budget(max_crossings),
        path,
        last_face,
        holonomy,
        veil,
    }
}

/// The colour seen along one camera ray (fog where it meets nothing).
#[must_use]
pub fn trace_pixel(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> DVec3 {
    let walls = walls_of(walker, scene);
    colour_along(walker, scene, None, walls.as_ref(), start, max_crossings)
}

/// What a shadow ray walks: the cell, the scene's objects (tested in each cell only where
/// the segment can come near them, where a [`FaceCulling`] is given) and the crossing
/// budget.
#[derive(Clone, Copy)]
pub struct ShadowWalk<'a> {
    /// The cell.
    pub walker: &'a CellWalker<DVec4>,
    /// The scene's culling, if any.
    pub culling: Option<&'a FaceCulling>,
    /// Crossings before a shadow ray gives up (unshadowed).
    pub max_crossings: usize,
}

impl<'a> ShadowWalk<'a> {
    /// A shadow walk through `walker`'s cell.
    #[must_use]
    pub fn new(
        walker: &'a CellWalker<DVec4>,
        culling: Option<&'a FaceCulling>,
        max_crossings: usize,
    ) -> Self {
        Self {
            walker,
            culling,
            max_crossings,
        }
    }

    /// Whether an object of `scene` lies on the geodesic from `point` along the unit
    /// tangent `tangent` within `length`: the walk of a camera ray through the faces, ended
    /// by any hit (the avatar's too); past the crossing budget it gives up, unshadowed.
    /// Walls do not shadow.
    #[must_use]
    pub fn occluded(&self, scene: &CurvedScene, point: DVec4, tangent: DVec4, length: f64) -> bool {
        let walker = self.walker;
        let g = walker.geometry;
        let mut ray = walker.normalized(Ray { point, tangent });
        let mut travelled = 0.0;
        let mut skip = None;
        for _ in 0..=self.max_crossings {
            let Some(exit) = walker.exit(&ray, skip) else {
                return false;
            };
            let (c, s) = g.cs(length - travelled);
            let s_left = if c > 0.0 { s / c } else { f64::INFINITY };
            let s_exit = exit.ratio();
            let s_max = s_exit.min(s_left);
            if scene
                .intersect_culled(
                    g,
                    ray.point,
                    ray.tangent,
                    s_max,
                    f64::INFINITY,
                    self.culling,
                )
                .is_some()
            {
                return true;
            }
            if s_left <= s_exit {
                return false;
            }
            let (next, step) = walker.cross(&ray, &exit);
            travelled += step;
            if travelled >= length {
                return false;
            }
            ray = next;
            skip = walker.entered(&exit);
        }
        false
    }
}

/// The colour of a traced ray, recoloured as the scene's [`ColourBy`] says (fog where it
/// met nothing), its lights' shadow rays walked by `walk`.
#[must_use]
pub fn colour_of_traced(walk: ShadowWalk<'_>, scene: &CurvedScene, traced: &TracedRay) -> DVec3 {
    let geometry = walk.walker.geometry;
    let by = scene.shading.colour_by;
    let behind = match &traced.end {
        RayEnd::Hit(h) if by != ColourBy::Shading => shade_hit(
            walk,
            scene,
            h,
            Some(by.tint(geometry, h.crossings, traced.last_face, traced.holonomy)),
        ),
        end => colour_of(walk, scene, end),
    };
    traced.veil.over(behind)
}

/// The colour of a ray that ended as `end` (fog where it met nothing), its lights' shadow
/// rays walked by `walk`.
#[must_use]
pub fn colour_of(walk: ShadowWalk<'_>, scene: &CurvedScene, end: &RayEnd) -> DVec3 {
    match end {
        RayEnd::Hit(h) => shade_hit(walk, scene, h, None),
        RayEnd::Fog(_) | RayEnd::Budget(_) => scene.shading.fog_colour,
    }
}

fn shade_hit(
    walk: ShadowWalk<'_>,
    scene: &CurvedScene,
    h: &SceneHit,
    tint: Option<DVec3>,
) -> DVec3 {
    scene.shading.shade_with(
        walk.walker.geometry,
        &scene.lights,
        &h.hit,
        h.distance,
        tint,
        &mut |p, v, length| walk.occluded(scene, p, v, length),
    )
}

/// A colour in [0, 1] as the 8-bit value the renderers write.
#[must_use]
pub fn to_byte(x: f64) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// Renders a picture (rows in parallel with rayon). Colours are written as they are
/// computed (no gamma curve), so the fog cut-off bound holds in 8-bit steps.
#[must_use]
pub fn render(
    space: &Space,
    scene: &CurvedScene,
    camera: &TraceCamera,
    settings: &RenderSettings,
) -> RgbImage {
    render_with_progress(space, scene, camera, settings, |_, _| {})
}

/// [`render`], calling `progress(rows_done, rows)` as rows complete (from worker threads).
#[must_use]
pub fn render_with_progress(
    space: &Space,
    scene: &CurvedScene,
    camera: &TraceCamera,
    settings: &RenderSettings,
    progress: impl Fn(u32, u32) + Sync,
) -> RgbImage {
    let layout = camera.layout(settings.width, settings.height);
    render_view(space, scene, &layout, settings, progress)
}

/// Renders a view of any layout (mono, stereo halves, anaglyph; see [`ViewLayout`]),
/// calling `progress(rows_done, rows)` as rows complete. The picture is
/// `settings.width × settings.height`; the layout should have been made for that size.
#[must_use]
pub fn render_view(
    space: &Space,
    scene: &CurvedScene,
    layout: &ViewLayout,
    settings: &RenderSettings,
    progress: impl Fn(u32, u32) + Sync,
) -> RgbImage {
    let walker = CellWalker::<DVec4>::new(space);
    let culling = FaceCulling::new(space, scene);
    let walls = scene
        .shading
        .walls
        .and_then(|style| WallPanels::new(space, style, &scene.shading));
    let g = space.geometry;
    let (w, h) = (settings.width, settings.height);
    let done = AtomicU32::new(0);
    let rows: Vec<Vec<u8>> = (0..h)
        .into_par_iter()
        .map(|j| {
            let mut row = Vec::with_capacity(3 * w as usize);
            for i in 0..w {
                let colour = |ray| {
                    colour_along(
                        &walker,
                        scene,
                        culling.as_ref(),
                        walls.as_ref(),
                        ray,
                        settings.max_crossings,
                    )
                    .clamp(DVec3::ZERO, DVec3::ONE)
                };
                let c = match layout.rays_at(g, i, j) {
                    PixelRays::One(ray) => colour(ray),
                    PixelRays::Two(left, right) => layout.mix_anaglyph(colour(left), colour(right)),
                };
                row.extend(c.to_array().map(to_byte));
            }
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, h);
            row
        })
        .collect();
    RgbImage::from_raw(w, h, rows.concat()).expect("buffer has width × height pixels")
}

/// What one ray did, for the inspector: the faces it crossed with the distance travelled at
/// each, and how it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct RayStory {
    /// Each crossing: the face left by and the distance travelled to it.
    pub crossings: Vec<(usize, f64)>,
    /// How the ray ended.
    pub end: RayEnd,
}

/// Traces one ray as [`first_hit_traced`] does and tells its story.
#[must_use]
pub fn ray_story(
    walker: &CellWalker<DVec4>,
    scene: &CurvedScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> RayStory {
    let mut crossings = Vec::new();
    let traced = trace_ray(
        walker,
        scene,
        None,
        None,
        (start, 0.0),
        max_crossings,
        |face, d| {
            crossings.push((face, d));
        },
    );
    RayStory {
        crossings,
        end: traced.end,
    }
}
