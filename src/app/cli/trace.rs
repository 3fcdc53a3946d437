//! `trace`: one geodesic walked through the cell, its face crossings printed.

use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::geometry::{Geometry, Ray, Vector4, chart_ray};
use bevy_curved_spaces::space::product::{ProductSpace, ProductWalker};
use bevy_curved_spaces::space::{CellWalker, Crossing, Limit, Space};
use glam::{DVec4, Vec4};
use serde_json::json;

/// Walks the ray in precision `V`, handing each crossing (in f64) to `visit` as it
/// happens; stops after [`MAX_WALK`] crossings whatever the limit. Returns the end, the
/// distance, and whether the crossing cap stopped a distance-limited walk early.
fn stream<V: Vector4>(
    space: &Space,
    start: Ray<DVec4>,
    limit: Limit,
    mut visit: impl FnMut(&Crossing<DVec4>) -> bool,
) -> (Ray<DVec4>, f64, bool) {
    let walker = CellWalker::<V>::new(space);
    let to_f64 = |r: Ray<V>| Ray {
        point: r.point.to_f64(),
        tangent: r.tangent.to_f64(),
    };
    let start = Ray {
        point: V::from_f64(start.point),
        tangent: V::from_f64(start.tangent),
    };
    let mut count = 0usize;
    let mut capped = false;
    let (end, distance) = walker.walk(start, limit, |c| {
        count += 1;
        let keep_on = visit(&Crossing {
            face: c.face,
            distance: c.distance,
            ray: to_f64(c.ray),
        });
        if count >= MAX_WALK && matches!(limit, Limit::Distance(_)) {
            capped = true;
            return false;
        }
        keep_on
    });
    (to_f64(end), distance, capped)
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

/// The gnomonic chart point `(x/w, y/w, z)` of a product's model point, or `None` for a
/// base point on or past the sphere's equator (`w ≤ 0`), which the chart cannot show: the
/// projective plane's cell reaches the equator (its gluing maps an equator point to its
/// antipode), and the whole sphere's cell goes past it.
fn product_chart(p: DVec4) -> Option<[f64; 3]> {
    let c = [p.x / p.w, p.y / p.w, p.z];
    (p.w > 0.0 && c.iter().all(|x| x.is_finite())).then_some(c)
}

/// Why a point of S³ has no chart point: the gnomonic chart shows the hemisphere `w > 0`.
const OFF_CHART_S3: &str = "the point lies on or past the equator w = 0 of S³, where the \
                            gnomonic chart x/w, y/w, z/w cannot show it: the model point \
                            [x, y, z, w] gives it";

/// Why a product point has no chart point (see [`product_chart`]).
const OFF_CHART: &str = "the base point lies on or past the sphere's equator (w <= 0), where \
                         the chart x/w, y/w (one hemisphere) cannot show it: the model point \
                         gives it";

/// The JSON of a product point: its chart point where it has one, else the reason, and its
/// model point `[x, y, w, z]`.
fn product_point_json(p: DVec4) -> serde_json::Map<String, serde_json::Value> {
    let mut m = serde_json::Map::new();
    match product_chart(p) {
        Some(c) => m.insert("point".into(), json!(c)),
        None => m.insert("off_chart".into(), json!(OFF_CHART)),
    };
    m.insert("model".into(), json!([p.x, p.y, p.w, p.z]));
    m
}

/// A product point for the text output.
fn product_point_text(p: DVec4) -> String {
    match product_chart(p) {
        Some(c) => format!("({:+.15}, {:+.15}, {:+.15})", c[0], c[1], c[2]),
        None => format!(
            "past the chart (w <= 0): model (x, y, w, z) = ({:+.15}, {:+.15}, {:+.15}, {:+.15})",
            p.x, p.y, p.w, p.z
        ),
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
                 for ever, going round a closed geodesic"
            ))
        }
        _ => None,
    }
}

