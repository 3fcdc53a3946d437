//! Scene content beyond the quadrics of [`crate::trace`]: triangle meshes with their
//! bounding-volume hierarchy ([`mesh`]), textures ([`texture`]), glTF models ([`gltf`]),
//! the player's avatar ([`avatar`]) and scene files ([`file`]).

pub mod assets;
pub mod avatar;
pub mod file;
pub mod gltf;
pub mod mesh;
pub mod texture;

use crate::geometry::Geometry;
use crate::trace::{Avatar, Material, Scene};
use std::sync::Arc;

impl Scene {
    /// Adds a model's triangles as a mesh placed by the scale rule of [`mesh`] (its
    /// materials and textures are appended to the scene's); returns the mesh's index for
    /// [`crate::trace::MeshInstance`]s.
    pub fn add_model(
        &mut self,
        geometry: Geometry,
        model: &gltf::Model,
        scale: f64,
    ) -> Result<u32, mesh::MeshError> {
        let (materials, textures) = (self.materials.len() as u32, self.textures.len() as u32);
        let mut source = model.source.clone();
        for m in &mut source.materials {
            *m += materials;
        }
        let mesh = source.place(geometry, scale)?;
        self.materials
            .extend(model.materials.iter().map(|m| Material {
                texture: m.texture.map(|t| t + textures),
                ..*m
            }));
        self.textures
            .extend(model.textures.iter().cloned().map(Arc::new));
        self.meshes.push(Arc::new(mesh));
        Ok(self.meshes.len() as u32 - 1)
    }

    /// Gives the scene the player's avatar ([`avatar::ship`]) of length `size`; place it
    /// with [`Scene::set_avatar_frame`] (the plugin does, every frame).
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
