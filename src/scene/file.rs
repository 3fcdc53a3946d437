//! Scene files: a TOML file naming the space, the objects (balls, globes, tubes, discs, glTF
//! meshes), the lights, the fog and the start view. `curved-spaces walk --scene FILE` and
//! `render --scene FILE` load them; `assets/scenes/` has examples and `docs/scenes.md`
//! describes every key.
//!
//! Lengths are in **inradii** of the space's cell (so a scene reads the same in a small
//! spherical space and a large hyperbolic one) and positions are **geodesic coordinates**
//! about the cell's centre: `[x, y, z]` is the point at distance `|(x, y, z)|` inradii in the
//! chart direction `(x, y, z)`. `chart = [x, y, z]` gives a chart point instead. Colours are
//! linear RGB in [0, 1]. Paths are relative to the scene file.
//!
//! An error names the file and the line: a TOML mistake or an unknown key, an unknown
//! space, a mesh or texture that cannot be read, an object outside the cell.

use super::gltf;
use super::texture::Texture;
use crate::geometry::Geometry;
use crate::scene::{
    Ball, BallTexture, CurvedScene, Disc, Light, MeshInstance, MovingError, MovingObject, Object,
    SceneParts, Shading, SurfaceMaterial, Tube,
};
use crate::space::Space;
use crate::space::invariants::inradius;
use crate::space::motion::Velocity;
use glam::{DMat4, DVec3, DVec4};
use serde::Deserialize;
use std::path::Path;
use std::sync::Arc;
use toml::Spanned;

pub use super::file_support::SceneFileError;
use super::file_support::{ambient_of, colour, failing, parse_toml, read_scene_text, walls_of};

/// A loaded scene file: the space, its own scene (objects with their images, lights,
/// shading, meshes), the default parts it asks for and the start view.
#[derive(Clone, Debug)]
pub struct SceneFile {
    /// The space's seed id or file, as written.
    pub space_id: String,
    /// The space the scene is in.
    pub space: Space,
    /// The file's own objects, lights and shading, without the parts: the base scene the
    /// plugin adds `TracerSettings::parts` to.
    pub base: CurvedScene,
    /// The player's start frame (`None`: the space's default view).
    pub start: Option<DMat4>,
    /// The start view's vertical field of view in degrees (`fov` in `[start]`; `None`: the
    /// camera's own).
    pub start_fov: Option<f64>,
    /// The default scene's parts the file asks for (the cell's edges, the centre ball, the
    /// avatar).
    pub parts: SceneParts,
    /// The objects with a `velocity`, as they start (not in `base`).
    pub moving: Vec<MovingObject>,
}

impl SceneFile {
    /// The whole scene at time 0: the base with the moving objects at their start and the
    /// parts the file asks for.
    #[must_use]
    pub fn scene(&self) -> CurvedScene {
        // At time 0 the moving objects are where the file placed them: placing cannot fail.
        self.scene_at(0.0)
            .unwrap_or_else(|_| self.base.adding_parts(&self.space, self.parts))
    }

    /// The whole scene at `time` seconds: each moving object where its motion has taken it
    /// (through the faces, turned by the pairings crossed).
    pub fn scene_at(&self, time: f64) -> Result<CurvedScene, MovingError> {
        Ok(self.base_at(time)?.adding_parts(&self.space, self.parts))
    }

    /// The base scene (without the parts) at `time` seconds.
    pub fn base_at(&self, time: f64) -> Result<CurvedScene, MovingError> {
        self.base.with_moving_at(&self.space, &self.moving, time)
    }
}

