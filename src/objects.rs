//! Game objects as entities: put a [`CurvedObject`] on an entity and it is drawn in the
//! curved space at its [`CurvedTransform`]; give it a [`CurvedVelocity`] and it flies along
//! geodesics, through the faces and back in through their partners, turned by each pairing
//! it crossed (its [`Holonomy`]), with an [`ObjectCrossedFace`] message for each crossing.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_curved_spaces::objects::{CurvedObject, CurvedTransform, CurvedVelocity};
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

use crate::components::{ActiveSpace, CurvedSpacesSystems, PlayerSettings};
use crate::geometry::Geometry;
use crate::scene::mesh::{MeshSource, Model};
use crate::scene::texture::Texture;
use crate::scene::{
    Ball, BallTexture, CurvedScene, Disc, MeshInstance, Object, SurfaceMaterial, TracedModel, Tube,
};
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
    /// An object of the base scene ([`crate::components::BaseScene`], whose textures and
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
}

impl CurvedObject {
    fn of(shape: CurvedShape, colour: Option<DVec3>) -> Self {
        Self {
            shape,
            colour,
            emission: DVec3::ZERO,
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
}

/// Where an object is: its frame, an isometry of the model whose columns are its right, up
/// and back unit tangents and its position (like [`crate::components::PlayerFrame`]). Kept
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
    pub fn from_geodesic(space: &Space, offset: DVec3) -> Self {
        let g = space.geometry;
        let centre = g.translation_to(space.centre());
        Self(crate::geometry::translate_local(g, centre, offset))
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

fn update_sightlines(active: Res<ActiveSpace>, mut sightlines: ResMut<ActiveSightlines>) {
    if active.is_changed() || sightlines.0.is_none() {
        sightlines.0 = Some(Arc::new(Sightlines::new(&active.space)));
    }
}

/// A drawn object's shape with its mesh or texture ready.
// Gathered anew each frame objects change: no box per object.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum ReadyShape {
    /// A ball.
    Ball(f64),
    /// A globe: radius, texture, spin.
    Globe(f64, Arc<Texture>, f64),
    /// A tube: length, radius.
    Tube(f64, f64),
    /// A disc: radius.
    Disc(f64),
    /// A mesh.
    Mesh(Arc<TracedModel>),
    /// A base scene's object at a start frame.
    Carried(Object, DMat4),
}

/// One object to draw: what it is and where.
#[derive(Clone, Debug)]
pub struct ReadyObject {
    /// Its entity.
    pub entity: Entity,
    /// Its shape.
    pub shape: ReadyShape,
    /// Its frame in the cell.
    pub frame: DMat4,
    /// Albedo (`None`: a mesh's own materials).
    pub colour: Option<DVec3>,
    /// Emission.
    pub emission: DVec3,
}

/// The entities' objects as the tracer will draw them, gathered when any changed; objects
/// whose mesh is not ready (still loading or building) are counted in `pending`, and
/// objects that cannot be drawn are described in `problems`.
#[derive(Resource, Clone, Debug, Default)]
pub struct EntityObjects {
    /// The objects, in entity order.
    pub objects: Vec<ReadyObject>,
    /// Objects whose mesh is still loading or being built.
    pub pending: usize,
    /// What is wrong with objects left out.
    pub problems: Vec<String>,
}

impl ReadyObject {
    /// The scene object: the shape placed at the frame, its mesh and texture added to
    /// `scene` (once each: `added` remembers them by identity).
    fn object(
        &self,
        geometry: Geometry,
        scene: &mut CurvedScene,
        added: &mut HashMap<usize, (u32, u32)>,
    ) -> Object {
        let g = geometry;
        let f = self.frame;
        let centre = g.project_point(f.w_axis);
        let colour = self.colour.unwrap_or(DVec3::ONE);
        match &self.shape {
            ReadyShape::Ball(r) => {
                Object::Ball(Ball::new(g, centre, *r, colour).with_emission(self.emission))
            }
            ReadyShape::Globe(r, texture, spin) => {
                let key = Arc::as_ptr(texture) as usize;
                let index = added
                    .entry(key)
                    .or_insert_with(|| {
                        scene.textures.push(texture.clone());
                        (scene.textures.len() as u32 - 1, 0)
                    })
                    .0;
                Object::Ball(
                    Ball::new(g, centre, *r, colour)
                        .with_emission(self.emission)
                        .with_texture(BallTexture {
                            texture: index,
                            frame: f,
                            spin: *spin,
                        }),
                )
            }
            ReadyShape::Tube(length, radius) => {
                let end = |t: f64| {
                    g.project_point(f * g.translation(DVec3::Y, t) * crate::geometry::ORIGIN)
                };
                Object::Tube(
                    Tube::new(g, end(-0.5 * length), end(0.5 * length), *radius, colour)
                        .with_emission(self.emission),
                )
            }
            ReadyShape::Disc(r) => Object::Disc(
                Disc::new(g, centre, g.unit_tangent(centre, f.z_axis), *r, colour)
                    .with_emission(self.emission),
            ),
            ReadyShape::Carried(object, start) => object.transformed(g, f * g.inverse(*start)),
            ReadyShape::Mesh(model) => {
                let key = Arc::as_ptr(&model.mesh) as usize;
                let (mesh, base) = *added.entry(key).or_insert_with(|| scene.add_traced(model));
                let mut instance = MeshInstance::new(g, mesh, f, model.mesh.radius);
                instance.material_base = base;
                if self.colour.is_some() || self.emission != DVec3::ZERO {
                    scene.materials.push(SurfaceMaterial {
                        colour,
                        texture: None,
                        emission: self.emission,
                    });
                    instance.material = Some(scene.materials.len() as u32 - 1);
                }
                Object::Mesh(instance)
            }
        }
    }
}

/// Adds the entities' objects to `scene` with their images through the faces
/// ([`CurvedScene::place`]); returns what could not be placed.
pub fn add_entity_objects(
    scene: &mut CurvedScene,
    space: &Space,
    objects: &[ReadyObject],
) -> Vec<String> {
    let mut added = HashMap::new();
    let mut problems = Vec::new();
    for o in objects {
        let object = o.object(space.geometry, scene, &mut added);
        if let Err(e) = scene.place(space, object) {
            problems.push(format!("object {}: {e}", o.entity));
        }
    }
    problems
}

/// Why a Bevy mesh asset cannot be traced.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum BevyMeshError {
    /// Only triangle lists are traced.
    #[error("the mesh is a {0:?}; only triangle lists are traced")]
    Topology(PrimitiveTopology),
    /// The mesh's data was sent to the render world only.
    #[error(
        "the mesh's vertex data is only in the render world; keep it in the main world (RenderAssetUsages::MAIN_WORLD)"
    )]
    NotInMainWorld,
    /// The positions are missing or not three 32-bit floats.
    #[error("the mesh has no Float32x3 positions")]
    NoPositions,
    /// A triangle names a vertex the mesh does not have.
    #[error("index {index} names vertex {vertex}, but the mesh has {count} vertices")]
    BadIndex {
        /// The index's place in the index list.
        index: usize,
        /// The vertex it names.
        vertex: usize,
        /// The mesh's vertices.
        count: usize,
    },
    /// The texture is not RGBA8 with its data in the main world.
    #[error("the texture is not an 8-bit RGBA image with its data in the main world ({0})")]
    Texture(String),
}

