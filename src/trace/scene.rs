//! Scene objects (exact quadrics in all three geometries) and the shading model.
//!
//! A ray segment inside the cell is `X(s) ∝ p + s v` for `s` in `[0, T_exit)` (a straight
//! chart line), and metric balls and tubes around geodesics are quadrics of R⁴, so each
//! hit is a root of a quadratic in `s`.

use crate::geometry::Geometry;
use crate::scene::mesh::Mesh;
use crate::scene::texture::Texture;
use crate::space::Space;
use glam::{DMat4, DVec2, DVec3, DVec4};
use std::sync::Arc;

/// A metric ball `d(X, centre) ≤ radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    pub centre: DVec4,
    pub radius: f64,
    pub colour: DVec3,
    /// Light the surface gives off itself (added to the lit colour).
    pub emission: DVec3,
    /// A picture wrapped round the ball (a globe), if any.
    pub texture: Option<BallTexture>,
    /// `C(radius)`.
    c_radius: f64,
}

/// An equirectangular picture on a ball: longitude across, latitude down, the north pole
/// on the ball's own `+y` axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallTexture {
    /// Index into [`Scene::textures`].
    pub texture: u32,
    /// The ball's orientation: an isometry taking the origin to the centre, its `y` axis
    /// the spin axis and its `z` axis longitude 0.
    pub frame: DMat4,
    /// Spin about the `y` axis, radians per second of [`Scene::time`].
    pub spin: f64,
}

impl BallTexture {
    /// Texture coordinates of the ball's point `x` at time `time`.
    #[must_use]
    pub fn uv(&self, geometry: Geometry, x: DVec4, time: f64) -> DVec2 {
        let local = geometry.inverse(self.frame) * x;
        let d = local.truncate().normalize_or_zero();
        let turn = std::f64::consts::TAU;
        let longitude = d.x.atan2(d.z) - self.spin * time;
        DVec2::new(
            (longitude / turn + 0.5).rem_euclid(1.0),
            d.y.clamp(-1.0, 1.0).acos() / std::f64::consts::PI,
        )
    }
}

impl Ball {
    #[must_use]
    pub fn new(geometry: Geometry, centre: DVec4, radius: f64, colour: DVec3) -> Self {
        Self {
            centre,
            radius,
            colour,
            emission: DVec3::ZERO,
            texture: None,
            c_radius: geometry.cs(radius).0,
        }
    }

    /// The ball giving off `emission`.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// The ball with a picture on it.
    #[must_use]
    pub fn with_texture(self, texture: BallTexture) -> Self {
        Self {
            texture: Some(texture),
            ..self
        }
    }
}

/// An equidistant tube `d(X, [a, b]) ≤ radius` around a geodesic segment (without caps:
/// put balls at the ends to close it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tube {
    pub a: DVec4,
    pub b: DVec4,
    pub radius: f64,
    pub colour: DVec3,
    pub emission: DVec3,
    /// Unit tangent at `a` towards `b`: with `a` it spans the segment's line.
    towards_b: DVec4,
    /// `(C(L), S(L))` of the segment's length `L`.
    cs_length: (f64, f64),
    /// `C(radius)²`.
    c_radius_sq: f64,
}

impl Tube {
    #[must_use]
    pub fn new(geometry: Geometry, a: DVec4, b: DVec4, radius: f64, colour: DVec3) -> Self {
        Self {
            a,
            b,
            radius,
            colour,
            emission: DVec3::ZERO,
            towards_b: geometry.tangent_towards(a, b),
            cs_length: geometry.cs(geometry.distance(a, b)),
            c_radius_sq: geometry.cs(radius).0.powi(2),
        }
    }

    /// The tube giving off `emission`.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// Unit tangent at `a` towards `b`.
    #[must_use]
    pub fn towards_b(&self) -> DVec4 {
        self.towards_b
    }

    /// `(C(L), S(L))` of the segment's length `L`.
    #[must_use]
    pub fn cs_length(&self) -> (f64, f64) {
        self.cs_length
    }

    /// `(σ, γ)` with `σ/γ = S(τ)/C(τ)` for the foot of `x` at distance τ from `a` along the
    /// line (up to a common positive factor).
    fn foot_coordinates(&self, geometry: Geometry, x: DVec4) -> (f64, f64) {
        match geometry {
            Geometry::Euclidean => (
                (x.truncate() / x.w - self.a.truncate()).dot(self.towards_b.truncate()),
                1.0,
            ),
            _ => (
                geometry.form(x, self.towards_b),
                geometry.kappa() * geometry.form(x, self.a),
            ),
        }
    }

