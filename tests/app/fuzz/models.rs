//! glTF models and Bevy meshes: hostile numbers, random bytes, the regression corpus.

use super::*;

/// The shipped models' bytes, and their JSON and BIN chunks.
fn glb_parts(name: &str) -> (Vec<u8>, Value, Vec<u8>) {
    let bytes = std::fs::read(manifest().join("assets/models").join(name)).unwrap();
    let json_length = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&bytes[20..20 + json_length]).unwrap();
    let bin = bytes[20 + json_length + 8..].to_vec();
    (bytes, json, bin)
}

fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    bevy_curved_spaces::scene::gltf::glb_container(&serde_json::to_vec(doc).unwrap(), bin)
}

/// Loads model bytes from a file within the time bound; a loaded model is finite.
fn model_outcome(bytes: &[u8], name: &str) -> bool {
    let path = crate::common::scratch_dir("fuzz-models").join(name);
    std::fs::write(&path, bytes).unwrap();
    let started = Instant::now();
    let result = load(&path);
    let seconds = started.elapsed().as_secs_f64();
    assert!(seconds < 10.0, "{name}: {seconds:.1} s");
    match result {
        Ok(model) => {
            assert!(
                model.source.positions.iter().all(|p| p.is_finite()),
                "{name}: non-finite positions loaded"
            );
            true
        }
        Err(e) => {
            assert!(e.to_string().contains(&path.display().to_string()), "{e}");
            false
        }
    }
}

/// Every number (and index) in a JSON value, as paths into it.
fn json_numbers(v: &Value, path: &mut Vec<Value>, out: &mut Vec<Vec<Value>>) {
    match v {
        Value::Number(_) => out.push(path.clone()),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(Value::from(i));
                json_numbers(x, path, out);
                path.pop();
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                path.push(Value::from(k.as_str()));
                json_numbers(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn at_path<'a>(v: &'a mut Value, path: &[Value]) -> &'a mut Value {
    path.iter().fold(v, |v, k| match k {
        Value::String(s) => &mut v[s.as_str()],
        k => &mut v[k.as_u64().unwrap() as usize],
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0xf022),
        ..ProptestConfig::default()
    })]

    /// A number or index of a shipped model's JSON replaced by a hostile one, or its key
    /// deleted.
    #[test]
    fn models_with_hostile_numbers(which in 0usize..2, slot in 0usize..512, value in prop_oneof![
        Just(serde_json::json!(-1)), Just(serde_json::json!(0)), Just(serde_json::json!(1u64 << 40)),
        Just(serde_json::json!(4_294_967_295u64)), Just(serde_json::json!(1e308)), Just(serde_json::json!(-1e308)),
        Just(serde_json::json!(1e-320)), Just(serde_json::json!(3)), Just(Value::Null), Just(serde_json::json!("x")),
    ], delete in any::<bool>()) {
        let name = ["cube.glb", "torus_knot.glb"][which];
        let (_, mut doc, bin) = glb_parts(name);
        let mut spots = Vec::new();
        json_numbers(&doc, &mut Vec::new(), &mut spots);
        let spot = &spots[slot % spots.len()];
        if delete {
            let (key, parent) = spot.split_last().unwrap();
            if let (Value::String(k), Some(o)) = (key, at_path(&mut doc, parent).as_object_mut()) {
                o.remove(k);
            }
        } else {
            *at_path(&mut doc, spot) = value;
        }
        model_outcome(&glb(&doc, &bin), &format!("numbers-{which}-{slot}.glb"));
    }

    /// A shipped model with random bytes overwritten, or cut short.
    #[test]
    fn models_with_random_bytes(which in 0usize..2, at in 0.0f64..1.0, bytes in proptest::collection::vec(any::<u8>(), 1..16), cut in any::<bool>()) {
        let name = ["cube.glb", "torus_knot.glb"][which];
        let (mut file, _, _) = glb_parts(name);
        let start = (at * file.len() as f64) as usize;
        if cut {
            file.truncate(start);
        } else {
            for (i, b) in bytes.iter().enumerate() {
                if let Some(x) = file.get_mut(start + i) {
                    *x = *b;
                }
            }
        }
        model_outcome(&file, &format!("bytes-{which}-{start}.glb"));
    }
}

/// Every file of the regression corpus (inputs that once panicked or hung) is refused with
/// an error, quickly.
#[test]
fn the_regression_corpus_is_refused_cleanly() {
    let dir = manifest().join("tests/corpus");
    let mut seen = 0;
    for entry in std::fs::read_dir(&dir).expect("tests/corpus exists") {
        let path = entry.unwrap().path();
        let started = Instant::now();
        let message = match path.extension().and_then(|e| e.to_str()) {
            Some("glb" | "gltf") => load(&path).err().map(|e| e.to_string()),
            Some("toml") => {
                match bevy_curved_spaces::trace::product::file::load_product_scene_file(&path) {
                    Err(e) => Some(e.to_string()),
                    Ok(Some(_)) => None,
                    Ok(None) => bevy_curved_spaces::scene::file::load_scene_file(&path)
                        .err()
                        .map(|e| e.to_string()),
                }
            }
            Some("json") => bevy_curved_spaces::space::file::load_space_file(&path)
                .err()
                .map(|e| e.to_string()),
            _ => continue,
        };
        assert!(message.is_some(), "{}: accepted", path.display());
        assert!(
            started.elapsed().as_secs_f64() < 5.0,
            "{}: slow",
            path.display()
        );
        seen += 1;
    }
    assert!(seen >= 8, "only {seen} corpus files");
}

