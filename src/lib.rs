//! # bevy_curved_spaces
//!
//! Walk inside closed 3-manifolds and orbifolds of constant curvature — the 3-torus and the
//! other flat spaces, the Seifert–Weber space, the Poincaré dodecahedral space, mirrored
//! cubes and dodecahedra — and see what light does there.
//!
//! This crate holds the exact geometry core ([`geometry`]), the validated spaces
//! ([`space`]) and the f64 CPU reference ray tracer ([`trace`]). They use glam types only,
//! so they work without a Bevy app.
//!
//! ```
//! use bevy_curved_spaces::prelude::*;
//! use bevy_curved_spaces::space::invariants::volume;
//! use bevy_curved_spaces::trace::{CellWalker, Limit, chart_ray};
//! use glam::{DVec3, DVec4};
//!
//! let space = seed_space("poincare")?;
//! // S³ has volume 2π² and the deck group of the Poincaré space has 120 elements.
//! assert!((volume(&space) - std::f64::consts::PI.powi(2) / 60.0).abs() < 1e-12);
//!
//! let ray = chart_ray(space.geometry, DVec3::ZERO, DVec3::new(0.3, 0.1, 1.0))?;
//! let trace = CellWalker::<DVec4>::new(&space).trace(ray, Limit::Crossings(10));
//! assert_eq!(trace.crossings.len(), 10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// `!(x < tol)` is how this crate rejects NaN along with large values: keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bench;
pub mod geometry;
pub mod headset;
pub mod player;
pub mod plugin;
pub mod render;
pub mod scene;
pub mod space;
pub mod stereo;
pub mod trace;
pub mod ui;
#[cfg(feature = "xr")]
pub mod xr;

pub use plugin::{
    ActiveSpace, CurvedSpaceCamera, CurvedSpacesPlugin, CurvedSpacesSystems, Quality, SceneObjects,
    TracerSettings,
};

/// The types most programs need.
pub mod prelude {
    pub use crate::geometry::{Geometry, GeometryError, ORIGIN};
    pub use crate::player::{Holonomy, KeyBindings, PlayerFrame, PlayerSettings};
    pub use crate::plugin::{
        ActiveSpace, CurvedSpaceCamera, CurvedSpacesPlugin, CurvedSpacesSystems, Quality,
        SceneObjects, TracerSettings,
    };
    pub use crate::render::CurvedSpaceEye;
    pub use crate::space::{SEED_SPACES, Space, SpaceError, seed_space};
    pub use crate::stereo::{StereoMode, StereoSettings};
}
