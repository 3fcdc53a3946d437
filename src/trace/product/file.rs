//! Scene files of the product spaces (H²×R, S²×R): the same TOML shape as the
//! constant-curvature scene files ([`crate::scene::file`]), with the product's own objects.
//! `render --scene FILE` and `walk --scene FILE` read either kind: the file's `space` says
//! which.
//!
//! Positions are `(x, y, z)` in units of [`ProductSpace::scale`] (the smaller of the base
//! polygon's inradius and half the circle), as in product flights: the surface point at
//! distance `|(x, y)|` from the cell's centre in the direction of `(x, y)` (side 0 is at
//! `+x`), at height `z`. Radii are in the same units. `docs/surfaces.md` lists every key.
//!
//! ```toml
//! space = "bitorus-circle"
//! edges = true            # the cell's vertical and horizontal edges (default true)
//! centre_ball = false     # the default scene's ball at the centre (default false)
//! fog = 3.0               # fog distance, in units of the scale
//! walls = 0.6             # walls with windows: how far open (0 solid, 1 none)
//!
//! [start]
//! position = [0.6, 0.2, 0.1]
//! look_at = [0.0, 0.0, 0.0]
//! fov = 70
//!
//! [[object]]
//! type = "ball"           # ball: position [x, y, z]; fibre: position [x, y] (a vertical
//! position = [0, 0, 0]    # tube); disc: position [x, y, z] (horizontal); geodesic: from
//! radius = 0.3            # [x, y], to [x, y] and height (a horizontal tube)
//! colour = [1.0, 0.8, 0.4]
//! velocity = [0.2, 0, 0]  # a ball may move: units of the scale a second, in its frame
//!
//! [[light]]               # one light at most (the default scene's where there is none)
//! position = [0.3, 0.2, 0.3]
//!
//! [lighting]              # as in the constant-curvature files (docs/light.md)
//! paths = "images"        # every image of the lamp in the cover, or "nearest"
//! reach = 2.0             # in units of the scale
//! tail = true
//! shadows = 8             # shadowed images
//! ```
//!
//! Every object must fit in the cell (its distance from each face at least its radius;
//! a fibre tube and a horizontal geodesic run through the cell and are cut by its faces),
//! because the tracer meets objects in the cell only: one reaching through a face would be
//! cut off there. An error names the file and the line.

use super::triangle::ProductTriangle;
use super::{
    ProductCamera, ProductObject, ProductParts, ProductScene, ProductShape, scene_with_parts,
};
use crate::geometry::Geometry;
use crate::scene::file::SceneFileError;
use crate::scene::file_support::{
    LightingSpec, PointLightSpec, PointStartSpec, colour, failing, fog_keys, lighting_of,
    load_family_scene, one_light, parse_toml, space_key, walls_of,
};
use crate::space::product::motion::camera_frame;
use crate::space::product::{ProductOrFlat, ProductSpace, product_space};
use glam::{DMat4, DVec2, DVec3, DVec4};
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// A loaded product scene file: the space, its scene and the start view.
#[derive(Clone, Debug)]
pub struct ProductSceneFile {
    /// The space's id, as written.
    pub space_id: String,
    /// The space.
    pub space: ProductSpace,
    /// The whole scene: the file's objects with the default parts it asks for.
    pub scene: ProductScene,
    /// The start view (`None`: the space's default camera).
    pub start: Option<ProductCamera>,
    /// The balls with a `velocity`, as they start (not in `scene`).
    pub moving: Vec<super::moving::ProductMover>,
}

impl ProductSceneFile {
    /// The start view as a player frame (columns right, up, back and the eye), if the file
    /// has one.
    #[must_use]
    pub fn start_frame(&self) -> Option<DMat4> {
        self.start.map(|c| camera_frame(c.point, c.frame))
    }