fn default_true() -> bool {
    true
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileSpec {
    space: Spanned<String>,
    /// Fog distance in inradii.
    fog: Option<Spanned<f64>>,
    #[serde(default = "default_true")]
    edges: bool,
    #[serde(default)]
    centre_ball: bool,
    #[serde(default = "default_true")]
    avatar: bool,
    /// Clifford parallels (spherical spaces).
    #[serde(default)]
    clifford: bool,
    /// A gyroscope at the centre (the same as `centrepiece = "gyroscope"`).
    #[serde(default)]
    gyroscope: bool,
    /// What sits at the cell's centre: none, ball, globe, gyroscope or galaxy.
    centrepiece: Option<Spanned<String>>,
    /// The cell's walls with windows: how far open (0 solid, 1 none).
    walls: Option<Spanned<f64>>,
    /// The share of light a wall stops.
    wall_opacity: Option<Spanned<f64>>,
    ambient: Option<Spanned<f64>>,
    fog_colour: Option<[f64; 3]>,
    start: Option<Spanned<StartSpec>>,
    #[serde(default, rename = "object")]
    objects: Vec<Spanned<ObjectSpec>>,
    #[serde(default, rename = "light")]
    lights: Vec<Spanned<LightSpec>>,
    /// How the lamps light the scene: every image or the nearest copy, how far, the tail,
    /// how many shadows.
    lighting: Option<Spanned<super::file_support::LightingSpec>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StartSpec {
    #[serde(flatten)]
    at: Place,
    look_at: Option<[f64; 3]>,
    /// Vertical field of view in degrees.
    fov: Option<f64>,
}

/// Where an object is: geodesic coordinates in inradii, or a chart point; its turn.
#[derive(Deserialize, Default)]
struct Place {
    position: Option<[f64; 3]>,
    chart: Option<[f64; 3]>,
    /// Degrees about the object's own y, x and z axes, in that order.
    #[serde(default)]
    yaw: f64,
    #[serde(default)]
    pitch: f64,
    #[serde(default)]
    roll: f64,
}

fn white() -> [f64; 3] {
    [1.0; 3]
}

#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
enum ObjectSpec {
    Ball {
        #[serde(flatten)]
        at: Place,
        /// Inradii per second along the object's own axes at its start.
        velocity: Option<[f64; 3]>,
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
        #[serde(default)]
        emission: [f64; 3],
        /// The share of light reflected as a mirror, 0 to 1.
        #[serde(default)]
        reflectance: f64,
    },
    Globe {
        #[serde(flatten)]
        at: Place,
        /// Inradii per second along the object's own axes at its start.
        velocity: Option<[f64; 3]>,
        radius: f64,
        texture: String,
        /// Radians per second.
        #[serde(default)]
        spin: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
        #[serde(default)]
        emission: [f64; 3],
        /// The share of light reflected as a mirror, 0 to 1.
        #[serde(default)]
        reflectance: f64,
    },
    Tube {
        from: [f64; 3],
        to: [f64; 3],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
        #[serde(default)]
        emission: [f64; 3],
    },
    Disc {
        #[serde(flatten)]
        at: Place,
        /// Inradii per second along the object's own axes at its start.
        velocity: Option<[f64; 3]>,
        normal: [f64; 3],
        radius: f64,
        #[serde(default = "white")]
        colour: [f64; 3],
        #[serde(default)]
        emission: [f64; 3],
        /// The share of light reflected as a mirror, 0 to 1.
        #[serde(default)]
        reflectance: f64,
    },
    Mesh {
        #[serde(flatten)]
        at: Place,
        /// Inradii per second along the object's own axes at its start.
        velocity: Option<[f64; 3]>,
        path: String,
        /// The mesh's radius (farthest vertex from its origin) in inradii.
        size: f64,
        /// A colour for the whole mesh instead of its materials.
        colour: Option<[f64; 3]>,
        #[serde(default)]
        emission: [f64; 3],
        /// The share of light reflected as a mirror, 0 to 1.
        #[serde(default)]
        reflectance: f64,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LightSpec {
    #[serde(flatten)]
    at: Place,
    #[serde(default = "white")]
    colour: [f64; 3],
    /// Brightness at one inradius.
    #[serde(default = "one")]
    intensity: f64,
}

fn one() -> f64 {
    1.0
}

/// Reads a scene file.
pub fn load_scene_file(path: &Path) -> Result<SceneFile, SceneFileError> {
    let (name, text) = read_scene_text(path)?;
    let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
    parse_scene(&text, &base, &name)
}

/// Parses a scene file's text; paths in it are relative to `base`, errors name `file`.
pub fn parse_scene(text: &str, base: &Path, file: &str) -> Result<SceneFile, SceneFileError> {
    let fail = failing(text, file);
    let spec: FileSpec = parse_toml(text, file, KEYS)?;

    let space_id = spec.space.get_ref().clone();
    let space = resolve_space(&space_id, base).map_err(|m| fail(Some(spec.space.span()), m))?;
    let g = space.geometry;
    let r = inradius(&space);
    let fog = match &spec.fog {
        Some(f) if !(*f.get_ref() > 0.0 && f.get_ref().is_finite()) => {
            return Err(fail(
                Some(f.span()),
                format!(
                    "the fog distance must be a positive number of inradii, got {}",
                    f.get_ref()
                ),
            ));
        }
        Some(f) => f.get_ref() * r,
        None => Shading::default_fog_distance(&space),
    };
    let mut scene = CurvedScene::with_parts(
        &space,
        fog,
        SceneParts {
            edges: false,
            centrepiece: crate::scene::Centrepiece::None,
            avatar: false,
            clifford: false,
        },
    );
    if let Some(a) = &spec.ambient {
        scene.shading.ambient = ambient_of(a).map_err(|(s, m)| fail(Some(s), m))?;
    }
    scene.shading.walls = walls_of(spec.walls.as_ref(), spec.wall_opacity.as_ref())
        .map_err(|(s, m)| fail(Some(s), m))?;
    if let Some(c) = spec.fog_colour {
        scene.shading.fog_colour = colour(c)
            .map_err(|m| fail(None, format!("fog_colour: {m}")))?
            .min(DVec3::ONE);
    }
    if !spec.lights.is_empty() {
        scene.lights.clear();
    }
    for light in &spec.lights {
        let at = |m: String| fail(Some(light.span()), m);
        let l = light.get_ref();
        let frame = frame_of(&space, &l.at).map_err(at)?;
        if !(l.intensity >= 0.0 && l.intensity.is_finite()) {
            return Err(at(format!(
                "the intensity must be 0 or more, got {}",
                l.intensity
            )));
        }
        let position = g.project_point(frame.w_axis);
        let outside = space.outside_by(position);
        if !(outside <= 1e-9) {
            return Err(at(format!(
                "the light is not inside the cell: its position is {outside:.3} (chart units) \
                 past a face; lights are placed in the cell, and their images follow"
            )));
        }
        scene.lights.push(Light::new(
            &space,
            position,
            colour(l.colour).map_err(at)?,
            l.intensity * g.s(r).powi(2),
        ));
    }
    if let Some(l) = &spec.lighting {
        let lighting = super::file_support::lighting_of(l).map_err(|(s, m)| fail(Some(s), m))?;
        scene
            .set_lighting(&space, lighting)
            .map_err(|m| fail(Some(l.span()), m))?;
    }
    let mut moving = Vec::new();
    for object in &spec.objects {
        let at = |m: String| fail(Some(object.span()), m);
        let (o, frame) = build_object(&space, &mut scene, object.get_ref(), base).map_err(at)?;
        match object.get_ref().velocity() {
            None => {
                scene.place(&space, o).map_err(|e| at(format!("{e}")))?;
            }
            Some(v) => {
                let v = DVec3::from_array(v);
                if !v.is_finite() {
                    return Err(at(format!(
                        "velocity must be finite inradii per second, got {:?}",
                        v.to_array()
                    )));
                }
                // Checked as a still object would be: inside the cell, not too large.
                scene
                    .clone()
                    .place(&space, o)
                    .map_err(|e| at(format!("{e}")))?;
                moving.push(MovingObject {
                    object: o,
                    frame,
                    velocity: Velocity {
                        linear: v * r,
                        angular: DVec3::ZERO,
                    },
                });
            }
        }
    }
    let start = match &spec.start {
        Some(s) => Some(start_frame(&space, s.get_ref()).map_err(|m| fail(Some(s.span()), m))?),
        None => None,
    };
    let start_fov = match spec
        .start
        .as_ref()
        .and_then(|s| s.get_ref().fov.map(|f| (s, f)))
    {
        Some((_, fov)) if fov > 0.0 && fov < 180.0 => Some(fov),
        Some((s, fov)) => {
            return Err(fail(
                Some(s.span()),
                format!("fov must be an angle between 0 and 180 degrees, got {fov}"),
            ));
        }
        None => None,
    };
    let centrepiece = centrepiece_of(&spec).map_err(|(span, m)| fail(span, m))?;
    Ok(SceneFile {
        space_id,
        space,
        base: scene,
        start,
        start_fov,
        parts: SceneParts {
            edges: spec.edges,
            centrepiece,
            avatar: spec.avatar,
            clifford: spec.clifford,
        },
        moving,
    })
}

/// The file's centrepiece: `centrepiece = "NAME"`, or the older switches `centre_ball` and
/// `gyroscope` (not both with it).
fn centrepiece_of(
    spec: &FileSpec,
) -> Result<crate::scene::Centrepiece, (Option<std::ops::Range<usize>>, String)> {
    use crate::scene::Centrepiece;
    match &spec.centrepiece {
        Some(name) => {
            if spec.centre_ball || spec.gyroscope {
                return Err((
                    Some(name.span()),
                    "give the centrepiece once: centrepiece, or centre_ball/gyroscope, not both"
                        .into(),
                ));
            }
            Centrepiece::from_name(name.get_ref()).ok_or_else(|| {
                let names: Vec<&str> = Centrepiece::ALL.iter().map(|c| c.name()).collect();
                (
                    Some(name.span()),
                    format!(
                        "unknown centrepiece `{}`; choose one of {}",
                        name.get_ref(),
                        names.join(", ")
                    ),
                )
            })
        }
        None if spec.gyroscope => Ok(Centrepiece::Gyroscope),
        None if spec.centre_ball => Ok(Centrepiece::Ball),
        None => Ok(Centrepiece::None),
    }
}

/// Every key a scene file knows, for suggestions.
const KEYS: &[&str] = &[
    "space",
    "fog",
    "edges",
    "centre_ball",
    "avatar",
    "ambient",
    "fog_colour",
    "start",
    "object",
    "light",
    "position",
    "chart",
    "yaw",
    "pitch",
    "roll",
    "look_at",
    "fov",
    "type",
    "radius",
    "colour",
    "emission",
    "texture",
    "spin",
    "from",
    "to",
    "normal",
    "path",
    "size",
    "intensity",
    "velocity",
    "clifford",
    "gyroscope",
    "walls",
    "wall_opacity",
    "centrepiece",
    "lighting",
    "reflectance",
    "paths",
    "reach",
    "tail",
    "shadows",
    "lamp_radius",
    "soft_samples",
];

/// A seed space by id, or a space file by path (relative to `base`).
fn resolve_space(id: &str, base: &Path) -> Result<Space, String> {
    crate::space::resolve_space(
        id,
        base,
        &crate::space::dirichlet::DirichletOptions::default(),
    )
}

fn positive(name: &str, x: f64) -> Result<f64, String> {
    if x > 0.0 && x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{name} must be a positive number, got {x}"))
    }
}

/// The point of a place: geodesic coordinates in inradii, or a chart point.
fn point_of(space: &Space, place: &Place) -> Result<DVec4, String> {
    let g = space.geometry;
    // Every number of a place is checked, the angles too where the object has no use for them.
    for (name, angle) in [
        ("yaw", place.yaw),
        ("pitch", place.pitch),
        ("roll", place.roll),
    ] {
        if !angle.is_finite() {
            return Err(format!(
                "{name} must be a finite angle in degrees, got {angle}"
            ));
        }
    }

    match (place.position, place.chart) {
        (Some(_), Some(_)) => Err("give either position or chart, not both".into()),
        (None, Some(c)) => g
            .from_chart(DVec3::from_array(c))
            .map_err(|e| format!("chart {c:?}: {e}")),
        (p, None) => {
            let p = DVec3::from_array(p.unwrap_or_default());
            if !p.is_finite() {
                return Err(format!("position {:?} is not finite", p.to_array()));
            }
            let d = p.length() * inradius(space);
            if g == Geometry::Spherical && d >= std::f64::consts::FRAC_PI_2 {
                return Err(format!(
                    "position {:?} is past the hemisphere of the cell",
                    p.to_array()
                ));
            }
            let point = if d > 0.0 {
                g.translation(p, d) * space.centre()
            } else {
                space.centre()
            };
            if !point.is_finite() {
                return Err(format!(
                    "position {:?} is too far from the centre for {} space",
                    p.to_array(),
                    g.name()
                ));
            }
            Ok(point)
        }
    }
}

/// The frame of a place: the translation to its point, turned by yaw, pitch and roll.
fn frame_of(space: &Space, place: &Place) -> Result<DMat4, String> {
    let g = space.geometry;
    // Checks the angles too.
    let point = point_of(space, place)?;
    let turn = g.rotation(DVec3::Y, place.yaw.to_radians())
        * g.rotation(DVec3::X, place.pitch.to_radians())
        * g.rotation(DVec3::Z, place.roll.to_radians());
    Ok(g.translation_to(point) * turn)
}

fn start_frame(space: &Space, start: &StartSpec) -> Result<DMat4, String> {
    let g = space.geometry;
    let frame = frame_of(space, &start.at)?;
    if space.outside_by(g.project_point(frame.w_axis)) > 0.0 {
        return Err("the start is outside the cell".into());
    }
    match start.look_at {
        None => Ok(frame),
        Some(target) => {
            let target = point_of(
                space,
                &Place {
                    position: Some(target),
                    ..Place::default()
                },
            )?;
            g.look_at(g.to_chart(frame.w_axis), g.to_chart(target), DVec3::Y)
                .map_err(|e| format!("look_at: {e}"))
        }
    }
}

impl ObjectSpec {
    /// The velocity the object was given, if any.
    fn velocity(&self) -> Option<[f64; 3]> {
        match self {
            ObjectSpec::Ball { velocity, .. }
            | ObjectSpec::Globe { velocity, .. }
            | ObjectSpec::Disc { velocity, .. }
            | ObjectSpec::Mesh { velocity, .. } => *velocity,
            ObjectSpec::Tube { .. } => None,
        }
    }
}

/// A mirror's share of the light, 0 to 1.
fn reflectance_of(r: f64) -> Result<f64, String> {
    if (0.0..=1.0).contains(&r) {
        Ok(r)
    } else {
        Err(format!("reflectance must be between 0 and 1, got {r}"))
    }
}

/// The object of a spec and its frame (a tube's: the translation to its midpoint).
fn build_object(
    space: &Space,
    scene: &mut CurvedScene,
    spec: &ObjectSpec,
    base: &Path,
) -> Result<(Object, DMat4), String> {
    let g = space.geometry;
    let r = inradius(space);
    Ok(match spec {
        ObjectSpec::Ball {
            at,
            radius,
            colour: c,
            emission,
            reflectance,
            ..
        } => {
            let radius = positive("radius", *radius)? * r;
            let frame = frame_of(space, at)?;
            (
                Object::Ball(
                    Ball::new(g, g.project_point(frame.w_axis), radius, colour(*c)?)
                        .with_emission(colour(*emission)?)
                        .with_reflectance(reflectance_of(*reflectance)?),
                ),
                frame,
            )
        }
        ObjectSpec::Globe {
            at,
            radius,
            texture,
            spin,
            colour: c,
            emission,
            reflectance,
            ..
        } => {
            let radius = positive("radius", *radius)? * r;
            let frame = frame_of(space, at)?;
            let path = base.join(texture);
            let t = Texture::load(&path).map_err(|e| e.to_string())?;
            scene.textures.push(Arc::new(t));
            let centre = g.project_point(frame.w_axis);
            if !spin.is_finite() {
                return Err(format!("spin must be finite, got {spin}"));
            }
            (
                Object::Ball(
                    Ball::new(g, centre, radius, colour(*c)?)
                        .with_emission(colour(*emission)?)
                        .with_reflectance(reflectance_of(*reflectance)?)
                        .with_texture(BallTexture {
                            texture: scene.textures.len() as u32 - 1,
                            frame,
                            spin: *spin,
                        }),
                ),
                frame,
            )
        }
        ObjectSpec::Tube {
            from,
            to,
            radius,
            colour: c,
            emission,
        } => {
            let radius = positive("radius", *radius)? * r;
            let end = |p: [f64; 3]| {
                point_of(
                    space,
                    &Place {
                        position: Some(p),
                        ..Place::default()
                    },
                )
            };
            let (a, b) = (end(*from)?, end(*to)?);
            if g.distance(a, b) < 1e-9 {
                return Err("the tube's ends are the same point".into());
            }
            let tube = Tube::new(g, a, b, radius, colour(*c)?).with_emission(colour(*emission)?);
            (Object::Tube(tube), g.translation_to(a))
        }
        ObjectSpec::Disc {
            at,
            normal,
            radius,
            colour: c,
            emission,
            reflectance,
            ..
        } => {
            let radius = positive("radius", *radius)? * r;
            let frame = frame_of(space, at)?;
            let centre = g.project_point(frame.w_axis);
            let n = g
                .tangent_from_chart(centre, DVec3::from_array(*normal))
                .map_err(|e| format!("normal: {e}"))?;
            (
                Object::Disc(
                    Disc::new(g, centre, n, radius, colour(*c)?)
                        .with_emission(colour(*emission)?)
                        .with_reflectance(reflectance_of(*reflectance)?),
                ),
                frame,
            )
        }
        ObjectSpec::Mesh {
            at,
            path,
            size,
            colour: c,
            emission,
            reflectance,
            ..
        } => {
            let reflectance = reflectance_of(*reflectance)?;
            let size = positive("size", *size)? * r;
            let frame = frame_of(space, at)?;
            let file = base.join(path);
            if !file.exists() {
                return Err(format!("mesh not found: {}", file.display()));
            }
            let model = gltf::load(&file).map_err(|e| e.to_string())?;
            let model_radius = model.source.radius();
            if !(model_radius > 0.0) {
                return Err(format!(
                    "the mesh {} has all its vertices at its origin",
                    file.display()
                ));
            }
            let first = scene.materials.len();
            let mesh = scene
                .add_model(g, &model, size / model_radius)
                .map_err(|e| format!("{}: {e}", file.display()))?;
            for m in &mut scene.materials[first..] {
                m.reflectance = reflectance;
            }
            let radius = scene.meshes[mesh as usize].radius;
            let mut instance = MeshInstance::new(g, mesh, frame, radius);
            if c.is_some() || *emission != [0.0; 3] {
                scene.materials.push(SurfaceMaterial {
                    colour: colour(c.unwrap_or([1.0; 3]))?,
                    texture: None,
                    emission: colour(*emission)?,
                    reflectance,
                });
                instance.material = Some(scene.materials.len() as u32 - 1);
            }
            (Object::Mesh(instance), frame)
        }
    })
}