    /// Whether the foot of `x` on the line lies on the segment: `0 ≤ τ ≤ L`, i.e. `σ ≥ 0`
    /// and `γ S(L) − σ C(L) ≥ 0`.
    fn over_segment(&self, geometry: Geometry, x: DVec4) -> bool {
        let (sigma, gamma) = self.foot_coordinates(geometry, x);
        let (cl, sl) = self.cs_length;
        sigma >= 0.0 && gamma * sl - sigma * cl >= 0.0
    }

    /// The point of the line nearest to the model point `x`.
    fn foot(&self, geometry: Geometry, x: DVec4) -> DVec4 {
        match geometry {
            Geometry::Euclidean => self.a + self.foot_coordinates(geometry, x).0 * self.towards_b,
            _ => geometry.project_point(
                geometry.kappa() * geometry.form(x, self.a) * self.a
                    + geometry.form(x, self.towards_b) * self.towards_b,
            ),
        }
    }
}

/// A flat round disc: the points of the totally geodesic plane through `centre` orthogonal
/// to `normal` within `radius` of the centre (seen from both sides).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disc {
    pub centre: DVec4,
    /// Unit tangent at the centre.
    pub normal: DVec4,
    pub radius: f64,
    pub colour: DVec3,
    pub emission: DVec3,
}

impl Disc {
    /// A disc; `normal` is made a unit tangent at `centre`.
    #[must_use]
    pub fn new(
        geometry: Geometry,
        centre: DVec4,
        normal: DVec4,
        radius: f64,
        colour: DVec3,
    ) -> Self {
        Self {
            centre,
            normal: geometry.unit_tangent(centre, normal),
            radius,
            colour,
            emission: DVec3::ZERO,
        }
    }

    /// The disc giving off `emission`.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// The plane's covector `P` for the Euclidean dot product: `P·X = 0` on the plane.
    #[must_use]
    pub fn covector(&self, geometry: Geometry) -> DVec4 {
        let n = self.normal;
        match geometry {
            Geometry::Euclidean => {
                let c = self.centre.truncate() / self.centre.w;
                n.truncate().extend(-c.dot(n.truncate()))
            }
            _ => n.truncate().extend(geometry.kappa() * n.w),
        }
    }
}

/// A mesh placed in the cell: [`Scene::meshes`]`[mesh]` in the frame `frame` (an isometry
/// taking the mesh's chart to the cell's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshInstance {
    /// Index into [`Scene::meshes`].
    pub mesh: u32,
    pub frame: DMat4,
    /// `frame⁻¹`.
    pub inverse: DMat4,
    /// The mesh's radius (largest vertex distance from its origin).
    pub radius: f64,
    /// A material used instead of the mesh's own (index into [`Scene::materials`]).
    pub material: Option<u32>,
}

impl MeshInstance {
    /// Mesh `mesh` of radius `radius` placed by `frame`.
    #[must_use]
    pub fn new(geometry: Geometry, mesh: u32, frame: DMat4, radius: f64) -> Self {
        Self {
            mesh,
            frame,
            inverse: geometry.inverse(frame),
            radius,
            material: None,
        }
    }

    /// The frame's origin.
    #[must_use]
    pub fn origin(&self, geometry: Geometry) -> DVec4 {
        geometry.project_point(self.frame.w_axis)
    }

    /// The ray `X ∝ p + s v` in the mesh's chart: origin `o`, direction `d` (the chart point
    /// at `s` is `o + t d` with `t = s / (p'.w + s v'.w)`, `p', v'` the local ray), and the
    /// local `(p'.w, v'.w)` to convert back. `None` where the ray starts in the far
    /// hemisphere of the mesh's frame (S³), which the mesh does not reach.
    #[must_use]
    pub fn local_ray(&self, p: DVec4, v: DVec4) -> Option<(DVec3, DVec3, f64, f64)> {
        let lp = self.inverse * p;
        let lv = self.inverse * v;
        if !(lp.w > 0.0) {
            return None;
        }
        let o = lp.truncate() / lp.w;
        Some((o, lv.truncate() - o * lv.w, lp.w, lv.w))
    }
}

/// Anything a ray can hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Object {
    Ball(Ball),
    Tube(Tube),
    Disc(Disc),
    Mesh(MeshInstance),
}

impl Object {
    /// The object moved by the isometry `m`.
    #[must_use]
    pub fn transformed(&self, geometry: Geometry, m: DMat4) -> Object {
        let map = |p: DVec4| geometry.project_point(m * p);
        match self {
            Object::Ball(b) => Object::Ball(Ball {
                texture: b.texture.map(|t| BallTexture {
                    frame: m * t.frame,
                    ..t
                }),
                emission: b.emission,
                ..Ball::new(geometry, map(b.centre), b.radius, b.colour)
            }),
            Object::Tube(t) => Object::Tube(
                Tube::new(geometry, map(t.a), map(t.b), t.radius, t.colour)
                    .with_emission(t.emission),
            ),
            Object::Disc(d) => {
                let c = map(d.centre);
                Object::Disc(
                    Disc::new(geometry, c, m * d.normal, d.radius, d.colour)
                        .with_emission(d.emission),
                )
            }
            Object::Mesh(i) => Object::Mesh(MeshInstance {
                material: i.material,
                ..MeshInstance::new(geometry, i.mesh, m * i.frame, i.radius)
            }),
        }
    }

