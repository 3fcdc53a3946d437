//! Scene objects (exact quadrics in all three geometries) and the shading model.
//!
//! A ray segment inside the cell is `X(s) ∝ p + s v` for `s` in `[0, T_exit)` (a straight
//! chart line), and metric balls and tubes around geodesics are quadrics of R⁴, so each
//! hit is a root of a quadratic in `s`.

use crate::geometry::Geometry;
use glam::{DMat4, DVec2, DVec3, DVec4};

/// A metric ball `d(X, centre) ≤ radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// The centre, a point of the model.
    pub centre: DVec4,
    /// The radius (geodesic).
    pub radius: f64,
    /// Albedo, linear RGB.
    pub colour: DVec3,
    /// Light the surface gives off itself (added to the lit colour).
    pub emission: DVec3,
    /// A picture wrapped round the ball (a globe), if any.
    pub texture: Option<BallTexture>,
    /// The share of light it reflects as a mirror, 0 to 1 ([`Ball::with_reflectance`]).
    pub reflectance: f64,
    /// `C(radius)`.
    c_radius: f64,
}

/// An equirectangular picture on a ball: longitude across, latitude down, the north pole
/// on the ball's own `+y` axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BallTexture {
    /// Index into [`CurvedScene::textures`](crate::scene::CurvedScene::textures).
    pub texture: u32,
    /// The ball's orientation: an isometry taking the origin to the centre, its `y` axis
    /// the spin axis and its `z` axis longitude 0.
    pub frame: DMat4,
    /// Spin about the `y` axis, radians per second of [`CurvedScene::time`](crate::scene::CurvedScene::time).
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
    /// A ball of radius `radius` around `centre` (projected onto the model).
    #[must_use]
    pub fn new(geometry: Geometry, centre: DVec4, radius: f64, colour: DVec3) -> Self {
        Self {
            centre,
            radius,
            colour,
            emission: DVec3::ZERO,
            texture: None,
            reflectance: 0.0,
            c_radius: geometry.cs(radius).0,
        }
    }

    /// The ball giving off `emission`.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// The ball as a mirror reflecting `reflectance` of the light (clamped to 0–1; the rest
    /// is lit as usual). A globe (a textured ball) reflects too.
    #[must_use]
    pub fn with_reflectance(self, reflectance: f64) -> Self {
        Self {
            reflectance: clamp_reflectance(reflectance),
            ..self
        }
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
    /// One end of the axis.
    pub a: DVec4,
    /// The other end.
    pub b: DVec4,
    /// The radius (geodesic).
    pub radius: f64,
    /// Albedo, linear RGB.
    pub colour: DVec3,
    /// Emitted colour, linear RGB.
    pub emission: DVec3,
    /// Unit tangent at `a` towards `b`: with `a` it spans the segment's line.
    pub(crate) towards_b: DVec4,
    /// `(C(L), S(L))` of the segment's length `L`.
    cs_length: (f64, f64),
    /// `C(radius)²`.
    c_radius_sq: f64,
}

impl Tube {
    /// A tube of radius `radius` around the geodesic segment from `a` to `b`.
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
    /// The centre, a point of the model.
    pub centre: DVec4,
    /// Unit tangent at the centre.
    pub normal: DVec4,
    /// The radius (geodesic).
    pub radius: f64,
    /// Albedo, linear RGB.
    pub colour: DVec3,
    /// Emitted colour, linear RGB.
    pub emission: DVec3,
    /// The share of light it reflects as a mirror, 0 to 1 ([`Disc::with_reflectance`]).
    pub reflectance: f64,
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
            reflectance: 0.0,
        }
    }

    /// The disc giving off `emission`.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// The disc as a mirror reflecting `reflectance` of the light (clamped to 0–1; both
    /// sides reflect).
    #[must_use]
    pub fn with_reflectance(self, reflectance: f64) -> Self {
        Self {
            reflectance: clamp_reflectance(reflectance),
            ..self
        }
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

/// A mesh placed in the cell: [`CurvedScene::meshes`](crate::scene::CurvedScene::meshes)`[mesh]` in the frame `frame` (an isometry
/// taking the mesh's chart to the cell's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshInstance {
    /// Index into [`CurvedScene::meshes`](crate::scene::CurvedScene::meshes).
    pub mesh: u32,
    /// Where the mesh is: its frame (an isometry).
    pub frame: DMat4,
    /// `frame⁻¹`.
    pub inverse: DMat4,
    /// The mesh's radius (largest vertex distance from its origin).
    pub radius: f64,
    /// A material used instead of the mesh's own (index into [`CurvedScene::materials`](crate::scene::CurvedScene::materials)).
    pub material: Option<u32>,
    /// Added to the mesh's own material indices: a mesh shared between scenes
    /// ([`crate::scene::TracedModel`]) keeps indices from 0, and each scene appends its
    /// materials where it has room (0 for meshes added by [`crate::scene::CurvedScene::add_model`]).
    pub material_base: u32,
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
            material_base: 0,
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
    /// A metric ball (a globe if textured).
    Ball(Ball),
    /// A tube around a geodesic segment.
    Tube(Tube),
    /// A flat disc.
    Disc(Disc),
    /// A placed triangle mesh.
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
                material_base: i.material_base,
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
                    && a.material_base == b.material_base
                    && crate::geometry::max_abs_entry(&(a.frame - b.frame).to_cols_array())
                        <= tolerance
            }
            _ => false,
        }
    }
}

/// A ray–object hit: the chart ratio `s` along the segment, the point and the object's
/// outward unit normal there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Chart ratio along the segment.
    pub s: f64,
    /// The hit point.
    pub point: DVec4,
    /// Outward unit normal tangent there.
    pub normal: DVec4,
    /// Albedo at the hit (textures applied).
    pub colour: DVec3,
    /// Emitted colour, linear RGB.
    pub emission: DVec3,
    /// The share reflected as a mirror (0: none).
    pub reflectance: f64,
}

/// A reflectance clamped to 0–1 (NaN taken as 0).
fn clamp_reflectance(r: f64) -> f64 {
    if r.is_nan() { 0.0 } else { r.clamp(0.0, 1.0) }
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
    /// needs the scene's meshes: see [`CurvedScene::intersect`](crate::scene::CurvedScene::intersect).
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
                    reflectance: disc.reflectance,
                });
            }
            Object::Mesh(_) => return None,
        };
        let point = geometry.project_point(p + s * v);
        let (foot, emission, reflectance) = match self {
            Object::Ball(ball) => (ball.centre, ball.emission, ball.reflectance),
            Object::Tube(tube) => (tube.foot(geometry, point), tube.emission, 0.0),
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
            reflectance,
        })
    }
}
