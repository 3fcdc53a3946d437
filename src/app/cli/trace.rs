//! `trace`: one geodesic walked through the cell, its face crossings printed as they happen.
//!
//! The walk and its printing are written once over the walk contract ([`CellWalk`]); each
//! geometry family says only how its faces and points read ([`TraceFamily`]).

use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::geometry::{Geometry, Ray, Vector4};
use bevy_curved_spaces::space::product::ProductSpace;
use bevy_curved_spaces::space::{CellWalk, Crossing, FamilySpace, Limit, Space};
use glam::{DVec4, Vec4};
use serde_json::{Map, Value, json};

/// How a family's faces and points read in `trace`'s output.
trait TraceFamily {
    /// The column heading of the points.
    fn point_heading(&self) -> &'static str;
    /// What the JSON says of the face a crossing left through.
    fn face_json(&self, face: usize) -> (&'static str, Value);
    /// The face a crossing left through, for the text table.
    fn face_text(&self, face: usize) -> String;
    /// A point: its chart point where it has one, else the model point and why.
    fn point_json(&self, p: DVec4) -> Map<String, Value>;
    /// A point for the text output.
    fn point_text(&self, p: DVec4) -> String;
    /// What the end adds besides its point (the direction where the chart shows it).
    fn end_json(&self, end: &Ray<DVec4>) -> Map<String, Value>;
    /// The JSON's fields before the crossings.
    fn header_json(&self) -> Map<String, Value> {
        Map::new()
    }
    /// The cell a crossing through `face` enters, in a space of several cells.
    fn entered_cell(&self, face: usize) -> Option<usize> {
        let _ = face;
        None
    }
}

/// A constant-curvature space: faces by their outward chart normals, points in the chart
/// (in S³ only the hemisphere `w > 0`: past it, the model point with the reason).
struct ConstantFamily<'a>(&'a Space);

/// Why a point of S³ has no chart point: the gnomonic chart shows the hemisphere `w > 0`.
const OFF_CHART_S3: &str = "the point lies on or past the equator w = 0 of S³, where the \
                            gnomonic chart x/w, y/w, z/w cannot show it: the model point \
                            [x, y, z, w] gives it";

impl ConstantFamily<'_> {
    fn chart(&self, p: DVec4) -> Option<[f64; 3]> {
        let g = self.0.geometry();
        let c = g.to_chart(p).to_array();
        (g != Geometry::Spherical || p.w > 0.0 && c.iter().all(|x| x.is_finite())).then_some(c)
    }
}

impl TraceFamily for ConstantFamily<'_> {
    fn point_heading(&self) -> &'static str {
        "entry point (chart)"
    }
    fn face_json(&self, face: usize) -> (&'static str, Value) {
        ("face_normal", json!(self.0.faces()[face].normal.to_array()))
    }
    fn face_text(&self, face: usize) -> String {
        match self.entered_cell(face) {
            Some(cell) => format!("{face}→{cell}"),
            None => face.to_string(),
        }
    }
    fn entered_cell(&self, face: usize) -> Option<usize> {
        let faces = self.0.faces();
        (self.0.cells().len() > 1).then(|| faces[faces[face].partner].cell)
    }
    fn point_json(&self, p: DVec4) -> Map<String, Value> {
        let mut m = Map::new();
        match self.chart(p) {
            Some(c) => m.insert("point".into(), json!(c)),
            None => {
                m.insert("off_chart".into(), json!(OFF_CHART_S3));
                m.insert("model".into(), json!(p.to_array()))
            }
        };
        m
    }
    fn point_text(&self, p: DVec4) -> String {
        match self.chart(p) {
            Some(c) => format!("({:+.15}, {:+.15}, {:+.15})", c[0], c[1], c[2]),
            None => format!(
                "past the chart (w <= 0): model (x, y, z, w) = ({:+.15}, {:+.15}, {:+.15}, {:+.15})",
                p.x, p.y, p.z, p.w
            ),
        }
    }
    fn end_json(&self, end: &Ray<DVec4>) -> Map<String, Value> {
        let mut m = Map::new();
        if self.chart(end.point).is_some() {
            let d = self.0.geometry().chart_direction(end.point, end.tangent);
            m.insert("direction".into(), json!(d.to_array()));
        } else {
            m.insert("tangent".into(), json!(end.tangent.to_array()));
        }
        m
    }
}

