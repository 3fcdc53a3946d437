//! The CPU reference tracer of the product spaces (H²×R, S²×R): a camera ray per pixel
//! walks the product cell ([`ProductWalker`]); in each segment the objects are met exactly.
//!
//! Every object of a product scene is the set where a distance is at most its radius: a
//! **ball** (the distance to a point), a **fibre tube** (the surface distance to a point:
//! a vertical edge of the cell), a **slice tube** (the distance to a surface geodesic in a
//! slice `z = z₀`: a horizontal edge). Along a geodesic segment `F(t) = d(t)² − r²` is a
//! convex function (H²×R is a Hadamard manifold; in S²×R the segments are at most π/4 of
//! surface arc and the objects small, where it holds too), so the segment meets the object
//! iff `F`'s minimum on it is negative, and then first at the one root of `F` before the
//! minimum. The minimum is found by golden-section search and the root by bisection, each
//! run to the last bit of `f64` (60 halvings): bracketed and safeguarded, never marched.
//!
//! Two exact shortcuts, because `d` is 1-Lipschitz along a unit-speed geodesic: the search
//! stops with a miss once the larger of its two probes' distances, less the bracket's
//! length, exceeds the radius (the minimum lies in the bracket); and each object is
//! searched only up to the nearest meeting found so far in the segment.

mod default_scene;
#[cfg(feature = "scene-files")]
pub mod file;
#[cfg(feature = "scene-files")]
pub mod flight;
pub mod lighting;
pub mod moving;
pub mod triangle;
pub mod walls;

pub use default_scene::{ProductParts, default_camera, default_scene, scene_with_parts};

use crate::geometry::{Geometry, Ray};
use crate::space::product::{ProductSpace, ProductWalker};
use crate::space::walk::NO_FACE;
use glam::{DVec3, DVec4};
use image::RgbImage;
use rayon::prelude::*;

/// What an object of a product scene is the neighbourhood of.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ProductShape {
    /// A point of the space (a ball).
    Point(DVec4),
    /// The fibre over a surface point (a vertical tube).
    Fibre(DVec4),
    /// A surface geodesic in the slice at a height: its unit covector in the surface's
    /// model (`(n, 0, −r)` scaled), and the height.
    Geodesic {
        /// The line's unit covector (its `z` component zero).
        covector: DVec4,
        /// The slice's height.
        height: f64,
    },
    /// A horizontal disc: the points of the slice at `centre.z` within the object's radius
    /// (a surface distance) of `centre`. It has no thickness: a ray meets it where its
    /// height reaches the slice's, exactly, and one along the slice does not see it.
    Disc(DVec4),
    /// A mesh triangle in a slice or over a surface geodesic ([`triangle`]), met exactly;
    /// the object's radius is not used.
    Triangle(triangle::ProductTriangle),
}

/// An object: every point within `radius` of its shape.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProductObject {
    /// What it surrounds.
    pub shape: ProductShape,
    /// Its radius.
    pub radius: f64,
    /// Its colour, linear RGB.
    pub colour: DVec3,
}

/// A scene of a product space: objects, one point light, ambient light and fog.
#[derive(Clone, Debug, PartialEq)]
pub struct ProductScene {
    /// The objects.
    pub objects: Vec<ProductObject>,
    /// The light's position.
    pub light: DVec4,
    /// How the light is gathered: along every image ([`lighting`]) or from the nearest
    /// copy; set with [`ProductScene::set_lighting`], which finds the images again.
    pub lighting: crate::scene::lighting::Lighting,
    /// The light's images in the cover ([`lighting::ProductLamp`]), found for `light` and
    /// `lighting` by [`ProductScene::set_lighting`].
    pub lamp: lighting::ProductLamp,
    /// Ambient share of the light.
    pub ambient: f64,
    /// Fog distance scale λ: a surface at distance `d` keeps `e^(−d/λ)` of its colour.
    pub fog_distance: f64,
    /// The fog's colour.
    pub fog_colour: DVec3,
    /// The cell's walls with windows ([`walls`]), if drawn.
    pub walls: Option<crate::scene::walls::WallStyle>,
    /// What surfaces are coloured by over their shading (the teaching views; faces are
    /// numbered as the walk does: the sides, then the top, then the bottom).
    pub colour_by: crate::scene::ColourBy,
}