    /// A metric ball `(centre, radius)` that contains the object.
    #[must_use]
    pub fn bounding_ball(&self, geometry: Geometry) -> (DVec4, f64) {
        match self {
            Object::Ball(b) => (b.centre, b.radius),
            Object::Tube(t) => {
                let half = 0.5 * geometry.distance(t.a, t.b);
                let (mid, _) = geometry.geodesic(t.a, t.towards_b, half);
                (geometry.project_point(mid), half + t.radius)
            }
            Object::Disc(d) => (d.centre, d.radius),
            Object::Mesh(i) => (i.origin(geometry), i.radius),
        }
    }

    /// Whether two objects are the same (to `tolerance` in distance), a tube's ends in
    /// either order.
    #[must_use]
    pub fn same_as(&self, other: &Object, geometry: Geometry, tolerance: f64) -> bool {
        let near = |p: DVec4, q: DVec4| geometry.distance(p, q) <= tolerance;
        match (self, other) {
            (Object::Ball(a), Object::Ball(b)) => {
                near(a.centre, b.centre)
                    && (a.radius - b.radius).abs() <= tolerance
                    && a.colour == b.colour
                    && a.texture.map(|t| t.texture) == b.texture.map(|t| t.texture)
            }
            (Object::Tube(a), Object::Tube(b)) => {
                ((near(a.a, b.a) && near(a.b, b.b)) || (near(a.a, b.b) && near(a.b, b.a)))
                    && (a.radius - b.radius).abs() <= tolerance
                    && a.colour == b.colour
            }
            (Object::Disc(a), Object::Disc(b)) => {
                near(a.centre, b.centre)
                    && (a.radius - b.radius).abs() <= tolerance
                    && ((a.normal - b.normal).length() <= tolerance
                        || (a.normal + b.normal).length() <= tolerance)
                    && a.colour == b.colour
            }
            (Object::Mesh(a), Object::Mesh(b)) => {
                a.mesh == b.mesh
                    && a.material == b.material
                    && crate::geometry::max_abs_entry(&(a.frame - b.frame).to_cols_array())
                        <= tolerance
            }
            _ => false,
        }
    }
}

/// The most images of one object [`Scene::place`] adds (an object far larger than the cell
/// would need more, and is refused).
pub const MAX_IMAGES: usize = 512;

/// An object could not be placed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlaceError {
    #[error("the object is not inside the cell: its centre is {0:.3} outside face {1}")]
    Outside(f64, usize),
    #[error(
        "the object meets more than {MAX_IMAGES} copies of the cell; make it smaller than the cell"
    )]
    TooLarge,
}

/// A ray–object hit: the chart ratio `s` along the segment, the point and the object's
/// outward unit normal there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub s: f64,
    pub point: DVec4,
    pub normal: DVec4,
    /// Albedo at the hit (textures applied).
    pub colour: DVec3,
    pub emission: DVec3,
}

