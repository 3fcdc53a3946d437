//! # bevy_curved_spaces
//!
//! Walk inside closed 3-manifolds and orbifolds of constant curvature — the 3-torus and the
//! other flat spaces, the Seifert–Weber space, the Poincaré dodecahedral space, mirrored
//! cubes and dodecahedra — and see what light does there: every frame is ray traced on the
//! GPU through the fundamental cell and its face pairings, so you see the universal cover
//! tiled with copies of the scene.
//!
//! ## The plugin
//!
//! Add [`CurvedSpacesPlugin`] and put [`CurvedSpaceCamera`] on an ordinary `Camera3d`:
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::prelude::*;
//!
//! App::new()
//!     .add_plugins(DefaultPlugins)
//!     .add_plugins(CurvedSpacesPlugin {
//!         space: "poincare".into(),
//!         ..default()
//!     })
//!     .add_systems(Startup, |mut commands: Commands| {
//!         commands.spawn((Camera3d::default(), CurvedSpaceCamera::default()));
//!     })
//!     .run();
//! ```
//!
//! The camera's place in the space is its [`prelude::PlayerFrame`], its face crossings are in
//! [`prelude::Holonomy`]; [`ActiveSpace`] switches spaces, [`TracerSettings`] holds the fog,
//! crossing budget and resolution, and [`TracerStatus`] reports what the tracer chose and
//! any problem. Your game's things are entities: a [`prelude::CurvedObject`] at a
//! [`prelude::CurvedTransform`], moving with a [`prelude::CurvedVelocity`] through the faces
//! ([`objects`]); [`SceneObjects`] and [`BaseScene`] add still objects, meshes and lights.
//! Our systems run in the sets [`CurvedSpacesSystems`].
//!
//! ## Without Bevy
//!
//! The maths core — [`geometry`], validated [`space`]s with their walk, the [`scene`] model,
//! [`view`]s and the f64 reference tracer [`trace`] — uses glam types only:
//!
//! ```
//! use bevy_curved_spaces::prelude::*;
//! use bevy_curved_spaces::space::invariants::volume;
//! use glam::{DVec3, DVec4};
//!
//! let space = seed_space("poincare")?;
//! // S³ has volume 2π² and the deck group of the Poincaré space has 120 elements.
//! assert!((volume(&space) - std::f64::consts::PI.powi(2) / 60.0).abs() < 1e-12);
//!
//! let ray = chart_ray(space.geometry(), DVec3::ZERO, DVec3::new(0.3, 0.1, 1.0))?;
//! let trace = CellWalker::<DVec4>::new(&space).trace(ray, Limit::Crossings(10));
//! assert_eq!(trace.crossings.len(), 10);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Features
//!
//! With `default-features = false` the crate is the plugin core: geometry, spaces, both
//! tracers, the shader and the player. `window` (winit, X11), `ui` (the egui panel),
//! `gltf` (glTF models), `scene-files` (TOML scene files), `bench` (the benchmark) and `xr`
//! (OpenXR headsets) add what they name; `app`, the default, is everything the
//! `curved-spaces` binary needs. The design — the model, the walk, the shader, the player,
//! the error bounds — is in `docs/design.md` of the repository and package.

// `!(x < tol)` is how this crate rejects NaN along with large values: keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]

#[cfg(feature = "bench")]
pub mod bench;
pub(crate) mod colour;
pub mod components;
pub mod files;
pub mod frame_rate;
pub mod geometry;
pub mod headset;
pub mod objects;
pub mod offscreen;
pub mod player;
pub mod plugin;
pub mod render;
pub mod scene;
pub mod space;
pub mod trace;
#[cfg(feature = "ui")]
pub mod ui;
pub mod view;
#[cfg(feature = "xr")]
pub mod xr;

pub use components::{
    ActiveSpace, BaseScene, CurvedSpaceCamera, CurvedSpaceEye, CurvedSpacesSystems, Quality,
    SceneObjects, TracerSettings, TracerStatus,
};
pub use plugin::CurvedSpacesPlugin;

/// The types most programs need.
pub mod prelude {
    pub use crate::components::{
        ActiveSpace, BaseScene, CurvedSpaceCamera, CurvedSpaceEye, CurvedSpacesSystems,
        KeyBindings, PlayerFrame, PlayerSettings, Quality, SceneObjects, StereoSettings,
        TracerSettings, TracerStatus,
    };
    pub use crate::geometry::{Geometry, GeometryError, ORIGIN, Ray, chart_ray};
    pub use crate::objects::{
        ActiveSightlines, CurvedObject, CurvedShape, CurvedTransform, CurvedVelocity,
        ObjectCrossedFace,
    };
    pub use crate::plugin::CurvedSpacesPlugin;
    #[cfg(feature = "scene-files")]
    pub use crate::scene::file::{SceneFile, load_scene_file};
    pub use crate::scene::{
        Ball, CurvedScene, Disc, Light, MeshInstance, Object, SceneParts, Shading, SurfaceMaterial,
        Tube,
    };
    pub use crate::space::{
        CellWalker, Holonomy, Limit, SEED_SPACES, Space, SpaceError, seed_space,
    };
    pub use crate::view::{StereoMode, TraceCamera};
}