impl ProductScene {
    /// Lights the scene as `lighting` says, the lamp at `light`: finds the lamp's images
    /// within the reach again. The message names a setting out of range.
    pub fn set_lighting(
        &mut self,
        space: &ProductSpace,
        light: DVec4,
        lighting: crate::scene::lighting::Lighting,
    ) -> Result<(), String> {
        lighting.check()?;
        if lighting.lamp_radius_inradii > 0.0 {
            use crate::space::{Family, Feature};
            Family::Product
                .supports(Feature::SoftShadows)
                .map_err(|e| format!("{e}; got a radius of {}", lighting.lamp_radius_inradii))?;
        }
        self.light = light;
        self.lighting = lighting;
        self.lamp = lighting::ProductLamp::new(space, light, &lighting);
        Ok(())
    }

    /// The distance past which a surface keeps under half a colour step of its own colour
    /// through the fog (`λ ln 510`): rays stop there.
    #[must_use]
    pub fn cutoff_distance(&self) -> f64 {
        self.fog_distance * 510f64.ln()
    }
}

/// The surface model's form on the base parts `(x, y, w)` of two vectors.
fn base_form(g: Geometry, a: DVec4, b: DVec4) -> f64 {
    a.x * b.x + a.y * b.y + g.kappa() * a.w * b.w
}

/// The base part of a vector.
fn base(v: DVec4) -> DVec4 {
    DVec4::new(v.x, v.y, 0.0, v.w)
}

/// The surface distance between two base points, from their chord (accurate near and far).
fn surface_distance(g: Geometry, p: DVec4, q: DVec4) -> f64 {
    let d = base(p) - base(q);
    let chord = base_form(g, d, d).max(0.0).sqrt();
    match g {
        Geometry::Spherical => 2.0 * (0.5 * chord).min(1.0).asin(),
        _ => 2.0 * (0.5 * chord).asinh(),
    }
}

/// The unit surface tangent at `p` pointing away from the base point `q`, and the distance.
fn away_from(g: Geometry, p: DVec4, q: DVec4) -> (DVec4, f64) {
    let (p, q) = (base(p), base(q));
    let along = base_form(g, q, p) / base_form(g, p, p);
    let toward = q - p * along;
    let len = base_form(g, toward, toward).max(0.0).sqrt();
    let d = surface_distance(g, p, q);
    if len > 0.0 {
        (-toward / len, d)
    } else {
        (DVec4::ZERO, d)
    }
}

impl ProductObject {
    /// The distance from `x` to the shape, and the unit normal there (the gradient of the
    /// distance: pointing away from the shape).
    fn distance(&self, g: Geometry, x: DVec4) -> (f64, DVec4) {
        match self.shape {
            ProductShape::Point(c) => {
                let (away, db) = away_from(g, x, c);
                let dz = x.z - c.z;
                let d = (db * db + dz * dz).sqrt();
                let n = away * db + DVec4::Z * dz;
                (d, if d > 0.0 { n / d } else { DVec4::Z })
            }
            ProductShape::Fibre(c) => {
                let (away, db) = away_from(g, x, c);
                (db, away)
            }
            // The normal is the fibre, up (the side facing a ray is chosen where it is met).
            ProductShape::Disc(c) => ((x.z - c.z).abs(), DVec4::Z),
            // Only the normal is asked of a triangle (on its slice or plane).
            ProductShape::Triangle(t) => (0.0, t.normal(g, x)),
            ProductShape::Geodesic { covector, height } => {
                let xb = base(x);
                let norm = (g.kappa() * base_form(g, xb, xb)).abs().sqrt();
                let xb = xb / norm;
                let s = covector.dot(xb);
                let db = match g {
                    Geometry::Spherical => s.clamp(-1.0, 1.0).asin().abs(),
                    _ => s.asinh().abs(),
                };
                // The covector as a vector (dual under the form), made tangent at x.
                let m = DVec4::new(covector.x, covector.y, 0.0, g.kappa() * covector.w);
                let t = m - xb * (base_form(g, m, xb) / base_form(g, xb, xb));
                let len = base_form(g, t, t).max(0.0).sqrt();
                let away = if len > 0.0 {
                    t * (s.signum() / len)
                } else {
                    DVec4::ZERO
                };
                let dz = x.z - height;
                let d = (db * db + dz * dz).sqrt();
                let n = away * db + DVec4::Z * dz;
                (d, if d > 0.0 { n / d } else { DVec4::Z })
            }
        }
    }
}

