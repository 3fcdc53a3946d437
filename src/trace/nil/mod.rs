//! The CPU reference tracer of the Nil spaces: a camera ray per pixel walks the box of
//! `nil-K` ([`NilWalker`], exits solved to the last bit), and in each segment the objects
//! are met exactly ([`objects`]: metric balls, fibre tubes, swept discs), each found by
//! steps that are safe by a Lipschitz bound and refined by bisection; the light comes
//! along the shortest geodesic to every image of the lamp within reach ([`light`]).
//!
//! Objects are kept in the box's chart with every lattice image of theirs that reaches
//! into the box, so a segment (which stays in the box) meets exactly the scene of the
//! universal cover.

#[cfg(feature = "scene-files")]
pub mod file;
#[cfg(feature = "scene-files")]
pub mod flight;
pub mod light;
pub mod moving;
pub mod objects;
pub mod walls;

pub use light::{NilLamp, area_density, gather};
pub use objects::{NilObject, NilShape};

use crate::geometry::Ray;
use crate::scene::lighting::Lighting;
use crate::space::nil::{NilRay, NilSpace, NilWalker, flow, group_product};
use glam::{DMat4, DVec3, DVec4};
use image::RgbImage;

/// The largest radius of a Nil scene's object (a scene file's, a game entity's): half the
/// box's side, so that the images of an object in the box that reach into it are its
/// neighbours'.
pub const MAX_NIL_RADIUS: f64 = 0.5;

/// The most objects (with their lattice images) a Nil scene file, or a game's entities, may
/// make: each is tested by every ray segment.
pub const MAX_NIL_OBJECTS: usize = 400;

/// A scene of a Nil space: objects (with their images that reach into the box), one point
/// light, ambient light and fog.
#[derive(Clone, Debug, PartialEq)]
pub struct NilScene {
    /// The objects.
    pub objects: Vec<NilObject>,
    /// The light's chart point, in the box.
    pub light: [f64; 3],
    /// How the light is gathered; set with [`NilScene::set_lighting`].
    pub lighting: Lighting,
    /// The lamp's images within the reach.
    pub lamp: NilLamp,
    /// The lamp's power: the light a surface facing it gets from one image at distance 1
    /// in a flat space (`A = 1`).
    pub power: f64,
    /// The distance within which the falloff stops growing (a lamp of that size).
    pub near_light: f64,
    /// Ambient share of the light.
    pub ambient: f64,
    /// Fog distance scale λ: a surface at distance `d` keeps `e^(−d/λ)` of its colour.
    pub fog_distance: f64,
    /// The fog's colour.
    pub fog_colour: DVec3,
    /// The box's walls with windows ([`walls`]), if drawn.
    pub walls: Option<crate::scene::walls::WallStyle>,
    /// The teaching view: surfaces tinted by the crossings or the last face crossed
    /// ([`crate::scene::ColourBy`]; the holonomy view is white: every copy is a left
    /// translation, which turns nothing).
    pub colour_by: crate::scene::ColourBy,
}

impl NilScene {
    /// Lights the scene as `lighting` says, the lamp at `light` (a chart point, brought
    /// into the box): finds the lamp's images again. The message names a setting out of
    /// range or a lamp that is no point.
    pub fn set_lighting(
        &mut self,
        space: &NilSpace,
        light: [f64; 3],
        lighting: Lighting,
    ) -> Result<(), String> {
        lighting.check()?;
        if lighting.lamp_radius_inradii > 0.0 {
            use crate::space::{Family, Feature};
            Family::Nil
                .supports(Feature::SoftShadows)
                .map_err(|e| format!("{e}; got a radius of {}", lighting.lamp_radius_inradii))?;
        }
        if !light.iter().all(|x| x.is_finite()) {
            return Err(format!("the lamp's position {light:?} is not a point"));
        }
        self.light = space.into_box(light);
        self.lighting = lighting;
        self.lamp = NilLamp::new(space, self.light, &lighting);
        Ok(())
    }

