//! Scene files of the Nil spaces: the same TOML shape as the other families' scene files
//! ([`crate::scene::file`], [`crate::trace::product::file`]), with Nil's own objects.
//! `render --scene FILE` and `walk --scene FILE` read every kind: the file's `space` says
//! which.
//!
//! Positions are chart points `(x, y, z)` of the Heisenberg group (the box of `nil-K` is
//! `|x|, |y| ≤ ½`, `|z| ≤ 1/2K`); a position outside the box is brought into it by the
//! lattice, and every object is drawn with each of its lattice images that reaches into the
//! box, so an object may straddle the box's faces. Radii are Nil distances.
//!
//! ```toml
//! space = "nil-3"
//! edges = true            # the box's edges (default true)
//! centre_ball = false     # the default scene's centrepiece ball (default false)
//! fog = 1.5               # fog distance
//! ambient = 0.3
//! walls = 0.6             # the box's walls with windows: how far open (0 solid, 1 none)
//!
//! [start]
//! position = [0.1, -0.45, 0.05]
//! look_at = [0.0, 0.0, 0.0]
//! fov = 70
//!
//! [[object]]
//! type = "ball"           # a metric ball: position [x, y, z]
//! position = [0.25, 0.1, 0.0]
//! radius = 0.1
//! colour = [0.9, 0.5, 0.2]
//! velocity = [0.2, 0, 0]  # a ball may move: chart units a second along E₁, E₂, E₃
//!
//! [[object]]
//! type = "fibre"          # a vertical tube (the points within radius of a fibre): [x, y]
//! position = [0.2, -0.3]
//! radius = 0.04
//!
//! [[light]]               # one light at most (the default scene's where there is none)
//! position = [-0.25, -0.3, 0.05]
//!
//! [lighting]              # as in the other files; a Nil lamp is a point
//! paths = "images"
//! reach = 2.0
//! shadows = 8
//! ```
//!
//! An error names the file and the line.

use super::{
    NilCamera, NilObject, NilParts, NilScene, NilShape, chart_point, default_camera,
    scene_with_parts,
};
use crate::scene::file::SceneFileError;
use crate::scene::file_support::{
    LightingSpec, PointLightSpec, PointStartSpec, colour, failing, fog_keys, lighting_of,
    load_family_scene, one_light, parse_toml, space_key, walls_of,
};
use crate::space::nil::{NilSpace, nil_space};
use glam::DVec3;
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

pub use super::{MAX_NIL_OBJECTS, MAX_NIL_RADIUS};

/// A loaded Nil scene file: the space, its scene and the start view.
#[derive(Clone, Debug)]
pub struct NilSceneFile {
    /// The space's id, as written.
    pub space_id: String,
    /// The space.
    pub space: NilSpace,
    /// The whole scene: the file's objects with their images and the default parts it asks
    /// for.
    pub scene: NilScene,
    /// The start view (`None`: the space's default camera).
    pub start: Option<NilCamera>,
    /// The balls with a `velocity`, as they start (not in `scene`).
    pub moving: Vec<super::moving::NilMover>,
}

impl NilSceneFile {
    /// The scene with its moving balls where they are at `time` seconds (with their lattice
    /// images); an error says why a time cannot be flown.
    pub fn scene_at(&self, time: f64) -> Result<NilScene, crate::space::motion::MotionError> {
        super::moving::scene_at(&self.space, &self.scene, &self.moving, time)
    }
}

/// The keys a Nil scene file knows (for "did you mean").
const KEYS: &[&str] = &[
    "space",
    "fog",
    "edges",
    "centre_ball",
    "ambient",
    "fog_colour",
    "walls",
    "wall_opacity",
    "start",
    "object",
    "light",
    "position",
    "look_at",
    "fov",
    "type",
    "radius",
    "colour",
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
    ambient: Option<Spanned<f64>>,
    fog_colour: Option<Spanned<[f64; 3]>>,
    walls: Option<Spanned<f64>>,
    wall_opacity: Option<Spanned<f64>>,
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
        velocity: Option<[f64; 3]>,
    },
    Fibre {
        position: [f64; 2],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
}

/// Whether a scene file's text names a Nil space in its `space` key (or a Nil id that is
/// wrong, such as `nil-0`: its loader says what is wrong with it); `false` where the key
/// cannot be read.
#[must_use]
pub fn names_nil_space(text: &str) -> bool {
    space_key(text).is_some_and(|id| nil_space(&id).is_some())
}

/// Reads a scene file if its space is a Nil space; `Ok(None)` for any other file (another
/// family's, or one whose `space` cannot be read: the constant-curvature loader says what
/// is wrong with it).
pub fn load_nil_scene_file(path: &Path) -> Result<Option<NilSceneFile>, SceneFileError> {
    load_family_scene(path, names_nil_space, parse_nil_scene)
}

