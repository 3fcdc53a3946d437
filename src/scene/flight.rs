//! Flights: a camera path through a space, from keyframes, for rendering to video.
//!
//! ```toml
//! space = "seifert-weber"     # or scene = "my-scene.toml" (its space, objects and lights)
//! fov = 70                    # vertical field of view in degrees (default 70)
//!
//! [[key]]
//! time = 0.0                  # seconds
//! position = [0.0, 0.0, 0.6]  # geodesic coordinates in inradii, as in scene files
//! look_at = [0.0, 0.0, 0.0]
//!
//! [[key]]
//! time = 3.0
//! position = [0.0, 0.0, -2.5] # beyond a face: reached by flying there
//! look_at = [0.0, 0.0, -4.0]
//! ```
//!
//! Keys lie in the universal cover: between two keys the camera moves along the geodesic
//! joining their positions while looking at the point moving along the geodesic joining their
//! targets, and each frame is brought back into the cell through the faces it passed
//! ([`crate::space::wrap_into_cell`]), turned by their pairings. So a key beyond a face is reached by
//! flying there, and the view arrives turned by the holonomy of the way. In S³ every
//! position and target must lie within π/2 of the centre.

use crate::geometry::Geometry;
use crate::space::invariants::inradius_at_most;
use crate::space::motion::CoverFlight;
use crate::space::{Holonomy, Space};
use glam::{DMat4, DVec3, DVec4};
use serde::Deserialize;

/// The default vertical field of view of a flight, in degrees.
pub const DEFAULT_FLIGHT_FOV: f64 = 70.0;

/// The most keys a flight file may have.
pub const MAX_KEYS: usize = 10_000;

