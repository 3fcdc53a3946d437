//! `trace`: one geodesic walked through the cell, its face crossings printed.

use super::*;
use bevy::prelude::*;
use bevy_curved_spaces::geometry::Vector4;
use bevy_curved_spaces::geometry::chart_ray;
use bevy_curved_spaces::space::Space;
use bevy_curved_spaces::space::{CellWalker, Limit, Trace};
use glam::{DVec4, Vec4};
use serde_json::json;

/// The trace in f64 whatever precision it ran in.
pub(super) fn trace_f64<V: Vector4>(
    space: &Space,
    start: DVec4,
    dir: DVec4,
    limit: Limit,
) -> Trace<DVec4> {
    let walker = CellWalker::<V>::new(space);
    let start = bevy_curved_spaces::geometry::Ray {
        point: V::from_f64(start),
        tangent: V::from_f64(dir),
    };
    let t = walker.trace(start, limit);
    let ray = |r: bevy_curved_spaces::geometry::Ray<V>| bevy_curved_spaces::geometry::Ray {
        point: r.point.to_f64(),
        tangent: r.tangent.to_f64(),
    };
    Trace {
        crossings: t
            .crossings
            .iter()
            .map(|c| bevy_curved_spaces::space::Crossing {
                face: c.face,
                distance: c.distance,
                ray: ray(c.ray),
            })
            .collect(),
        end: ray(t.end),
        distance: t.distance,
    }
}

pub(super) fn trace(args: &TraceArgs) -> Result<(), String> {
    let space = resolve_space(&args.space)?;
    let g = space.geometry();
    let start = chart_ray(g, args.from, args.dir).map_err(|e| e.to_string())?;
    if space.outside_by(start.point) > 1e-12 {
        return Err(format!(
            "start point {:?} is outside the cell of {}",
            args.from.to_array(),
            space.name()
        ));
    }
    let limit = match (args.crossings, args.distance) {
        (Some(n), _) => Limit::Crossings(n),
        (None, Some(d)) => Limit::Distance(d),
        (None, None) => return Err("give --crossings N or --distance D".into()),
    };
    let result = match args.precision {
        Precision::F64 => trace_f64::<DVec4>(&space, start.point, start.tangent, limit),
        Precision::F32 => trace_f64::<Vec4>(&space, start.point, start.tangent, limit),
    };
    let chart = |p: DVec4| g.to_chart(p).to_array();
    if args.json {
        let crossings: Vec<_> = result
            .crossings
            .iter()
            .map(|c| {
                json!({
                    "face_normal": space.faces()[c.face].normal.to_array(),
                    "distance": c.distance,
                    "point": chart(c.ray.point),
                })
            })
            .collect();
        let out = json!({
            "crossings": crossings,
            "end": {
                "point": chart(result.end.point),
                "direction": g.chart_direction(result.end.point, result.end.tangent).to_array(),
                "distance": result.distance,
            }
        });
        say!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
    } else {
        say!(
            "{:>5} {:>5} {:>20}  entry point (chart)",
            "#",
            "face",
            "distance"
        );
        for (i, c) in result.crossings.iter().enumerate() {
            let p = chart(c.ray.point);
            say!(
                "{:>5} {:>5} {:>20.15}  ({:+.15}, {:+.15}, {:+.15})",
                i + 1,
                c.face,
                c.distance,
                p[0],
                p[1],
                p[2]
            );
        }
        let p = chart(result.end.point);
        say!(
            "end at distance {:.15}: ({:+.15}, {:+.15}, {:+.15})",
            result.distance,
            p[0],
            p[1],
            p[2]
        );
    }
    Ok(())
}