/// `trace` through a product space (H²×R, S²×R): each crossing's face (a side, `top` or
/// `bottom`), distance, chart point `(x/w, y/w, z)` and model point `[x, y, w, z]`, printed
/// as it is walked (any length runs in constant memory).
fn trace_product(args: &TraceArgs, space: &ProductSpace) -> Result<(), String> {
    let start = bevy_curved_spaces::space::product::chart_ray(space.base(), args.from, args.dir)?;
    let limit = start_and_limit(args, space.outside_by(start.point), space.name())?;
    let sides = space.face_count() - 2;
    let face_name = |f: usize| match f {
        f if f == sides => "top".to_string(),
        f if f == sides + 1 => "bottom".to_string(),
        f => format!("side {f}"),
    };
    let mut pending: Option<String> = None;
    let mut count = 0usize;
    let mut capped = false;
    let mut overflowed = false;
    let mut last = (start.point, 0.0);
    let mut visit = |face: usize, distance: f64, p: DVec4| {
        if !distance.is_finite() {
            overflowed = true;
            return false;
        }
        last = (p, distance);
        count += 1;
        if args.json {
            let mut item = serde_json::Map::new();
            item.insert("face".into(), json!(face_name(face)));
            item.insert("distance".into(), json!(distance));
            item.extend(product_point_json(p));
            let item = serde_json::Value::Object(item).to_string();
            if let Some(previous) = pending.replace(item) {
                say!("    {previous},");
            }
        } else {
            say!(
                "{:>5} {:>8} {:>20.15}  {}",
                count,
                face_name(face),
                distance,
                product_point_text(p)
            );
        }
        if count >= MAX_WALK && matches!(limit, Limit::Distance(_)) {
            capped = true;
            return false;
        }
        true
    };
    if args.json {
        say!("{{\n  \"space\": {},", json!(space.name()));
        say!("  \"geometry\": {},", json!(space.geometry_name()));
        say!("  \"crossings\": [");
    } else {
        say!(
            "{:>5} {:>8} {:>20}  entry point (chart x/w, y/w, z)",
            "#",
            "face",
            "distance"
        );
    }
    let (end, distance) = match args.precision {
        Precision::F64 => {
            let w = ProductWalker::<DVec4>::new(space);
            let (end, d) = w.walk(start, limit, |c| visit(c.face, c.distance, c.ray.point));
            (end.point, d)
        }
        Precision::F32 => {
            let w = ProductWalker::<Vec4>::new(space);
            let start = Ray {
                point: Vec4::from_f64(start.point),
                tangent: Vec4::from_f64(start.tangent),
            };
            let (end, d) = w.walk(start, limit, |c| {
                visit(c.face, c.distance, c.ray.point.to_f64())
            });
            (end.point.to_f64(), d)
        }
    };
    let stopped = if capped {
        Some(format!(
            "reaching distance {} needs more than {MAX_WALK} crossings, the most `trace` walks: \
             stopped at distance {distance}",
            args.distance.unwrap_or(distance)
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
    // The end of a walk whose distance overflowed is the last crossing's.
    let (end, distance) = if overflowed {
        (last.0, last.1)
    } else {
        (end, distance)
    };
    if args.json {
        if let Some(last) = pending.take() {
            say!("    {last}");
        }
        let mut end = product_point_json(end);
        end.insert("distance".into(), json!(distance));
        if let Some(s) = &stopped {
            end.insert("stopped".into(), json!(s));
        }
        say!("  ],\n  \"end\": {}\n}}", serde_json::Value::Object(end));
    } else {
        say!(
            "end at distance {:.15}: {}",
            distance,
            product_point_text(end)
        );
    }
    match stopped {
        Some(s) => Err(s),
        None => Ok(()),
    }
}

pub(super) fn trace(args: &TraceArgs) -> Result<(), String> {
    if let Some(p) = product(&args.space)? {
        return trace_product(args, &p);
    }
    let space = resolve_space(&args.space)?;
    let g = space.geometry();
    let start = chart_ray(g, args.from, args.dir).map_err(|e| e.to_string())?;
    let limit = start_and_limit(args, space.outside_by(start.point), space.name())?;
    // A spherical cell that reaches the equator goes past the gnomonic chart: such points
    // are given in the model, with the reason.
    let chart = |p: DVec4| {
        let c = g.to_chart(p).to_array();
        (g != Geometry::Spherical || p.w > 0.0 && c.iter().all(|x| x.is_finite())).then_some(c)
    };
    let point_json = |p: DVec4| {
        let mut m = serde_json::Map::new();
        match chart(p) {
            Some(c) => m.insert("point".into(), json!(c)),
            None => {
                m.insert("off_chart".into(), json!(OFF_CHART_S3));
                m.insert("model".into(), json!(p.to_array()))
            }
        };
        m
    };
    let point_text = |p: DVec4| match chart(p) {
        Some(c) => format!("({:+.15}, {:+.15}, {:+.15})", c[0], c[1], c[2]),
        None => format!(
            "past the chart (w <= 0): model (x, y, z, w) = ({:+.15}, {:+.15}, {:+.15}, {:+.15})",
            p.x, p.y, p.z, p.w
        ),
    };
    // Each crossing is printed as it is walked: any length runs in constant memory, and
    // the JSON is written piece by piece (an array, then the end).
    // The JSON item before the current one: it gets its comma once another follows.
    let mut pending: Option<String> = None;
    let mut index = 0usize;
    let mut print = |c: &Crossing<DVec4>| {
        index += 1;
        if args.json {
            let mut item = point_json(c.ray.point);
            item.insert(
                "face_normal".into(),
                json!(space.faces()[c.face].normal.to_array()),
            );
            item.insert("distance".into(), json!(c.distance));
            if let Some(previous) = pending.replace(serde_json::Value::Object(item).to_string()) {
                say!("    {previous},");
            }
        } else {
            say!(
                "{:>5} {:>5} {:>20.15}  {}",
                index,
                c.face,
                c.distance,
                point_text(c.ray.point)
            );
        }
        true
    };
    if args.json {
        say!("{{\n  \"crossings\": [");
    } else {
        say!(
            "{:>5} {:>5} {:>20}  entry point (chart)",
            "#",
            "face",
            "distance"
        );
    }
    let (end, distance, capped) = match args.precision {
        Precision::F64 => stream::<DVec4>(&space, start, limit, &mut print),
        Precision::F32 => stream::<Vec4>(&space, start, limit, &mut print),
    };
    let stopped = if capped {
        Some(format!(
            "reaching distance {} needs more than {MAX_WALK} crossings, the most `trace` walks: \
             stopped at distance {distance}",
            args.distance.unwrap_or(distance)
        ))
    } else {
        ended_early(limit, index, distance)
    };
    if args.json {
        if let Some(last) = pending.take() {
            say!("    {last}");
        }
        let mut out = point_json(end.point);
        if chart(end.point).is_some() {
            out.insert(
                "direction".into(),
                json!(g.chart_direction(end.point, end.tangent).to_array()),
            );
        } else {
            out.insert("tangent".into(), json!(end.tangent.to_array()));
        }
        out.insert("distance".into(), json!(distance));
        if let Some(s) = &stopped {
            out.insert("stopped".into(), json!(s));
        }
        say!("  ],\n  \"end\": {}\n}}", serde_json::Value::Object(out));
    } else {
        say!(
            "end at distance {:.15}: {}",
            distance,
            point_text(end.point)
        );
    }
    match stopped {
        Some(s) => Err(s),
        None => Ok(()),
    }
}