/// The smallest root of `a s² + b s + c = 0` in `(lo, hi)` that passes `accept`, computed
/// without cancellation.
fn first_root(
    a: f64,
    b: f64,
    c: f64,
    lo: f64,
    hi: f64,
    accept: impl Fn(f64) -> bool,
) -> Option<f64> {
    let disc = b * b - 4.0 * a * c;
    if !(disc >= 0.0) {
        return None;
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (r1, r2) = (q / a, c / q);
    let (r1, r2) = if r1 <= r2 { (r1, r2) } else { (r2, r1) };
    [r1, r2]
        .into_iter()
        .find(|&s| s.is_finite() && s > lo && s < hi && accept(s))
}

impl Object {
    /// The first hit along `X(s) ∝ p + s v` with `0 < s < s_max` (`p` on the model, `v` a
    /// unit tangent at `p`) of a ball, tube or disc, with its own colour (untextured). A mesh
    /// needs the scene's meshes: see [`Scene::intersect`].
    #[must_use]
    pub fn intersect(&self, geometry: Geometry, p: DVec4, v: DVec4, s_max: f64) -> Option<Hit> {
        let k = geometry.kappa();
        let form = |a: DVec4, b: DVec4| geometry.form(a, b);
        let (s, colour) = match self {
            Object::Ball(ball) => {
                let c = ball.centre;
                let s = if geometry == Geometry::Euclidean {
                    let d = p.truncate() - c.truncate();
                    let v3 = v.truncate();
                    let c0 = d.length_squared() - ball.radius * ball.radius;
                    first_root(v3.length_squared(), 2.0 * d.dot(v3), c0, 0.0, s_max, |_| {
                        true
                    })
                } else {
                    // (⟨p,c⟩ + s⟨v,c⟩)² = C(ρ)² (1 + κ s²), on the sheet where ⟨X,c⟩ has
                    // the sign of κ C(ρ) (not the antipodal ball of S³).
                    let (a, b) = (form(p, c), form(v, c));
                    let cr = ball.c_radius;
                    let sheet = k * cr;
                    first_root(
                        b * b - k * cr * cr,
                        2.0 * a * b,
                        a * a - cr * cr,
                        0.0,
                        s_max,
                        |s| (a + s * b) * sheet > 0.0,
                    )
                }?;
                (s, ball.colour)
            }
            Object::Tube(tube) => {
                let (a2, b1, c0) = if geometry == Geometry::Euclidean {
                    let u = tube.towards_b.truncate();
                    let perp = |x: DVec3| x - x.dot(u) * u;
                    let d = perp(p.truncate() - tube.a.truncate());
                    let w = perp(v.truncate());
                    let r2 = tube.radius * tube.radius;
                    (w.length_squared(), 2.0 * d.dot(w), d.length_squared() - r2)
                } else {
                    // κ⟨X,e1⟩² + ⟨X,e2⟩² = C(ρ)² ⟨X,X⟩ with ⟨X,X⟩ = κ + s², e1 = a.
                    let (e1, e2) = (tube.a, tube.towards_b);
                    let (a0, a1) = (form(p, e1), form(v, e1));
                    let (b0, b1) = (form(p, e2), form(v, e2));
                    let cr2 = tube.c_radius_sq;
                    (
                        k * a1 * a1 + b1 * b1 - cr2,
                        2.0 * (k * a0 * a1 + b0 * b1),
                        k * a0 * a0 + b0 * b0 - k * cr2,
                    )
                };
                let s = first_root(a2, b1, c0, 0.0, s_max, |s| {
                    tube.over_segment(geometry, p + s * v)
                })?;
                (s, tube.colour)
            }
            Object::Disc(disc) => {
                let n = disc.covector(geometry);
                let (np, nv) = (n.dot(p), n.dot(v));
                let s = -np / nv;
                if !(s > 0.0 && s < s_max) {
                    return None;
                }
                let point = geometry.project_point(p + s * v);
                if !(geometry.distance(point, disc.centre) <= disc.radius) {
                    return None;
                }
                // The side facing the ray.
                let mut normal = geometry.unit_tangent(point, disc.normal);
                if geometry.form(normal, v) > 0.0 {
                    normal = -normal;
                }
                return Some(Hit {
                    s,
                    point,
                    normal,
                    colour: disc.colour,
                    emission: disc.emission,
                });
            }
            Object::Mesh(_) => return None,
        };
        let point = geometry.project_point(p + s * v);
        let (foot, emission) = match self {
            Object::Ball(ball) => (ball.centre, ball.emission),
            Object::Tube(tube) => (tube.foot(geometry, point), tube.emission),
            Object::Disc(_) | Object::Mesh(_) => unreachable!("returned above"),
        };
        // Outward normal: the tangent at the hit pointing away from the nearest point of
        // the ball's centre or the tube's axis.
        let normal = geometry.unit_tangent(point, point - foot);
        Some(Hit {
            s,
            point,
            normal,
            colour,
            emission,
        })
    }
}

/// Half a colour step of an 8-bit image.
pub const DEFAULT_CUTOFF_WEIGHT: f64 = 1.0 / 510.0;

/// A point light, with its copies in the cells around the fundamental cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub position: DVec4,
    pub colour: DVec3,
    /// Brightness at distance `d` is `power / S(d)²` (`sin²`, `d²`, `sinh²`).
    pub power: f64,
    /// The light and its images under the face pairings, in the cell's coordinates: a
    /// surface point is lit by the nearest of them.
    pub images: Vec<DVec4>,
}

impl Light {
    /// A light at `position` (inside the cell) with its images under the pairings.
    #[must_use]
    pub fn new(space: &Space, position: DVec4, colour: DVec3, power: f64) -> Self {
        let g = space.geometry;
        let mut images = vec![position];
        for face in &space.faces {
            let image = g.project_point(face.pairing * position);
            if images.iter().all(|q| g.distance(*q, image) > 1e-9) {
                images.push(image);
            }
        }
        Self {
            position,
            colour,
            power,
            images,
        }
    }