/// Our model of a Bevy mesh (and texture): its triangles with normals and UVs where it has
/// them, one white material (textured by `texture`).
pub fn model_from_bevy_mesh(mesh: &Mesh, texture: Option<&Image>) -> Result<Model, BevyMeshError> {
    use bevy::mesh::VertexAttributeValues as V;
    let topology = mesh.primitive_topology();
    if topology != PrimitiveTopology::TriangleList {
        return Err(BevyMeshError::Topology(topology));
    }
    let positions = match mesh.try_attribute_option(Mesh::ATTRIBUTE_POSITION) {
        Err(_) => return Err(BevyMeshError::NotInMainWorld),
        Ok(Some(V::Float32x3(p))) => p,
        Ok(_) => return Err(BevyMeshError::NoPositions),
    };
    let count = positions.len();
    let normals = match mesh.try_attribute_option(Mesh::ATTRIBUTE_NORMAL) {
        Ok(Some(V::Float32x3(n))) if n.len() == count => Some(
            n.iter()
                .map(|v| DVec3::from_array(v.map(f64::from)))
                .collect(),
        ),
        _ => None,
    };
    let uvs = match mesh.try_attribute_option(Mesh::ATTRIBUTE_UV_0) {
        Ok(Some(V::Float32x2(u))) if u.len() == count => Some(
            u.iter()
                .map(|v| DVec2::from_array(v.map(f64::from)))
                .collect(),
        ),
        _ => None,
    };
    let flat: Vec<usize> = match mesh.try_indices_option() {
        Err(_) => return Err(BevyMeshError::NotInMainWorld),
        Ok(Some(indices)) => indices.iter().collect(),
        Ok(None) => (0..count).collect(),
    };
    if let Some((index, &vertex)) = flat.iter().enumerate().find(|(_, v)| **v >= count) {
        return Err(BevyMeshError::BadIndex {
            index,
            vertex,
            count,
        });
    }
    let indices: Vec<[u32; 3]> = flat
        .chunks_exact(3)
        .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
        .collect();
    let textures = match texture {
        None => Vec::new(),
        Some(image) => vec![texture_from_image(image)?],
    };
    let materials = vec![SurfaceMaterial {
        colour: DVec3::ONE,
        texture: (!textures.is_empty()).then_some(0),
        emission: DVec3::ZERO,
    }];
    Ok(Model {
        source: MeshSource {
            positions: positions
                .iter()
                .map(|p| DVec3::from_array(p.map(f64::from)))
                .collect(),
            normals,
            uvs,
            materials: vec![0; indices.len()],
            indices,
        },
        materials,
        textures,
    })
}