    /// The distance past which a surface keeps under half a colour step of its own colour
    /// through the fog (`λ ln 510`): rays stop there.
    #[must_use]
    pub fn cutoff_distance(&self) -> f64 {
        self.fog_distance * 510f64.ln()
    }

    /// Adds `object` and every image `γ·object` (`γ ∈ Γ_K`) that may reach into the box:
    /// those whose chart bounding box meets the box's ([`push_with_images`]).
    pub fn add_with_images(&mut self, space: &NilSpace, object: NilObject) {
        push_with_images(space, object, &mut self.objects);
    }
}

/// Pushes onto `out` the images `γ·object` (`γ ∈ Γ_K`, the identity included) that may
/// reach into the box of `space`: those whose chart bounding box meets the box's.
pub fn push_with_images(space: &NilSpace, object: NilObject, out: &mut Vec<NilObject>) {
    let h = space.half_height();
    let k = f64::from(space.k());
    for p in -1i32..=1 {
        for q in -1i32..=1 {
            let (p, q) = (f64::from(p), f64::from(q));
            // The heights of the moved bounds, to pick the powers of C.
            let (lo, hi) = bounds(object, space.element(p, q, 0));
            // A fibre is its own image by the centre.
            let (m_lo, m_hi) = if matches!(object.shape, NilShape::Fibre(_)) {
                (0, 0)
            } else {
                (
                    ((-h - hi[2]) * k).floor() as i64,
                    ((h - lo[2]) * k).ceil() as i64,
                )
            };
            for m in m_lo..=m_hi {
                let g = space.element(p, q, m);
                let (lo, hi) = bounds(object, g);
                let inside = lo[0] <= 0.5
                    && hi[0] >= -0.5
                    && lo[1] <= 0.5
                    && hi[1] >= -0.5
                    && lo[2] <= h
                    && hi[2] >= -h;
                if inside {
                    out.push(moved(object, g));
                }
            }
        }
    }
}

/// `object` moved by the lattice element `g`.
fn moved(object: NilObject, g: [f64; 3]) -> NilObject {
    let shape = match object.shape {
        NilShape::Ball(c) => NilShape::Ball(group_product(g, c)),
        NilShape::Fibre(b) => NilShape::Fibre([b[0] + g[0], b[1] + g[1]]),
        NilShape::Edge {
            image,
            along,
            offset,
            height,
        } => NilShape::Edge {
            image: group_product(g, image),
            along,
            offset,
            height,
        },
    };
    NilObject { shape, ..object }
}

/// The chart box `(lowest, highest corner)` holding the box `(lo, hi)` moved by the left
/// translation by `g` (affine, so its extremes are at the corners).
fn moved_box(g: [f64; 3], (lo, hi): ([f64; 3], [f64; 3])) -> ([f64; 3], [f64; 3]) {
    let mut out = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for corner in 0..8 {
        let p = [0, 1, 2].map(|i| if corner >> i & 1 == 0 { lo[i] } else { hi[i] });
        for (i, x) in group_product(g, p).into_iter().enumerate() {
            out.0[i] = out.0[i].min(x);
            out.1[i] = out.1[i].max(x);
        }
    }
    out
}

/// A chart box holding `g·object`.
///
/// A metric ball of radius `r` about the origin lies in `|x|, |y| ≤ r`, `|z| ≤ r + r²/4`
/// (the chart's vertical speed is at most `1 + t/2` at time `t`), moved to its centre by a
/// left translation. A swept disc's points `e(s)·(0, a, b) = (s, y₀ + a, h + b + ½sa)` (and
/// likewise along `y`) lie in a box about the segment.
fn bounds(object: NilObject, g: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let r = object.radius;
    match object.shape {
        NilShape::Ball(c) => {
            let z = r + r * r / 4.0;
            let own = moved_box(c, ([-r, -r, -z], [r, r, z]));
            moved_box(g, own)
        }
        // A fibre is every height.
        NilShape::Fibre(b) => (
            [b[0] + g[0] - r, b[1] + g[1] - r, f64::NEG_INFINITY],
            [b[0] + g[0] + r, b[1] + g[1] + r, f64::INFINITY],
        ),
        NilShape::Edge {
            image,
            along,
            offset,
            height,
        } => {
            let z = 1.25 * r;
            let mut lo = [0.0; 3];
            let mut hi = [0.0; 3];
            lo[along] = -0.5;
            hi[along] = 0.5;
            lo[1 - along] = offset - r;
            hi[1 - along] = offset + r;
            lo[2] = height - z;
            hi[2] = height + z;
            moved_box(g, moved_box(image, (lo, hi)))
        }
    }
}

