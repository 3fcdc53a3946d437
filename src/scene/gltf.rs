//! glTF 2.0 models (`.gltf` with its buffers and images, or `.glb`) read with the `gltf`
//! crate: positions, normals, texture coordinates, base colour (factor and texture) and
//! emission of every triangle primitive of the default scene, node transforms applied.

use super::mesh::MeshSource;
use super::texture::{Texture, TextureError};
use crate::trace::Material;
use glam::{DMat3, DMat4, DVec2, DVec3};
use std::path::Path;

/// A model could not be read.
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    #[error("cannot read the glTF {path}: {source}")]
    Read {
        path: String,
        #[source]
        source: gltf::Error,
    },
    #[error("the glTF {path} has no triangle meshes in its scene")]
    NoTriangles { path: String },
    #[error("the glTF {path}: mesh {mesh:?}, primitive {primitive} has no positions")]
    NoPositions {
        path: String,
        mesh: String,
        primitive: usize,
    },
    #[error(
        "the glTF {path}: mesh {mesh:?}, primitive {primitive} indexes vertex {index}, past its {count} vertices"
    )]
    BadIndex {
        path: String,
        mesh: String,
        primitive: usize,
        index: u32,
        count: usize,
    },
    #[error(
        "the glTF {path}: image {image} is in {format}, which is not supported (use 8-bit RGB or RGBA)"
    )]
    ImageFormat {
        path: String,
        image: usize,
        format: String,
    },
    #[error("the glTF {path}: image {image}: {source}")]
    Texture {
        path: String,
        image: usize,
        #[source]
        source: TextureError,
    },
}

/// A model's triangles with its materials and textures (indices local to the model).
#[derive(Clone, Debug, PartialEq)]
pub struct Model {
    pub source: MeshSource,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
}

/// Reads a glTF model. Primitives that are not triangles (points, lines) are left out;
/// a model with no triangles at all is an error.
pub fn load(path: &Path) -> Result<Model, GltfError> {
    let name = path.display().to_string();
    let (document, buffers, images) = gltf::import(path).map_err(|source| GltfError::Read {
        path: name.clone(),
        source,
    })?;
    let textures = images
        .iter()
        .enumerate()
        .map(|(i, image)| {
            let rgba: Vec<u8> = match image.format {
                gltf::image::Format::R8G8B8A8 => image.pixels.clone(),
                gltf::image::Format::R8G8B8 => image
                    .pixels
                    .chunks_exact(3)
                    .flat_map(|c| [c[0], c[1], c[2], 255])
                    .collect(),
                gltf::image::Format::R8 => {
                    image.pixels.iter().flat_map(|&c| [c, c, c, 255]).collect()
                }
                other => {
                    return Err(GltfError::ImageFormat {
                        path: name.clone(),
                        image: i,
                        format: format!("{other:?}"),
                    });
                }
            };
            Texture::from_rgba8(image.width, image.height, &rgba).map_err(|source| {
                GltfError::Texture {
                    path: name.clone(),
                    image: i,
                    source,
                }
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    // glTF material i is ours i; primitives without a material use the last (the default).
    let mut materials: Vec<Material> = document
        .materials()
        .map(|m| {
            let pbr = m.pbr_metallic_roughness();
            let [r, g, b, _] = pbr.base_color_factor();
            let [er, eg, eb] = m.emissive_factor();
            Material {
                colour: DVec3::new(r.into(), g.into(), b.into()),
                texture: pbr
                    .base_color_texture()
                    .map(|t| t.texture().source().index() as u32),
                emission: DVec3::new(er.into(), eg.into(), eb.into()),
            }
        })
        .collect();
    let default_material = materials.len() as u32;
    materials.push(Material::default());

    let mut source = MeshSource::default();
    let roots: Vec<gltf::Node> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().collect(),
        None => document.nodes().collect(),
    };
    let mut stack: Vec<(gltf::Node, DMat4)> =
        roots.into_iter().map(|n| (n, DMat4::IDENTITY)).collect();
    while let Some((node, parent)) = stack.pop() {
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        let world = parent * local;
        let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
        if let Some(mesh) = node.mesh() {
            let mesh_name = mesh.name().unwrap_or("unnamed").to_string();
            for (pi, primitive) in mesh.primitives().enumerate() {
                if primitive.mode() != gltf::mesh::Mode::Triangles {
                    continue;
                }
                let reader = primitive.reader(|b| buffers.get(b.index()).map(|d| &d.0[..]));
                let positions: Vec<DVec3> = reader
                    .read_positions()
                    .ok_or_else(|| GltfError::NoPositions {
                        path: name.clone(),
                        mesh: mesh_name.clone(),
                        primitive: pi,
                    })?
                    .map(|p| world.transform_point3(DVec3::from_array(p.map(f64::from))))
                    .collect();
                let count = positions.len();
                let normals = reader.read_normals().map(|n| {
                    n.map(|n| {
                        (normal_matrix * DVec3::from_array(n.map(f64::from))).normalize_or_zero()
                    })
                    .collect::<Vec<_>>()
                });
                let uvs = reader.read_tex_coords(0).map(|t| {
                    t.into_f32()
                        .map(|[u, v]| DVec2::new(u.into(), v.into()))
                        .collect::<Vec<_>>()
                });
                let indices: Vec<u32> = match reader.read_indices() {
                    Some(i) => i.into_u32().collect(),
                    None => (0..count as u32).collect(),
                };
                if let Some(&bad) = indices.iter().find(|&&i| i as usize >= count) {
                    return Err(GltfError::BadIndex {
                        path: name.clone(),
                        mesh: mesh_name.clone(),
                        primitive: pi,
                        index: bad,
                        count,
                    });
                }
                let material = primitive
                    .material()
                    .index()
                    .map_or(default_material, |i| i as u32);
                let triangles: Vec<[u32; 3]> = indices
                    .chunks_exact(3)
                    .map(|c| [c[0], c[1], c[2]])
                    .collect();
                let n = triangles.len();
                source.append(MeshSource {
                    positions,
                    normals: normals.filter(|n| n.len() == count),
                    uvs: uvs.filter(|u| u.len() == count),
                    indices: triangles,
                    materials: vec![material; n],
                });
            }
        }
        stack.extend(node.children().map(|c| (c, world)));
    }
    if source.indices.is_empty() {
        return Err(GltfError::NoTriangles { path: name });
    }
    Ok(Model {
        source,
        materials,
        textures,
    })
}