/// A Nil space: faces by their planes, points in the chart, the end's direction the unit
/// body velocity in the frame `E₁, E₂, E₃`.
struct NilFamily;

impl TraceFamily for NilFamily {
    fn point_heading(&self) -> &'static str {
        "entry point (chart)"
    }
    fn face_json(&self, face: usize) -> (&'static str, Value) {
        ("face", json!(self.face_text(face)))
    }
    fn face_text(&self, face: usize) -> String {
        [
            "x = +1/2", "x = -1/2", "y = +1/2", "y = -1/2", "top", "bottom",
        ]
        .get(face)
        .map_or_else(|| face.to_string(), |s| (*s).to_string())
    }
    fn point_json(&self, p: DVec4) -> Map<String, Value> {
        let mut m = Map::new();
        m.insert("point".into(), json!([p.x, p.y, p.z]));
        m
    }
    fn point_text(&self, p: DVec4) -> String {
        format!("({:+.15}, {:+.15}, {:+.15})", p.x, p.y, p.z)
    }
    fn end_json(&self, end: &Ray<DVec4>) -> Map<String, Value> {
        let mut m = Map::new();
        m.insert("direction".into(), json!(end.tangent.truncate().to_array()));
        m
    }
}

/// An SL̃(2,R) space: faces by side, points as the base point `[x, y, w]` on the
/// hyperboloid; the end adds the whole model point `[p, e]` and the body direction.
struct Sl2rFamily<'a>(&'a bevy_curved_spaces::space::sl2r::UnitTangentSpace);

impl TraceFamily for Sl2rFamily<'_> {
    fn point_heading(&self) -> &'static str {
        "entry base point (hyperboloid)"
    }
    fn face_json(&self, face: usize) -> (&'static str, Value) {
        ("side", json!(face))
    }
    fn face_text(&self, face: usize) -> String {
        format!("side {face}")
    }
    // A walk's point packs (p_x, p_y, sheet, e_x): the base point's w is derived.
    fn point_json(&self, p: DVec4) -> Map<String, Value> {
        let mut m = Map::new();
        let w = (1.0 + p.x * p.x + p.y * p.y).sqrt();
        m.insert("base_point".into(), json!([p.x, p.y, w]));
        if self.0.sheets() > 1 {
            m.insert("sheet".into(), json!(p.z.round()));
        }
        m
    }
    fn point_text(&self, p: DVec4) -> String {
        let w = (1.0 + p.x * p.x + p.y * p.y).sqrt();
        let sheet = if self.0.sheets() > 1 {
            format!(" on sheet {}", p.z.round())
        } else {
            String::new()
        };
        format!("({:+.15}, {:+.15}, {:+.15}){sheet}", p.x, p.y, w)
    }
    fn end_json(&self, end: &Ray<DVec4>) -> Map<String, Value> {
        use bevy_curved_spaces::space::sl2r::Sl2rWalker;
        let r = Sl2rWalker::<DVec4>::sl2r_ray(end);
        let [e, _, p] = r.frame;
        let mut m = Map::new();
        m.insert("model".into(), json!([p[0], p[1], p[2], e[0], e[1], e[2]]));
        m.insert("direction".into(), json!(r.velocity));
        if self.0.sheets() > 1 {
            m.insert("sheet".into(), json!(Sl2rWalker::<DVec4>::sheet_of(end)));
        }
        m
    }
}

/// A product space (H²×R, S²×R): faces by name (`side k`, `top`, `bottom`), points as the
/// chart point `(x/w, y/w, z)` beside the model point `[x, y, w, z]`.
struct ProductFamily<'a>(&'a ProductSpace);

/// Why a product point has no chart point (see [`product_chart`]).
const OFF_CHART: &str = "the base point lies on or past the sphere's equator (w <= 0), where \
                         the chart x/w, y/w (one hemisphere) cannot show it: the model point \
                         gives it";