/// A camera: its frame (the columns right, up and back as body vectors in the frame
/// `E₁, E₂, E₃`, the fourth its chart point with `w = 1`) and vertical field of view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NilCamera {
    /// Right, up, back and the eye.
    pub frame: DMat4,
    /// Vertical field of view in degrees.
    pub fov_y_degrees: f64,
}

impl NilCamera {
    /// The camera at the chart point `eye` (brought into the box by the lattice) looking
    /// along the shortest geodesic to `target`, `E₃` up as far as the view allows, with a
    /// vertical field of view of `fov` degrees. Refused where a point is no chart point
    /// within 10⁶, the two are one point, or `fov` is no angle between 0 and 180 degrees.
    pub fn looking_at(
        space: &NilSpace,
        eye: DVec3,
        target: DVec3,
        fov: f64,
    ) -> Result<Self, String> {
        chart_point(eye.to_array(), "the camera's position")?;
        chart_point(target.to_array(), "the point looked at")?;
        if !(fov > 0.0 && fov < 180.0) {
            return Err(format!(
                "fov must be an angle between 0 and 180 degrees, got {fov}"
            ));
        }
        let mut frame = look_frame(eye, target)
            .ok_or("the camera looks at its own position: nothing to look towards")?;
        frame.w_axis = DVec3::from_array(space.into_box(eye.to_array())).extend(1.0);
        Ok(NilCamera {
            frame,
            fov_y_degrees: fov,
        })
    }
}

/// The farthest a chart point given by a user (a scene file, a flight, the command line)
/// may lie from the origin in each coordinate: the lattice brings it into the box in f64.
pub const MAX_CHART_COORDINATE: f64 = 1e6;

/// `p` where it is a chart point within [`MAX_CHART_COORDINATE`], else an error naming it
/// as `what`.
pub fn chart_point(p: [f64; 3], what: &str) -> Result<[f64; 3], String> {
    if p.iter()
        .all(|x| x.is_finite() && x.abs() <= MAX_CHART_COORDINATE)
    {
        Ok(p)
    } else {
        Err(format!(
            "{what} {p:?} is not a chart point of Nil within 10⁶"
        ))
    }
}

/// The frame at the chart point `eye` (not moved into the box) looking along the shortest
/// geodesic to `target`, `E₃` up as far as the view allows; `None` where the two are one
/// point.
#[must_use]
pub fn look_frame(eye: DVec3, target: DVec3) -> Option<DMat4> {
    let (length, forward) = crate::space::nil::shortest(eye.to_array(), target.to_array());
    if !(length > 1e-9) {
        return None;
    }
    let forward = DVec3::from_array(forward);
    let right = forward.cross(DVec3::Z);
    let right = if right.length() > 1e-9 {
        right.normalize()
    } else {
        DVec3::X
    };
    let up = right.cross(forward);
    Some(DMat4::from_cols(
        right.extend(0.0),
        up.extend(0.0),
        (-forward).extend(0.0),
        eye.extend(1.0),
    ))
}

/// How big the default scene's objects are in the box of half height `h`.
fn scaled(size: f64, h: f64) -> f64 {
    size.min(0.6 * h)
}

/// The default lamp's size: the falloff is held at its value there.
pub const NEAR_LIGHT: f64 = 0.05;

/// Below this half height (`nil-K` for K > 10) the default scene leaves out the swept discs
/// along the box's horizontal edges.
pub const THIN_BOX: f64 = 0.05;