    /// The image nearest to `x` and its distance.
    #[must_use]
    pub fn nearest(&self, geometry: Geometry, x: DVec4) -> (DVec4, f64) {
        self.images
            .iter()
            .map(|q| (*q, geometry.distance(x, *q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((self.position, geometry.distance(x, self.position)))
    }
}

/// The shading model, in one place (`DESIGN.md` §1, §3):
///
/// ```text
/// lit     = albedo · (ambient + (1 − ambient) · Σ_lights light · power · max(0, ⟨n, l⟩) / max(S(d_L)², S(r₀)²))
/// surface = min(lit + emission, 1)                        per channel
/// colour  = e^(−d/λ) · surface + (1 − e^(−d/λ)) · fog     d = distance along the ray
/// ```
///
/// `l` is the unit tangent at the hit towards the light's nearest copy (among the light and
/// its images under the face pairings), `d_L` its distance, `r₀` a small radius that keeps
/// the falloff finite. No shadows.
/// A ray stops at the distance `λ ln(1/w)` where the fog weight `e^(−d/λ)` falls to
/// `w = cutoff_weight`. Surface and fog colours lie in [0, 1], so whatever lies beyond
/// changes the pixel by at most `w` per channel: with the default `w = 1/510` that is half a
/// colour step of an 8-bit image, the cut-off's error bound.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shading {
    pub ambient: f64,
    pub fog_colour: DVec3,
    /// Fog distance scale λ.
    pub fog_distance: f64,
    pub near_light: f64,
    /// Fog weight at which a ray stops (the cut-off's error bound per channel).
    pub cutoff_weight: f64,
}

impl Default for Shading {
    /// The default scene's shading with a fog distance of 1 (set it for the space:
    /// [`Shading::default_fog_distance`]).
    fn default() -> Self {
        Self {
            ambient: 0.3,
            fog_colour: DVec3::new(0.04, 0.05, 0.08),
            fog_distance: 1.0,
            near_light: 0.05,
            cutoff_weight: DEFAULT_CUTOFF_WEIGHT,
        }
    }
}

impl Shading {
    /// The default fog distance scale λ: three times the inradius, several cells deep in
    /// every space.
    #[must_use]
    pub fn default_fog_distance(space: &Space) -> f64 {
        3.0 * crate::space::invariants::inradius(space)
    }

    /// The distance past which nothing changes the image by half a colour step or more.
    #[must_use]
    pub fn cutoff_distance(&self) -> f64 {
        self.fog_distance * (1.0 / self.cutoff_weight).ln()
    }

    /// The colour of a surface point seen at distance `d`.
    #[must_use]
    pub fn shade(&self, geometry: Geometry, lights: &[Light], hit: &Hit, d: f64) -> DVec3 {
        let mut lit = DVec3::splat(self.ambient);
        for light in lights {
            let (at, dl) = light.nearest(geometry, hit.point);
            if dl > 0.0 {
                let l = geometry.tangent_towards(hit.point, at);
                let lambert = geometry.form(hit.normal, l).max(0.0);
                let s = geometry.s(dl).abs().max(geometry.s(self.near_light));
                lit += (1.0 - self.ambient) * light.colour * (light.power * lambert / (s * s));
            }
        }
        let surface = (hit.colour * lit + hit.emission).min(DVec3::ONE);
        let w = (-d / self.fog_distance).exp();
        w * surface + (1.0 - w) * self.fog_colour
    }
}

/// A surface's look: albedo (times its texture, if any) and emission, linear RGB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    pub colour: DVec3,
    /// Index into [`Scene::textures`].
    pub texture: Option<u32>,
    pub emission: DVec3,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            colour: DVec3::splat(0.8),
            texture: None,
            emission: DVec3::ZERO,
        }
    }
}

/// The player's own avatar: a mesh at the player's frame, seen only where rays come back
/// round the space (hits closer than `skip` to the eye are the copy the eye sits in, and
/// are passed through).
#[derive(Clone, Debug, PartialEq)]
pub struct Avatar {
    /// Index into [`Scene::meshes`].
    pub mesh: u32,
    /// The avatar at the player's frame and its images under the pairings that meet the
    /// cell ([`Scene::set_avatar_frame`]).
    pub instances: Vec<MeshInstance>,
    /// Hits nearer than this to the eye are not drawn.
    pub skip: f64,
}

/// The most images of the avatar drawn (its copy and those through nearby faces, edges and
/// vertices).
pub const MAX_AVATAR_IMAGES: usize = 8;