/// Parses a Nil scene file's text; errors name `file` and the line.
pub fn parse_nil_scene(text: &str, file: &str) -> Result<NilSceneFile, SceneFileError> {
    let fail = failing(text, file);
    let spec: FileSpec = parse_toml(text, file, KEYS)?;
    let space_id = spec.space.get_ref().clone();
    let space = match nil_space(&space_id) {
        Some(Ok(space)) => space,
        Some(Err(e)) => return Err(fail(Some(spec.space.span()), e.to_string())),
        None => {
            return Err(fail(
                Some(spec.space.span()),
                format!("{space_id} is not a Nil space (`nil-K`, `heisenberg`)"),
            ));
        }
    };
    let mut scene = scene_with_parts(
        &space,
        NilParts {
            edges: spec.edges,
            centre_ball: spec.centre_ball,
        },
    );
    let fog = fog_keys(
        spec.fog.as_ref(),
        spec.ambient.as_ref(),
        spec.fog_colour.as_ref(),
        "",
    )
    .map_err(|(s, m)| fail(Some(s), m))?;
    if let Some(f) = fog.fog {
        scene.fog_distance = f;
        scene.power = super::default_power(&space, f);
    }
    scene.ambient = fog.ambient.unwrap_or(scene.ambient);
    scene.fog_colour = fog.fog_colour.unwrap_or(scene.fog_colour);
    scene.walls = walls_of(spec.walls.as_ref(), spec.wall_opacity.as_ref())
        .map_err(|(s, m)| fail(Some(s), m))?
        .filter(|w| w.opening < 1.0);
    if let Some((position, span)) =
        one_light(&spec.lights, "a Nil scene").map_err(|(s, m)| fail(Some(s), m))?
    {
        scene.light = chart_point(position, "the light").map_err(|m| fail(Some(span), m))?;
    }
    let mut moving = Vec::new();
    for object in &spec.objects {
        let at = |m: String| fail(Some(object.span()), m);
        let made = build_object(&space, object.get_ref()).map_err(at)?;
        if let ObjectSpec::Ball {
            velocity: Some(v), ..
        } = object.get_ref()
        {
            moving.push(mover(made, *v).map_err(at)?);
            // Counted with its images where it starts.
            let mut start = NilScene {
                objects: Vec::new(),
                ..scene.clone()
            };
            start.add_with_images(&space, made);
            if scene.objects.len() + start.objects.len() > MAX_NIL_OBJECTS {
                return Err(at(format!(
                    "the scene has more than {MAX_NIL_OBJECTS} objects with the lattice \
                     images that reach into the box: make the objects fewer or smaller"
                )));
            }
            continue;
        }
        scene.add_with_images(&space, made);
        if scene.objects.len() > MAX_NIL_OBJECTS {
            return Err(at(format!(
                "the scene has more than {MAX_NIL_OBJECTS} objects with the lattice images \
                 that reach into the box ({} so far; the box of {space_id} is {:.3} high, so a \
                 ball is seen about {} times over): make the objects fewer or smaller",
                scene.objects.len(),
                2.0 * space.half_height(),
                ((2.0 * made.radius + 2.0 * space.half_height()) * f64::from(space.k())).ceil()
            )));
        }
    }
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
    Ok(NilSceneFile {
        space_id,
        space,
        scene,
        start,
        moving,
    })
}

/// A ball flying with `velocity` (chart units a second in the frame `E₁, E₂, E₃` at its
/// centre): its frame those axes at its centre in the box.
fn mover(ball: NilObject, velocity: [f64; 3]) -> Result<super::moving::NilMover, String> {
    let v = DVec3::from_array(velocity);
    if !v.is_finite() {
        return Err(format!(
            "velocity must be finite (chart units a second), got {velocity:?}"
        ));
    }
    let NilShape::Ball(centre) = ball.shape else {
        return Err("only a ball moves".into());
    };
    let mut frame = glam::DMat4::IDENTITY;
    frame.w_axis = DVec3::from_array(centre).extend(1.0);
    Ok(super::moving::NilMover {
        object: ball,
        frame,
        velocity: crate::space::motion::Velocity {
            linear: v,
            angular: DVec3::ZERO,
        },
    })
}

/// A radius: positive, at most [`MAX_NIL_RADIUS`].
fn radius_of(r: f64) -> Result<f64, String> {
    if r > 0.0 && r <= MAX_NIL_RADIUS {
        Ok(r)
    } else {
        Err(format!(
            "radius must be a positive distance of at most {MAX_NIL_RADIUS} (half the box's \
             side), got {r}"
        ))
    }
}

/// An object of the file, brought into the box (its images are added by the scene).
fn build_object(space: &NilSpace, spec: &ObjectSpec) -> Result<NilObject, String> {
    let (shape, radius, c) = match spec {
        ObjectSpec::Ball {
            position,
            radius,
            colour,
            ..
        } => (
            NilShape::Ball(space.into_box(chart_point(*position, "the ball")?)),
            radius_of(*radius)?,
            colour,
        ),
        ObjectSpec::Fibre {
            position,
            radius,
            colour,
        } => {
            let [x, y, _] = chart_point([position[0], position[1], 0.0], "the fibre")?;
            // Its foot in the box's square (a fibre is its own image by the centre).
            (
                NilShape::Fibre([x - x.round(), y - y.round()]),
                radius_of(*radius)?,
                colour,
            )
        }
    };
    Ok(NilObject {
        shape,
        radius,
        colour: colour(*c)?.min(DVec3::ONE),
    })
}

fn start_camera(space: &NilSpace, start: &PointStartSpec) -> Result<NilCamera, String> {
    let eye = DVec3::from_array(chart_point(start.position, "the start position")?);
    let fov = start
        .fov
        .unwrap_or_else(|| default_camera(space).fov_y_degrees);
    let target = match start.look_at {
        Some(t) => DVec3::from_array(chart_point(t, "look_at")?),
        None => DVec3::ZERO,
    };
    NilCamera::looking_at(space, eye, target, fov)
}