/// Which parts of the default scene a scene is built on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NilParts {
    /// The box's edges: fibre tubes up its vertical edges, swept discs along its
    /// horizontal ones where the box is not thin ([`THIN_BOX`]).
    pub edges: bool,
    /// The centrepiece: a ball at the origin.
    pub centre_ball: bool,
}

/// The default scene of `space`: the box's edges (fibre tubes up its vertical edges, swept
/// discs along its horizontal ones where the box is not thin, [`THIN_BOX`]), a centrepiece
/// ball at the origin and two smaller balls off the axes, whose copies climb or sink across
/// the cells by the twist; a lamp in the box, lit along every image within two inradii.
#[must_use]
pub fn default_scene(space: &NilSpace) -> NilScene {
    let h = space.half_height();
    let mut scene = scene_with_parts(
        space,
        NilParts {
            edges: true,
            centre_ball: true,
        },
    );
    let balls = [
        (
            [0.3, 0.0, 0.0],
            scaled(0.07, h),
            DVec3::new(0.85, 0.2, 0.15),
        ),
        ([0.0, 0.3, 0.0], scaled(0.07, h), DVec3::new(0.2, 0.45, 0.9)),
    ];
    for (centre, radius, colour) in balls {
        scene.add_with_images(
            space,
            NilObject {
                shape: NilShape::Ball(centre),
                radius,
                colour,
            },
        );
    }
    scene
}

/// The default scene's lamp, fog and lighting with the parts `parts` asks for (a scene
/// file's start).
#[must_use]
pub fn scene_with_parts(space: &NilSpace, parts: NilParts) -> NilScene {
    let h = space.half_height();
    let mut scene = NilScene {
        objects: Vec::new(),
        light: [0.0; 3],
        lighting: Lighting::default(),
        lamp: NilLamp::default(),
        power: 1.0,
        near_light: NEAR_LIGHT,
        ambient: 0.3,
        fog_distance: 1.5,
        fog_colour: DVec3::new(0.05, 0.06, 0.09),
        walls: None,
        colour_by: crate::scene::ColourBy::Shading,
    };
    let edge_colour = DVec3::new(0.85, 0.7, 0.35);
    let vertical = scaled(0.03, h);
    // In a box thinner than a tenth its images crowd into a sieve of tubes finer than the
    // fibres (and hundreds of objects to test): only the fibres mark its edges there.
    let sides: &[(usize, f64)] = if parts.edges && h >= THIN_BOX {
        &[(0, 0.5), (0, -0.5), (1, 0.5), (1, -0.5)]
    } else {
        &[]
    };
    if parts.edges {
        for (x, y) in [(0.5, 0.5), (-0.5, 0.5), (0.5, -0.5), (-0.5, -0.5)] {
            scene.objects.push(NilObject {
                shape: NilShape::Fibre([x, y]),
                radius: vertical,
                colour: edge_colour,
            });
        }
    }
    let horizontal = scaled(0.025, 0.7 * h);
    for &(along, offset) in sides {
        let edge = NilObject {
            shape: NilShape::Edge {
                image: [0.0; 3],
                along,
                offset,
                height: h,
            },
            radius: horizontal,
            colour: edge_colour,
        };
        scene.add_with_images(space, edge);
    }
    if parts.centre_ball {
        scene.add_with_images(
            space,
            NilObject {
                shape: NilShape::Ball([0.0; 3]),
                radius: scaled(0.17, h),
                colour: DVec3::new(0.9, 0.9, 0.92),
            },
        );
    }
    let lighting = Lighting::default();
    scene
        .set_lighting(space, [-0.25, -0.3, 0.5 * h], lighting)
        .expect("the default lighting is in range");
    scene.power = default_power(space, scene.fog_distance);
    scene
}

