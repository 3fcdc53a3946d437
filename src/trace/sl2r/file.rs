//! Scene files of the SL̃(2,R) spaces: the same TOML shape as the other families' scene
//! files ([`crate::scene::file`]), with SL̃(2,R)'s own objects. `render --scene FILE --cpu`
//! reads every kind: the file's `space` says which.
//!
//! A tube's `position` is the chart point `[x, y]` of its base point `(x, y, √(1 + x² + y²))`
//! on the hyperboloid; it is brought into the polygon by the surface group, and drawn with
//! each of its images that reaches into the cell. A ball's `position` and the start view's
//! are `[x, y, θ]`: the base point, and `e` at angle `θ` (radians) in the frame boosted from
//! the origin's; the camera looks along `e` with the fibre up (turn it by `θ`). A tube's
//! radius is a distance in `H²`, a ball's a distance in the space (at most ½).
//!
//! ```toml
//! space = "unit-tangent-bitorus"
//! edges = true            # the cell's edges: tubes over the polygon's vertices (default true)
//! centre_pillar = false   # the default scene's pillar over the centre (default false)
//! fog = 1.5               # fog distance
//! ambient = 0.3
//! fog_colour = [0.55, 0.6, 0.7]
//!
//! [start]
//! position = [-0.8, 0.0, 0.0]
//! look_at = [-0.8, 0.0, 1.0]   # optional: along the shortest geodesic to it (here up the fibre)
//! fov = 70
//!
//! [[object]]
//! type = "tube"           # the points within radius of the fibre over [x, y]
//! position = [0.3, 0.2]
//! radius = 0.15
//! colour = [0.9, 0.5, 0.2]
//!
//! [[object]]
//! type = "ball"           # the points within radius of the point [x, y, θ]
//! position = [0.0, 0.4, 1.5]
//! radius = 0.2
//! colour = [0.3, 0.6, 0.95]
//! ```
//!
//! One `[[light]]` puts the lamp at `position = [x, y, θ]` (a point of the space: the base
//! point and the fibre angle, brought into the cell like an object; the default scene's lamp
//! where there is none), and `[lighting]` is as in the other files (`paths`, `reach` in
//! inradii — held below 3, under the injectivity radius —, `tail`, `shadows`; the lamp is a
//! point). `walls = OPENING` and `wall_opacity = A` draw the cell's sides as walls with
//! windows ([`super::walls`]). SL̃(2,R) scenes have no moving objects yet. An error names the
//! file and the line.
//!
//! ```toml
//! [[light]]
//! position = [-0.3, 0.4, 0.3]
//!
//! [lighting]
//! shadows = 2
//! ```

use super::{
    FibreTube, Sl2rBall, Sl2rCamera, Sl2rParts, Sl2rScene, default_camera, scene_with_parts,
};
use crate::scene::file::SceneFileError;
use crate::scene::file_support::{
    LightingSpec, PointLightSpec, colour, failing, fog_keys, lighting_of, load_family_scene,
    one_light, parse_toml, space_key, walls_of,
};
use crate::space::sl2r::ball::MAX_SL2R_BALL_RADIUS;
use crate::space::sl2r::{UnitTangentSpace, sl2r_space};
use glam::DVec3;
use serde::Deserialize;
use std::path::Path;
use toml::Spanned;

/// The most tubes (with their images) a scene file may make: each is tested by every ray
/// segment of the CPU reference.
pub const MAX_SL2R_TUBES: usize = 400;

/// The most balls (with their images) a scene file may make: each is a root search along
/// every ray segment that comes near it.
pub const MAX_SL2R_BALLS: usize = 120;

/// A loaded SL̃(2,R) scene file: the space, its scene and the start view.
#[derive(Clone, Debug)]
pub struct Sl2rSceneFile {
    /// The space's id, as written.
    pub space_id: String,
    /// The space.
    pub space: UnitTangentSpace,
    /// The scene: the file's tubes with their images and the default parts it asks for.
    pub scene: Sl2rScene,
    /// The start view (the space's default camera where the file has none).
    pub start: Sl2rCamera,
}

