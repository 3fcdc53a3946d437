//! Game objects as entities: put a [`CurvedObject`] on an entity and it is drawn in the
//! curved space at its [`CurvedTransform`]; give it a [`CurvedVelocity`] and it flies along
//! geodesics, through the faces and back in through their partners, turned by each pairing
//! it crossed (its [`Holonomy`]), with an [`ObjectCrossedFace`] message for each crossing.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::plugin::objects::{CurvedObject, CurvedTransform, CurvedVelocity};
//! use bevy_curved_spaces::prelude::*;
//! use glam::DVec3;
//!
//! fn spawn_ball(mut commands: Commands, active: Res<ActiveSpace>) {
//!     let r = active.inradius;
//!     commands.spawn((
//!         CurvedObject::ball(0.2 * r, DVec3::new(0.9, 0.3, 0.2)),
//!         CurvedTransform::from_geodesic(&active.space, DVec3::new(0.3 * r, 0.0, 0.0)),
//!         // Half an inradius a second along its own −z (forward).
//!         CurvedVelocity::linear(DVec3::new(0.0, 0.0, -0.5 * r)),
//!     ));
//! }
//! App::new()
//!     .add_plugins((DefaultPlugins, CurvedSpacesPlugin::default()))
//!     .add_systems(Startup, spawn_ball)
//!     .run();
//! ```
//!
//! Shapes are balls, globes, tubes and discs (exact in every geometry) and triangle meshes:
//! a [`Model`] of ours (from [`crate::scene::gltf`] or built in code) or a Bevy
//! `Handle<Mesh>` (with an optional `Handle<Image>` texture) from the game's own assets,
//! drawn once loaded and again when the asset changes. A mesh's hierarchy is built once per
//! model, size and geometry ([`TracedMeshes`]); a large one is built off the main thread and
//! its objects appear when it is ready. Moving an object rewrites its instance in the
//! uniform only; the scene data (meshes, textures) stays on the GPU.
//!
//! Motion runs in `FixedUpdate` ([`crate::space::motion`]: one step per fixed tick, wrapped
//! with the player's rule), so a scene file's `velocity` at time `T` and a game's objects
//! after `T` seconds of fixed steps are in the same place. [`Sightlines`] gives the shortest
//! geodesic between two points of the manifold (to aim, or to play a sound by distance).

use crate::geometry::Geometry;
use crate::plugin::components::{ActiveSpace, CurvedSpacesSystems, PlayerSettings};
use crate::scene::mesh::{MeshSource, Model};
use crate::scene::texture::Texture;
use crate::scene::{
    Ball, BallTexture, CurvedScene, Disc, MeshInstance, Object, SurfaceMaterial, TracedModel, Tube,
};
use crate::space::Family;
use crate::space::motion::{Sightline, Sightlines, Velocity};
use crate::space::{Holonomy, Space, wrap_into_cell};
use bevy::asset::{AssetEvent, AssetId, Assets, Handle};
use bevy::image::Image;
use bevy::mesh::{Mesh, PrimitiveTopology};
use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, futures::check_ready};
use glam::{DMat4, DVec2, DVec3, DVec4};
use std::collections::HashMap;
use std::sync::Arc;

pub mod gather;
mod meshes;
pub mod nil;
pub mod product;
mod ready;
mod systems;

pub use meshes::{
    BevyMeshError, TracedMeshes, bevy_mesh_from_model, model_from_bevy_mesh, texture_from_image,
};
pub use ready::{EntityObjects, ReadyObject, ReadyShape, add_entity_objects};
use systems::update_sightlines;
pub use systems::{
    SceneMover, collect_objects, forget_changed_assets, move_objects, spawn_scene_movers,
    wrap_objects,
};

/// Meshes with more triangles than this get their hierarchy built off the main thread.
pub const ASYNC_MESH_TRIANGLES: usize = 4096;

