//! Bevy meshes and images as traced models and textures, and back; each mesh traced once
//! per model, size and geometry (off the main thread when it is large).

use super::*;

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
        reflectance: 0.0,
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
pub(super) enum MeshKey {
    Model(usize, Geometry, u64),
    Asset(AssetId<Mesh>, Option<AssetId<Image>>, Geometry, u64),
}

pub(super) enum MeshState {
    Ready(Arc<TracedModel>),
    Building(Task<Result<TracedModel, String>>),
    Failed(String),
}

/// The meshes the entities use, traced once per model, size and geometry: the models
/// themselves are kept alive here while any entity uses them.
#[derive(Resource, Default)]
pub struct TracedMeshes {
    pub(super) states: HashMap<MeshKey, MeshState>,
    /// Models by the identity in their key, kept alive while their key is.
    pub(super) models: HashMap<usize, Arc<Model>>,
    /// An asset changed: gather the objects again.
    pub(super) changed: bool,
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
    pub(super) fn get(
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
    pub(super) fn forget_mesh(&mut self, id: AssetId<Mesh>) {
        self.states
            .retain(|k, _| !matches!(k, MeshKey::Asset(m, _, _, _) if *m == id));
        self.changed = true;
    }

    pub(super) fn forget_image(&mut self, id: AssetId<Image>) {
        self.states
            .retain(|k, _| !matches!(k, MeshKey::Asset(_, Some(t), _, _) if *t == id));
        self.changed = true;
    }

    /// Drops the traced meshes no entity uses any more.
    pub(super) fn keep_only(&mut self, used: &std::collections::HashSet<MeshKey>) {
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
