//! A camera flight in a product space (H²×R, S²×R): a flight file's keys as points of the
//! product's universal cover, the camera between two keys on the product geodesic between
//! them, looking at the point between their targets with the fibre up, and brought back
//! into the cell through the faces it passed.
//!
//! A key's `position` and `look_at` are `(x, y, z)` in units of [`ProductSpace::scale`]:
//! the surface point at distance `|(x, y)|` from the cell's centre in the direction of
//! `(x, y)` (side 0 is at `+x`), at height `z`. The keys' `up` is not used: the fibre is up.

use super::{ProductCamera, along, tangent_towards};
use crate::geometry::{Geometry, Ray};
use crate::scene::flight::FlightFile;
use crate::space::Holonomy;
use crate::space::motion::{CoverFlight, keyed};
use crate::space::product::ProductSpace;
use crate::space::product::motion::{camera_frame, transport};
use glam::{DMat4, DVec3, DVec4};

/// A flight through a product space: its keys as points of the universal cover.
#[derive(Clone, Debug)]
pub struct ProductFlight {
    geometry: Geometry,
    /// Time, position and target of each key.
    keys: Vec<(f64, DVec4, DVec4)>,
    /// Vertical field of view in degrees.
    pub fov: f64,
}

/// How many times round the circle a key may be from the cell (its height keeps ten digits
/// of the cell's size in f64).
pub const MAX_CIRCLES: f64 = 1e6;

/// The point of the product at key coordinates `p` (in units of `scale`): refused where it
/// is π or more round the sphere, or too far to hold in f64.
pub(super) fn point_at(space: &ProductSpace, p: DVec3, what: &str) -> Result<DVec4, String> {
    let g = space.base();
    let scale = space.scale();
    let d = p.truncate().length() * scale;
    if g == Geometry::Spherical && d >= 0.999 * std::f64::consts::PI {
        return Err(format!(
            "{what} {:?} is π or more round the sphere from the centre (at most {:.3} in this \
             space's units)",
            p.to_array(),
            0.999 * std::f64::consts::PI / scale
        ));
    }
    if (p.z * scale).abs() > MAX_CIRCLES * space.length() {
        return Err(format!(
            "{what} {:?} is more than {MAX_CIRCLES} circles up or down the fibre: too far to be \
             held in f64 to the cell's precision",
            p.to_array()
        ));
    }
    let (c, s) = g.cs(d);
    let dir = p.truncate().normalize_or_zero();
    let point = DVec4::new(s * dir.x, s * dir.y, p.z * scale, c);
    if !point.is_finite() || point.abs().max_element() > 1e12 {
        return Err(format!(
            "{what} {:?} is too far from the centre to be held in f64",
            p.to_array()
        ));
    }
    Ok(point)
}

/// The key coordinates of a point of the product (the inverse of [`point_at`]); `None` where
/// a key cannot hold it (π or more round the sphere, too far up the fibre, not finite).
fn key_coordinates(space: &ProductSpace, p: DVec4) -> Option<DVec3> {
    let g = space.base();
    let scale = space.scale();
    let planar = p.x.hypot(p.y);
    let d = match g {
        Geometry::Spherical => planar.atan2(p.w),
        Geometry::Hyperbolic => planar.asinh(),
        Geometry::Euclidean => planar,
    };
    if (g == Geometry::Spherical && d >= 0.999 * std::f64::consts::PI)
        || p.z.abs() > MAX_CIRCLES * space.length()
    {
        return None;
    }
    let dir = if planar > 0.0 {
        DVec3::new(p.x / planar, p.y / planar, 0.0)
    } else {
        DVec3::ZERO
    };
    let key = DVec3::new(dir.x * d / scale, dir.y * d / scale, p.z / scale);
    key.is_finite().then_some(key)
}