/// The point at distance `t` along a ray of the product (the exact geodesic).
fn along(g: Geometry, ray: &Ray<DVec4>, t: f64) -> DVec4 {
    let vb = base(ray.tangent);
    let lambda = base_form(g, vb, vb).max(0.0).sqrt();
    let (c, s) = g.cs(lambda * t);
    let pb = base(ray.point);
    let p = if lambda > 0.0 {
        pb * c + vb * (s / lambda)
    } else {
        pb
    };
    DVec4::new(p.x, p.y, ray.point.z + ray.tangent.z * t, p.w)
}

/// The unit tangent at distance `t` along a ray of the product.
fn along_tangent(g: Geometry, ray: &Ray<DVec4>, t: f64) -> DVec4 {
    let vb = base(ray.tangent);
    let lambda = base_form(g, vb, vb).max(0.0).sqrt();
    let (c, s) = g.cs(lambda * t);
    let v = if lambda > 0.0 {
        base(ray.point) * (-g.kappa() * lambda * s) + vb * c
    } else {
        DVec4::ZERO
    };
    DVec4::new(v.x, v.y, ray.tangent.z, v.w)
}

/// The first `t` in `[0, t_max]` where the segment meets the object, if it does.
fn first_meeting(g: Geometry, object: &ProductObject, ray: &Ray<DVec4>, t_max: f64) -> Option<f64> {
    if let ProductShape::Disc(c) = object.shape {
        // Where the height reaches the slice's, if within the disc.
        let mu = ray.tangent.z;
        if mu == 0.0 {
            return None;
        }
        let t = (c.z - ray.point.z) / mu;
        return ((0.0..=t_max).contains(&t)
            && surface_distance(g, along(g, ray, t), c) <= object.radius)
            .then_some(t);
    }
    if let ProductShape::Triangle(triangle) = object.shape {
        return triangle
            .plane_meeting(g, ray, t_max)
            .filter(|&t| triangle.contains(g, along(g, ray, t)));
    }
    let f = |t: f64| {
        let d = object.distance(g, along(g, ray, t)).0;
        d * d - object.radius * object.radius
    };
    // The distance is 1-Lipschitz along a unit-speed geodesic: a segment whose midpoint is
    // further from the shape than half its length plus the radius cannot meet it.
    let mid = object.distance(g, along(g, ray, 0.5 * t_max)).0;
    if mid > 0.5 * t_max + object.radius {
        return None;
    }
    if f(0.0) <= 0.0 {
        return Some(0.0);
    }
    // Golden-section search for the minimum of the convex F on [0, t_max].
    let ratio = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (0.0, t_max);
    let mut c = b - ratio * (b - a);
    let mut d = a + ratio * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    let r2 = object.radius * object.radius;
    for _ in 0..80 {
        if fc <= 0.0 || fd <= 0.0 {
            break;
        }
        // The minimum lies in [a, b], where the distance is at least either probe's less
        // the bracket's length (1-Lipschitz): past the radius, a miss.
        if (fc.max(fd) + r2).sqrt() - (b - a) > object.radius {
            return None;
        }
        if fc < fd {
            b = d;
            d = c;
            fd = fc;
            c = b - ratio * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + ratio * (b - a);
            fd = f(d);
        }
        if b - a <= 1e-13 * t_max.max(1.0) {
            break;
        }
    }
    let inside = if fc <= 0.0 {
        c
    } else if fd <= 0.0 {
        d
    } else if f(t_max) <= 0.0 {
        t_max
    } else {
        return None;
    };
    // Bisection on [0, inside]: F > 0 at the left end, ≤ 0 at the right.
    let (mut lo, mut hi) = (0.0, inside);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

/// A product camera: a point and an orthonormal frame (right, up, back) of tangents there,
/// with a vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProductCamera {
    /// The eye.
    pub point: DVec4,
    /// Right, up and back, unit tangents at the eye.
    pub frame: [DVec4; 3],
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

/// The unit tangent at `p` of the geodesic towards `q` (its surface part along the surface
/// geodesic, its height part the difference in height, in proportion).
#[must_use]
pub fn tangent_towards(g: Geometry, p: DVec4, q: DVec4) -> DVec4 {
    let (away, db) = away_from(g, p, q);
    let v = -away * db + DVec4::Z * (q.z - p.z);
    let len = (base_form(g, v, v) + v.z * v.z).sqrt();
    if len > 0.0 { v / len } else { DVec4::Z }
}

/// The product metric's inner product of two tangents.
fn dot(g: Geometry, a: DVec4, b: DVec4) -> f64 {
    base_form(g, a, b) + a.z * b.z
}

impl ProductCamera {
    /// A camera at `eye` looking at `target`, the fibre up (as far as the view allows).
    #[must_use]
    pub fn looking_at(g: Geometry, eye: DVec4, target: DVec4, fov_y_degrees: f64) -> Self {
        let forward = tangent_towards(g, eye, target);
        let mut up = DVec4::Z - forward * forward.z;
        let len = dot(g, up, up).sqrt();
        up = if len > 1e-9 {
            up / len
        } else {
            // Looking along the fibre: any surface direction is up.
            let (a, _) = away_from(g, eye, DVec4::new(0.3, 0.1, 0.0, 1.0));
            a
        };
        // right = forward × up in the tangent space, built from the surface basis.
        let e = surface_basis(g, eye);
        let coords = |v: DVec4| DVec3::new(dot(g, v, e[0]), dot(g, v, e[1]), v.z);
        let r = coords(forward).cross(coords(up));
        let right = e[0] * r.x + e[1] * r.y + DVec4::Z * r.z;
        Self {
            point: eye,
            frame: [right, up, -forward],
            fov_y_degrees,
        }
    }

    /// The ray through pixel `(i, j)` of a `width × height` image.
    #[must_use]
    pub fn ray(&self, i: u32, j: u32, width: u32, height: u32) -> Ray<DVec4> {
        let t = (0.5 * self.fov_y_degrees.to_radians()).tan();
        let aspect = f64::from(width) / f64::from(height);
        let px = ((f64::from(i) + 0.5) / f64::from(width) * 2.0 - 1.0) * t * aspect;
        let py = (1.0 - (f64::from(j) + 0.5) / f64::from(height) * 2.0) * t;
        let [right, up, back] = self.frame;
        let v = right * px + up * py - back;
        Ray {
            point: self.point,
            tangent: v,
        }
    }
}

/// An orthonormal basis of the surface's tangent plane at `p` (as tangents of the product).
fn surface_basis(g: Geometry, p: DVec4) -> [DVec4; 2] {
    let pb = base(p);
    let mut out: Vec<DVec4> = Vec::new();
    for axis in [DVec4::X, DVec4::Y, DVec4::W] {
        if out.len() == 2 {
            break;
        }
        let mut v = axis - pb * (base_form(g, axis, pb) / base_form(g, pb, pb));
        for b in &out {
            v -= *b * base_form(g, v, *b);
        }
        let len = base_form(g, v, v).max(0.0).sqrt();
        if len > 0.3 {
            out.push(v / len);
        }
    }
    // A point off the model (not finite) has no basis: the axes stand in, never a panic.
    let e0 = out.first().copied().unwrap_or(DVec4::X);
    let mut e1 = out.get(1).copied().unwrap_or(DVec4::Y);
    // One orientation everywhere, counter-clockwise seen from the fibre's +z as at the
    // centre (e0, e1, p) = (x, y, w): the axes the Gram–Schmidt starts from give the other
    // one past the sphere's equator, where a camera built on them saw the world mirrored.
    let xyw = |v: DVec4| DVec3::new(v.x, v.y, v.w);
    if xyw(e0).cross(xyw(e1)).dot(xyw(pb)) < 0.0 {
        e1 = -e1;
    }
    [e0, e1]
}

/// Where a ray of a product scene ends: at an object (the distance walked, the crossings
/// made, the point met and the object), in the fog (nothing before the fog's cut-off) or
/// at the crossing budget (the crossings made).
#[derive(Clone, Copy, Debug, PartialEq)]
// One per ray, returned by value: a box would cost an allocation per ray.
#[allow(clippy::large_enum_variant)]
pub enum ProductRayEnd<'a> {
    /// The ray met an object.
    Hit {
        /// The distance from the eye.
        distance: f64,
        /// Face crossings before the meeting.
        crossings: usize,
        /// The point met.
        at: DVec4,
        /// The ray's unit tangent there.
        tangent: DVec4,
        /// The last face the ray left through (`None` before any crossing).
        last_face: Option<usize>,
        /// The product of the pairings applied to the ray (their linear parts, the latest
        /// on the left): the copy of the cell the object was seen in.
        held: glam::DMat4,
        /// The object met.
        object: &'a ProductObject,
    },
    /// Nothing before the fog's cut-off.
    Fog,
    /// The budget ran out after this many crossings.
    Budget(usize),
}

