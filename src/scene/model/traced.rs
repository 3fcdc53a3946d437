//! Meshes in scenes: models traced once (their hierarchy, materials and textures) and
//! shared by the scenes of one geometry, and the avatar.

use super::*;

impl CurvedScene {
    /// Adds a model's triangles as a mesh placed by the scale rule of [`mesh`] (its
    /// materials and textures are appended to the scene's); returns the mesh's index for
    /// [`crate::scene::MeshInstance`]s.
    pub fn add_model(
        &mut self,
        geometry: Geometry,
        model: &Model,
        scale: f64,
    ) -> Result<u32, mesh::MeshError> {
        let (materials, textures) = (self.materials.len() as u32, self.textures.len() as u32);
        let mut source = model.source.clone();
        for m in &mut source.materials {
            *m += materials;
        }
        let mesh = source.place(geometry, scale)?;
        self.materials
            .extend(model.materials.iter().map(|m| SurfaceMaterial {
                texture: m.texture.map(|t| t + textures),
                ..*m
            }));
        self.textures
            .extend(model.textures.iter().cloned().map(Arc::new));
        self.meshes.push(Arc::new(mesh));
        Ok(self.meshes.len() as u32 - 1)
    }

    /// Gives the scene the player's avatar ([`avatar::ship`]) of length `size`; place it
    /// with [`CurvedScene::set_avatar_frame`] (the plugin does, every frame).
    pub fn add_avatar(&mut self, geometry: Geometry, size: f64) -> Result<(), mesh::MeshError> {
        let model = avatar::ship();
        let mesh = self.add_model(geometry, &model, size / avatar::SHIP_LENGTH)?;
        let radius = self.meshes[mesh as usize].radius;
        self.avatar = Some(Avatar {
            mesh,
            instances: Vec::new(),
            skip: avatar::SKIP_FACTOR * radius,
        });
        Ok(())
    }
}

/// The avatar's length in a space of inradius `inradius`: small beside the cell, so that
/// the copy the eye sits in is far from every other copy.
#[must_use]
pub fn avatar_size(inradius: f64) -> f64 {
    0.3 * inradius
}

/// A mesh ready to be placed in any scene of one geometry: its hierarchy (built once, at a
/// size), its materials and textures. Scenes share it (an [`Arc`]): adding it to a scene
/// ([`CurvedScene::add_traced`]) appends its materials and textures, not its triangles.
#[derive(Clone, Debug, PartialEq)]
pub struct TracedModel {
    /// The geometry its chart triangles are for.
    pub geometry: Geometry,
    /// The triangles and their hierarchy; material indices count from 0 in `materials`.
    pub mesh: Arc<Mesh>,
    /// Its materials; their texture indices count from 0 in `textures`.
    pub materials: Vec<SurfaceMaterial>,
    /// Its textures.
    pub textures: Vec<Arc<Texture>>,
}

impl TracedModel {
    /// A model scaled so that its farthest vertex from its origin is `size` (geodesic) away
    /// from the frame's origin, as scene files' `size` does.
    pub fn new(geometry: Geometry, model: &Model, size: f64) -> Result<Self, mesh::MeshError> {
        let model_radius = model.source.radius();
        if model.source.indices.is_empty() {
            return Err(mesh::MeshError::Empty);
        }
        if !(model_radius > 0.0 && model_radius.is_finite()) {
            return Err(mesh::MeshError::Scale(model_radius));
        }
        let mesh = model.source.place(geometry, size / model_radius)?;
        Ok(Self {
            geometry,
            mesh: Arc::new(mesh),
            materials: model.materials.clone(),
            textures: model.textures.iter().cloned().map(Arc::new).collect(),
        })
    }
}

impl CurvedScene {
    /// Adds a shared model's mesh (the same [`Arc`], no copy of its triangles), its
    /// materials and its textures; returns the mesh's index and the material base for its
    /// [`MeshInstance::material_base`]. Each call appends: add a model once per scene and
    /// give every instance of it the same pair.
    pub fn add_traced(&mut self, model: &TracedModel) -> (u32, u32) {
        let textures = self.textures.len() as u32;
        let base = self.materials.len() as u32;
        self.materials
            .extend(model.materials.iter().map(|m| SurfaceMaterial {
                texture: m.texture.map(|t| t + textures),
                ..*m
            }));
        self.textures.extend(model.textures.iter().cloned());
        self.meshes.push(model.mesh.clone());
        (self.meshes.len() as u32 - 1, base)
    }
}
