//! glTF 2.0 models (`.gltf` with its buffers and images, or `.glb`) read with the `gltf`
//! crate: positions, normals, texture coordinates, base colour (factor and texture) and
//! emission of every triangle primitive of the default scene, node transforms applied.

use super::mesh::{MeshSource, Model};
use super::shading::SurfaceMaterial;
use super::texture::{Texture, TextureError};
use glam::{DMat3, DMat4, DVec2, DVec3};
use std::path::Path;

/// The most node instances a model's scene may expand to (a node reached along several
/// paths counts once per path).
pub const MAX_NODE_INSTANCES: usize = 100_000;

/// The most triangles a model may have, over all its node instances.
pub const MAX_MODEL_TRIANGLES: usize = 4_000_000;

/// A model could not be read.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// Cannot read `what` of the glTF `path`: `source` (not a regular file, too large, …).
    #[error("cannot read {what} of the glTF {path}: {source}")]
    File {
        path: String,
        what: String,
        #[source]
        source: std::io::Error,
    },
    /// The glTF `path` is malformed: `problem`.
    #[error("the glTF {path}: {problem}")]
    Malformed { path: String, problem: String },
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
    let (document, buffers, images) = import(path, &name)?;
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
                reflectance: 0.0,
            }
        })
        .collect();
    let default_material = materials.len() as u32;
    materials.push(SurfaceMaterial::default());

    let source = scene_meshes(&document, &buffers, &name, default_material)?;
    if source.indices.is_empty() {
        return Err(GltfError::NoTriangles { path: name });
    }
    Ok(Model {
        source,
        materials,
        textures,
    })
}

/// Every triangle primitive of the document's scene (its default scene, else its first, else
/// all nodes), node transforms applied; node cycles, too many node instances or triangles,
/// attributes of the wrong type and non-finite numbers are errors.
fn scene_meshes(
    document: &gltf::Document,
    buffers: &[gltf::buffer::Data],
    name: &str,
    default_material: u32,
) -> Result<MeshSource, GltfError> {
    let name = name.to_string();
    let mut source = MeshSource::default();
    let roots: Vec<gltf::Node> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().collect(),
        None => document.nodes().collect(),
    };
    let malformed = |problem: String| GltfError::Malformed {
        path: name.clone(),
        problem,
    };
    // Depth-first, with the path from the root: a node among its own ancestors is a cycle.
    let mut stack: Vec<(gltf::Node, DMat4, usize)> =
        roots.into_iter().map(|n| (n, DMat4::IDENTITY, 0)).collect();
    let mut ancestors: Vec<usize> = Vec::new();
    let mut instances = 0usize;
    while let Some((node, parent, depth)) = stack.pop() {
        ancestors.truncate(depth);
        if ancestors.contains(&node.index()) {
            return Err(malformed(format!(
                "node {} is its own descendant (the node hierarchy has a cycle)",
                node.index()
            )));
        }
        ancestors.push(node.index());
        instances += 1;
        if instances > MAX_NODE_INSTANCES {
            return Err(malformed(format!(
                "its scene expands to more than {MAX_NODE_INSTANCES} node instances"
            )));
        }
        let local = DMat4::from_cols_array_2d(&node.transform().matrix().map(|c| c.map(f64::from)));
        if !local.is_finite() {
            return Err(malformed(format!(
                "node {} has a transform that is not finite",
                node.index()
            )));
        }
        let world = parent * local;
        let normal_matrix = DMat3::from_mat4(world).inverse().transpose();
        if let Some(mesh) = node.mesh() {
            let mesh_name = mesh.name().unwrap_or("unnamed").to_string();
            for (pi, primitive) in mesh.primitives().enumerate() {
                if primitive.mode() != gltf::mesh::Mode::Triangles {
                    continue;
                }
                check_attribute_types(&primitive).map_err(|problem| {
                    malformed(format!("mesh {mesh_name:?}, primitive {pi}: {problem}"))
                })?;
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
                if source.indices.len() + n > MAX_MODEL_TRIANGLES {
                    return Err(malformed(format!(
                        "it has more than {MAX_MODEL_TRIANGLES} triangles over its node instances"
                    )));
                }
                if let Some(p) = positions.iter().find(|p| !p.is_finite()) {
                    return Err(malformed(format!(
                        "mesh {mesh_name:?}, primitive {pi} has a vertex at {p} (not finite)"
                    )));
                }
                source.append(MeshSource {
                    positions,
                    normals: normals.filter(|n| n.len() == count),
                    uvs: uvs.filter(|u| u.len() == count),
                    indices: triangles,
                    materials: vec![material; n],
                });
            }
        }
        stack.extend(node.children().map(|c| (c, world, depth + 1)));
    }
    Ok(source)
}

/// What `gltf::import` does, made safe for any input: the file and every buffer or image
/// file it names are read only when regular and within [`crate::files::MAX_MODEL_BYTES`];
/// the GLB header is checked before the `gltf` crate does arithmetic on it; every buffer
/// view and accessor is checked against its buffer before anything indexes into it.
fn import(
    path: &Path,
    name: &str,
) -> Result<
    (
        gltf::Document,
        Vec<gltf::buffer::Data>,
        Vec<gltf::image::Data>,
    ),
    GltfError,