/// What an object looks like: its shape about its own origin (sizes are geodesic lengths in
/// the space's units; [`ActiveSpace::inradius`] gives the scale of the cell).
// One per entity: the carried object's size costs less than a box per shape.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum CurvedShape {
    /// A metric ball.
    Ball {
        /// Radius.
        radius: f64,
    },
    /// A ball with a picture on it (equirectangular, north pole on the object's own `+y`),
    /// turning about its `+y` axis by `spin` radians a second of the tracer's clock.
    Globe {
        /// Radius.
        radius: f64,
        /// The picture.
        texture: Arc<Texture>,
        /// Radians per second.
        spin: f64,
    },
    /// A tube around the geodesic segment of this length along the object's own `y` axis,
    /// centred on its origin.
    Tube {
        /// The segment's length.
        length: f64,
        /// The tube's radius.
        radius: f64,
    },
    /// A flat disc through the origin, its normal the object's own `z` axis.
    Disc {
        /// Radius.
        radius: f64,
    },
    /// One of our models (glTF through [`crate::scene::gltf`], or built in code), scaled so
    /// that its farthest vertex is `size` from the origin; its own materials and textures.
    Model {
        /// The model (shared: its hierarchy is built once per size and geometry).
        model: Arc<Model>,
        /// The distance of its farthest vertex from the origin.
        size: f64,
    },
    /// A mesh already traced for the space's geometry (shared between entities and
    /// scenes: [`TracedModel::new`]).
    Traced(Arc<TracedModel>),
    /// An object of the base scene ([`crate::plugin::components::BaseScene`], whose textures and
    /// meshes its indices name) as it is at the frame `start`: drawn carried from `start`
    /// to the entity's frame. The plugin spawns a scene file's moving objects this way.
    Carried {
        /// The object at `start`.
        object: Object,
        /// The frame it was placed at.
        start: DMat4,
    },
    /// A Bevy mesh asset (triangle list, positions with optional normals and UVs), scaled
    /// so that its farthest vertex is `size` from the origin; drawn once the asset is loaded.
    /// Its data must stay in the main world (`RenderAssetUsages::MAIN_WORLD`, as loaded
    /// assets are by default).
    Mesh {
        /// The mesh.
        mesh: Handle<Mesh>,
        /// A picture on it by its UVs (RGBA8 images).
        texture: Option<Handle<Image>>,
        /// The distance of its farthest vertex from the origin.
        size: f64,
    },
}

/// Makes its entity part of the curved scene: a shape with a colour, at the entity's
/// [`CurvedTransform`]. Spawning, changing and despawning it change what every curved-space
/// camera shows from the next frame on.
#[derive(Component, Clone, Debug, PartialEq)]
#[require(CurvedTransform, Holonomy)]
pub struct CurvedObject {
    /// The shape.
    pub shape: CurvedShape,
    /// Albedo, linear RGB; for meshes `None` keeps their own materials (white for a Bevy
    /// mesh, times its texture).
    pub colour: Option<DVec3>,
    /// Light it gives off itself, linear RGB.
    pub emission: DVec3,
    /// The share of light it reflects as a mirror (0 to 1; docs/light.md): balls, globes,
    /// discs and meshes (a mesh's materials are then replaced, as by a colour); tubes, and
    /// objects in the product spaces, do not reflect.
    pub reflectance: f64,
}

impl CurvedObject {
    fn of(shape: CurvedShape, colour: Option<DVec3>) -> Self {
        Self {
            shape,
            colour,
            emission: DVec3::ZERO,
            reflectance: 0.0,
        }
    }

    /// A ball of `radius` and `colour`.
    #[must_use]
    pub fn ball(radius: f64, colour: DVec3) -> Self {
        Self::of(CurvedShape::Ball { radius }, Some(colour))
    }

    /// A globe: a ball of `radius` with `texture` on it, spinning `spin` radians a second.
    #[must_use]
    pub fn globe(radius: f64, texture: Arc<Texture>, spin: f64) -> Self {
        Self::of(
            CurvedShape::Globe {
                radius,
                texture,
                spin,
            },
            Some(DVec3::ONE),
        )
    }

