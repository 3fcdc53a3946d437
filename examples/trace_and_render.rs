//! The Bevy-free core in a few lines: build a seed space, read its invariants, follow a
//! geodesic through the cell and render a picture with the f64 reference tracer.
//!
//! Run: `cargo run --release --example trace_and_render` (writes `trace_and_render.png`).

use bevy_curved_spaces::geometry::chart_ray;
use bevy_curved_spaces::prelude::*;
use bevy_curved_spaces::scene::CurvedScene;
use bevy_curved_spaces::space::invariants::{injectivity_radius, volume};
use bevy_curved_spaces::space::{CellWalker, Limit};
use bevy_curved_spaces::trace::{RenderSettings, render};
use bevy_curved_spaces::view::TraceCamera;
use glam::{DVec3, DVec4};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let space = seed_space("seifert-weber")?;
    println!(
        "{}: volume {:.7}, injectivity radius {:.7}",
        space.name(),
        volume(&space),
        injectivity_radius(&space).unwrap_or(0.0)
    );

    // A geodesic from the centre: which faces it leaves through, and how far it has gone.
    let ray = chart_ray(space.geometry(), DVec3::ZERO, DVec3::new(0.3, 0.1, 1.0))?;
    let trace = CellWalker::<DVec4>::new(&space).trace(ray, Limit::Crossings(5));
    for c in &trace.crossings {
        println!(
            "left through face {:>2} at distance {:.6}",
            c.face, c.distance
        );
    }

    // A picture of the default scene: edges coloured by edge cycle, a ball at the centre.
    let scene = CurvedScene::default_for(&space, 3.0);
    let camera = TraceCamera::default_for(&space);
    let settings = RenderSettings {
        width: 320,
        height: 180,
        max_crossings: 64,
    };
    render(&space, &scene, &camera, &settings).save("trace_and_render.png")?;
    println!("wrote trace_and_render.png");
    Ok(())
}