/// The default lamp's power: full (1) at 0.35 from it, but no more than makes the mean
/// light of all its images (`πλ/vol`, what a small space fills with) ½: in a thin box the
/// lamp's images crowd together and light it evenly.
#[must_use]
pub fn default_power(space: &NilSpace, fog_distance: f64) -> f64 {
    let mean = std::f64::consts::PI * fog_distance / space.volume();
    (0.35f64 * 0.35).min(0.5 / mean)
}

/// The default view: from near the box's `−y` side, a little to the side, looking along
/// `E₂` at the centrepiece, `E₃` up.
#[must_use]
pub fn default_camera(space: &NilSpace) -> NilCamera {
    let h = space.half_height();
    NilCamera {
        frame: DMat4::from_cols(
            DVec4::X,
            DVec4::Z,
            DVec4::new(0.0, -1.0, 0.0, 0.0),
            DVec4::new(0.12, -0.45, 0.2 * h, 1.0),
        ),
        fov_y_degrees: 70.0,
    }
}

/// Where a walked ray ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NilRayEnd<'a> {
    /// It met an object.
    Hit {
        /// The geodesic length from the eye.
        distance: f64,
        /// Faces crossed before.
        crossings: usize,
        /// The face crossed last, if any.
        last_face: Option<usize>,
        /// The ray at the object (chart point, body velocity).
        at: NilRay<f64>,
        /// The object.
        object: &'a NilObject,
    },
    /// Nothing before the fog's cut-off.
    Fog,
    /// It ran out of crossings.
    Budget(usize),
}

/// A walk's ray as the flow's.
fn nil_ray(ray: &Ray<DVec4>) -> NilRay<f64> {
    NilRay {
        point: ray.point.truncate().to_array(),
        velocity: ray.tangent.truncate().to_array(),
    }
}

/// A chart box holding the geodesic segment of `ray` of length `t_max`: its shadow in the
/// plane runs at speed `a` (the horizontal part of the velocity) round a circle of radius
/// `a/|c|`, and its height changes at `c + ½(x ẏ − y ẋ)`, within `|c| ± ½ a max|(x, y)|`.
fn segment_box(ray: &NilRay<f64>, t_max: f64) -> ([f64; 3], [f64; 3]) {
    let [x, y, z] = ray.point;
    let [u, v, c] = ray.velocity;
    let a = u.hypot(v);
    let mut reach = [a * t_max; 2];
    let mut centre = [x, y];
    if c.abs() * t_max > 1e-9 {
        // The circle: centred a/c to the left of the horizontal velocity.
        let radius = a / c.abs();
        let circle = [x - v / c, y + u / c];
        for i in 0..2 {
            let (lo, hi) = (
                (centre[i] - reach[i]).max(circle[i] - radius),
                (centre[i] + reach[i]).min(circle[i] + radius),
            );
            centre[i] = 0.5 * (lo + hi);
            reach[i] = 0.5 * (hi - lo);
        }
    }
    let far = (centre[0].abs() + reach[0]).hypot(centre[1].abs() + reach[1]);
    let slack = 0.5 * a * far;
    let lo_z = z + (t_max * (c - slack)).min(0.0);
    let hi_z = z + (t_max * (c + slack)).max(0.0);
    (
        [centre[0] - reach[0], centre[1] - reach[1], lo_z],
        [centre[0] + reach[0], centre[1] + reach[1], hi_z],
    )
}

/// A chart box: its lowest and highest corner.
pub type ChartBox = ([f64; 3], [f64; 3]);

impl NilObject {
    /// A chart box holding the object (a fibre tube's is unbounded in height).
    #[must_use]
    pub fn chart_box(&self) -> ChartBox {
        bounds(*self, [0.0; 3])
    }
}

/// The chart boxes of a scene's objects, in order.
fn object_boxes(scene: &NilScene) -> Vec<ChartBox> {
    scene.objects.iter().map(NilObject::chart_box).collect()
}

/// Whether two chart boxes meet.
fn boxes_meet(a: &ChartBox, b: &ChartBox) -> bool {
    (0..3).all(|i| a.0[i] <= b.1[i] && b.0[i] <= a.1[i])
}