    /// A tube of `radius` around a segment of `length` along the object's `y` axis.
    #[must_use]
    pub fn tube(length: f64, radius: f64, colour: DVec3) -> Self {
        Self::of(CurvedShape::Tube { length, radius }, Some(colour))
    }

    /// A disc of `radius` facing the object's `z` axis.
    #[must_use]
    pub fn disc(radius: f64, colour: DVec3) -> Self {
        Self::of(CurvedShape::Disc { radius }, Some(colour))
    }

    /// One of our models with its own materials, its farthest vertex `size` from the origin.
    #[must_use]
    pub fn model(model: Arc<Model>, size: f64) -> Self {
        Self::of(CurvedShape::Model { model, size }, None)
    }

    /// A traced mesh with its own materials.
    #[must_use]
    pub fn traced(model: Arc<TracedModel>) -> Self {
        Self::of(CurvedShape::Traced(model), None)
    }

    /// A Bevy mesh asset, white (or textured, [`CurvedObject::with_texture`]), its farthest
    /// vertex `size` from the origin.
    #[must_use]
    pub fn mesh(mesh: Handle<Mesh>, size: f64) -> Self {
        Self::of(
            CurvedShape::Mesh {
                mesh,
                texture: None,
                size,
            },
            None,
        )
    }

    /// A Bevy mesh's object with a picture on it by its UVs (ignored for other shapes).
    #[must_use]
    pub fn with_texture(mut self, image: Handle<Image>) -> Self {
        if let CurvedShape::Mesh { texture, .. } = &mut self.shape {
            *texture = Some(image);
        }
        self
    }

    /// The object in another colour (for meshes: instead of their materials).
    #[must_use]
    pub fn with_colour(self, colour: DVec3) -> Self {
        Self {
            colour: Some(colour),
            ..self
        }
    }

    /// The object giving off light.
    #[must_use]
    pub fn with_emission(self, emission: DVec3) -> Self {
        Self { emission, ..self }
    }

    /// The object as a mirror reflecting `reflectance` of the light (clamped to 0–1; the
    /// rest is lit as usual): see [`CurvedObject::reflectance`].
    #[must_use]
    pub fn with_reflectance(self, reflectance: f64) -> Self {
        Self {
            reflectance: if reflectance.is_finite() {
                reflectance.clamp(0.0, 1.0)
            } else {
                0.0
            },
            ..self
        }
    }
}

/// Where an object is: its frame, an isometry of the model whose columns are its right, up
/// and back unit tangents and its position (like [`crate::plugin::components::PlayerFrame`]). Kept
/// inside the cell by the plugin: an object moved past a face comes back in through its
/// partner, its frame turned by the pairing.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct CurvedTransform(pub DMat4);

impl Default for CurvedTransform {
    fn default() -> Self {
        Self(DMat4::IDENTITY)
    }
}

impl CurvedTransform {
    /// The frame at the end of the geodesic from the cell's centre along `offset` (its
    /// direction in the centre's axes, its length the distance), with the centre's axes
    /// carried along: geodesic coordinates about the centre.
    #[must_use]
    pub fn from_geodesic(space: &impl crate::space::family::CentreFrame, offset: DVec3) -> Self {
        Self(space.frame_from_centre(offset))
    }

    /// The frame `frame` moved as a Bevy [`Transform`] would move a child: by its
    /// translation in `frame`'s axes (a geodesic of that length), then turned by its
    /// rotation (the scale is not used).
    #[must_use]
    pub fn relative_to(geometry: Geometry, frame: DMat4, local: &Transform) -> Self {
        let t = local.translation.as_dvec3();
        let mut f = crate::geometry::translate_local(geometry, frame, t);
        let (axis, angle) = local.rotation.as_dquat().to_axis_angle();
        if angle != 0.0 && angle.is_finite() && axis.is_finite() {
            f *= geometry.rotation(axis, angle);
        }
        Self(f)
    }

