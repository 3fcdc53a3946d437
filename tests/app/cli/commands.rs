//! Each command end to end: `list`, `info`, `trace`, `render`, `export`, `light`, generator
//! files, long traces and closed pipes.

use super::*;

#[test]
fn list_shows_every_space() {
    let out = run(&["list"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for seed in bevy_curved_spaces::space::SEED_SPACES {
        assert!(text.contains(seed.id), "{} missing", seed.id);
    }
    assert!(text.contains("11.1990647"));
}

#[test]
fn info_json_has_the_documented_fields() {
    let v = json(&["info", "seifert-weber", "--json"]);
    assert_eq!(v["name"], "seifert-weber");
    assert_eq!(v["geometry"], "hyperbolic");
    assert_eq!(v["faces"].as_array().unwrap().len(), 12);
    let f = &v["faces"][0];
    let n: Vec<f64> = f["normal"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((n.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-15);
    assert!(f["offset"].as_f64().unwrap() > 0.0);
    assert!((v["volume"].as_f64().unwrap() - 11.1990647).abs() < 5e-8);
    for key in [
        "inradius",
        "circumradius",
        "edge_length",
        "injectivity_radius",
    ] {
        assert!(v[key].as_f64().unwrap() > 0.0, "{key}");
    }
    assert_eq!(v["edge_cycles"].as_array().unwrap().len(), 6);
    assert_eq!(v["edge_cycles"][0]["edges"], 5);
    assert_eq!(v["vertex_cycles"], 1);
    assert_eq!(v["orientable"], true);
    assert_eq!(v["manifold"], true);
    assert!(v["holonomy_order"].is_null() && v["group_order"].is_null());
    assert!(!v["closed_geodesics"].as_array().unwrap().is_empty());
    assert!(v["closed_geodesics"][0]["count"].as_u64().unwrap() > 0);

    let p = json(&["info", "poincare", "--json"]);
    assert_eq!(p["group_order"], 120);
    assert_eq!(p["closed_geodesics"].as_array().unwrap().len(), 0);
    let c = json(&["info", "mirrored-cube", "--json"]);
    assert_eq!(c["holonomy_order"], 8);
    assert!(c["injectivity_radius"].is_null());
    assert_eq!(c["manifold"], false);
    assert!(json(&["info", "third-turn", "--json"])["edge_length"].is_null());
}

#[test]
fn trace_json_in_both_precisions() {
    let v = json(&[
        "trace",
        "torus",
        "--dir",
        "1,0,0",
        "--crossings",
        "3",
        "--json",
    ]);
    let crossings = v["crossings"].as_array().unwrap();
    assert_eq!(crossings.len(), 3);
    for (i, c) in crossings.iter().enumerate() {
        assert_eq!(c["face_normal"], serde_json::json!([1.0, 0.0, 0.0]));
        assert!((c["distance"].as_f64().unwrap() - (0.5 + i as f64)).abs() < 1e-15);
        assert_eq!(c["point"][0], -0.5);
    }
    assert_eq!(v["end"]["direction"], serde_json::json!([1.0, 0.0, 0.0]));

    let by_distance = json(&[
        "trace",
        "seifert-weber",
        "--dir",
        "0.2,-0.4,1",
        "--from",
        "0.1,0,-0.2",
        "--distance",
        "5",
        "--json",
    ]);
    assert!((by_distance["end"]["distance"].as_f64().unwrap() - 5.0).abs() < 1e-12);
    let single = json(&[
        "trace",
        "poincare",
        "--dir",
        "1,2,3",
        "--crossings",
        "10",
        "--precision",
        "f32",
        "--json",
    ]);
    let double = json(&[
        "trace",
        "poincare",
        "--dir",
        "1,2,3",
        "--crossings",
        "10",
        "--json",
    ]);
    let d = |v: &Value| v["end"]["distance"].as_f64().unwrap();
    assert!((d(&single) - d(&double)).abs() < 1e-5);
    assert_ne!(
        d(&single),
        d(&double),
        "f32 should differ in the last digits"
    );
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = temp_dir("render");
    let out = dir.join("sub/torus.png");
    let o = run(&[
        "render",
        "torus",
        "--cpu",
        "--size",
        "48x27",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("torus.png"));
    let image = image::open(&out).unwrap();
    assert_eq!((image.width(), image.height()), (48, 27));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn export_then_use_a_space_file() {
    let dir = temp_dir("export");
    let file = dir.join("sw.json");
    let o = run(&["export", "seifert-weber", "--out", file.to_str().unwrap()]);
    assert!(o.status.success());
    let v = json(&["info", file.to_str().unwrap(), "--json"]);
    assert!((v["volume"].as_f64().unwrap() - 11.1990647).abs() < 5e-8);
    // Break the twist of one pairing: the error names the problem and the file.
    let mut record: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    record["faces"][0]["pairing"][0][0] = Value::from(0.5);
    std::fs::write(&file, record.to_string()).unwrap();
    fails_with(&["info", file.to_str().unwrap()], "not an isometry");
    fails_with(&["info", file.to_str().unwrap()], "sw.json");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_closed_pipe_is_not_a_crash() {
    use std::io::Read;
    let mut child = Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(["info", "seifert-weber"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let status = child.wait().unwrap();
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    assert!(status.success(), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// `trace` streams: a walk of 10⁶ crossings prints valid JSON in constant memory, and a
/// distance that needs more crossings than that ends the JSON properly, says where it
/// stopped, and fails naming the limit.
#[test]
fn long_traces_stream_valid_json_and_name_their_limit() {
    let out = run(&[
        "trace",
        "seifert-weber",
        "--dir",
        "1,0.3,0.2",
        "--crossings",
        "1000000",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(v["crossings"].as_array().unwrap().len(), 1_000_000);
    let out = run(&[
        "trace",
        "torus",
        "--dir",
        "1,0.3,0.2",
        "--distance",
        "1e6",
        "--json",
    ]);
    assert!(!out.status.success());
    let v: Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(v["crossings"].as_array().unwrap().len(), 1_000_000);
    assert!(
        v["end"]["stopped"]
            .as_str()
            .unwrap()
            .contains("1000000 crossings")
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("needs more than 1000000 crossings"), "{err}");
}

#[test]
fn generator_files_load_export_and_name_their_mistakes() {
    let dir = temp_dir("gen");
    // Export a seed space as a .gen file and read it back: the same volume.
    let path = dir.join("sw.gen");
    let out = run(&["export", "seifert-weber", "--out", path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("#\tseifert-weber"));
    let v = json(&["info", path.to_str().unwrap(), "--json"]);
    assert!((v["volume"].as_f64().unwrap() - 11.199064740815).abs() < 1e-9);
    assert_eq!(v["homology"], "Z/5 + Z/5 + Z/5");
    // --gen-format writes the same to standard output.
    let out = run(&["export", "poincare", "--gen-format"]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("#\tpoincare"));
    // A library member by id, and a census manifold from its shipped file.
    let v = json(&["info", "lens-7-2", "--json"]);
    assert_eq!(v["group_order"], 7);
    let census = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/spaces/census/m003_-3_1.gen"
    );
    let v = json(&["info", census, "--json"]);
    assert_eq!(v["homology"], "Z/5 + Z/5");
    // A moved basepoint gives another cell of the same space.
    let moved = json(&["info", census, "--json", "--basepoint", "0.05,0,0"]);
    assert!((moved["volume"].as_f64().unwrap() - 0.9427073627769).abs() < 1e-9);
    // Mistakes.
    let bad = dir.join("bad.gen");
    std::fs::write(&bad, "1 0 0 0\n0 1 0 0\n0 0 1 0\n1 0 0 one\n").unwrap();
    fails_with(
        &["info", bad.to_str().unwrap()],
        "line 4: `one` is not a number",
    );
    std::fs::write(
        &bad,
        "1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1  1 0 0 0 0 1 0 0 0 0 1 0 0 1 0 1\n",
    )
    .unwrap();
    fails_with(&["info", bad.to_str().unwrap()], "not cocompact");
    std::fs::write(&bad, "0 1 0 0 -1 0 0 0 0 0 1 0 0 0 0 1\n").unwrap();
    fails_with(&["info", bad.to_str().unwrap()], "--basepoint");
    fails_with(
        &["info", "missing.gen"],
        "cannot read generator file missing.gen",
    );
    fails_with(&["info", "lens-6-3"], "common factor 3");
    // Projective space reaches π/2: a generator file holds it, a JSON space file cannot.
    fails_with(&["export", "projective-space"], "--gen-format");
    let out = run(&["export", "projective-space", "--gen-format"]);
    assert!(out.status.success());
    let v = json(&["info", "projective-space", "--json"]);
    assert_eq!(v["group_order"], 2);
    assert_eq!(v["homology"], "Z/2");
    fails_with(&["info", "census-99"], "census-10");
    fails_with(&["info", census, "--basepoint", "2,0,0"], "basepoint");
    fails_with(&["info", census, "--basepoint", "nan,0,0"], "");
    let out = run(&["list"]);
    let text = String::from_utf8_lossy(&out.stdout);
    for family in bevy_curved_spaces::space::library::FAMILIES {
        assert!(text.contains(family.pattern), "{} missing", family.pattern);
    }
}

#[test]
fn light_sums_a_lamps_images_and_checks_its_shortcut() {
    let v = json(&[
        "light",
        "torus",
        "--at",
        "0.2,0.1,-0.3",
        "--fog",
        "1.5",
        "--reach",
        "3",
        "--check",
        "6",
        "--json",
    ]);
    let total = v["total"].as_f64().unwrap();
    let (exact, tail) = (v["exact"].as_f64().unwrap(), v["tail"].as_f64().unwrap());
    assert!((total - exact - tail).abs() < 1e-12 * total);
    assert!(v["images"].as_u64().unwrap() > 100);
    // The longer sum is within the stated bounds of the shorter one's tail.
    let check = &v["check"];
    let difference = check["difference"].as_f64().unwrap();
    assert!((total - check["total"].as_f64().unwrap() - difference).abs() < 1e-12);
    assert!(difference.abs() <= v["bound"].as_f64().unwrap() + check["bound"].as_f64().unwrap());
    // A spherical space: every image, nothing left over.
    let p = json(&["light", "poincare", "--at", "0.1,0,0", "--json"]);
    assert_eq!(
        (p["images"].as_u64(), p["tail"].as_f64()),
        (Some(120), Some(0.0))
    );
    fails_with(&["light", "torus", "--at", "2,0,0"], "outside the cell");
    fails_with(
        &[
            "light", "torus", "--at", "0.1,0,0", "--reach", "3", "--check", "2",
        ],
        "must be longer than the reach",
    );
    // A product space: the same sum along every geodesic to each image, reciprocal at one
    // reach; without --reach, the mean of the rest is within 1 % of the total or a note
    // says why not.
    let there = json(&[
        "light",
        "bitorus-circle",
        "--light",
        "0.1,0,0",
        "--at",
        "-0.2,0.1,0.3",
        "--reach",
        "3",
        "--json",
    ]);
    let back = json(&[
        "light",
        "bitorus-circle",
        "--light",
        "-0.2,0.1,0.3",
        "--at",
        "0.1,0,0",
        "--reach",
        "3",
        "--json",
    ]);
    assert!(there["images"].as_u64().unwrap() > 1);
    let (a, b) = (
        there["exact"].as_f64().unwrap(),
        back["exact"].as_f64().unwrap(),
    );
    assert!(((a - b) / a).abs() < 1e-9, "{a} against {b}");
    assert!(there["bound_note"].as_str().unwrap().contains("--check"));
    let default = json(&["light", "bitorus-circle", "--at", "0.1,0,0", "--json"]);
    let (tail, total) = (
        default["tail"].as_f64().unwrap(),
        default["total"].as_f64().unwrap(),
    );
    assert!(
        tail <= 0.01 * total || default["tail_note"].as_str().is_some(),
        "{tail} of {total} with no note"
    );
    fails_with(
        &[
            "light",
            "bitorus-circle",
            "--at",
            "0,0,0",
            "--radius",
            "0.1",
        ],
        "lamp is a point",
    );
    fails_with(
        &["light", "sphere-circle", "--at", "0,0,5"],
        "outside the cell",
    );
}
