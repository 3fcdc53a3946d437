//! What the rays see: objects (exact quadrics in all three geometries: balls, tubes, discs,
//! globes) and triangle meshes with their bounding-volume hierarchy ([`mesh`]), lights and
//! the shading model ([`shading`]), textures ([`texture`]), the player's avatar ([`avatar`]),
//! and the scene that holds them and places objects through the faces ([`model`]). glTF
//! models ([`gltf`]) and scene files ([`file`](mod@file)) come with the `gltf` and `scene-files`
//! features.

pub mod assets;
pub mod avatar;
pub mod centrepiece;
pub mod culling;
#[cfg(feature = "scene-files")]
pub mod file;
#[cfg(feature = "scene-files")]
pub(crate) mod file_support;
#[cfg(feature = "scene-files")]
pub mod flight;
#[cfg(feature = "gltf")]
pub mod gltf;
pub mod light_images;
pub mod lighting;
pub mod mesh;
pub mod model;
pub mod moving;
pub mod object;
pub mod shading;
pub mod texture;
pub mod walls;

pub use culling::FaceCulling;
pub use lighting::{LightPaths, Lighting};
pub use mesh::Model;
pub use model::{
    Avatar, Centrepiece, CurvedScene, MAX_AVATAR_IMAGES, MAX_IMAGES, PlaceError, SceneParts,
    SegmentHit, TracedModel, avatar_instances, avatar_size, clifford_parallels, gyroscope, palette,
};
pub use moving::{MovingError, MovingObject};
pub use object::{Ball, BallTexture, Disc, Hit, MeshInstance, Object, Tube};
pub use shading::{ColourBy, DEFAULT_CUTOFF_WEIGHT, Light, Shading, SurfaceMaterial, holonomy_bin};
pub use walls::{Veil, WallError, WallPanels, WallStyle};