/// Our texture of a Bevy image (8-bit RGBA, sRGB or linear taken as sRGB).
pub fn texture_from_image(image: &Image) -> Result<Texture, BevyMeshError> {
    use bevy::render::render_resource::TextureFormat as F;
    let format = image.texture_descriptor.format;
    if !matches!(format, F::Rgba8UnormSrgb | F::Rgba8Unorm) {
        return Err(BevyMeshError::Texture(format!("its format is {format:?}")));
    }
    let data = image
        .data
        .as_ref()
        .ok_or_else(|| BevyMeshError::Texture("it has no data in the main world".into()))?;
    Texture::from_rgba8(image.width(), image.height(), data)
        .map_err(|e| BevyMeshError::Texture(e.to_string()))
}

/// Where a mesh's traced form comes from.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum MeshKey {
    Model(usize, Geometry, u64),
    Asset(AssetId<Mesh>, Option<AssetId<Image>>, Geometry, u64),
}

enum MeshState {
    Ready(Arc<TracedModel>),
    Building(Task<Result<TracedModel, String>>),
    Failed(String),
}

/// The meshes the entities use, traced once per model, size and geometry: the models
/// themselves are kept alive here while any entity uses them.
#[derive(Resource, Default)]
pub struct TracedMeshes {
    states: HashMap<MeshKey, MeshState>,
    /// Models by the identity in their key, kept alive while their key is.
    models: HashMap<usize, Arc<Model>>,
    /// An asset changed: gather the objects again.
    changed: bool,
}

impl TracedMeshes {
    /// Meshes ready.
    #[must_use]
    pub fn ready(&self) -> usize {
        self.states
            .values()
            .filter(|s| matches!(s, MeshState::Ready(_)))
            .count()
    }

    /// Meshes being built.
    #[must_use]
    pub fn building(&self) -> usize {
        self.states
            .values()
            .filter(|s| matches!(s, MeshState::Building(_)))
            .count()
    }

    /// The traced model of `key` (made from `model()` now, or started off the main thread
    /// if large); `Ok(None)` while it is being built.
    fn get(
        &mut self,
        key: MeshKey,
        geometry: Geometry,
        size: f64,
        model: impl FnOnce() -> Result<Model, String>,
    ) -> Result<Option<Arc<TracedModel>>, String> {
        if let Some(MeshState::Building(task)) = self.states.get_mut(&key)
            && let Some(result) = check_ready(task)
        {
            let state = match result {
                Ok(m) => MeshState::Ready(Arc::new(m)),
                Err(e) => MeshState::Failed(e),
            };
            self.states.insert(key.clone(), state);
        }
        match self.states.get(&key) {
            Some(MeshState::Ready(m)) => return Ok(Some(m.clone())),
            Some(MeshState::Failed(e)) => return Err(e.clone()),
            Some(MeshState::Building(_)) => return Ok(None),
            None => {}
        }
        let model = match model() {
            Ok(m) => m,
            Err(e) => {
                self.states.insert(key, MeshState::Failed(e.clone()));
                return Err(e);
            }
        };
        let large = model.source.indices.len() > ASYNC_MESH_TRIANGLES;
        let build = move || TracedModel::new(geometry, &model, size).map_err(|e| e.to_string());
        let state = if large {
            MeshState::Building(AsyncComputeTaskPool::get().spawn(async move { build() }))
        } else {
            match build() {
                Ok(m) => MeshState::Ready(Arc::new(m)),
                Err(e) => MeshState::Failed(e),
            }
        };
        let out = match &state {
            MeshState::Ready(m) => Ok(Some(m.clone())),
            MeshState::Failed(e) => Err(e.clone()),
            MeshState::Building(_) => Ok(None),
        };
        self.states.insert(key, state);
        out
    }