/// The longest flight, in seconds.
pub const MAX_FLIGHT_SECONDS: f64 = 24.0 * 3600.0;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct FlightSpec {
    space: Option<String>,
    scene: Option<String>,
    fov: Option<f64>,
    #[serde(default)]
    key: Vec<KeySpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct KeySpec {
    time: f64,
    position: [f64; 3],
    look_at: [f64; 3],
    /// A point above the camera (geodesic coordinates in inradii): the view's up; without
    /// it, up is the chart's +y.
    up: Option<[f64; 3]>,
}

/// A flight file as written: where its space comes from, and its keys.
#[derive(Clone, Debug, PartialEq)]
pub struct FlightFile {
    /// The space's id or path (`space = …`), if given.
    pub space: Option<String>,
    /// A scene file's path (`scene = …`), relative to the flight file, if given.
    pub scene: Option<String>,
    /// Vertical field of view in degrees.
    pub fov: f64,
    /// The keys: time (seconds), position and target (geodesic coordinates in inradii).
    pub keys: Vec<(f64, DVec3, DVec3)>,
    /// Each key's point above the camera (`up`), where given (recorded walks give it, so
    /// the replay keeps the walker's roll).
    pub ups: Vec<Option<DVec3>>,
}

/// Parses a flight file's text; `file` names it in errors.
pub fn parse_flight(text: &str, file: &str) -> Result<FlightFile, String> {
    let spec: FlightSpec = toml::from_str(text).map_err(|e| format!("{file}: {e}"))?;
    let fail = |m: String| Err(format!("{file}: {m}"));
    match (&spec.space, &spec.scene) {
        (Some(_), Some(_)) => return fail("give either space or scene, not both".into()),
        (None, None) => return fail("name a space (space = \"…\") or a scene file".into()),
        _ => {}
    }
    let fov = spec.fov.unwrap_or(DEFAULT_FLIGHT_FOV);
    if !(fov > 0.0 && fov < 180.0) {
        return fail(format!("fov must be between 0 and 180 degrees, got {fov}"));
    }
    if spec.key.is_empty() {
        return fail("a flight needs at least one [[key]]".into());
    }
    if spec.key.len() > MAX_KEYS {
        return fail(format!(
            "{} keys are more than the limit of {MAX_KEYS}",
            spec.key.len()
        ));
    }
    let mut keys = Vec::with_capacity(spec.key.len());
    let mut ups = Vec::with_capacity(spec.key.len());
    let mut last = f64::NEG_INFINITY;
    for (i, k) in spec.key.iter().enumerate() {
        let n = i + 1;
        if !(k.time.is_finite() && (0.0..=MAX_FLIGHT_SECONDS).contains(&k.time)) {
            return fail(format!(
                "key {n}: time must be between 0 and {MAX_FLIGHT_SECONDS} seconds, got {}",
                k.time
            ));
        }
        if k.time <= last {
            return fail(format!(
                "key {n}: time {} does not come after the previous key's {last}",
                k.time
            ));
        }
        last = k.time;
        let (p, t) = (DVec3::from_array(k.position), DVec3::from_array(k.look_at));
        if !(p.is_finite() && t.is_finite()) {
            return fail(format!("key {n}: position and look_at must be finite"));
        }
        if (p - t).length() < 1e-9 {
            return fail(format!("key {n}: look_at is the position itself"));
        }
        let up = k.up.map(DVec3::from_array);
        if let Some(u) = up {
            if !u.is_finite() {
                return fail(format!("key {n}: up must be finite"));
            }
            if (u - p).length() < 1e-9 {
                return fail(format!("key {n}: up is the position itself"));
            }
        }
        keys.push((k.time, p, t));
        ups.push(up);
    }
    Ok(FlightFile {
        space: spec.space,
        scene: spec.scene,
        fov,
        keys,
        ups,
    })
}

/// A flight in a space: its keys as points of the universal cover.
#[derive(Clone, Debug)]
pub struct Flight {
    geometry: Geometry,
    /// Time, position and target of each key (model points).
    keys: Vec<(f64, DVec4, DVec4)>,
    /// Each key's point above the camera, where every key has one.
    ups: Option<Vec<DVec4>>,
    /// Vertical field of view in degrees.
    pub fov: f64,
}

/// The model point at geodesic coordinates `p` (in inradii) from the centre.
fn point_at(space: &Space, p: DVec3, what: &str) -> Result<DVec4, String> {
    let g = space.geometry();
    let d = p.length() * inradius_at_most(space, std::f64::consts::FRAC_PI_2);
    if g == Geometry::Spherical && d >= 0.999 * std::f64::consts::FRAC_PI_2 {
        return Err(format!(
            "{what} {:?} is π/2 or more from the centre, past the hemisphere a flight in S³ \
             keeps to",
            p.to_array()
        ));
    }
    let point = if d > 0.0 {
        g.translation(p, d) * space.centre()
    } else {
        space.centre()
    };
    if !point.is_finite() || (g == Geometry::Hyperbolic && g.to_chart(point).length() >= 1.0) {
        return Err(format!(
            "{what} {:?} is too far from the centre to be held in f64",
            p.to_array()
        ));
    }
    Ok(point)
}

impl Flight {
    /// The flight of a file's keys in `space`.
    pub fn new(space: &Space, file: &FlightFile) -> Result<Self, String> {
        let mut keys = Vec::with_capacity(file.keys.len());
        for (i, &(time, position, target)) in file.keys.iter().enumerate() {
            let p = point_at(space, position, &format!("key {}: position", i + 1))?;
            let t = point_at(space, target, &format!("key {}: look_at", i + 1))?;
            keys.push((time, p, t));
        }
        // Up points are used where every key has one (interpolated like the targets).
        let ups = if !file.ups.is_empty() && file.ups.iter().all(Option::is_some) {
            let mut ups = Vec::with_capacity(file.ups.len());
            for (i, u) in file.ups.iter().flatten().enumerate() {
                ups.push(point_at(space, *u, &format!("key {}: up", i + 1))?);
            }
            Some(ups)
        } else {
            None
        };
        Ok(Self {
            geometry: space.geometry(),
            keys,
            ups,
            fov: file.fov,
        })
    }

    /// The time of the last key: the flight's length in seconds.
    #[must_use]
    pub fn duration(&self) -> f64 {
        self.keys.last().map_or(0.0, |k| k.0)
    }

    /// How many frames the flight has at `fps`: one every `1/fps` seconds from 0, up to but
    /// not including the end (one at least).
    #[must_use]
    pub fn frame_count(&self, fps: f64) -> usize {
        ((self.duration() * fps).round() as usize).max(1)
    }

    /// The camera frame at time `t` in the universal cover (before wrapping).
    #[must_use]
    pub fn cover_frame(&self, t: f64) -> DMat4 {
        let g = self.geometry;
        let i = self.keys.partition_point(|k| k.0 <= t);
        let (p, target, up) = if i == 0 {
            (
                self.keys[0].1,
                self.keys[0].2,
                self.ups.as_ref().map(|u| u[0]),
            )
        } else if i == self.keys.len() {
            let k = self.keys[i - 1];
            (k.1, k.2, self.ups.as_ref().map(|u| u[i - 1]))
        } else {
            let (a, b) = (self.keys[i - 1], self.keys[i]);
            let s = (t - a.0) / (b.0 - a.0);
            (
                along(g, a.1, b.1, s),
                along(g, a.2, b.2, s),
                self.ups.as_ref().map(|u| along(g, u[i - 1], u[i], s)),
            )
        };
        if let Some(frame) = up.and_then(|u| frame_towards(g, p, target, u)) {
            return frame;
        }
        g.look_at(g.to_chart(p), g.to_chart(target), DVec3::Y)
            .or_else(|_| g.look_at(g.to_chart(p), g.to_chart(target), DVec3::X))
            .unwrap_or_else(|_| g.translation_to(p))
    }

    /// The camera frame at time `t` in the cell: the cover frame brought back through the
    /// faces it passed, turned by their pairings.
    #[must_use]
    pub fn frame(&self, space: &Space, t: f64) -> DMat4 {
        self.frame_and_crossings(space, t).0
    }

    /// [`Flight::frame`] with the faces the way from the first key's cell crossed, in order
    /// (the camera's holonomy).
    #[must_use]
    pub fn frame_and_crossings(&self, space: &Space, t: f64) -> (DMat4, Vec<usize>) {
        let (frame, crossed) = self.frame_in_cell(space, t);
        (frame, crossed.iter().map(|c| c.face).collect())
    }
}

impl CoverFlight for Flight {
    type Space = Space;

    fn duration(&self) -> f64 {
        Flight::duration(self)
    }

    fn cover_frame(&self, t: f64) -> DMat4 {
        Flight::cover_frame(self, t)
    }
}

/// The frame at `p` looking at `target` with its up towards the point `up` (right-handed):
/// `None` where up is along the view.
fn frame_towards(g: Geometry, p: DVec4, target: DVec4, up: DVec4) -> Option<DMat4> {
    let back = -g.tangent_towards(p, target);
    let u = g.tangent_towards(p, up);
    let u = u - g.form(u, back) * back;
    let n = g.form(u, u);
    if !(n > 1e-12) {
        return None;
    }
    Some(g.frame_from(p, u / n.sqrt(), back))
}

/// Geodesic coordinates in inradii of a point of the model (the inverse of a flight key's
/// and a scene file's `position`), for cells centred at the origin; `None` for other
/// cells, and in S³ for points π/2 or more from the centre.
#[must_use]
pub fn coordinates_of(space: &Space, x: DVec4) -> Option<DVec3> {
    let g = space.geometry();
    let centre = space.centre();
    if (centre - crate::geometry::ORIGIN).abs().max_element() > 1e-12 {
        return None;
    }
    let x = g.project_point(x);
    let d = g.distance(crate::geometry::ORIGIN, x);
    if g == Geometry::Spherical && d >= 0.999 * std::f64::consts::FRAC_PI_2 {
        return None;
    }
    let scale = inradius_at_most(space, std::f64::consts::FRAC_PI_2);
    let dir = x.truncate().normalize_or_zero();
    Some(dir * (d / scale))
}

/// The point a fraction `s` of the way along the geodesic from `a` to `b`.
fn along(g: Geometry, a: DVec4, b: DVec4, s: f64) -> DVec4 {
    let d = g.distance(a, b);
    if d < 1e-12 {
        return a;
    }
    let v = g.tangent_towards(a, b);
    g.project_point(g.geodesic(a, v, s * d).0)
}

/// The largest flight file read (bytes).
pub const MAX_FLIGHT_FILE_BYTES: u64 = 16 << 20;

/// Reads and parses a flight file.
pub fn load_flight_file(path: &std::path::Path) -> Result<FlightFile, String> {
    let name = path.display().to_string();
    let text = crate::files::read_text(path, MAX_FLIGHT_FILE_BYTES)
        .map_err(|e| format!("cannot read flight file {name}: {e}"))?;
    parse_flight(&text, &name)
}

/// Where a recorded flight's space comes from: a space's id or path, or a scene file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FlightSource {
    /// `space = "…"`.
    Space(String),
    /// `scene = "…"` (written as given; make it absolute, or relative to the flight file).
    Scene(String),
}