/// Walks one ray to its first object: the nearest object in each segment of the walk,
/// until the fog's cut-off (the distance past which a surface keeps under half a colour
/// step) or `max_crossings` crossings.
#[must_use]
pub fn first_product_hit<'a>(
    walker: &ProductWalker<DVec4>,
    scene: &'a ProductScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> ProductRayEnd<'a> {
    walk_to_hit(walker, scene, start, max_crossings, |_, _, _| true)
}

/// [`first_product_hit`], handing each face crossing to `crossed` (the face entered, the
/// ray there and the distance from the eye); `false` ends the ray in the fog.
fn walk_to_hit<'a>(
    walker: &ProductWalker<DVec4>,
    scene: &'a ProductScene,
    start: Ray<DVec4>,
    max_crossings: usize,
    mut crossed: impl FnMut(usize, &Ray<DVec4>, f64) -> bool,
) -> ProductRayEnd<'a> {
    let g = walker.base;
    let cutoff = scene.cutoff_distance();
    let mut ray = walker.normalized(start);
    let mut distance = 0.0;
    let mut skip = None;
    let mut crossings = 0usize;
    let mut steps = 0usize;
    let mut last_face = None;
    let mut held = glam::DMat4::IDENTITY;
    while distance < cutoff {
        let Some(exit) = walker.exit(&ray, skip) else {
            break;
        };
        let t_max = exit.distance.min(cutoff - distance);
        let mut nearest: Option<(f64, &ProductObject)> = None;
        for object in &scene.objects {
            // Only a meeting before the nearest so far matters.
            let before = nearest.map_or(t_max, |(best, _)| best);
            if let Some(t) = first_meeting(g, object, &ray, before)
                && nearest.is_none_or(|(best, _)| t < best)
            {
                nearest = Some((t, object));
            }
        }
        if let Some((t, object)) = nearest {
            return ProductRayEnd::Hit {
                distance: distance + t,
                crossings,
                at: along(g, &ray, t),
                tangent: along_tangent(g, &ray, t),
                last_face,
                held,
                object,
            };
        }
        if exit.distance >= cutoff - distance {
            break;
        }
        let (next, _) = walker.cross(&ray, &exit);
        distance += exit.distance;
        skip = walker.entered(&exit);
        ray = next;
        if exit.face == NO_FACE {
            steps += 1;
            if steps > 64 {
                break;
            }
            continue;
        }
        steps = 0;
        crossings += 1;
        last_face = Some(exit.face);
        let pairing = if exit.face == walker.top() {
            walker.up.0
        } else if exit.face == walker.bottom() {
            walker.down.0
        } else {
            walker.pairings[exit.face]
        };
        held = pairing * held;
        if crossings > max_crossings {
            return ProductRayEnd::Budget(max_crossings);
        }
        let entered = skip.unwrap_or(if exit.face == walker.top() {
            walker.bottom()
        } else {
            walker.top()
        });
        if !crossed(entered, &ray, distance) {
            break;
        }
    }
    ProductRayEnd::Fog
}