/// A Bevy mesh built from fuzzed data: positions (some hostile), normals and UVs of the
/// right or a wrong length, indices some of which may point past the vertices, and a
/// topology that may not be a triangle list.
fn fuzzed_bevy_mesh(
    positions: &[[f32; 3]],
    normals: Option<usize>,
    uvs: Option<usize>,
    indices: Option<&[u32]>,
    strip: bool,
) -> bevy::mesh::Mesh {
    use bevy::asset::RenderAssetUsages;
    use bevy::mesh::{Indices, Mesh, PrimitiveTopology};
    let topology = if strip {
        PrimitiveTopology::TriangleStrip
    } else {
        PrimitiveTopology::TriangleList
    };
    let mut mesh = Mesh::new(topology, RenderAssetUsages::default())
        .with_inserted_attribute(Mesh::ATTRIBUTE_POSITION, positions.to_vec());
    if let Some(n) = normals {
        mesh.insert_attribute(Mesh::ATTRIBUTE_NORMAL, vec![[0.0f32, 1.0, 0.0]; n]);
    }
    if let Some(n) = uvs {
        mesh.insert_attribute(Mesh::ATTRIBUTE_UV_0, vec![[0.5f32, 0.5]; n]);
    }
    if let Some(i) = indices {
        mesh.insert_indices(Indices::U32(i.to_vec()));
    }
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, failure_persistence: None, ..ProptestConfig::default() })]

    /// Bevy meshes with hostile data (the path of `CurvedObject` with a `Handle<Mesh>`): a
    /// model or a named error, then a traced model or a named error in every geometry —
    /// never a panic, never a non-finite triangle.
    #[test]
    fn bevy_meshes_with_hostile_data(
        raw in proptest::collection::vec((any::<u8>(), -2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0), 0..24),
        normals_off in prop_oneof![Just(None), Just(Some(0usize)), Just(Some(1usize))],
        uvs_off in prop_oneof![Just(None), Just(Some(0usize)), Just(Some(2usize))],
        indices in proptest::option::of(proptest::collection::vec(0u32..30, 0..36)),
        strip in proptest::bool::weighted(0.1),
        size in prop_oneof![Just(0.3f64), Just(0.0), Just(-1.0), Just(f64::NAN), Just(1e300), Just(3.0)],
    ) {
        use bevy_curved_spaces::plugin::objects::model_from_bevy_mesh;
        use bevy_curved_spaces::scene::TracedModel;
        let hostile = [f32::NAN, f32::INFINITY, -f32::INFINITY, 1e38, -1e38, 1e-40, 0.0];
        let positions: Vec<[f32; 3]> = raw
            .iter()
            .map(|&(k, x, y, z)| {
                // One vertex in eight gets a hostile coordinate.
                if k % 8 == 0 {
                    [hostile[usize::from(k / 8) % hostile.len()], y, z]
                } else {
                    [x, y, z]
                }
            })
            .collect();
        let n = positions.len();
        let mesh = fuzzed_bevy_mesh(
            &positions,
            normals_off.map(|d: usize| n + d),
            uvs_off.map(|d: usize| n.saturating_sub(d)),
            indices.as_deref(),
            strip,
        );
        let started = Instant::now();
        if let Ok(model) = model_from_bevy_mesh(&mesh, None) {
            for g in Geometry::ALL {
                if let Ok(traced) = TracedModel::new(g, &model, size) {
                    for t in &traced.mesh.triangles {
                        prop_assert!(t.corners.iter().all(|c| c.is_finite()), "{g:?}: {t:?}");
                    }
                }
            }
        }
        prop_assert!(started.elapsed().as_secs_f64() < 5.0);
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    /// Any model of finite triangles goes to a Bevy mesh and back to the same traced
    /// triangles, in every geometry: the asset path and the file path draw alike.
    #[test]
    fn models_round_trip_through_bevy_meshes(
        corners in proptest::collection::vec((-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0), 3..30),
    ) {
        use bevy_curved_spaces::plugin::objects::{bevy_mesh_from_model, model_from_bevy_mesh};
        use bevy_curved_spaces::scene::mesh::MeshSource;
        use bevy_curved_spaces::scene::{Model, SurfaceMaterial, TracedModel};
        use glam::DVec3;
        let positions: Vec<DVec3> = corners
            .iter()
            .map(|&(x, y, z)| DVec3::new(f64::from(x), f64::from(y), f64::from(z)))
            .collect();
        let triangles = positions.len() / 3;
        let model = Model {
            source: MeshSource {
                indices: (0..triangles as u32).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
                materials: vec![0; triangles],
                positions,
                normals: None,
                uvs: None,
            },
            materials: vec![SurfaceMaterial::default()],
            textures: Vec::new(),
        };
        let back = model_from_bevy_mesh(&bevy_mesh_from_model(&model), None).expect("our own mesh");
        for g in Geometry::ALL {
            match (TracedModel::new(g, &model, 0.3), TracedModel::new(g, &back, 0.3)) {
                (Ok(a), Ok(b)) => prop_assert_eq!(&a.mesh, &b.mesh, "{:?}", g),
                (Err(a), Err(b)) => prop_assert_eq!(a.to_string(), b.to_string()),
                (a, b) => prop_assert!(false, "{g:?}: {:?} against {:?}", a.is_ok(), b.is_ok()),
            }
        }
    }
}