/// A flight file's text: the source, the field of view and the keys (time, position,
/// look_at, up, in geodesic coordinates in inradii), as [`parse_flight`] reads it back.
#[must_use]
pub fn flight_text(source: &FlightSource, fov: f64, keys: &[(f64, DVec3, DVec3, DVec3)]) -> String {
    use std::fmt::Write as _;
    let mut out = String::from(
        "# A recorded walk (curved-spaces walk --record): replay it with\n\
         #   curved-spaces walk --replay FILE, or render it with curved-spaces flight FILE\n",
    );
    let quoted = |s: &str| toml::Value::String(s.to_string()).to_string();
    match source {
        FlightSource::Space(id) => {
            let _ = writeln!(out, "space = {}", quoted(id));
        }
        FlightSource::Scene(path) => {
            let _ = writeln!(out, "scene = {}", quoted(path));
        }
    }
    let _ = writeln!(out, "fov = {fov}");
    let v = |x: DVec3| format!("[{:?}, {:?}, {:?}]", x.x, x.y, x.z);
    for (t, p, look, up) in keys {
        let _ = write!(
            out,
            "\n[[key]]\ntime = {t:?}\nposition = {}\nlook_at = {}\nup = {}\n",
            v(*p),
            v(*look),
            v(*up)
        );
    }
    out
}

/// The key of a camera at `frame` inside the cell that reached it through `holonomy`: its
/// position, a point it looks at and a point above it, carried back into the universal cover
/// (`F_now = H · F_cover`) as geodesic coordinates in inradii; `None` where a flight file
/// cannot hold them (in S³ beyond the hemisphere about the centre).
#[must_use]
pub fn recorded_key(
    space: &Space,
    frame: DMat4,
    holonomy: &Holonomy,
) -> Option<(DVec3, DVec3, DVec3)> {
    let g = space.geometry();
    let cover = g.inverse(holonomy.matrix) * frame;
    let r = 0.5 * inradius_at_most(space, std::f64::consts::FRAC_PI_4);
    let at = |local: DMat4| coordinates_of(space, g.project_point((cover * local).w_axis));
    Some((
        at(DMat4::IDENTITY)?,
        at(g.translation(DVec3::NEG_Z, r))?,
        at(g.translation(DVec3::Y, r))?,
    ))
}