/// Whether an object of the scene lies on the geodesic from `start` within `length`: a
/// shadow ray, walked through the faces as a camera ray is. Any object met ends it; one
/// that runs out of crossings counts as clear.
#[must_use]
pub fn product_occluded(
    walker: &ProductWalker<DVec4>,
    scene: &ProductScene,
    start: Ray<DVec4>,
    length: f64,
    max_crossings: usize,
) -> bool {
    let g = walker.base;
    let mut ray = walker.normalized(start);
    let mut distance = 0.0;
    let mut skip = None;
    let (mut crossings, mut steps) = (0usize, 0usize);
    while distance < length {
        let Some(exit) = walker.exit(&ray, skip) else {
            return false;
        };
        let t_max = exit.distance.min(length - distance);
        if scene
            .objects
            .iter()
            .any(|o| first_meeting(g, o, &ray, t_max).is_some())
        {
            return true;
        }
        if exit.distance >= length - distance {
            return false;
        }
        let (next, _) = walker.cross(&ray, &exit);
        distance += exit.distance;
        skip = walker.entered(&exit);
        ray = next;
        if exit.face == NO_FACE {
            steps += 1;
            if steps > 64 {
                return false;
            }
            continue;
        }
        steps = 0;
        crossings += 1;
        if crossings > max_crossings {
            return false;
        }
    }
    false
}