/// What a walk looks for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Seek {
    /// The nearest object, where it is met to the last bit.
    Nearest,
    /// Whether any object is met (a shadow ray): the first found, where only roughly.
    Any,
}

/// The nearest object `ray` meets within `t_max` (with [`Seek::Any`], the first found).
fn nearest_in_segment<'a>(
    scene: &'a NilScene,
    boxes: &[ChartBox],
    ray: &NilRay<f64>,
    t_max: f64,
    seek: Seek,
) -> Option<(f64, &'a NilObject)> {
    let mut nearest: Option<(f64, &NilObject)> = None;
    let segment = segment_box(ray, t_max);
    for (object, chart_box) in scene.objects.iter().zip(boxes) {
        let before = nearest.map_or(t_max, |(t, _)| t);
        if !boxes_meet(&segment, chart_box) || object.clearance(ray.point) > before {
            continue;
        }
        if seek == Seek::Any {
            if object.meets(ray, before) {
                return Some((before, object));
            }
            continue;
        }
        if let Some(t) = object.first_meeting(ray, before)
            && nearest.is_none_or(|(best, _)| t < best)
        {
            nearest = Some((t, object));
        }
    }
    nearest
}

/// Walks `start` (chart point and body velocity in the box) to its first object within
/// `length`, through at most `max_crossings` faces.
#[must_use]
pub fn first_nil_hit<'a>(
    walker: &NilWalker<DVec4>,
    scene: &'a NilScene,
    start: NilRay<f64>,
    length: f64,
    max_crossings: usize,
) -> NilRayEnd<'a> {
    walk_to_hit(
        walker,
        scene,
        &object_boxes(scene),
        (start, length),
        max_crossings,
        Seek::Nearest,
        None,
    )
}

/// [`first_nil_hit`] with the objects' chart boxes made once.
/// With [`Seek::Any`] the hit's distance and point are only where the object was found.
///
/// With `walls`, every panel crossed is added to the veil, and the walk ends in the fog
/// once the veil lets too little light through.
fn walk_to_hit<'a>(
    walker: &NilWalker<DVec4>,
    scene: &'a NilScene,
    boxes: &[ChartBox],
    (start, length): (NilRay<f64>, f64),
    max_crossings: usize,
    seek: Seek,
    mut walls: Option<(&walls::NilWalls, &mut crate::scene::walls::Veil)>,
) -> NilRayEnd<'a> {
    use crate::space::walk::CellWalk;
    let mut ray = walker.on_model(Ray {
        point: DVec3::from_array(start.point).extend(1.0),
        tangent: DVec3::from_array(start.velocity).extend(0.0),
    });
    let mut distance = 0.0;
    let mut crossings = 0;
    let mut last_face = None;
    while distance < length {
        let Some(exit) = walker.exit(&ray) else {
            break;
        };
        let here = nil_ray(&ray);
        let t_max = exit.t.min(length - distance);
        if let Some((t, object)) = nearest_in_segment(scene, boxes, &here, t_max, seek) {
            return NilRayEnd::Hit {
                distance: distance + t,
                crossings,
                last_face,
                at: flow(&here, t),
                object,
            };
        }
        if exit.t >= length - distance {
            break;
        }
        ray = walker.through(&ray, &exit);
        distance += exit.t;
        crossings += 1;
        last_face = Some(exit.face);
        if let Some((walls, veil)) = walls.as_mut() {
            // The panel is judged on the pair's face at −½ (or the bottom): where the ray
            // leaves through it, or where it comes in after leaving through its partner.
            let left = flow(&here, exit.t);
            let on_face = if exit.face & 1 == 1 {
                left.point
            } else {
                nil_ray(&ray).point
            };
            let through = (on_face, left.point, left.velocity);
            if !walls.cross(veil, scene, exit.face, through, distance) {
                return NilRayEnd::Fog;
            }
        }
        if crossings > max_crossings {
            return NilRayEnd::Budget(max_crossings);
        }
    }
    NilRayEnd::Fog
}

