//! The cost of game objects as entities ([`crate::plugin::objects`]), measured on the CPU side of
//! the plugin in a headless app: an update with N moving objects against the same update
//! with none (the per-object cost: motion, wrap, gathering, placing images, packing the
//! uniform), and building a new mesh's hierarchy. Written to `entities.csv`,
//! `new_meshes.csv` and `entities.md`.

use crate::plugin::CurvedSpacesPlugin;
use crate::plugin::components::ActiveSpace;
use crate::plugin::objects::{CurvedObject, CurvedTransform, CurvedVelocity};
use crate::random::SplitMix64;
use crate::scene::TracedModel;
use crate::scene::mesh::{Model, cube_source};
use crate::space::motion::MOTION_STEP;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use glam::DVec3;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// One measured update cost.
#[derive(Clone, Debug, PartialEq)]
pub struct EntityTiming {
    /// The space.
    pub space: String,
    /// Moving objects.
    pub objects: usize,
    /// What they are (`ball` or `mesh`).
    pub kind: &'static str,
    /// Median milliseconds per update (one fixed step each).
    pub update_ms: f64,
    /// Microseconds per object above the update with none.
    pub per_object_us: f64,
}

/// One measured mesh build.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshBuild {
    /// The model.
    pub model: String,
    /// Its triangles.
    pub triangles: usize,
    /// Median milliseconds to build its traced form (hierarchy).
    pub build_ms: f64,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median ms of an update with `n` moving objects of `kind` in `space`.
fn time_updates(space: &str, n: usize, kind: &'static str, updates: usize) -> f64 {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
            MOTION_STEP,
        )))
        .add_plugins(CurvedSpacesPlugin {
            space: space.into(),
            controls: false,
            ..default()
        });
    app.finish();
    app.update();
    let active = app.world().resource::<ActiveSpace>().clone();
    let r = active.inradius;
    let g = active.space.model_geometry();
    let cube = Arc::new(
        TracedModel::new(
            g,
            &Model {
                source: cube_source(0.5, 0),
                materials: vec![crate::scene::SurfaceMaterial::default()],
                textures: Vec::new(),
            },
            0.08 * r,
        )
        .expect("a cube is a mesh"),
    );
    let mut rng = SplitMix64(11);
    for _ in 0..n {
        let object = match kind {
            "mesh" => CurvedObject::traced(cube.clone()),
            _ => CurvedObject::ball(0.06 * r, DVec3::ONE),
        };
        app.world_mut().spawn((
            object,
            CurvedTransform::from_geodesic(&active.space, rng.direction() * 0.6 * r * rng.unit()),
            CurvedVelocity::linear(rng.direction() * 0.5 * r).with_angular(rng.direction()),
        ));
    }
    // Spawning builds the budget and the lists once: not part of the steady cost.
    for _ in 0..3 {
        app.update();
    }
    let times = (0..updates)
        .map(|_| {
            let t = Instant::now();
            app.update();
            t.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    median(times)
}

/// Measures the update costs and mesh builds (`quick`: fewer updates and counts).
#[must_use]
pub fn run_entities(quick: bool) -> (Vec<EntityTiming>, Vec<MeshBuild>) {
    let updates = if quick { 20 } else { 200 };
    let counts: &[usize] = if quick { &[1, 10] } else { &[1, 10, 50, 200] };
    let mut timings = Vec::new();
    for space in ["seifert-weber", "torus", "poincare"] {
        let none = time_updates(space, 0, "ball", updates);
        timings.push(EntityTiming {
            space: space.into(),
            objects: 0,
            kind: "none",
            update_ms: none,
            per_object_us: 0.0,
        });
        for kind in ["ball", "mesh"] {
            for &n in counts {
                let ms = time_updates(space, n, kind, updates);
                timings.push(EntityTiming {
                    space: space.into(),
                    objects: n,
                    kind,
                    update_ms: ms,
                    per_object_us: 1e3 * (ms - none) / n as f64,
                });
            }
        }
    }
    let mut builds = Vec::new();
    let models: Vec<(String, Model)> = {
        let mut m = vec![(
            "cube".to_string(),
            Model {
                source: cube_source(0.5, 0),
                materials: vec![crate::scene::SurfaceMaterial::default()],
                textures: Vec::new(),
            },
        )];
        #[cfg(feature = "gltf")]
        {
            let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/models/torus_knot.glb");
            if let Ok(knot) = crate::scene::gltf::load(&path) {
                m.push(("torus_knot.glb".to_string(), knot));
            }
        }
        m
    };
    for (name, model) in &models {
        let runs = if quick { 3 } else { 21 };
        let times = (0..runs)
            .map(|_| {
                let t = Instant::now();
                let traced = TracedModel::new(crate::geometry::Geometry::Hyperbolic, model, 0.3);
                let ms = t.elapsed().as_secs_f64() * 1e3;
                assert!(traced.is_ok(), "{name} traces");
                ms
            })
            .collect();
        builds.push(MeshBuild {
            model: name.clone(),
            triangles: model.source.indices.len(),
            build_ms: median(times),
        });
    }
    (timings, builds)
}

/// Writes `entities.csv`, `new_meshes.csv` and `entities.md` into `out`; returns the
/// summary's text.
pub fn write_entities(
    timings: &[EntityTiming],
    builds: &[MeshBuild],
    out: &Path,
) -> std::io::Result<String> {
    std::fs::create_dir_all(out)?;
    let mut csv = String::from("space,objects,kind,update_ms,per_object_us\n");
    for t in timings {
        let _ = writeln!(
            csv,
            "{},{},{},{:.4},{:.2}",
            t.space, t.objects, t.kind, t.update_ms, t.per_object_us
        );
    }
    crate::files::write_atomic(&out.join("entities.csv"), csv.as_bytes())?;
    let mut csv = String::from("model,triangles,build_ms\n");
    for b in builds {
        let _ = writeln!(csv, "{},{},{:.3}", b.model, b.triangles, b.build_ms);
    }
    crate::files::write_atomic(&out.join("new_meshes.csv"), csv.as_bytes())?;
    let mut md = String::from(
        "# Objects as entities: CPU cost per update\n\n\
         A headless app (MinimalPlugins), one fixed step per update; the median update with N \
         moving, tumbling objects against the same space with none. Per object: motion, wrap, \
         gathering, placing its images and packing the uniform (the scene data is shared, and \
         the automatic budget is kept while objects only move).\n\n\
         | space | kind | objects | update (ms) | per object (µs) |\n|---|---|---|---|---|\n",
    );
    for t in timings {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.3} | {:.1} |",
            t.space, t.kind, t.objects, t.update_ms, t.per_object_us
        );
    }
    md.push_str("\nA new mesh's hierarchy, built once per model, size and geometry (larger than ");
    let _ = writeln!(
        md,
        "{} triangles: off the main thread):\n\n| model | triangles | build (ms) |\n|---|---|---|",
        crate::plugin::objects::ASYNC_MESH_TRIANGLES
    );
    for b in builds {
        let _ = writeln!(md, "| {} | {} | {:.2} |", b.model, b.triangles, b.build_ms);
    }
    crate::files::write_atomic(&out.join("entities.md"), md.as_bytes())?;
    Ok(md)
}