    /// Forgets what was traced of a changed or removed asset.
    fn forget_mesh(&mut self, id: AssetId<Mesh>) {
        self.states
            .retain(|k, _| !matches!(k, MeshKey::Asset(m, _, _, _) if *m == id));
        self.changed = true;
    }

    fn forget_image(&mut self, id: AssetId<Image>) {
        self.states
            .retain(|k, _| !matches!(k, MeshKey::Asset(_, Some(t), _, _) if *t == id));
        self.changed = true;
    }

    /// Drops the traced meshes no entity uses any more.
    fn keep_only(&mut self, used: &std::collections::HashSet<MeshKey>) {
        self.states.retain(|k, _| used.contains(k));
        let models: std::collections::HashSet<usize> = used
            .iter()
            .filter_map(|k| match k {
                MeshKey::Model(p, _, _) => Some(*p),
                MeshKey::Asset(..) => None,
            })
            .collect();
        self.models.retain(|p, _| models.contains(p));
    }
}

/// Moves every object with a velocity by one fixed step (`FixedUpdate`).
pub fn move_objects(
    time: Res<Time>,
    active: Res<ActiveSpace>,
    mut objects: Query<(&mut CurvedTransform, &CurvedVelocity)>,
) {
    let g = active.space.geometry;
    let dt = time.delta_secs_f64();
    for (mut transform, velocity) in &mut objects {
        if !velocity.0.is_zero() {
            transform.0 = g.orthonormalize_frame(velocity.0.step(g, transform.0, dt));
        }
    }
}

/// Brings objects that left the cell back in through the faces (the player's rule and
/// margin), recording each crossing in their [`Holonomy`] and as an [`ObjectCrossedFace`].
/// Runs after the fixed-step motion and again after `Update`'s motion (objects the game
/// moved itself); on a change of space every object is checked.
pub fn wrap_objects(
    active: Res<ActiveSpace>,
    settings: Res<PlayerSettings>,
    mut objects: Query<(Entity, &mut CurvedTransform, &mut Holonomy), With<CurvedObject>>,
    mut crossed_faces: MessageWriter<ObjectCrossedFace>,
) {
    let space = &active.space;
    for (entity, mut transform, mut holonomy) in &mut objects {
        if !(transform.is_changed() || active.is_changed()) {
            continue;
        }
        let (wrapped, crossed) = wrap_into_cell(space, transform.0, settings.wrap_margin);
        if crossed.is_empty() {
            continue;
        }
        for face in crossed {
            let pairing = space.faces[face].pairing;
            holonomy.record(face, pairing);
            crossed_faces.write(ObjectCrossedFace {
                entity,
                face,
                pairing,
                crossings: holonomy.crossings,
            });
        }
        transform.0 = wrapped;
    }
}

/// The objects whose shape or frame changed since the last run.
type ChangedObjects<'w, 's> =
    Query<'w, 's, (), Or<(Changed<CurvedObject>, Changed<CurvedTransform>)>>;

/// The scale of a size as a key (sizes are compared exactly).
fn size_key(size: f64) -> u64 {
    size.to_bits()
}