/// The gnomonic chart point `(x/w, y/w, z)` of a product's model point, or `None` for a
/// base point on or past the sphere's equator (`w ≤ 0`), which the chart cannot show: the
/// projective plane's cell reaches the equator (its gluing maps an equator point to its
/// antipode), and the whole sphere's cell goes past it.
fn product_chart(p: DVec4) -> Option<[f64; 3]> {
    let c = [p.x / p.w, p.y / p.w, p.z];
    (p.w > 0.0 && c.iter().all(|x| x.is_finite())).then_some(c)
}

impl TraceFamily for ProductFamily<'_> {
    fn point_heading(&self) -> &'static str {
        "entry point (chart x/w, y/w, z)"
    }
    fn face_json(&self, face: usize) -> (&'static str, Value) {
        ("face", json!(self.face_text(face)))
    }
    fn face_text(&self, face: usize) -> String {
        let sides = self.0.face_count() - 2;
        match face {
            f if f == sides => "top".to_string(),
            f if f == sides + 1 => "bottom".to_string(),
            f => format!("side {f}"),
        }
    }
    fn point_json(&self, p: DVec4) -> Map<String, Value> {
        let mut m = Map::new();
        match product_chart(p) {
            Some(c) => m.insert("point".into(), json!(c)),
            None => m.insert("off_chart".into(), json!(OFF_CHART)),
        };
        m.insert("model".into(), json!([p.x, p.y, p.w, p.z]));
        m
    }
    fn point_text(&self, p: DVec4) -> String {
        match product_chart(p) {
            Some(c) => format!("({:+.15}, {:+.15}, {:+.15})", c[0], c[1], c[2]),
            None => format!(
                "past the chart (w <= 0): model (x, y, w, z) = ({:+.15}, {:+.15}, {:+.15}, {:+.15})",
                p.x, p.y, p.w, p.z
            ),
        }
    }
    fn end_json(&self, _: &Ray<DVec4>) -> Map<String, Value> {
        Map::new()
    }
    fn header_json(&self) -> Map<String, Value> {
        let mut m = Map::new();
        m.insert("space".into(), json!(self.0.name()));
        m.insert("geometry".into(), json!(self.0.geometry_name()));
        m
    }
}

/// The walk's limit from `--crossings`/`--distance`, once the start (`outside` by so much)
/// is known to lie in the cell of `name`.
fn start_and_limit(args: &TraceArgs, outside: f64, name: &str) -> Result<Limit, String> {
    // NaN (a point the model cannot hold) is outside too.
    if !(outside <= 1e-12) {
        return Err(format!(
            "start point {:?} is outside the cell of {name}",
            args.from.to_array()
        ));
    }
    match (args.crossings, args.distance) {
        (Some(n), _) => Ok(Limit::Crossings(n)),
        (None, Some(d)) => Ok(Limit::Distance(d)),
        (None, None) => Err("give --crossings N or --distance D".into()),
    }
}

/// What a walk that ended short of its limit says: the geodesic meets no face again.
fn ended_early(limit: Limit, crossed: usize, distance: f64) -> Option<String> {
    match limit {
        Limit::Crossings(n) if crossed < n => {
            let after = if crossed == 0 {
                "meets no face at all".to_string()
            } else {
                format!("meets no face after its {crossed} crossings (at distance {distance})")
            };
            Some(format!(
                "asked for {n} crossings, but the geodesic {after}: it stays inside the cell \
                 for ever"
            ))
        }
        _ => None,
    }
}