/// The key of a camera at `frame` in a product cell that reached it through `holonomy`
/// (`walk --record`): its position and a point half a unit ahead that it looks at, carried
/// back into the universal cover (the pairings' surface parts undone, the fibre shift taken
/// off the height), in the keys' coordinates; the `up` written is the point above (the
/// replay keeps the fibre up). `None` where a key cannot hold them.
#[must_use]
pub fn recorded_product_key(
    space: &ProductSpace,
    frame: DMat4,
    holonomy: &Holonomy,
) -> Option<(DVec3, DVec3, DVec3)> {
    let g = space.base();
    let mut cover = g.inverse(holonomy.matrix) * frame;
    cover.w_axis.z -= holonomy.fibre_shift;
    let r = 0.5 * space.scale();
    let ahead = transport(g, cover, -cover.z_axis, r).w_axis;
    let above = cover.w_axis + DVec4::Z * r;
    Some((
        key_coordinates(space, cover.w_axis)?,
        key_coordinates(space, ahead)?,
        key_coordinates(space, above)?,
    ))
}

/// The point a fraction `s` of the way along the product geodesic from `a` to `b`.
fn between(g: Geometry, a: DVec4, b: DVec4, s: f64) -> DVec4 {
    let v = tangent_towards(g, a, b);
    let db = super::surface_distance(g, a, b);
    let dz = b.z - a.z;
    let d = (db * db + dz * dz).sqrt();
    if d < 1e-12 {
        return a;
    }
    along(
        g,
        &Ray {
            point: a,
            tangent: v,
        },
        s * d,
    )
}

impl ProductFlight {
    /// The flight of a file's keys in `space`.
    pub fn new(space: &ProductSpace, file: &FlightFile) -> Result<Self, String> {
        let g = space.base();
        let mut keys = Vec::with_capacity(file.keys.len());
        for (i, &(time, position, target)) in file.keys.iter().enumerate() {
            let p = point_at(space, position, &format!("key {}: position", i + 1))?;
            let t = point_at(space, target, &format!("key {}: look_at", i + 1))?;
            if g == Geometry::Spherical
                && super::surface_distance(g, p, t) >= 0.999 * std::f64::consts::PI
            {
                return Err(format!(
                    "key {}: look_at is opposite the position on the sphere: no one geodesic \
                     joins them",
                    i + 1
                ));
            }
            keys.push((time, p, t));
        }
        for w in keys.windows(2) {
            let (a, b) = (w[0].1, w[1].1);
            if g == Geometry::Spherical
                && super::surface_distance(g, a, b) >= 0.999 * std::f64::consts::PI
            {
                return Err(format!(
                    "the keys at {} s and {} s are opposite on the sphere: no one geodesic \
                     joins them",
                    w[0].0, w[1].0
                ));
            }
        }
        Ok(Self {
            geometry: g,
            keys,
            fov: file.fov,
        })
    }

    /// The camera at time `t` in the universal cover (before wrapping).
    #[must_use]
    pub fn cover_camera(&self, t: f64) -> ProductCamera {
        let g = self.geometry;
        let (p, target) = keyed(&self.keys, t, |a, b, s| between(g, a, b, s));
        ProductCamera::looking_at(g, p, target, self.fov)
    }

    /// The camera frame at time `t` in the cell (columns right, up, back and the eye): the
    /// cover's frame brought back through the faces it passed.
    #[must_use]
    pub fn frame(&self, space: &ProductSpace, t: f64) -> DMat4 {
        self.frame_in_cell(space, t).0
    }

    /// [`ProductFlight::frame`] as a camera.
    #[must_use]
    pub fn camera(&self, space: &ProductSpace, t: f64) -> ProductCamera {
        let f = self.frame(space, t);
        ProductCamera {
            point: f.w_axis,
            frame: [f.x_axis, f.y_axis, f.z_axis],
            fov_y_degrees: self.fov,
        }
    }
}

impl CoverFlight for ProductFlight {
    type Space = ProductSpace;

    fn duration(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.0)
    }

    fn cover_frame(&self, t: f64) -> DMat4 {
        let c = self.cover_camera(t);
        camera_frame(c.point, c.frame)
    }
}