/// The avatar (mesh `mesh` of radius `radius`) at the player's `frame` and its images under
/// the pairings that meet the cell, nearest first, at most [`MAX_AVATAR_IMAGES`].
#[must_use]
pub fn avatar_instances(space: &Space, mesh: u32, radius: f64, frame: DMat4) -> Vec<MeshInstance> {
    let g = space.geometry;
    let instance = MeshInstance::new(g, mesh, frame, radius);
    let mut scratch = Scene::new(Vec::new(), Vec::new(), Shading::default());
    // The player is kept inside the cell, so placing cannot fail; keep the avatar itself
    // if it somehow does.
    if scratch.place(space, Object::Mesh(instance)).is_err() {
        scratch.objects = vec![Object::Mesh(instance)];
    }
    let origin = instance.origin(g);
    let mut instances: Vec<MeshInstance> = scratch
        .objects
        .into_iter()
        .filter_map(|o| match o {
            Object::Mesh(m) => Some(m),
            _ => None,
        })
        .collect();
    instances.sort_by(|a, b| {
        g.distance(a.origin(g), origin)
            .total_cmp(&g.distance(b.origin(g), origin))
    });
    instances.truncate(MAX_AVATAR_IMAGES);
    instances
}

/// What the rays can see: objects in the cell, lights, meshes with their materials and
/// textures, the player's avatar, the shading.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub objects: Vec<Object>,
    pub lights: Vec<Light>,
    pub shading: Shading,
    pub meshes: Vec<Arc<Mesh>>,
    pub materials: Vec<Material>,
    pub textures: Vec<Arc<Texture>>,
    /// Seconds since the start: turns the spinning globes.
    pub time: f64,
    pub avatar: Option<Avatar>,
}

/// What a ray segment meets first: the object's index (`objects.len() + k` for the avatar's
/// `k`-th image) and the hit.
pub type SegmentHit = (usize, Hit);

impl Scene {
    /// A scene with these objects and lights, nothing else.
    #[must_use]
    pub fn new(objects: Vec<Object>, lights: Vec<Light>, shading: Shading) -> Self {
        Self {
            objects,
            lights,
            shading,
            meshes: Vec::new(),
            materials: Vec::new(),
            textures: Vec::new(),
            time: 0.0,
            avatar: None,
        }
    }

    /// The first hit along the segment `X(s) ∝ p + s v`, `0 < s < s_max`, of a ray that has
    /// come `travelled` from the eye.
    #[must_use]
    pub fn intersect(
        &self,
        g: Geometry,
        p: DVec4,
        v: DVec4,
        s_max: f64,
        travelled: f64,
    ) -> Option<SegmentHit> {
        let mut best: Option<SegmentHit> = None;
        let mut limit = s_max;
        for (i, o) in self.objects.iter().enumerate() {
            let hit = match o {
                Object::Mesh(m) => self.intersect_mesh(g, m, p, v, limit),
                _ => o.intersect(g, p, v, limit).map(|mut h| {
                    if let Object::Ball(Ball {
                        texture: Some(t), ..
                    }) = o
                    {
                        h.colour *= self.texture_colour(t.texture, t.uv(g, h.point, self.time));
                    }
                    h
                }),
            };
            if let Some(h) = hit {
                limit = h.s;
                best = Some((i, h));
            }
        }
        if let Some(avatar) = &self.avatar {
            for (k, m) in avatar.instances.iter().enumerate() {
                if let Some(h) = self.intersect_mesh(g, m, p, v, limit)
                    && travelled + g.distance_from_ratio(h.s, 1.0) >= avatar.skip
                {
                    limit = h.s;
                    best = Some((self.objects.len() + k, h));
                }
            }
        }
        best
    }

    fn texture_colour(&self, texture: u32, uv: DVec2) -> DVec3 {
        self.textures
            .get(texture as usize)
            .map_or(DVec3::ONE, |t| t.sample(uv))
    }

    /// A mesh instance's first hit on the segment, with the material's colour and the
    /// normal of the plane through the hit whose chart normal is the interpolated vertex
    /// normal (facing the ray).
    #[must_use]
    pub fn intersect_mesh(
        &self,
        g: Geometry,
        m: &MeshInstance,
        p: DVec4,
        v: DVec4,
        s_max: f64,
    ) -> Option<Hit> {
        let mesh = self.meshes.get(m.mesh as usize)?;
        let (o, d, pw, vw) = m.local_ray(p, v)?;
        let den = pw + s_max * vw;
        let t_max = if den > 0.0 {
            s_max / den
        } else {
            f64::INFINITY
        };
        let h = mesh.intersect(o, d, t_max)?;
        let s = h.t * pw / (1.0 - h.t * vw);
        if !(s > 0.0 && s < s_max) {
            return None;
        }
        let tri = &mesh.triangles[h.triangle];
        let w = [1.0 - h.u - h.v, h.u, h.v];
        let x = o + h.t * d;
        let n = (tri.normals[0] * w[0] + tri.normals[1] * w[1] + tri.normals[2] * w[2])
            .normalize_or_zero();
        let k = g.kappa();
        let local_normal = if k == 0.0 {
            n.extend(0.0)
        } else {
            n.extend(-n.dot(x) / k)
        };
        let point = g.project_point(p + s * v);
        let mut normal = g.unit_tangent(point, m.frame * local_normal);
        if g.form(normal, v) > 0.0 {
            normal = -normal;
        }
        let material = m
            .material
            .unwrap_or(tri.material)
            .min(self.materials.len().saturating_sub(1) as u32);
        let mat = self
            .materials
            .get(material as usize)
            .copied()
            .unwrap_or_default();
        let uv = tri.uvs[0] * w[0] + tri.uvs[1] * w[1] + tri.uvs[2] * w[2];
        let colour = match mat.texture {
            Some(t) => mat.colour * self.texture_colour(t, uv),
            None => mat.colour,
        };
        Some(Hit {
            s,
            point,
            normal,
            colour,
            emission: mat.emission,
        })
    }