/// Gathers the entities' objects into [`EntityObjects`] when any of them, the space or a
/// mesh they use changed, or while a mesh is loading or being built.
// A Bevy system takes its resources as arguments.
#[allow(clippy::too_many_arguments)]
pub fn collect_objects(
    active: Res<ActiveSpace>,
    objects: Query<(Entity, &CurvedObject, &CurvedTransform)>,
    changed: ChangedObjects,
    mut removed: RemovedComponents<CurvedObject>,
    meshes: Option<Res<Assets<Mesh>>>,
    images: Option<Res<Assets<Image>>>,
    mut traced: ResMut<TracedMeshes>,
    mut out: ResMut<EntityObjects>,
) {
    let removed_any = removed.read().count() > 0;
    if !(active.is_changed()
        || removed_any
        || !changed.is_empty()
        || traced.changed
        || out.pending > 0)
    {
        return;
    }
    traced.changed = false;
    let g = active.space.geometry;
    let mut ready = Vec::with_capacity(objects.iter().len());
    let mut pending = 0;
    let mut problems = Vec::new();
    let mut used = std::collections::HashSet::new();
    let mut sorted: Vec<_> = objects.iter().collect();
    sorted.sort_by_key(|(e, _, _)| *e);
    for (entity, object, transform) in sorted {
        let positive = |name: &str, x: f64| -> Result<f64, String> {
            if x > 0.0 && x.is_finite() {
                Ok(x)
            } else {
                Err(format!("its {name} must be a positive number, got {x}"))
            }
        };
        let shape: Result<Option<ReadyShape>, String> = match &object.shape {
            CurvedShape::Ball { radius } => {
                positive("radius", *radius).map(|r| Some(ReadyShape::Ball(r)))
            }
            CurvedShape::Globe {
                radius,
                texture,
                spin,
            } => positive("radius", *radius).and_then(|r| {
                if spin.is_finite() {
                    Ok(Some(ReadyShape::Globe(r, texture.clone(), *spin)))
                } else {
                    Err(format!("its spin must be finite, got {spin}"))
                }
            }),
            CurvedShape::Tube { length, radius } => positive("length", *length)
                .and_then(|l| positive("radius", *radius).map(|r| Some(ReadyShape::Tube(l, r)))),
            CurvedShape::Disc { radius } => {
                positive("radius", *radius).map(|r| Some(ReadyShape::Disc(r)))
            }
            CurvedShape::Model { model, size } => positive("size", *size).and_then(|size| {
                let ptr = Arc::as_ptr(model) as usize;
                traced.models.entry(ptr).or_insert_with(|| model.clone());
                let key = MeshKey::Model(ptr, g, size_key(size));
                used.insert(key.clone());
                let model = model.clone();
                traced
                    .get(key, g, size, move || Ok((*model).clone()))
                    .map(|m| m.map(ReadyShape::Mesh))
            }),
            CurvedShape::Carried { object, start } => {
                Ok(Some(ReadyShape::Carried(*object, *start)))
            }
            CurvedShape::Traced(model) => {
                if model.geometry == g {
                    Ok(Some(ReadyShape::Mesh(model.clone())))
                } else {
                    Err(format!(
                        "its mesh was traced for {} space, not {}",
                        model.geometry.name(),
                        g.name()
                    ))
                }
            }
            CurvedShape::Mesh {
                mesh,
                texture,
                size,
            } => positive("size", *size).and_then(|size| {
                let key = MeshKey::Asset(
                    mesh.id(),
                    texture.as_ref().map(Handle::id),
                    g,
                    size_key(size),
                );
                let Some(meshes) = meshes.as_deref() else {
                    return Err("the app has no mesh assets (add Bevy's MeshPlugin)".into());
                };
                let Some(m) = meshes.get(mesh) else {
                    return Ok(None);
                };
                let image = match texture {
                    None => None,
                    Some(t) => match images.as_deref().and_then(|i| i.get(t)) {
                        Some(i) => Some(i),
                        None => return Ok(None),
                    },
                };
                used.insert(key.clone());
                traced
                    .get(key, g, size, || {
                        model_from_bevy_mesh(m, image).map_err(|e| e.to_string())
                    })
                    .map(|m| m.map(ReadyShape::Mesh))
            }),
        };
        match shape {
            Ok(Some(shape)) => {
                if transform.0.is_finite() {
                    // A frame the game set past a face this frame (wrapped in the next
                    // update) is drawn where it is: at its image in the cell.
                    let frame =
                        if active.space.outside_by(g.project_point(transform.0.w_axis)) > 0.0 {
                            wrap_into_cell(&active.space, transform.0, 0.0).0
                        } else {
                            transform.0
                        };
                    ready.push(ReadyObject {
                        entity,
                        shape,
                        frame,
                        colour: object.colour,
                        emission: object.emission,
                    });
                } else {
                    problems.push(format!("object {entity}: its frame is not finite"));
                }
            }
            Ok(None) => pending += 1,
            Err(e) => problems.push(format!("object {entity}: {e}")),
        }
    }
    traced.keep_only(&used);
    for p in &problems {
        if !out.problems.contains(p) {
            warn!("{p}");
        }
    }
    *out = EntityObjects {
        objects: ready,
        pending,
        problems,
    };
}

