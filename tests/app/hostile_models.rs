//! glTF files built to break the importer — views and accessors past their buffers, cycles
//! and exponential node graphs, wrong attribute types, broken GLB headers, FIFOs and
//! devices for files — each refused with a clear error, quickly, never a panic or a hang.

use bevy_curved_spaces::files::MAX_MODEL_BYTES;
use bevy_curved_spaces::scene::gltf::load;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::time::Instant;

fn dir() -> PathBuf {
    crate::common::scratch_dir("hostile-models")
}

/// A GLB of `doc` (JSON) and `bin` (the BIN chunk, padded).
fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    bevy_curved_spaces::scene::gltf::glb_container(&serde_json::to_vec(doc).unwrap(), bin)
}

/// One triangle: positions (36 bytes) then indices (12 bytes) in the BIN chunk.
fn triangle() -> (Value, Vec<u8>) {
    let mut bin: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    bin.extend([0u32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": 48}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 12}
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [1.0, 1.0, 0.0]},
            {"bufferView": 1, "componentType": 5125, "count": 3, "type": "SCALAR"}
        ]
    });
    (doc, bin)
}

/// Loads `path` and expects an error containing `expect`, within a few seconds.
fn refused(path: &Path, expect: &str) {
    let started = Instant::now();
    let result = load(path);
    let seconds = started.elapsed().as_secs_f64();
    let e = result
        .err()
        .unwrap_or_else(|| panic!("{}: accepted", path.display()));
    let message = e.to_string();
    assert!(message.contains(expect), "{}: {message}", path.display());
    assert!(message.contains(&path.display().to_string()), "{message}");
    assert!(seconds < 5.0, "{}: {seconds:.1} s", path.display());
}

fn write(name: &str, doc: &Value, bin: &[u8]) -> PathBuf {
    let path = dir().join(name);
    std::fs::write(&path, glb(doc, bin)).unwrap();
    path
}

#[test]
fn the_plain_triangle_loads() {
    let (doc, bin) = triangle();
    let model = load(&write("triangle.glb", &doc, &bin)).expect("a valid triangle");
    assert_eq!(model.source.indices.len(), 1);
}

#[test]
fn views_and_accessors_past_their_buffers_are_refused() {
    let (doc, bin) = triangle();
    // An image whose view starts past the end of the buffer (the gltf crate panicked).
    let mut d = doc.clone();
    d["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({"buffer": 0, "byteOffset": 4096, "byteLength": 16}));
    d["images"] = json!([{"bufferView": 2, "mimeType": "image/png"}]);
    refused(&write("image_view_past_end.glb", &d, &bin), "buffer view 2");
    // A view of 2^40 bytes.
    let mut d = doc.clone();
    d["bufferViews"][0]["byteLength"] = json!(1u64 << 40);
    refused(&write("view_2_40.glb", &d, &bin), "buffer view 0");
    // An accessor of more elements than its view holds.
    let mut d = doc.clone();
    d["accessors"][0]["count"] = json!(1000);
    refused(&write("accessor_too_long.glb", &d, &bin), "accessor 0");
    // A buffer declaring more bytes than the file holds.
    let mut d = doc;
    d["buffers"][0]["byteLength"] = json!(1u64 << 40);
    refused(&write("buffer_2_40.glb", &d, &bin), "buffer 0");
}

#[test]
fn node_cycles_and_exponential_node_graphs_are_refused() {
    let (doc, bin) = triangle();
    let mut d = doc.clone();
    d["nodes"] = json!([{"children": [1]}, {"children": [0], "mesh": 0}]);
    refused(&write("cycle.glb", &d, &bin), "cycle");
    // Nodes 2i and 2i+1 both have children 2i+2 and 2i+3: 2^40 instances at depth 40.
    let mut d = doc;
    let nodes: Vec<Value> = (0..82)
        .map(|i| {
            let level = i / 2;
            if level < 40 {
                json!({"children": [2 * level + 2, 2 * level + 3]})
            } else {
                json!({"mesh": 0})
            }
        })
        .collect();
    d["nodes"] = json!(nodes);
    refused(&write("doubling.glb", &d, &bin), "node instances");
}

#[test]
fn attributes_of_the_wrong_type_and_non_finite_transforms_are_refused() {
    let (doc, bin) = triangle();
    // u8 normalised positions (glTF requires floats without an extension).
    let mut d = doc.clone();
    d["accessors"][0]["componentType"] = json!(5121);
    d["accessors"][0]["normalized"] = json!(true);
    refused(&write("u8_positions.glb", &d, &bin), "Positions");
    // A node matrix with a NaN in it (as JSON has no NaN, a huge scale that overflows).
    let mut d = doc;
    d["nodes"][0]["scale"] = json!([1e39, 1.0, 1.0]);
    refused(&write("huge_scale.glb", &d, &bin), "not finite");
}

#[test]
fn broken_glb_headers_are_refused() {
    let (doc, bin) = triangle();
    let mut bytes = glb(&doc, &bin);
    bytes[8..12].copy_from_slice(&5u32.to_le_bytes());
    let short = dir().join("short_header.glb");
    std::fs::write(&short, &bytes).unwrap();
    refused(&short, "GLB header");
    let cut = dir().join("cut.glb");
    std::fs::write(&cut, b"glTF\x02\0").unwrap();
    refused(&cut, "GLB header");
    let long = dir().join("long_header.glb");
    bytes[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(&long, &bytes).unwrap();
    refused(&long, "GLB header");
}

#[test]
fn fifos_devices_and_huge_files_are_refused_before_reading() {
    let d = dir();
    let fifo = d.join("fifo.glb");
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        refused(&fifo, "not a regular file");
    }
    if Path::new("/dev/zero").exists() {
        refused(Path::new("/dev/zero"), "not a regular file");
        // A .gltf whose buffer is /dev/zero (through a link next to it).
        let link = d.join("zero.bin");
        let _ = std::fs::remove_file(&link);
        if std::os::unix::fs::symlink("/dev/zero", &link).is_ok() {
            let (mut doc, _) = triangle();
            doc["buffers"][0]["uri"] = json!("zero.bin");
            let path = d.join("zero_buffer.gltf");
            std::fs::write(&path, serde_json::to_vec(&doc).unwrap()).unwrap();
            refused(&path, "not a regular file");
        }
    }
    // A sparse buffer file one byte over the limit.
    let huge = d.join("huge.bin");
    std::fs::File::create(&huge)
        .unwrap()
        .set_len(MAX_MODEL_BYTES + 1)
        .unwrap();
    let (mut doc, _) = triangle();
    doc["buffers"][0]["uri"] = json!("huge.bin");
    let path = d.join("huge_buffer.gltf");
    std::fs::write(&path, serde_json::to_vec(&doc).unwrap()).unwrap();
    refused(&path, "more than the limit");
}

/// Image and buffer URIs whose percent-escapes decode to no UTF-8 text (the gltf crate
/// unwrapped that decoding and panicked) name no file: a clear error.
#[test]
fn uris_that_decode_to_no_text_are_refused() {
    let (doc, bin) = triangle();
    let mut d = doc.clone();
    d["images"] = json!([{"uri": "%ff.png"}]);
    refused(&write("image_uri_not_utf8.glb", &d, &bin), "not a file");
    let mut d = doc;
    d["buffers"][0]["uri"] = json!("%ff%fe.bin");
    let path = dir().join("buffer_uri_not_utf8.gltf");
    std::fs::write(&path, serde_json::to_vec(&d).unwrap()).unwrap();
    refused(&path, "not a file");
}