    /// Puts the avatar at the player's `frame`, with its images under the pairings where it
    /// sticks out of the cell ([`avatar_instances`]).
    pub fn set_avatar_frame(&mut self, space: &Space, frame: DMat4) {
        let Some(avatar) = self.avatar.as_mut() else {
            return;
        };
        let radius = self
            .meshes
            .get(avatar.mesh as usize)
            .map_or(0.0, |m| m.radius);
        avatar.instances = avatar_instances(space, avatar.mesh, radius, frame);
    }
}

/// Distinct colours for edge cycles (a golden-angle walk around the hue circle).
#[must_use]
pub fn palette(i: usize) -> DVec3 {
    let h = (i as f64 * 0.618_033_988_75 + 0.08).fract() * 6.0;
    let x = 1.0 - (h % 2.0 - 1.0).abs();
    let (r, g, b) = match h as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    DVec3::new(r, g, b) * 0.75 + DVec3::splat(0.2)
}

/// Which parts of the default scene to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SceneParts {
    /// The cell's edges (tubes coloured by edge cycle) and a small ball at each vertex.
    pub edges: bool,
    /// A ball at the cell's centre.
    pub centre_ball: bool,
    /// The player's ship ([`crate::scene::avatar`]), seen where rays come back round the
    /// space; put it at the player with [`Scene::set_avatar_frame`].
    pub avatar: bool,
}

impl Default for SceneParts {
    /// Edges and the centre ball; no avatar (still pictures have no player).
    fn default() -> Self {
        Self {
            edges: true,
            centre_ball: true,
            avatar: false,
        }
    }
}