/// Forgets traced meshes whose assets changed or went away (hot reloading).
pub fn forget_changed_assets(
    mut mesh_events: MessageReader<AssetEvent<Mesh>>,
    mut image_events: MessageReader<AssetEvent<Image>>,
    mut traced: ResMut<TracedMeshes>,
) {
    for e in mesh_events.read() {
        match e {
            AssetEvent::Modified { id }
            | AssetEvent::Removed { id }
            | AssetEvent::Unused { id } => {
                traced.forget_mesh(*id);
            }
            AssetEvent::LoadedWithDependencies { .. } | AssetEvent::Added { .. } => {
                traced.changed = true;
            }
        }
    }
    for e in image_events.read() {
        match e {
            AssetEvent::Modified { id }
            | AssetEvent::Removed { id }
            | AssetEvent::Unused { id } => {
                traced.forget_image(*id);
            }
            AssetEvent::LoadedWithDependencies { .. } | AssetEvent::Added { .. } => {
                traced.changed = true;
            }
        }
    }
}

/// Marks the entities the plugin spawned for the base scene's moving objects (the index in
/// [`crate::components::BaseScene::moving`]): despawned when the base scene or the space
/// changes.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct SceneMover(pub usize);

/// Spawns an entity for each moving object of the base scene while it is in use.
pub fn spawn_scene_movers(
    base: Res<crate::components::BaseScene>,
    active: Res<ActiveSpace>,
    movers: Query<Entity, With<SceneMover>>,
    mut commands: Commands,
) {
    if !(base.is_changed() || active.is_changed()) {
        return;
    }
    for e in &movers {
        commands.entity(e).despawn();
    }
    if base.for_space(&active).is_none() {
        return;
    }
    for (i, m) in base.moving.iter().enumerate() {
        commands.spawn((
            SceneMover(i),
            CurvedObject::of(
                CurvedShape::Carried {
                    object: m.object,
                    start: m.frame,
                },
                None,
            ),
            CurvedTransform(m.frame),
            CurvedVelocity(m.velocity),
        ));
    }
}

/// Adds the entities' systems (the plugin calls it).
pub(crate) fn add_systems(app: &mut App) {
    app.init_resource::<EntityObjects>()
        .init_resource::<TracedMeshes>()
        .init_resource::<ActiveSightlines>()
        .add_message::<ObjectCrossedFace>()
        .add_systems(FixedUpdate, (move_objects, wrap_objects).chain())
        .add_systems(
            Update,
            (
                wrap_objects.in_set(CurvedSpacesSystems::Wrap),
                collect_objects
                    .in_set(CurvedSpacesSystems::Upload)
                    .before(crate::render::upload::upload_scene),
                update_sightlines.before(CurvedSpacesSystems::Upload),
                spawn_scene_movers.before(CurvedSpacesSystems::Move),
            ),
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

/// A Bevy mesh of our model's triangles (positions, and normals and UVs where it has them),
/// kept in both worlds: the same model in a game's ordinary Bevy views, or handed back to
/// the tracer as [`CurvedObject::mesh`]. Its materials are not carried (Bevy's live in
/// the material, not the mesh).
#[must_use]
pub fn bevy_mesh_from_model(model: &Model) -> Mesh {
    use bevy::asset::RenderAssetUsages;
    use bevy::mesh::Indices;
    let s = &model.source;
    let f3 = |v: &DVec3| v.as_vec3().to_array();
    let mut mesh = Mesh::new(
        PrimitiveTopology::TriangleList,
        RenderAssetUsages::default(),
    )
    .with_inserted_attribute(
        Mesh::ATTRIBUTE_POSITION,
        s.positions.iter().map(f3).collect::<Vec<_>>(),
    );
    if let Some(n) = &s.normals {
        mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, n.iter().map(f3).collect::<Vec<_>>());
    }
    if let Some(u) = &s.uvs {
        mesh.insert_attribute(
            Mesh::ATTRIBUTE_UV_0,
            u.iter().map(|v| v.as_vec2().to_array()).collect::<Vec<_>>(),
        );
    }
    mesh.insert_indices(Indices::U32(s.indices.iter().flatten().copied().collect()));
    mesh
}