> {
    use crate::files::{MAX_MODEL_BYTES, check_regular, read_bytes};
    let malformed = |problem: String| GltfError::Malformed {
        path: name.to_string(),
        problem,
    };
    let file_error = |what: &str, source| GltfError::File {
        path: name.to_string(),
        what: what.to_string(),
        source,
    };
    let bytes = read_bytes(path, MAX_MODEL_BYTES).map_err(|e| file_error("the file", e))?;
    if bytes.starts_with(b"glTF") {
        let declared = bytes
            .get(8..12)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]));
        match declared {
            Some(length) if (12..=bytes.len() as u64).contains(&u64::from(length)) => {}
            Some(length) => {
                return Err(malformed(format!(
                    "its GLB header gives a length of {length} bytes; the file has {}",
                    bytes.len()
                )));
            }
            None => return Err(malformed("its GLB header is cut short".into())),
        }
    }
    // The gltf crate's own validation indexes the accessors a primitive's POSITION names
    // before checking that they exist: check every attribute's accessor first.
    let unchecked =
        gltf::Gltf::from_slice_without_validation(&bytes).map_err(|source| GltfError::Read {
            path: name.to_string(),
            source,
        })?;
    let root = unchecked.document.as_json();
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            if let Some(index) = primitive
                .attributes
                .values()
                .map(|i| i.value())
                .find(|&i| i >= root.accessors.len())
            {
                return Err(malformed(format!(
                    "mesh {m}, primitive {p} names accessor {index}, but there are {}",
                    root.accessors.len()
                )));
            }
        }
    }
    let gltf::Gltf { document, mut blob } = gltf::Gltf::from_slice(&bytes).map_err(|source| {
        // The reader checks that every primitive has positions: name that plainly.
        if let gltf::Error::Validation(errors) = &source
            && let Some((at, _)) = errors
                .iter()
                .find(|(at, _)| at.as_str().ends_with("[\"POSITION\"]"))
        {
            let at = at.as_str();
            return GltfError::MissingPositions {
                path: name.to_string(),
                at: at
                    .strip_suffix(".attributes[\"POSITION\"]")
                    .unwrap_or(at)
                    .to_string(),
            };
        }
        GltfError::Read {
            path: name.to_string(),
            source,
        }
    })?;
    let base = path.parent().unwrap_or(Path::new("."));
    let read_error = |source| GltfError::Read {
        path: name.to_string(),
        source,
    };
    let mut buffers = Vec::new();
    for buffer in document.buffers() {
        let data = match buffer.source() {
            gltf::buffer::Source::Uri(uri) if !uri.starts_with("data:") => {
                let file = external_file(base, uri).ok_or_else(|| {
                    malformed(format!(
                        "buffer {} names {uri:?}, not a file",
                        buffer.index()
                    ))
                })?;
                let mut data = read_bytes(&file, MAX_MODEL_BYTES)
                    .map_err(|e| file_error(&format!("buffer {} ({uri})", buffer.index()), e))?;
                data.resize(data.len().next_multiple_of(4), 0);
                gltf::buffer::Data(data)
            }
            source => gltf::buffer::Data::from_source_and_blob(source, Some(base), &mut blob)
                .map_err(read_error)?,
        };
        if data.len() < buffer.length() {
            return Err(malformed(format!(
                "buffer {} declares {} bytes but holds {}",
                buffer.index(),
                buffer.length(),
                data.len()
            )));
        }
        buffers.push(data);
    }
    check_views_and_accessors(&document, &buffers).map_err(malformed)?;
    // The gltf crate unwraps these when asked for an image's source.
    for (i, image) in document.as_json().images.iter().enumerate() {
        match (&image.buffer_view, &image.mime_type, &image.uri) {
            (Some(_), None, _) => {
                return Err(malformed(format!(
                    "image {i} is in a buffer view but gives no mimeType"
                )));
            }
            (None, _, None) => {
                return Err(malformed(format!(
                    "image {i} gives neither a buffer view nor a uri"
                )));
            }
            _ => {}
        }
    }
    let mut images = Vec::new();
    for image in document.images() {
        if let gltf::image::Source::Uri { uri, .. } = image.source()
            && !uri.starts_with("data:")
        {
            let file = external_file(base, uri).ok_or_else(|| {
                malformed(format!("image {} names {uri:?}, not a file", image.index()))
            })?;
            check_regular(&file, MAX_MODEL_BYTES)
                .map_err(|e| file_error(&format!("image {} ({uri})", image.index()), e))?;
        }
        images.push(
            gltf::image::Data::from_source(image.source(), Some(base), &buffers)
                .map_err(read_error)?,
        );
    }
    Ok((document, buffers, images))
}