impl Scene {
    /// Adds `object` (its centre inside the cell) and, where it sticks out through faces,
    /// its images under the pairings that meet the cell, so that it is seen whole from
    /// every side and in every copy of the cell. Images equal to an object already in the
    /// scene are not added twice. Returns how many objects were added.
    ///
    /// A ray that leaves through face `f` continues from `g_f` of its exit point, so the
    /// part of an object outside `f` is seen inside the cell as `g_f(object)`: that image
    /// is added when the object reaches past `f` and the image comes within reach of the
    /// cell (tested at points along a tube's axis); images of images are followed the same way (edges, vertices).
    /// The test is conservative: a tube whose flat end only touches the cell at a vertex
    /// (an edge of a neighbouring cell) is kept too; it costs time, never a wrong pixel.
    pub fn place(&mut self, space: &Space, object: Object) -> Result<usize, PlaceError> {
        let g = space.geometry;
        let (centre, _) = object.bounding_ball(g);
        let faces = space.faces.len();
        if let Some((f, d)) = (0..faces)
            .map(|f| (f, space.face_distance(f, centre)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .filter(|(_, d)| *d > 1e-9)
        {
            return Err(PlaceError::Outside(d, f));
        }
        const SAME: f64 = 1e-9;
        // Points along the object's core (a ball's centre, a tube's axis at spacing ≤ its
        // radius) and the slack they need: every point of the object is within `reach` of one.
        let cores = |o: &Object| -> (Vec<DVec4>, f64) {
            match o {
                Object::Ball(b) => (vec![b.centre], b.radius),
                Object::Disc(d) => (vec![d.centre], d.radius),
                Object::Mesh(m) => (vec![m.origin(g)], m.radius),
                Object::Tube(t) => {
                    let length = g.distance(t.a, t.b);
                    let steps = ((length / t.radius.max(1e-9)).ceil() as usize).clamp(1, 256);
                    let step = length / steps as f64;
                    let points = (0..=steps)
                        .map(|i| g.project_point(g.geodesic(t.a, t.towards_b, i as f64 * step).0))
                        .collect();
                    (points, t.radius + 0.5 * step)
                }
            }
        };
        // Conservative: a point whose largest face distance is under `reach` may be within
        // `reach` of the cell (the face distances underestimate near edges and vertices).
        let meets_cell = |o: &Object| {
            let (points, reach) = cores(o);
            points.iter().any(|p| {
                (0..faces)
                    .map(|f| space.face_distance(f, *p))
                    .fold(f64::NEG_INFINITY, f64::max)
                    < reach
            })
        };
        let mut found: Vec<Object> = Vec::new();
        let mut queue = vec![object];
        while let Some(o) = queue.pop() {
            if found.iter().any(|x| x.same_as(&o, g, SAME)) {
                continue;
            }
            if found.len() >= MAX_IMAGES {
                return Err(PlaceError::TooLarge);
            }
            let (points, reach) = cores(&o);
            for (f, face) in space.faces.iter().enumerate() {
                if points.iter().any(|p| space.face_distance(f, *p) > -reach) {
                    let image = o.transformed(g, face.pairing);
                    if meets_cell(&image) && !found.iter().any(|x| x.same_as(&image, g, SAME)) {
                        queue.push(image);
                    }
                }
            }
            found.push(o);
        }
        let before = self.objects.len();
        for o in found {
            if !self.objects.iter().any(|x| x.same_as(&o, g, SAME)) {
                self.objects.push(o);
            }
        }
        Ok(self.objects.len() - before)
    }

    /// The default scene of a space: the cell's edges as thin tubes coloured by edge cycle,
    /// a small ball at each vertex, a ball at the centre and one light, with fog at `fog`.
    #[must_use]
    pub fn default_for(space: &Space, fog_distance: f64) -> Self {
        Self::with_parts(space, fog_distance, SceneParts::default())
    }

    /// The default scene with only the chosen parts (the light and shading are the same).
    #[must_use]
    pub fn with_parts(space: &Space, fog_distance: f64, parts: SceneParts) -> Self {
        let g = space.geometry;
        let inradius = crate::space::invariants::inradius(space);
        let light_at = g.translation(DVec3::new(0.45, 0.8, 0.4), 0.65 * inradius) * space.centre();
        let light = Light::new(space, light_at, DVec3::ONE, g.s(0.7 * inradius).powi(2));
        Scene::new(
            Vec::new(),
            vec![light],
            Shading {
                ambient: 0.3,
                fog_colour: DVec3::new(0.04, 0.05, 0.08),
                fog_distance,
                near_light: 0.05 * inradius,
                cutoff_weight: DEFAULT_CUTOFF_WEIGHT,
            },
        )
        .adding_parts(space, parts)
    }

    /// This scene with the default scene's parts added: the part objects before its own,
    /// and the avatar given or taken away as `parts.avatar` says. A scene file's scene and
    /// the plugin's base scene are made whole this way.
    #[must_use]
    pub fn adding_parts(&self, space: &Space, parts: SceneParts) -> Scene {
        let mut scene = self.clone();
        scene.objects.splice(0..0, Self::part_objects(space, parts));
        if !parts.avatar {
            scene.avatar = None;
        } else if scene.avatar.is_none() {
            let size = crate::scene::avatar_size(crate::space::invariants::inradius(space));
            // The ship is a fixed small model: placing it cannot fail.
            let _ = scene.add_avatar(space.geometry, size);
        }
        scene
    }

    /// The objects of the default scene's parts: the cell's edges as thin tubes coloured by
    /// edge cycle with a small ball at each vertex, and the centre ball (the avatar is not
    /// an object: see [`Scene::add_avatar`]).
    #[must_use]
    pub fn part_objects(space: &Space, parts: SceneParts) -> Vec<Object> {
        let g = space.geometry;
        let inradius = crate::space::invariants::inradius(space);
        let tube = 0.05 * inradius;
        let edges = if parts.edges {
            space.edges.as_slice()
        } else {
            &[]
        };
        let vertices = if parts.edges { space.vertices.len() } else { 0 };
        let mut objects: Vec<Object> = edges
            .iter()
            .map(|e| {
                Object::Tube(Tube::new(
                    g,
                    space.vertex_point(e.vertices[0]),
                    space.vertex_point(e.vertices[1]),
                    tube,
                    palette(e.cycle),
                ))
            })
            .collect();
        objects.extend((0..vertices).map(|v| {
            Object::Ball(Ball::new(
                g,
                space.vertex_point(v),
                1.6 * tube,
                DVec3::splat(0.9),
            ))
        }));
        if parts.centre_ball {
            objects.push(Object::Ball(Ball::new(
                g,
                space.centre(),
                0.25 * inradius,
                DVec3::new(1.0, 0.78, 0.45),
            )));
        }
        objects
    }
}