    /// The scene with its moving balls where they are at `time` seconds (with their images
    /// through the faces they reach past); the scene itself without any. An error says why
    /// a time cannot be flown.
    pub fn scene_at(&self, time: f64) -> Result<ProductScene, crate::space::motion::MotionError> {
        let mut scene = self.scene.clone();
        scene
            .objects
            .extend(super::moving::movers_at(&self.space, &self.moving, time)?);
        Ok(scene)
    }
}

/// The keys a product scene file knows (for "did you mean").
const KEYS: &[&str] = &[
    "space",
    "fog",
    "edges",
    "centre_ball",
    "walls",
    "wall_opacity",
    "ambient",
    "fog_colour",
    "start",
    "object",
    "light",
    "position",
    "look_at",
    "fov",
    "type",
    "radius",
    "colour",
    "from",
    "to",
    "height",
    "vertices",
    "triangles",
    "corners",
    "bottom",
    "top",
    "lighting",
    "paths",
    "reach",
    "tail",
    "shadows",
    "lamp_radius",
    "soft_samples",
    "velocity",
];

fn default_true() -> bool {
    true
}

fn white() -> [f64; 3] {
    [1.0; 3]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    space: Spanned<String>,
    fog: Option<Spanned<f64>>,
    #[serde(default = "default_true")]
    edges: bool,
    #[serde(default)]
    centre_ball: bool,
    walls: Option<Spanned<f64>>,
    wall_opacity: Option<Spanned<f64>>,
    ambient: Option<Spanned<f64>>,
    fog_colour: Option<Spanned<[f64; 3]>>,
    start: Option<Spanned<PointStartSpec>>,
    #[serde(default, rename = "object")]
    objects: Vec<Spanned<ObjectSpec>>,
    #[serde(default, rename = "light")]
    lights: Vec<Spanned<PointLightSpec>>,
    lighting: Option<Spanned<LightingSpec>>,
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
enum ObjectSpec {
    Ball {
        position: [f64; 3],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
        /// Units of the scale a second, in the ball's frame (the centre's axes carried to
        /// it, `z` the fibre): the ball flies through the faces.
        velocity: Option<[f64; 3]>,
    },
    Fibre {
        position: [f64; 2],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
    Disc {
        position: [f64; 3],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
    Geodesic {
        from: [f64; 2],
        to: [f64; 2],
        height: f64,
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
    Mesh {
        vertices: Vec<[f64; 3]>,
        triangles: Vec<[usize; 3]>,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
    Prism {
        corners: Vec<[f64; 2]>,
        bottom: f64,
        top: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
}

/// The most triangles a product scene file may hold (each is one object of the tracer).
pub const MAX_PRODUCT_TRIANGLES: usize = 512;

/// Reads a scene file if its space is a product space; `Ok(None)` for any other file (a
/// constant-curvature scene file, or one whose `space` cannot be read: the
/// constant-curvature loader says what is wrong with it).
pub fn load_product_scene_file(path: &Path) -> Result<Option<ProductSceneFile>, SceneFileError> {
    load_family_scene(path, names_product_space, parse_product_scene)
}

/// Whether a scene file's text names a product space in its `space` key (or a product id
/// that is wrong: its loader says what is wrong with it); `false` where the key cannot be
/// read.
#[must_use]
pub fn names_product_space(text: &str) -> bool {
    space_key(text).is_some_and(|id| {
        matches!(
            product_space(&id),
            Some(Ok(ProductOrFlat::Product(_)) | Err(_))
        )
    })
}

/// Parses a product scene file's text; errors name `file` and the line.
pub fn parse_product_scene(text: &str, file: &str) -> Result<ProductSceneFile, SceneFileError> {
    let fail = failing(text, file);
    let spec: FileSpec = parse_toml(text, file, KEYS)?;
    let space_id = spec.space.get_ref().clone();
    let space = match product_space(&space_id) {
        Some(Ok(ProductOrFlat::Product(p))) => *p,
        Some(Ok(ProductOrFlat::Flat(_))) => {
            return Err(fail(
                Some(spec.space.span()),
                format!(
                    "{space_id} is flat (E²×R is E³): write its scene as a constant-curvature \
                     scene file"
                ),
            ));
        }
        Some(Err(e)) => return Err(fail(Some(spec.space.span()), e)),
        None => {
            return Err(fail(
                Some(spec.space.span()),
                format!(
                    "{space_id} is not a product space (H²×R or S²×R); `curved-spaces list` \
                     names them"
                ),
            ));
        }
    };
    let scale = space.scale();
    let mut scene = scene_with_parts(
        &space,
        ProductParts {
            edges: spec.edges,
            centre_ball: spec.centre_ball,
        },
    );
    let fog = fog_keys(
        spec.fog.as_ref(),
        spec.ambient.as_ref(),
        spec.fog_colour.as_ref(),
        " (in units of the space's scale)",
    )
    .map_err(|(s, m)| fail(Some(s), m))?;
    if let Some(f) = fog.fog {
        scene.fog_distance = f * scale;
    }
    scene.ambient = fog.ambient.unwrap_or(scene.ambient);
    scene.fog_colour = fog.fog_colour.unwrap_or(scene.fog_colour);
    scene.walls = walls_of(spec.walls.as_ref(), spec.wall_opacity.as_ref())
        .map_err(|(s, m)| fail(Some(s), m))?
        .filter(|w| w.opening < 1.0);
    if let Some((position, span)) =
        one_light(&spec.lights, "a product scene").map_err(|(s, m)| fail(Some(s), m))?
    {
        scene.light =
            inside(&space, position, 0.0, "the light").map_err(|m| fail(Some(span), m))?;
    }
    let mut triangles = 0;
    let mut moving = Vec::new();
    for object in &spec.objects {
        let at = |m: String| fail(Some(object.span()), m);
        if let ObjectSpec::Ball {
            position,
            radius,
            colour: c,
            velocity: Some(v),
        } = object.get_ref()
        {
            moving.push(mover(&space, *position, *radius, *c, *v).map_err(at)?);
            continue;
        }
        let made = build_object(&space, object.get_ref()).map_err(at)?;
        triangles += made
            .iter()
            .filter(|o| matches!(o.shape, ProductShape::Triangle(_)))
            .count();
        if triangles > MAX_PRODUCT_TRIANGLES {
            return Err(at(format!(
                "the file's meshes have more than {MAX_PRODUCT_TRIANGLES} triangles \
                 ({triangles} so far): each is one object of the tracer"
            )));
        }
        scene.objects.extend(made);
    }
    // The lamp's images, for the file's light and lighting.
    let lighting = match &spec.lighting {
        Some(l) => lighting_of(l).map_err(|(s, m)| fail(Some(s), m))?,
        None => scene.lighting,
    };
    let light = scene.light;
    scene
        .set_lighting(&space, light, lighting)
        .map_err(|m| fail(spec.lighting.as_ref().map(Spanned::span), m))?;
    let start = match &spec.start {
        Some(s) => Some(start_camera(&space, s.get_ref()).map_err(|m| fail(Some(s.span()), m))?),
        None => None,
    };
    Ok(ProductSceneFile {
        space_id,
        space,
        scene,
        start,
        moving,
    })
}

/// A ball with a velocity: its centre in the cell at the start (it may reach through faces:
/// it is drawn with its images there), its frame the centre's axes carried to it.
fn mover(
    space: &ProductSpace,
    position: [f64; 3],
    radius: f64,
    c: [f64; 3],
    velocity: [f64; 3],
) -> Result<super::moving::ProductMover, String> {
    use crate::space::family::CentreFrame;
    let scale = space.scale();
    let r = radius_of(space, radius, true)?;
    let v = DVec3::from_array(velocity);
    if !v.is_finite() {
        return Err(format!(
            "velocity must be finite (units of the scale a second), got {velocity:?}"
        ));
    }
    // In the cell (its point, as the frame's: both the geodesic from the centre).
    inside(space, position, 0.0, "the moving ball's centre")?;
    let frame = space.frame_from_centre(DVec3::from_array(position) * scale);
    Ok(super::moving::ProductMover {
        object: ProductObject {
            shape: ProductShape::Point(frame.w_axis),
            radius: r,
            colour: colour(c)?,
        },
        frame,
        velocity: crate::space::motion::Velocity {
            linear: v * scale,
            angular: DVec3::ZERO,
        },
    })
}

fn positive_finite(x: f64, what: &str) -> Result<f64, String> {
    if x > 0.0 && x.is_finite() {
        Ok(x)
    } else {
        Err(format!(
            "{what} must be a positive number (in units of the space's scale), got {x}"
        ))
    }
}

/// The surface point at `xy` (units of the scale) at height `z` (units of the scale),
/// refused where it cannot be held ([`super::flight::point_at`]).
fn surface_point(space: &ProductSpace, xy: DVec2, z: f64, what: &str) -> Result<DVec4, String> {
    if !xy.is_finite() || !z.is_finite() {
        return Err(format!("{what}: positions must be finite numbers"));
    }
    super::flight::point_at(space, xy.extend(z), what)
}

/// How far the surface point `p` (of the base) is inside the polygon: its least distance
/// to a side line (negative outside); infinite for the whole sphere.
fn base_room(space: &ProductSpace, p: DVec4) -> f64 {
    let g = space.base();
    space
        .side_faces()
        .iter()
        .map(|f| {
            let n = space.side_covector(f).round_f64();
            let x = n.x * p.x + n.y * p.y + n.w * p.w;
            match g {
                Geometry::Spherical => -x.clamp(-1.0, 1.0).asin(),
                _ => -x.asinh(),
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// The point at `position` (units of the scale), checked to lie `radius` or more inside
/// every face.
fn inside(
    space: &ProductSpace,
    position: [f64; 3],
    radius: f64,
    what: &str,
) -> Result<DVec4, String> {
    let scale = space.scale();
    let p = surface_point(
        space,
        DVec2::new(position[0], position[1]),
        position[2],
        what,
    )?;
    let room_base = base_room(space, p);
    let room_top = 0.5 * space.length() - p.z.abs();
    let room = room_base.min(room_top);
    if !(room >= radius) {
        let too = if radius > 0.0 {
            format!(" by {:.3}", (radius - room) / scale)
        } else {
            String::new()
        };
        return Err(format!(
            "{what} at {position:?} does not fit in the cell{too} (units of the scale {scale:.4}): \
             the cell reaches {:.3} from the centre to a side and {:.3} up and down",
            space.base_inradius() / scale,
            0.5 * space.length() / scale
        ));
    }
    Ok(p)
}

/// A radius in units of the scale, checked against the cell: at most the polygon's
/// inradius, and with `vertical` (a ball, a horizontal tube) half the circle too.
fn radius_of(space: &ProductSpace, r: f64, vertical: bool) -> Result<f64, String> {
    let r = positive_finite(r, "radius")? * space.scale();
    let mut most = space.base_inradius();
    if vertical {
        most = most.min(0.5 * space.length());
    }
    if space.base() == Geometry::Spherical {
        // The tracer's search needs the distance convex along each step (π/4 of arc).
        most = most.min(0.25 * std::f64::consts::PI);
    }
    if r > most {
        return Err(format!(
            "radius {:.3} is larger than the cell (at most {:.3} in units of the scale)",
            r / space.scale(),
            most / space.scale()
        ));
    }
    Ok(r)
}

/// A mesh's triangles: every vertex in the cell, every index a vertex.
fn mesh(
    space: &ProductSpace,
    vertices: &[[f64; 3]],
    triangles: &[[usize; 3]],
    colour: [f64; 3],
) -> Result<Vec<ProductObject>, String> {
    if triangles.is_empty() {
        return Err("the mesh has no triangles".into());
    }
    let mut points = Vec::with_capacity(vertices.len());
    for (i, v) in vertices.iter().enumerate() {
        points.push(inside(space, *v, 0.0, &format!("vertex {i}"))?);
    }
    for (k, t) in triangles.iter().enumerate() {
        if let Some(i) = t.iter().find(|&&i| i >= points.len()) {
            return Err(format!(
                "triangle {k} names vertex {i}, but the mesh has {} (counted from 0)",
                points.len()
            ));
        }
    }
    exact_triangles(space, &points, triangles, colour)
}

/// A prism's triangles: two per side wall, a fan on the bottom and the top; its corners
/// must make a convex polygon, in order.
fn prism(
    space: &ProductSpace,
    corners: &[[f64; 2]],
    bottom: f64,
    top: f64,
    colour: [f64; 3],
) -> Result<Vec<ProductObject>, String> {
    let n = corners.len();
    if n < 3 {
        return Err(format!("a prism needs 3 corners or more, got {n}"));
    }
    if !(bottom < top) {
        return Err(format!(
            "the prism's bottom {bottom} must be below its top {top}"
        ));
    }
    let mut points = Vec::with_capacity(2 * n);
    for z in [bottom, top] {
        for (i, xy) in corners.iter().enumerate() {
            points.push(inside(
                space,
                [xy[0], xy[1], z],
                0.0,
                &format!("corner {i}"),
            )?);
        }
    }
    // Convex, in order: every corner on one side of every edge's geodesic.
    let b = |i: usize| DVec3::new(points[i].x, points[i].y, points[i].w);
    let mut sign = 0.0;
    for i in 0..n {
        let edge = b(i).cross(b((i + 1) % n));
        for k in (0..n).filter(|&k| k != i && k != (i + 1) % n) {
            let side = edge.dot(b(k));
            if !(side.abs() >= 1e-12) || (sign != 0.0 && side.signum() != sign) {
                return Err(
                    "the prism's corners must make a convex polygon, in order round it".into(),
                );
            }
            sign = side.signum();
        }
    }
    let mut faces = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push([i, j, n + j]);
        faces.push([i, n + j, n + i]);
    }
    for i in 1..n - 1 {
        faces.push([0, i, i + 1]);
        faces.push([n, n + i, n + i + 1]);
    }
    exact_triangles(space, &points, &faces, colour)
}

/// Triangles of `points`, each checked exact ([`ProductTriangle::new`]).
fn exact_triangles(
    space: &ProductSpace,
    points: &[DVec4],
    faces: &[[usize; 3]],
    c: [f64; 3],
) -> Result<Vec<ProductObject>, String> {
    let colour = colour(c)?.min(DVec3::ONE);
    faces
        .iter()
        .enumerate()
        .map(|(k, t)| {
            let triangle = ProductTriangle::new(space.base(), t.map(|i| points[i]))
                .map_err(|e| format!("triangle {k}: {e}"))?;
            Ok(ProductObject {
                shape: ProductShape::Triangle(triangle),
                radius: 0.0,
                colour,
            })
        })
        .collect()
}

/// An object's pieces: one, or a mesh's or prism's triangles.
fn build_object(space: &ProductSpace, spec: &ObjectSpec) -> Result<Vec<ProductObject>, String> {
    let g = space.base();
    let scale = space.scale();
    let h = 0.5 * space.length();
    let (shape, radius, c) = match spec {
        ObjectSpec::Ball {
            position,
            radius,
            colour,
            ..
        } => {
            let r = radius_of(space, *radius, true)?;
            (
                ProductShape::Point(inside(space, *position, r, "the ball")?),
                r,
                colour,
            )
        }
        ObjectSpec::Fibre {
            position,
            radius,
            colour,
        } => {
            let r = radius_of(space, *radius, false)?;
            let p = surface_point(space, DVec2::from_array(*position), 0.0, "the fibre")?;
            let room = base_room(space, p);
            if !(room >= r) {
                return Err(format!(
                    "the fibre tube at {position:?} does not fit in the polygon by {:.3} (units \
                     of the scale {scale:.4})",
                    (r - room) / scale
                ));
            }
            (ProductShape::Fibre(p), r, colour)
        }
        ObjectSpec::Disc {
            position,
            radius,
            colour,
        } => {
            let r = radius_of(space, *radius, false)?;
            let p = inside(space, *position, 0.0, "the disc")?;
            let room = base_room(space, p);
            if !(room >= r) || p.z.abs() >= h {
                return Err(format!(
                    "the disc at {position:?} does not fit in the cell by {:.3} (units of the \
                     scale {scale:.4})",
                    (r - room) / scale
                ));
            }
            (ProductShape::Disc(p), r, colour)
        }
        ObjectSpec::Mesh {
            vertices,
            triangles,
            colour,
        } => return mesh(space, vertices, triangles, *colour),
        ObjectSpec::Prism {
            corners,
            bottom,
            top,
            colour,
        } => return prism(space, corners, *bottom, *top, *colour),
        ObjectSpec::Geodesic {
            from,
            to,
            height,
            radius,
            colour,
        } => {
            let r = radius_of(space, *radius, true)?;
            let z = height * scale;
            if !(z.abs() <= h) {
                return Err(format!(
                    "height {height} is outside the cell (it reaches {:.3} up and down in units \
                     of the scale)",
                    h / scale
                ));
            }
            let p = surface_point(space, DVec2::from_array(*from), *height, "from")?;
            let q = surface_point(space, DVec2::from_array(*to), *height, "to")?;
            // The plane through the origin spanned by p and q cuts the surface in the
            // geodesic: its normal is their cross product, made a unit covector.
            let n = DVec3::new(p.x, p.y, p.w).cross(DVec3::new(q.x, q.y, q.w));
            let norm = n.x * n.x + n.y * n.y + g.kappa() * n.z * n.z;
            if !(norm > 1e-18) {
                return Err(format!(
                    "the geodesic's from {from:?} and to {to:?} name no one line (the same \
                     point, or opposite on the sphere)"
                ));
            }
            let n = n / norm.sqrt();
            (
                ProductShape::Geodesic {
                    covector: DVec4::new(n.x, n.y, 0.0, n.z),
                    height: z,
                },
                r,
                colour,
            )
        }
    };
    Ok(vec![ProductObject {
        shape,
        radius,
        colour: colour(*c)?.min(DVec3::ONE),
    }])
}

fn start_camera(space: &ProductSpace, start: &PointStartSpec) -> Result<ProductCamera, String> {
    let eye = inside(space, start.position, 0.0, "the start position")?;
    let target = match start.look_at {
        Some(t) => surface_point(space, DVec2::new(t[0], t[1]), t[2], "look_at")?,
        None => DVec4::W,
    };
    let fov = match start.fov {
        Some(f) if f > 0.0 && f < 180.0 => f,
        Some(f) => {
            return Err(format!(
                "fov must be an angle between 0 and 180 degrees, got {f}"
            ));
        }
        None => super::default_camera(space).fov_y_degrees,
    };
    camera_between(space, eye, target, fov)
}

/// A camera at the model point `eye` looking towards `target` with a vertical field of view
/// of `fov` degrees; refused where the two are one point or, on the sphere, opposite (no one
/// geodesic joins them). A scene file's `[start]`, and `render --eye --look-at`.
pub fn camera_between(
    space: &ProductSpace,
    eye: DVec4,
    target: DVec4,
    fov: f64,
) -> Result<ProductCamera, String> {
    let g = space.base();
    if super::surface_distance(g, eye, target) < 1e-9 && (eye.z - target.z).abs() < 1e-9 {
        return Err("look_at is the start position: nothing to look towards".into());
    }
    if g == Geometry::Spherical
        && super::surface_distance(g, eye, target) >= 0.999 * std::f64::consts::PI
    {
        return Err(
            "look_at is opposite the start position on the sphere: no one geodesic joins them"
                .into(),
        );
    }
    Ok(ProductCamera::looking_at(g, eye, target, fov))
}