/// Walks `start` in the precision `V` with `walker`, printing each crossing as it happens
/// (any length runs in constant memory; the JSON is written piece by piece), then the end
/// and, where the walk stopped short, why. A walk by distance stops after [`MAX_WALK`]
/// crossings, and any walk where the distance walked passes f64.
fn stream<V: Vector4, W: CellWalk<V>>(
    walker: &W,
    family: &dyn TraceFamily,
    start: Ray<DVec4>,
    limit: Limit,
    json_out: bool,
) -> Result<(), String> {
    let to_f64 = |r: Ray<V>| Ray {
        point: r.point.to_f64(),
        tangent: r.tangent.to_f64(),
    };
    let mut pending: Option<String> = None;
    let mut count = 0usize;
    let (mut capped, mut overflowed) = (false, false);
    let mut last = (start, 0.0);
    if json_out {
        say!("{{");
        for (k, v) in family.header_json() {
            say!("  {}: {v},", json!(k));
        }
        say!("  \"crossings\": [");
    } else {
        say!(
            "{:>5} {:>8} {:>20}  {}",
            "#",
            family.entered_cell(0).map_or("face", |_| "face→cell"),
            "distance",
            family.point_heading()
        );
    }
    let walked_start = Ray {
        point: V::from_f64(start.point),
        tangent: V::from_f64(start.tangent),
    };
    let (end, distance) = walker.walk(walked_start, limit, |c: &Crossing<V>| {
        if !c.distance.is_finite() {
            overflowed = true;
            return false;
        }
        let ray = to_f64(c.ray);
        last = (ray, c.distance);
        count += 1;
        if json_out {
            let mut item = family.point_json(ray.point);
            let (key, face) = family.face_json(c.face);
            item.insert(key.into(), face);
            if let Some(cell) = family.entered_cell(c.face) {
                item.insert("cell".into(), json!(cell));
            }
            item.insert("distance".into(), json!(c.distance));
            if let Some(previous) = pending.replace(Value::Object(item).to_string()) {
                say!("    {previous},");
            }
        } else {
            say!(
                "{:>5} {:>8} {:>20.15}  {}",
                count,
                family.face_text(c.face),
                c.distance,
                family.point_text(ray.point)
            );
        }
        if count >= MAX_WALK && matches!(limit, Limit::Distance(_)) {
            capped = true;
            return false;
        }
        true
    });
    let stopped = if capped {
        Some(format!(
            "reaching distance {} needs more than {MAX_WALK} crossings, the most `trace` walks: \
             stopped at distance {distance}",
            match limit {
                Limit::Distance(d) => d,
                Limit::Crossings(_) => distance,
            }
        ))
    } else if overflowed {
        Some(format!(
            "the distance to crossing {} is larger than f64 can hold (1.8e308): stopped after \
             {count} crossings",
            count + 1
        ))
    } else {
        ended_early(limit, count, distance)
    };
    // The end of a walk whose distance overflowed is its last crossing.
    let (end, distance) = if overflowed {
        last
    } else {
        (to_f64(end), distance)
    };
    if json_out {
        if let Some(item) = pending.take() {
            say!("    {item}");
        }
        let mut out = family.point_json(end.point);
        out.extend(family.end_json(&end));
        out.insert("distance".into(), json!(distance));
        if let Some(s) = &stopped {
            out.insert("stopped".into(), json!(s));
        }
        say!("  ],\n  \"end\": {}\n}}", Value::Object(out));
    } else {
        say!(
            "end at distance {:.15}: {}",
            distance,
            family.point_text(end.point)
        );
    }
    match stopped {
        Some(s) => Err(s),
        None => Ok(()),
    }
}

/// `trace` in the space `space` of any family: the start from the family's chart, the walk
/// by the family's walker in the precision `--precision` asks for ([`FamilySpace::walker`]),
/// printed as `family` reads points and faces.
fn trace_in<S: FamilySpace>(
    args: &TraceArgs,
    space: &S,
    name: &str,
    family: &dyn TraceFamily,
) -> Result<(), String> {
    let start = space.chart_ray(args.from, args.dir)?;
    let limit = start_and_limit(args, space.outside_by(start.point), name)?;
    match args.precision {
        Precision::F64 => stream(&space.walker::<DVec4>(), family, start, limit, args.json),
        Precision::F32 => stream(&space.walker::<Vec4>(), family, start, limit, args.json),
    }
}

pub(super) fn trace(args: &TraceArgs) -> Result<(), String> {
    match space_named(&args.space)? {
        AnySpace::Constant(space) => trace_in(args, &*space, space.name(), &ConstantFamily(&space)),
        AnySpace::Product(space) => trace_in(args, &*space, space.name(), &ProductFamily(&space)),
        AnySpace::Nil(space) => trace_in(args, &*space, space.name(), &NilFamily),
        AnySpace::Sl2r(space) => trace_in(args, &*space, space.name(), &Sl2rFamily(&space)),
    }
}
