//! glTF 2.0 models (`.gltf` with its buffers and images, or `.glb`) read with the `gltf`
//! crate: positions, normals, texture coordinates, base colour (factor and texture) and
//! emission of every triangle primitive of the default scene, node transforms applied.

use super::mesh::{MeshSource, Model};
use super::shading::SurfaceMaterial;
use super::texture::{Texture, TextureError};
use glam::{DMat3, DMat4, DVec2, DVec3};
use std::path::Path;

/// A model could not be read.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// Cannot read the glTF `path`: `source`.
    #[error("cannot read the glTF {path}: {source}")]
    Read {
        path: String,
        #[source]
        source: gltf::Error,
    },
    /// The glTF `path`: `at` has no positions.
    #[error("the glTF {path}: {at} has no positions")]
    MissingPositions { path: String, at: String },
    /// The glTF `path` has no triangle meshes in its scene.
    #[error("the glTF {path} has no triangle meshes in its scene")]
    NoTriangles { path: String },
    /// The glTF `path`: mesh `mesh`, primitive `primitive` has no positions.
    #[error("the glTF {path}: mesh {mesh:?}, primitive {primitive} has no positions")]
    NoPositions {
        path: String,
        mesh: String,
        primitive: usize,
    },
    /// The glTF `path`: mesh `mesh`, primitive `primitive` indexes vertex `index`, past its `count` vertices.
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
    /// The glTF `path`: image `image` is in `format`, which is not supported (use 8-bit RGB or RGBA).
    #[error(
        "the glTF {path}: image {image} is in {format}, which is not supported (use 8-bit RGB or RGBA)"
    )]
    ImageFormat {
        path: String,
        image: usize,
        format: String,
    },
    /// The glTF `path`: image `image`: `source`.
    #[error("the glTF {path}: image {image}: {source}")]
    Texture {
        path: String,
        image: usize,
        #[source]
        source: TextureError,
    },
}

/// Reads a glTF model. Primitives that are not triangles (points, lines) are left out;
/// a model with no triangles at all is an error.
pub fn load(path: &Path) -> Result<Model, GltfError> {
    let name = path.display().to_string();
    let (document, buffers, images) = gltf::import(path).map_err(|source| {
        // The reader checks that every primitive has positions: name that plainly.
        if let gltf::Error::Validation(errors) = &source
            && let Some((at, _)) = errors
                .iter()
                .find(|(at, _)| at.as_str().ends_with("[\"POSITION\"]"))
        {
            let at = at.as_str();
            return GltfError::MissingPositions {
                path: name.clone(),
                at: at
                    .strip_suffix(".attributes[\"POSITION\"]")
                    .unwrap_or(at)
                    .to_string(),
            };
        }
        GltfError::Read {
            path: name.clone(),
            source,
        }
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
    let mut materials: Vec<SurfaceMaterial> = document
        .materials()
        .map(|m| {
            let pbr = m.pbr_metallic_roughness();
            let [r, g, b, _] = pbr.base_color_factor();
            let [er, eg, eb] = m.emissive_factor();
            SurfaceMaterial {
                colour: DVec3::new(r.into(), g.into(), b.into()),
                texture: pbr
                    .base_color_texture()
                    .map(|t| t.texture().source().index() as u32),
                emission: DVec3::new(er.into(), eg.into(), eb.into()),
            }
        })
        .collect();
    let default_material = materials.len() as u32;
    materials.push(SurfaceMaterial::default());

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

/// What [`write_glb`] writes: one mesh of one primitive with one material.
#[derive(Clone, Debug, Default)]
pub struct GlbMesh<'a> {
    /// Vertex positions.
    pub positions: &'a [[f32; 3]],
    /// Vertex normals, if any.
    pub normals: Option<&'a [[f32; 3]]>,
    /// Texture coordinates, if any.
    pub uvs: Option<&'a [[f32; 2]]>,
    /// Triangle corners, three per triangle.
    pub indices: &'a [u32],
    /// Linear RGBA.
    pub base_colour: [f32; 4],
    /// Emitted colour (linear RGB).
    pub emission: [f32; 3],
    /// A PNG for the base-colour texture.
    pub texture_png: Option<&'a [u8]>,
    /// Leave the POSITION attribute out (to make a broken file for tests).
    pub omit_positions: bool,
}

/// Writes a binary glTF (`.glb`) of one mesh: what the project's asset generator uses for
/// the models under `assets/`, and tests for files of their own.
pub fn write_glb(path: &Path, mesh: &GlbMesh) -> std::io::Result<()> {
    use serde_json::json;
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut push = |bin: &mut Vec<u8>, bytes: &[u8], target: Option<u32>| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let offset = bin.len();
        bin.extend_from_slice(bytes);
        let mut view = json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len()});
        if let Some(t) = target {
            view["target"] = json!(t);
        }
        views.push(view);
        views.len() - 1
    };
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut attributes = serde_json::Map::new();
    if !mesh.omit_positions {
        let flat: Vec<f32> = mesh.positions.iter().flatten().copied().collect();
        let view = push(&mut bin, &floats(&flat), Some(34962));
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in mesh.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        accessors.push(json!({"bufferView": view, "componentType": 5126, "count": mesh.positions.len(), "type": "VEC3", "min": lo, "max": hi}));
        attributes.insert("POSITION".into(), json!(accessors.len() - 1));
    }
    if let Some(n) = mesh.normals {
        let flat: Vec<f32> = n.iter().flatten().copied().collect();
        let view = push(&mut bin, &floats(&flat), Some(34962));
        accessors.push(
            json!({"bufferView": view, "componentType": 5126, "count": n.len(), "type": "VEC3"}),
        );
        attributes.insert("NORMAL".into(), json!(accessors.len() - 1));
    }
    if let Some(t) = mesh.uvs {
        let flat: Vec<f32> = t.iter().flatten().copied().collect();
        let view = push(&mut bin, &floats(&flat), Some(34962));
        accessors.push(
            json!({"bufferView": view, "componentType": 5126, "count": t.len(), "type": "VEC2"}),
        );
        attributes.insert("TEXCOORD_0".into(), json!(accessors.len() - 1));
    }
    let index_bytes: Vec<u8> = mesh.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
    let view = push(&mut bin, &index_bytes, Some(34963));
    accessors.push(json!({"bufferView": view, "componentType": 5125, "count": mesh.indices.len(), "type": "SCALAR"}));
    let indices = accessors.len() - 1;
    let mut material = json!({
        "pbrMetallicRoughness": {"baseColorFactor": mesh.base_colour, "metallicFactor": 0.0},
        "emissiveFactor": mesh.emission,
    });
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": "bevy_curved_spaces"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attributes, "indices": indices, "material": 0}]}],
    });
    if let Some(png) = mesh.texture_png {
        let view = push(&mut bin, png, None);
        doc["images"] = json!([{"bufferView": view, "mimeType": "image/png"}]);
        doc["samplers"] = json!([{"magFilter": 9729, "minFilter": 9729}]);
        doc["textures"] = json!([{"source": 0, "sampler": 0}]);
        material["pbrMetallicRoughness"]["baseColorTexture"] = json!({"index": 0});
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    doc["materials"] = json!([material]);
    doc["buffers"] = json!([{"byteLength": bin.len()}]);
    doc["bufferViews"] = json!(views);
    doc["accessors"] = json!(accessors);
    let mut json_bytes = serde_json::to_vec(&doc).map_err(std::io::Error::other)?;
    while !json_bytes.len().is_multiple_of(4) {
        json_bytes.push(b' ');
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    std::fs::write(path, out)
}