    /// The object's position, a point of the model.
    #[must_use]
    pub fn position(&self, geometry: Geometry) -> DVec4 {
        geometry.project_point(self.0.w_axis)
    }
}

/// A constant velocity in the object's own axes: it flies along a geodesic (turning
/// about its own axis if `angular` is set) and through the faces.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct CurvedVelocity(pub Velocity);

impl CurvedVelocity {
    /// Moving at `linear` (distance per second along its own right, up, back axes).
    #[must_use]
    pub fn linear(linear: DVec3) -> Self {
        Self(Velocity {
            linear,
            angular: DVec3::ZERO,
        })
    }

    /// The velocity also turning at `angular` (radians per second about its own axes).
    #[must_use]
    pub fn with_angular(self, angular: DVec3) -> Self {
        Self(Velocity { angular, ..self.0 })
    }
}

/// An object went out through a face and came back in through its partner.
#[derive(Message, Clone, Copy, Debug, PartialEq)]
pub struct ObjectCrossedFace {
    /// The object.
    pub entity: Entity,
    /// The face it left by (it came in through the partner face).
    pub face: usize,
    /// The face's pairing, applied to its frame.
    pub pairing: DMat4,
    /// Its crossings so far, this one included.
    pub crossings: u64,
}

/// The shortest geodesics between points of the active space ([`Sightlines`] of it), made
/// when the space changes (`None` before the first update).
#[derive(Resource, Clone, Debug, Default)]
pub struct ActiveSightlines(pub Option<Arc<Sightlines>>);

impl ActiveSightlines {
    /// The shortest geodesic from one frame's origin to another's, through any faces:
    /// its length, the direction it leaves in (in `from`'s own axes) and the copy of
    /// `to` it reaches. `None` before the plugin's first update.
    #[must_use]
    pub fn between(&self, from: &CurvedTransform, to: &CurvedTransform) -> Option<Sightline> {
        self.0.as_ref().map(|s| s.between(from.0, to.0.w_axis))
    }
}

/// Adds the entities' systems (the plugin calls it).
pub(crate) fn add_systems(app: &mut App) {
    app.init_resource::<EntityObjects>()
        .init_resource::<TracedMeshes>()
        .init_resource::<ActiveSightlines>()
        .init_resource::<product::ProductEntityObjects>()
        .init_resource::<nil::NilEntityObjects>()
        .add_message::<ObjectCrossedFace>()
        .add_systems(
            Update,
            (
                gather::collect_entity_objects::<crate::space::product::ProductSpace>
                    .in_set(CurvedSpacesSystems::Upload),
                product::spawn_product_movers.before(CurvedSpacesSystems::Move),
            )
                .run_if(ActiveSpace::shows(Family::Product)),
        )
        .add_systems(
            Update,
            gather::collect_entity_objects::<crate::space::nil::NilSpace>
                .in_set(CurvedSpacesSystems::Upload)
                .run_if(ActiveSpace::shows(Family::Nil)),
        )
        .add_systems(
            Update,
            (
                // The plugin orders the upload after it.
                collect_objects.in_set(CurvedSpacesSystems::Upload),
                update_sightlines.before(CurvedSpacesSystems::Upload),
                spawn_scene_movers.before(CurvedSpacesSystems::Move),
            )
                .run_if(ActiveSpace::shows(Family::Constant)),
        );
}

/// Adds the asset systems once the app's plugins are built, where the app has mesh and
/// image assets.
pub(crate) fn finish(app: &mut App) {
    let world = app.world();
    if world.contains_resource::<Messages<AssetEvent<Mesh>>>()
        && world.contains_resource::<Messages<AssetEvent<Image>>>()
    {
        app.add_systems(Update, forget_changed_assets.before(collect_objects));
    }
}