/// The keys an SL̃(2,R) scene file knows (for "did you mean").
const KEYS: &[&str] = &[
    "space",
    "fog",
    "edges",
    "centre_pillar",
    "ambient",
    "fog_colour",
    "start",
    "object",
    "position",
    "look_at",
    "fov",
    "type",
    "radius",
    "colour",
    "light",
    "lighting",
    "walls",
    "wall_opacity",
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
    centre_pillar: bool,
    ambient: Option<Spanned<f64>>,
    fog_colour: Option<Spanned<[f64; 3]>>,
    walls: Option<Spanned<f64>>,
    wall_opacity: Option<Spanned<f64>>,
    start: Option<Spanned<StartSpec>>,
    #[serde(default, rename = "object")]
    objects: Vec<Spanned<ObjectSpec>>,
    #[serde(default, rename = "light")]
    lights: Vec<Spanned<PointLightSpec>>,
    lighting: Option<Spanned<LightingSpec>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StartSpec {
    position: [f64; 3],
    look_at: Option<[f64; 3]>,
    fov: Option<f64>,
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
enum ObjectSpec {
    Tube {
        position: [f64; 2],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
    Ball {
        position: [f64; 3],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
    },
}

/// Whether a scene file's text names an SL̃(2,R) space in its `space` key (or such an id
/// that is wrong: its loader says what is wrong with it); `false` where the key cannot be
/// read.
#[must_use]
pub fn names_sl2r_space(text: &str) -> bool {
    space_key(text).is_some_and(|id| sl2r_space(&id).is_some())
}

/// Reads a scene file if its space is an SL̃(2,R) space; `Ok(None)` for any other file.
pub fn load_sl2r_scene_file(path: &Path) -> Result<Option<Sl2rSceneFile>, SceneFileError> {
    load_family_scene(path, names_sl2r_space, parse_sl2r_scene)
}

/// Parses an SL̃(2,R) scene file's text; errors name `file` and the line.
pub fn parse_sl2r_scene(text: &str, file: &str) -> Result<Sl2rSceneFile, SceneFileError> {
    let fail = failing(text, file);
    let spec: FileSpec = parse_toml(text, file, KEYS)?;
    let space_id = spec.space.get_ref().clone();
    let space = match sl2r_space(&space_id) {
        Some(Ok(space)) => space,
        Some(Err(e)) => return Err(fail(Some(spec.space.span()), e.to_string())),
        None => {
            return Err(fail(
                Some(spec.space.span()),
                format!("{space_id} is not an SL̃(2,R) space (`unit-tangent-WORD`)"),
            ));
        }
    };
    let mut scene = scene_with_parts(
        &space,
        Sl2rParts {
            edges: spec.edges,
            centre_pillar: spec.centre_pillar,
            pillars: false,
            ball_stack: false,
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
    for object in &spec.objects {
        let at = |m: String| fail(Some(object.span()), m);
        match build_object(&space, object.get_ref()).map_err(at)? {
            Built::Tube(tube) => scene.add_with_images(&space, tube),
            Built::Ball(ball) => scene.add_ball_with_images(&space, ball),
        }
        if scene.balls.len() > MAX_SL2R_BALLS {
            return Err(at(format!(
                "the scene has more than {MAX_SL2R_BALLS} balls with the images that reach into \
                 the cell ({} so far): make the balls fewer or smaller",
                scene.balls.len()
            )));
        }
        if scene.tubes.len() > MAX_SL2R_TUBES {
            return Err(at(format!(
                "the scene has more than {MAX_SL2R_TUBES} tubes with the images that reach into \
                 the cell ({} so far): make the tubes fewer or thinner",
                scene.tubes.len()
            )));
        }
    }
    let mut light = (scene.light, scene.light_sheet);
    if let Some((position, span)) =
        one_light(&spec.lights, "an SL̃(2,R) scene").map_err(|(s, m)| fail(Some(s), m))?
    {
        light = space
            .frame_at_chart_point(DVec3::from_array(position))
            .map_err(|m| fail(Some(span), format!("the light's position: {m}")))?;
    }
    let lighting = match &spec.lighting {
        Some(l) => lighting_of(l).map_err(|(s, m)| fail(Some(s), m))?,
        None => scene.lighting,
    };
    scene
        .set_lighting(&space, light, lighting)
        .map_err(|m| fail(spec.lighting.as_ref().map(Spanned::span), m))?;
    let start = match &spec.start {
        Some(s) => {
            let st = s.get_ref();
            let fov = st
                .fov
                .unwrap_or_else(|| default_camera(&space).fov_y_degrees);
            let eye = DVec3::from_array(st.position);
            match st.look_at {
                Some(target) => Sl2rCamera::looking_at(&space, eye, DVec3::from_array(target), fov),
                None => Sl2rCamera::at(&space, eye, fov),
            }
            .map_err(|m| fail(Some(s.span()), format!("start: {m}")))?
        }
        None => default_camera(&space),
    };
    Ok(Sl2rSceneFile {
        space_id,
        space,
        scene,
        start,
    })
}

/// An object of the file, before its images.
enum Built {
    Tube(FibreTube),
    Ball(Sl2rBall),
}

/// An object of the file, its base point brought into the polygon (its images are added by
/// the scene).
fn build_object(space: &UnitTangentSpace, spec: &ObjectSpec) -> Result<Built, String> {
    let (point, radius, c, largest, what) = match spec {
        ObjectSpec::Tube {
            position,
            radius,
            colour,
        } => (
            DVec3::new(position[0], position[1], 0.0),
            *radius,
            *colour,
            space.inradius(),
            "the polygon's inradius",
        ),
        ObjectSpec::Ball {
            position,
            radius,
            colour,
        } => (
            DVec3::from_array(*position),
            *radius,
            *colour,
            MAX_SL2R_BALL_RADIUS.min(space.inradius()),
            "the largest ball radius (half a unit, and the polygon's inradius)",
        ),
    };
    if !(radius > 0.0 && radius <= largest) {
        return Err(format!(
            "radius must be a positive distance of at most {largest:.6} ({what}), got {radius}"
        ));
    }
    let (frame, sheet) = space
        .frame_at_chart_point(point)
        .map_err(|m| format!("the object's position: {m}"))?;
    let colour = colour(c)?.min(DVec3::ONE);
    Ok(match spec {
        ObjectSpec::Tube { .. } => Built::Tube(FibreTube {
            base: frame[2],
            radius,
            colour,
        }),
        ObjectSpec::Ball { .. } => Built::Ball(Sl2rBall {
            centre: frame,
            radius,
            colour,
            sheet,
        }),
    })
}