/// The product's falloff of a point light: the area, per unit solid angle at the light, of
/// the geodesic sphere through a point `db` away on the surface and `dz` along the fibre.
///
/// A geodesic leaving the light at elevation `θ` reaches distance `r` at surface distance
/// `ρ = r cos θ` and height `r sin θ`; in these coordinates the volume is
/// `S(ρ) dρ dφ dz = r S(r cos θ) dr dθ dφ`, so the sphere's area per solid angle
/// `cos θ dθ dφ` is `r S(ρ) / cos θ = r² S(ρ)/ρ`, with `S` = sinh (H²×R) or sin (S²×R).
/// It is `r²` near the light and along the fibre (where the product looks Euclidean),
/// grows like `r² e^ρ/ρ` across H², and falls to 0 where the geodesics from the light
/// meet again on S² (`ρ = π`): the caller clamps it from below.
#[must_use]
pub fn light_spread(g: Geometry, db: f64, dz: f64) -> f64 {
    let r2 = db * db + dz * dz;
    let ratio = if db < 1e-4 {
        // S(ρ)/ρ = 1 + κ' ρ²/6 + …, κ' = +1 for sinh, −1 for sin.
        1.0 - g.kappa() * db * db / 6.0
    } else {
        g.s(db) / db
    };
    r2 * ratio.max(0.0)
}

/// The colour seen along one ray: its first object ([`first_product_hit`]) shaded with the
/// light (Lambert, the product's falloff [`light_spread`], never more than at distance 1)
/// and fog; the fog colour where nothing is met before the
/// fog's cut-off or within the crossing budget.
///
/// With `walls` ([`walls::ProductWalls`], the scene's walls built once), every panel the
/// ray passes adds its colour and takes its share of the light, as in the
/// constant-curvature cells.
#[must_use]
pub fn trace_product_pixel(
    walker: &ProductWalker<DVec4>,
    walls: Option<&walls::ProductWalls>,
    scene: &ProductScene,
    start: Ray<DVec4>,
    max_crossings: usize,
) -> DVec3 {
    let g = walker.base;
    let mut veil = crate::scene::walls::Veil::CLEAR;
    let end = walk_to_hit(walker, scene, start, max_crossings, |face, ray, d| {
        walls.is_none_or(|w| w.cross(&mut veil, scene, face, ray.point, ray.tangent, d))
    });
    let ProductRayEnd::Hit {
        distance,
        crossings,
        at,
        tangent,
        last_face,
        held,
        object,
    } = end
    else {
        return veil.over(scene.fog_colour);
    };
    let (_, mut normal) = object.distance(g, at);
    if matches!(
        object.shape,
        ProductShape::Disc(_) | ProductShape::Triangle(_)
    ) && dot(g, normal, tangent) > 0.0
    {
        // A flat piece is lit on the side the ray comes from.
        normal = -normal;
    }
    let mut occluded = |point, tangent, length| {
        product_occluded(walker, scene, Ray { point, tangent }, length, max_crossings)
    };
    let light = lighting::product_gather(g, scene, at, normal, &mut occluded);
    let lit = scene.ambient + (1.0 - scene.ambient) * light;
    let mut surface = (object.colour * lit).min(DVec3::ONE);
    if scene.colour_by != crate::scene::ColourBy::Shading {
        let tint = scene.colour_by.tint(g, crossings, last_face, held);
        surface = crate::scene::ColourBy::recolour(tint, surface);
    }
    let w = (-distance / scene.fog_distance).exp();
    veil.over(w * surface + (1.0 - w) * scene.fog_colour)
}