/// The file a relative or `file:` URI names (percent-escapes decoded), as the `gltf` crate
/// resolves it; `None` for any other scheme, and for escapes that decode to no UTF-8 text.
fn external_file(base: &Path, uri: &str) -> Option<std::path::PathBuf> {
    if let Some(rest) = uri
        .strip_prefix("file://")
        .or_else(|| uri.strip_prefix("file:"))
    {
        Some(std::path::PathBuf::from(rest))
    } else if uri.contains(':') {
        None
    } else {
        // Not UTF-8 once decoded: the gltf crate would unwrap the error, so it names no file.
        urlencoding::decode(uri).ok().map(|path| base.join(&*path))
    }
}

/// Every buffer view inside its buffer, every accessor (and sparse part) inside its view.
fn check_views_and_accessors(
    document: &gltf::Document,
    buffers: &[gltf::buffer::Data],
) -> Result<(), String> {
    for view in document.views() {
        let held = buffers.get(view.buffer().index()).map_or(0, |b| b.len());
        let end = view.offset().checked_add(view.length());
        if end.is_none_or(|end| end > held) {
            return Err(format!(
                "buffer view {} spans bytes {}..{} of buffer {}, which holds {held}",
                view.index(),
                view.offset(),
                end.map_or_else(|| "overflow".to_string(), |e| e.to_string()),
                view.buffer().index()
            ));
        }
    }
    let fits = |view: &gltf::buffer::View, offset: usize, count: usize, element: usize| {
        let stride = view.stride().unwrap_or(element).max(element);
        count == 0
            || stride
                .checked_mul(count - 1)
                .and_then(|s| s.checked_add(offset))
                .and_then(|s| s.checked_add(element))
                .is_some_and(|end| end <= view.length())
    };
    for accessor in document.accessors() {
        let element = accessor.size();
        // The gltf reader computes `count − 1` and asserts `stride ≥ element`.
        if accessor.count() == 0 {
            return Err(format!("accessor {} has no elements", accessor.index()));
        }
        if let Some(view) = accessor.view()
            && view.stride().is_some_and(|s| s < element)
        {
            return Err(format!(
                "accessor {} has elements of {element} bytes but buffer view {} strides {} bytes",
                accessor.index(),
                view.index(),
                view.stride().unwrap_or(0)
            ));
        }
        if let Some(view) = accessor.view()
            && !fits(&view, accessor.offset(), accessor.count(), element)
        {
            return Err(format!(
                "accessor {} ({} elements of {element} bytes from byte {}) does not fit in buffer view {} ({} bytes)",
                accessor.index(),
                accessor.count(),
                accessor.offset(),
                view.index(),
                view.length()
            ));
        }
        if let Some(sparse) = accessor.sparse() {
            if sparse.count() == 0 {
                return Err(format!(
                    "the sparse part of accessor {} has no elements",
                    accessor.index()
                ));
            }
            let indices = sparse.indices();
            let values = sparse.values();
            let index_size = indices.index_type().size();
            if !fits(
                &indices.view(),
                indices.offset(),
                sparse.count(),
                index_size,
            ) || !fits(&values.view(), values.offset(), sparse.count(), element)
            {
                return Err(format!(
                    "the sparse part of accessor {} does not fit in its buffer views",
                    accessor.index()
                ));
            }
        }
    }
    Ok(())
}

/// Positions and normals must be float triples, texture coordinates float or normalised
/// 8/16-bit pairs, indices unsigned scalars: anything else would be read as something it
/// is not.
fn check_attribute_types(primitive: &gltf::Primitive) -> Result<(), String> {
    use gltf::Semantic;
    use gltf::accessor::{DataType, Dimensions};
    for (semantic, accessor) in primitive.attributes() {
        let (ty, dims, normalised) = (
            accessor.data_type(),
            accessor.dimensions(),
            accessor.normalized(),
        );
        let ok = match semantic {
            Semantic::Positions | Semantic::Normals => {
                ty == DataType::F32 && dims == Dimensions::Vec3
            }
            Semantic::TexCoords(_) => {
                dims == Dimensions::Vec2
                    && (ty == DataType::F32
                        || (normalised && matches!(ty, DataType::U8 | DataType::U16)))
            }
            _ => true,
        };
        if !ok {
            return Err(format!(
                "its {semantic:?} are {}{ty:?} {dims:?}, which glTF does not allow there",
                if normalised { "normalised " } else { "" }
            ));
        }
    }
    if let Some(indices) = primitive.indices()
        && (indices.dimensions() != Dimensions::Scalar
            || !matches!(
                indices.data_type(),
                DataType::U8 | DataType::U16 | DataType::U32
            ))
    {
        return Err(format!(
            "its indices are {:?} {:?}, not unsigned integers",
            indices.data_type(),
            indices.dimensions()
        ));
    }
    Ok(())
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
    let json_bytes = serde_json::to_vec(&doc).map_err(std::io::Error::other)?;
    let out = glb_container(&json_bytes, &bin);
    crate::files::write_atomic(path, &out)
}

/// A binary glTF container of a JSON chunk and a BIN chunk (each padded to 4 bytes as the
/// format asks): how [`write_glb`] packs a model, and how tests build files of their own.
#[must_use]
pub fn glb_container(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let mut json = json.to_vec();
    json.resize(json.len().next_multiple_of(4), b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().next_multiple_of(4), 0);
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    out
}
