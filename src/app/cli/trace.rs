//! `trace`: one geodesic walked through the cell, its face crossings printed.

use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::geometry::{Ray, Vector4, chart_ray};
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
    if outside > 1e-12 {
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

/// `trace` through a product space (H²×R, S²×R): each crossing's face (a side, `top` or
/// `bottom`), distance, chart point `(x/w, y/w, z)` and model point `[x, y, w, z]`.
fn trace_product(args: &TraceArgs, space: &ProductSpace) -> Result<(), String> {
    let start = bevy_curved_spaces::space::product::chart_ray(space.base(), args.from, args.dir)?;
    let limit = match start_and_limit(args, space.outside_by(start.point), space.name())? {
        Limit::Crossings(n) => Limit::Crossings(n.min(MAX_WALK)),
        other => other,
    };
    let sides = space.face_count() - 2;
    let face_name = |f: usize| match f {
        f if f == sides => "top".to_string(),
        f if f == sides + 1 => "bottom".to_string(),
        f => format!("side {f}"),
    };
    let chart = |p: DVec4| [p.x / p.w, p.y / p.w, p.z];
    let model = |p: DVec4| [p.x, p.y, p.w, p.z];
    let mut rows = Vec::new();
    let mut capped = false;
    let mut visit = |face: usize, distance: f64, p: DVec4| {
        rows.push((face, distance, p));
        if rows.len() >= MAX_WALK {
            capped = true;
            return false;
        }
        true
    };
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
    if args.json {
        let crossings: Vec<serde_json::Value> = rows
            .iter()
            .map(|&(f, d, p)| {
                json!({"face": face_name(f), "distance": d, "point": chart(p), "model": model(p)})
            })
            .collect();
        let out = json!({
            "space": space.name(),
            "geometry": space.geometry_name(),
            "crossings": crossings,
            "end": {"point": chart(end), "model": model(end), "distance": distance},
        });
        say!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
    } else {
        say!(
            "{:>5} {:>8} {:>20}  entry point (chart x/w, y/w, z)",
            "#",
            "face",
            "distance"
        );
        for (i, &(f, d, p)) in rows.iter().enumerate() {
            let c = chart(p);
            say!(
                "{:>5} {:>8} {:>20.15}  ({:+.15}, {:+.15}, {:+.15})",
                i + 1,
                face_name(f),
                d,
                c[0],
                c[1],
                c[2]
            );
        }
        let c = chart(end);
        say!(
            "end at distance {:.15}: ({:+.15}, {:+.15}, {:+.15})",
            distance,
            c[0],
            c[1],
            c[2]
        );
    }
    if capped {
        return Err(format!(
            "stopped after {MAX_WALK} crossings, the most `trace` walks"
        ));
    }
    Ok(())
}

pub(super) fn trace(args: &TraceArgs) -> Result<(), String> {
    if let Some(p) = product(&args.space)? {
        return trace_product(args, &p);
    }
    let space = resolve_space(&args.space)?;
    let g = space.geometry();
    let start = chart_ray(g, args.from, args.dir).map_err(|e| e.to_string())?;
    let limit = start_and_limit(args, space.outside_by(start.point), space.name())?;
    let chart = |p: DVec4| g.to_chart(p).to_array();
    // Each crossing is printed as it is walked: any length runs in constant memory, and
    // the JSON is written piece by piece (an array, then the end).
    // The JSON item before the current one: it gets its comma once another follows.
    let mut pending: Option<String> = None;
    let mut index = 0usize;
    let mut print = |c: &Crossing<DVec4>| {
        index += 1;
        if args.json {
            let item = json!({
                "face_normal": space.faces()[c.face].normal.to_array(),
                "distance": c.distance,
                "point": chart(c.ray.point),
            });
            if let Some(previous) = pending.replace(item.to_string()) {
                say!("    {previous},");
            }
        } else {
            let p = chart(c.ray.point);
            say!(
                "{:>5} {:>5} {:>20.15}  ({:+.15}, {:+.15}, {:+.15})",
                index,
                c.face,
                c.distance,
                p[0],
                p[1],
                p[2]
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
    let stopped = capped.then(|| {
        format!(
            "reaching distance {} needs more than {MAX_WALK} crossings, the most `trace` walks: \
             stopped at distance {distance}",
            args.distance.unwrap_or(distance)
        )
    });
    if args.json {
        if let Some(last) = pending.take() {
            say!("    {last}");
        }
        let mut end = json!({
            "point": chart(end.point),
            "direction": g.chart_direction(end.point, end.tangent).to_array(),
            "distance": distance,
        });
        if let Some(s) = &stopped {
            end["stopped"] = json!(s);
        }
        say!("  ],\n  \"end\": {end}\n}}");
    } else {
        let p = chart(end.point);
        say!(
            "end at distance {:.15}: ({:+.15}, {:+.15}, {:+.15})",
            distance,
            p[0],
            p[1],
            p[2]
        );
    }
    match stopped {
        Some(s) => Err(s),
        None => Ok(()),
    }
}