/// The colour seen along one ray: its first object shaded by the lamp ([`gather`], shadows
/// walked through the faces) and the fog, seen through the walls crossed on the way; the
/// fog's colour where nothing is met before the fog's cut-off or within the crossing budget.
#[must_use]
pub fn trace_nil_pixel(
    space: &NilSpace,
    scene: &NilScene,
    start: NilRay<f64>,
    max_crossings: usize,
) -> DVec3 {
    let walker = NilWalker::<DVec4>::new(space.k());
    let walls = scene_walls(space, scene);
    colour_along(
        (&walker, walls.as_ref()),
        scene,
        &object_boxes(scene),
        start,
        max_crossings,
    )
}

/// The scene's walls, built once; rays stop behind walls that let less light through than
/// the fog's cut-off weight.
fn scene_walls(space: &NilSpace, scene: &NilScene) -> Option<walls::NilWalls> {
    scene
        .walls
        .and_then(|style| walls::NilWalls::new(space, style, crate::scene::DEFAULT_CUTOFF_WEIGHT))
}

/// [`trace_nil_pixel`] with the objects' chart boxes made once.
fn colour_along(
    (walker, walls): (&NilWalker<DVec4>, Option<&walls::NilWalls>),
    scene: &NilScene,
    boxes: &[ChartBox],
    start: NilRay<f64>,
    max_crossings: usize,
) -> DVec3 {
    let mut veil = crate::scene::walls::Veil::CLEAR;
    let NilRayEnd::Hit {
        distance,
        crossings,
        last_face,
        at,
        object,
    } = walk_to_hit(
        walker,
        scene,
        boxes,
        (start, scene.cutoff_distance()),
        max_crossings,
        Seek::Nearest,
        walls.map(|w| (w, &mut veil)),
    )
    else {
        return veil.over(scene.fog_colour);
    };
    let normal = object.normal(at.point);
    let mut occluded = |ray: NilRay<f64>, length: f64| {
        matches!(
            walk_to_hit(
                walker,
                scene,
                boxes,
                (ray, length),
                max_crossings,
                Seek::Any,
                None,
            ),
            NilRayEnd::Hit { .. }
        )
    };
    let light = gather(scene, at.point, normal, &mut occluded);
    let lit = scene.ambient + (1.0 - scene.ambient) * scene.power * light;
    let mut surface = (object.colour * lit).min(DVec3::ONE);
    if let Some(tint) = nil_tint(scene.colour_by, crossings, last_face) {
        surface = crate::scene::ColourBy::recolour(tint, surface);
    }
    let w = (-distance / scene.fog_distance).exp();
    veil.over(w * surface + (1.0 - w) * scene.fog_colour)
}

/// The teaching view's tint of a surface seen after `crossings` crossings, the last through
/// `last_face` (`None` for the plain picture): as [`crate::scene::ColourBy::tint`] with the
/// copy's rotation always none (a left translation turns nothing).
fn nil_tint(
    colour_by: crate::scene::ColourBy,
    crossings: usize,
    last_face: Option<usize>,
) -> Option<DVec3> {
    (colour_by != crate::scene::ColourBy::Shading).then(|| {
        colour_by.tint(
            crate::geometry::Geometry::Euclidean,
            crossings,
            last_face,
            DMat4::IDENTITY,
        )
    })
}

/// Renders `layout`'s view of a Nil scene with the CPU reference: the layout's frames are
/// Nil camera frames ([`NilCamera::frame`]).
#[must_use]
pub fn render_nil_view(
    space: &NilSpace,
    scene: &NilScene,
    layout: &crate::view::ViewLayout,
    max_crossings: usize,
) -> RgbImage {
    let walker = NilWalker::<DVec4>::new(space.k());
    let walls = scene_walls(space, scene);
    let boxes = object_boxes(scene);
    super::render_layout(layout, |ray| {
        colour_along(
            (&walker, walls.as_ref()),
            scene,
            &boxes,
            nil_ray(&ray),
            max_crossings,
        )
    })
}