/// The crossing budget that shows a product scene from `eye` as a budget without limit
/// would for all but `miss_fraction` of `samples` rays in directions spread over the
/// sphere (the same rays every run), at most [`super::MAX_AUTO_BUDGET`]: the
/// smallest budget past which at most that fraction of the rays still needs crossings to
/// reach its object. Rays that end in the fog need none.
#[must_use]
pub fn product_auto_budget(
    space: &ProductSpace,
    scene: &ProductScene,
    eye: DVec4,
    miss_fraction: f64,
    samples: usize,
) -> super::BudgetChoice {
    let walker = ProductWalker::<DVec4>::new(space);
    let e = surface_basis(walker.base, eye);
    let mut random = crate::random::SplitMix64(0x9e0d_0c7a_b0d6);
    let rays: Vec<Ray<DVec4>> = (0..samples.max(1))
        .map(|_| {
            let d = random.direction();
            Ray {
                point: eye,
                tangent: e[0] * d.x + e[1] * d.y + DVec4::Z * d.z,
            }
        })
        .collect();
    let cap = super::budget::MAX_AUTO_BUDGET as usize;
    let needed: Vec<u32> = rays
        .par_iter()
        .map(|ray| match first_product_hit(&walker, scene, *ray, cap) {
            ProductRayEnd::Hit { crossings, .. } => crossings as u32,
            ProductRayEnd::Fog => 0,
            ProductRayEnd::Budget(c) => c as u32 + 1,
        })
        .collect();
    super::budget::choose_from_needed(needed, miss_fraction, miss_fraction)
}

/// Renders a product space's scene on the CPU from one camera (rows in parallel).
#[must_use]
pub fn render_product(
    space: &ProductSpace,
    scene: &ProductScene,
    camera: &ProductCamera,
    width: u32,
    height: u32,
    max_crossings: usize,
) -> RgbImage {
    let frame = crate::space::product::motion::camera_frame(camera.point, camera.frame);
    let lens = crate::view::Lens::symmetric(
        camera.fov_y_degrees,
        f64::from(width.max(1)) / f64::from(height.max(1)),
    );
    let layout = crate::view::ViewLayout::mono(frame, lens, width, height);
    render_product_view(space, scene, &layout, max_crossings)
}

/// Renders a product space's scene on the CPU over a view layout: mono, or the two eyes
/// of a stereo mode ([`crate::view::ViewLayout::new`] with frames from
/// [`crate::space::product::motion::product_eye_frames`]), rows in parallel. Pixel `(i, j)`
/// of each eye's picture sees along `x·right + y·up − back` of the eye's frame, `(x, y)`
/// from the layout's lens.
#[must_use]
pub fn render_product_view(
    space: &ProductSpace,
    scene: &ProductScene,
    layout: &crate::view::ViewLayout,
    max_crossings: usize,
) -> RgbImage {
    let walker = ProductWalker::<DVec4>::new(space);
    // Rays stop behind walls that let less light through than the fog's cut-off weight.
    let walls = scene.walls.and_then(|style| {
        walls::ProductWalls::new(space, style, crate::scene::DEFAULT_CUTOFF_WEIGHT)
    });
    super::render_layout(layout, |ray| {
        trace_product_pixel(&walker, walls.as_ref(), scene, ray, max_crossings)
    })
}
