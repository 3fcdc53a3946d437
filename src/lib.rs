//! # bevy_curved_spaces
//!
//! Walk inside closed 3-manifolds and orbifolds — the 3-torus and the other flat spaces, the
//! Seifert–Weber space, the Poincaré dodecahedral space, lens spaces, SnapPy's census,
//! mirrored cubes and dodecahedra, surfaces times a circle (H²×R, S²×R), the Heisenberg
//! nilmanifolds (Nil) — and see what light does there: every frame is ray traced on the GPU
//! through the fundamental cell and its face pairings, so you see the universal cover tiled
//! with copies of the scene. The unit tangent bundles of hyperbolic surfaces (SL̃(2,R)) are
//! walked exactly too ([`space::sl2r`], [`trace::sl2r`]).
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
//! ([`plugin::objects`]); [`SceneObjects`] and [`BaseScene`] add still objects, meshes and lights.
//! Our systems run in the sets [`CurvedSpacesSystems`].
//!
//! ## Three layers
//!
//! - **The maths core**, with no Bevy at compile time (glam types only): [`geometry`],
//!   validated [`space`]s with their walk, the [`scene`] model, [`view`]s, the f64 reference
//!   tracer [`trace`], and the small [`files`] and [`random`] helpers.
//! - **The plugin**, [`plugin`]: components and resources, the player, entities, the render
//!   node and the WGSL tracer, offscreen pictures, the frame-rate target, the panel and the
//!   headset, all over the core.
//! - **The app**: the `curved-spaces` binary (`src/app`) and its benchmark ([`mod@bench`], feature `bench`).
//!
//! Dependencies run down only, and no two sibling modules name each other; the crate's own
//! tests read the source to keep it so.
//!
//! ## Without Bevy
//!
//! The maths core uses glam types only:
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
//!
//! ## The guide
//!
//! The [`guide`] module holds the guide's pages (`docs/guide/` of the repository and
//! package): the command line, the spaces and their files, the product spaces, light,
//! scenes, the plugin and the library, stereo and VR, accuracy and speed, and the layout.

// `!(x < tol)` is how this crate rejects NaN along with large values: keep it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![warn(missing_docs)]

// The maths core: no Bevy at compile time (glam types only; `tests/core/layers.rs` keeps it so).
pub(crate) mod colour;
pub mod files;
pub mod geometry;
pub mod guide;
pub mod random;
pub mod scene;
pub mod space;
pub mod trace;
pub mod view;

// The Bevy layer: components, player, entities, render, offscreen, frame rate, panel, headset.
pub mod plugin;

// The app's library half (the `curved-spaces` binary is `src/app/main.rs` with its CLI).
#[cfg(feature = "bench")]
#[path = "app/bench/mod.rs"]
pub mod bench;

pub use plugin::CurvedSpacesPlugin;
pub use plugin::components::{
    ActiveSpace, BaseProductScene, BaseScene, BaseScenes, CurvedSpaceCamera, CurvedSpaceEye,
    CurvedSpacesSystems, Quality, SceneObjects, TracerSettings, TracerStatus,
};
pub use plugin::nil::BaseNilScene;
pub use plugin::sl2r::BaseSl2rScene;

/// The types most programs need.
pub mod prelude {
    pub use crate::geometry::{Geometry, GeometryError, ORIGIN, Ray, chart_ray};
    pub use crate::plugin::CurvedSpacesPlugin;
    pub use crate::plugin::components::{
        ActiveSpace, BaseProductScene, BaseScene, CurvedSpaceCamera, CurvedSpaceEye,
        CurvedSpacesSystems, KeyBindings, PlayerFrame, PlayerSettings, Quality, SceneObjects,
        StereoSettings, TracerSettings, TracerStatus,
    };
    pub use crate::plugin::nil::BaseNilScene;
    pub use crate::plugin::objects::{
        ActiveSightlines, CurvedObject, CurvedShape, CurvedTransform, CurvedVelocity,
        ObjectCrossedFace,
    };
    pub use crate::plugin::sl2r::BaseSl2rScene;
    #[cfg(feature = "scene-files")]
    pub use crate::scene::file::{SceneFile, load_scene_file};
    pub use crate::scene::{
        Ball, CurvedScene, Disc, Light, MeshInstance, Object, SceneParts, Shading, SurfaceMaterial,
        Tube,
    };
    pub use crate::space::motion::CoverFlight;
    pub use crate::space::{
        AnySpace, CellWalk, CellWalker, Family, Holonomy, Limit, SEED_SPACES, Space, SpaceError,
        seed_space,
    };
    pub use crate::view::{StereoMode, TraceCamera};
}
