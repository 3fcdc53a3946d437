//! The `curved-spaces` command line: outputs a script can rely on, and clear errors.

use serde_json::{Value, json};
use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    // Commands that render on the GPU wait for the GPU tests (one GPU user at a time).
    let _gpu = ["render", "walk", "bench"]
        .iter()
        .any(|c| args.first() == Some(c) && !args.contains(&"--cpu"))
        .then(crate::common::gpu_lock);
    Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON")
}

fn fails_with(args: &[&str], needle: &str) {
    let out = run(args);
    assert!(!out.status.success(), "{args:?} should fail");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(needle), "{args:?}: `{err}` lacks `{needle}`");
    assert!(!err.contains("panicked"), "{err}");
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    crate::common::scratch_dir(&format!("cli-{name}"))
}

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

#[test]
fn bad_input_gets_a_clear_error() {
    fails_with(&["info", "klein-bottle"], "unknown space `klein-bottle`");
    fails_with(&["info", "missing.json"], "cannot read space file");
    fails_with(
        &["trace", "torus", "--dir", "1,0"],
        "three comma-separated numbers",
    );
    fails_with(
        &["trace", "torus", "--dir", "0,0,0", "--crossings", "2"],
        "zero length",
    );
    fails_with(&["trace", "torus", "--dir", "1,0,0"], "--crossings");
    fails_with(
        &[
            "trace",
            "torus",
            "--dir",
            "1,0,0",
            "--from",
            "2,0,0",
            "--crossings",
            "1",
        ],
        "outside the cell",
    );
    fails_with(
        &[
            "trace",
            "seifert-weber",
            "--dir",
            "1,0,0",
            "--from",
            "0.9,0.5,0",
            "--crossings",
            "1",
        ],
        "Klein model",
    );
    fails_with(
        &["trace", "torus", "--dir", "1,0,0", "--distance", "-1"],
        "positive number",
    );
    fails_with(
        &["trace", "torus", "--dir", "1,0,0", "--distance", "1e300"],
        "up to 1000000",
    );
    fails_with(
        &[
            "trace",
            "torus",
            "--dir",
            "1,0,0",
            "--crossings",
            "99999999999",
        ],
        "from 0 to 1000000",
    );
    fails_with(&["render", "torus", "--size", "0x10"], "WIDTHxHEIGHT");
    fails_with(&["render", "torus", "--size", "big"], "WIDTHxHEIGHT");
    fails_with(&["render", "torus", "--fov", "200"], "between 0 and 180");
    fails_with(
        &["render", "torus", "--eye", "0,0,0", "--look-at", "0,0,0"],
        "zero length",
    );
    fails_with(&["frobnicate"], "unrecognized subcommand");
}

/// `bench --quick` (what CI runs) writes every table and chart, and its figures hold the
/// bounds they state: the fog cut-off's error is within its bound, f32 keeps the torus's
/// faces within the conditioning bound, and the automatic budgets are ordered by quality.
#[test]
fn bench_straightforward_times_the_tracer_against_the_straightforward_one() {
    let dir = temp_dir("bench-straightforward");
    let out = run(&[
        "bench",
        "--straightforward",
        "--quick",
        "--spaces",
        "poincare",
        "--budgets",
        "8",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("straightforward.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("× straightforward"), "{summary}");
    // It times one thing: with --edges it is refused, by name.
    let both = run(&["bench", "--straightforward", "--edges"]);
    assert!(!both.status.success());
    assert!(String::from_utf8_lossy(&both.stderr).contains("--edges"));
}

/// `bench --edges` takes a member of the library (`weeks`, not a seed space) and reports
/// the work with the time: the tiles' table is in the summary.
#[test]
fn bench_edges_takes_a_library_member_and_reports_the_tiles() {
    let dir = temp_dir("bench-edges-weeks");
    let out = run(&[
        "bench",
        "--edges",
        "--quick",
        "--spaces",
        "weeks",
        "--sizes",
        "48x32",
        "--budgets",
        "8",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("edges.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
    assert!(csv.contains("tiles_never_parting"), "{csv}");
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("| weeks |"), "{summary}");
    assert!(summary.contains("8×8 tiles"), "{summary}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// `bench --lighting` writes a row per lighting with its time and error, and the figures
/// say what they should: every image with the tail is nearer the reference than the
/// nearest copy, and the tail is what brings it there; the soft shadows come nearer their
/// own reference with more rays than with the one to the lamp's centre.
#[test]
fn bench_lighting_measures_each_lighting_against_the_reference() {
    let dir = temp_dir("bench-lighting");
    let out = run(&[
        "bench",
        "--lighting",
        "--quick",
        "--spaces",
        "torus",
        "--sizes",
        "32x18",
        "--budgets",
        "8",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("lighting.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("{name} missing from {header:?}"))
    };
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 12, "{csv}");
    let error = |lighting: &str| -> f64 {
        let row = rows
            .iter()
            .find(|r| r[col("lighting")] == lighting)
            .unwrap_or_else(|| panic!("no {lighting} in {csv}"));
        assert!(row[col("median_ms")].parse::<f64>().unwrap() > 0.0);
        row[col("mean_error")].parse().unwrap()
    };
    let (nearest, images, untailed) = (
        error("nearest"),
        error("images R=4"),
        error("images R=4 no tail"),
    );
    assert!(images < 0.5 * nearest, "{images} against {nearest}");
    assert!(
        images < untailed,
        "{images} against {untailed} without the tail"
    );
    let (hard, soft) = (
        error("images R=2 + 4 shadows lamp 0.25 rays 1"),
        error("images R=2 + 4 shadows lamp 0.25 rays 16"),
    );
    assert!(soft <= hard, "16 rays {soft} against one {hard}");
    assert!(dir.join("lighting.png").exists() && dir.join("lighting.svg").exists());
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(summary.contains("× nearest"), "{summary}");
}

#[test]
fn bench_quick_writes_results_that_respect_their_bounds() {
    let dir = temp_dir("bench");
    let out = run(&[
        "bench",
        "--quick",
        "--spaces",
        "torus,seifert-weber",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for file in [
        "bench.json",
        "timings.csv",
        "errors.csv",
        "drift.csv",
        "cutoff.csv",
        "auto_budgets.csv",
        "specialisation.csv",
        "meshes.csv",
        "edges.csv",
        "straightforward.csv",
        "mesh_triangles.png",
        "speed_vs_colour_error.png",
        "speed_vs_hit_error.svg",
        "drift.png",
    ] {
        let meta = std::fs::metadata(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
        assert!(meta.len() > 0, "{file} is empty");
    }
    let json: Value =
        serde_json::from_slice(&std::fs::read(dir.join("bench.json")).unwrap()).unwrap();
    let report = &json["report"];
    assert!(report["device"]["name"].is_string());
    let rows = |table: &str| report[table].as_array().unwrap().clone();
    // 2 spaces × (2 budgets + 2 fogs) × 1 size.
    assert_eq!(rows("timings").len(), 8);
    for t in rows("timings") {
        let ms = t["median_ms"].as_f64().unwrap();
        assert!(ms.is_finite() && ms > 0.0, "{t}");
    }
    // The face culling leaves what every ray meets alone (HIT_ID, culled against unculled).
    let edges = rows("edges");
    assert_eq!(edges.len(), 2);
    for e in edges {
        assert_eq!(e["hit_ids_differing"], 0, "{e}");
        assert!(e["with_edges_ms"].as_f64().unwrap() > 0.0, "{e}");
        // The CPU's count of the view's work: every ray passes a cell at least, and the
        // share of blocks near two faces is at least the share of segments.
        let (segments, near, blocks) = (
            e["segments_per_pixel"].as_f64().unwrap(),
            e["near_two_faces"].as_f64().unwrap(),
            e["blocks_near_two_faces"].as_f64().unwrap(),
        );
        assert!(segments >= 1.0, "{e}");
        assert!(
            (0.0..=1.0).contains(&near) && near <= blocks && blocks <= 1.0,
            "{e}"
        );
        // The work beside the time: the 90th percentile of a pixel's segments is a whole
        // count no less than their mean's floor, the cost a segment is positive, and every
        // 8x8 tile's corners part at some depth or never (the shares add up to 1).
        let p90 = e["segments_p90"].as_f64().unwrap();
        assert!(p90 >= segments.floor() && p90.fract() == 0.0, "{e}");
        assert!(e["ns_per_segment"].as_f64().unwrap() > 0.0, "{e}");
        let tiles: f64 = [
            "tiles_parting_at_0",
            "tiles_parting_at_1",
            "tiles_parting_at_2",
            "tiles_parting_at_3",
            "tiles_parting_later",
            "tiles_never_parting",
        ]
        .iter()
        .map(|k| e[*k].as_f64().unwrap_or_else(|| panic!("{k}: {e}")))
        .sum();
        assert!((tiles - 1.0).abs() < 1e-9, "{e}");
        let near_edge = e["tiles_near_edge_before_parting"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&near_edge), "{e}");
    }
    // The straightforward tracer draws the same walk: the same picture but for rounding
    // (budget 16 is in the quick run's budgets).
    let plain = rows("straightforward");
    assert_eq!(plain.len(), 2, "{plain:?}");
    for r in plain {
        assert!(r["differing_pixels"].as_f64().unwrap() < 0.01, "{r}");
        assert!(r["straightforward_ms"].as_f64().unwrap() > 0.0, "{r}");
    }
    for c in rows("cutoff") {
        assert!(
            c["max_error"].as_f64().unwrap() <= c["bound"].as_f64().unwrap(),
            "fog cut-off error above its bound: {c}"
        );
    }
    for e in rows("errors") {
        let hit = e["hit_differs"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&hit), "{e}");
        if e["space"] == "torus" && e["budget_from"] == "auto-high" {
            assert_eq!(hit, 0.0, "f32 in the torus with a sufficient budget: {e}");
        }
    }
    // The work per pixel beside the time: crossings per pixel from the HIT_ID pass.
    for e in rows("errors") {
        let mean = e["mean_crossings"].as_f64().unwrap();
        let p90 = e["p90_crossings"].as_f64().unwrap();
        let budget = e["budget"].as_f64().unwrap();
        assert!(
            mean > 0.0 && mean <= budget && p90 >= mean.floor() && p90 <= budget,
            "{e}"
        );
    }
    assert!(
        std::fs::read_to_string(dir.join("summary.md"))
            .unwrap()
            .contains("ns per pixel-crossing")
    );
    // The walks against the double-double reference: both spaces, both precisions, both
    // pairings, over 30 and 100 crossings; the walk itself within the accuracy target.
    let conditioning = rows("conditioning");
    assert_eq!(conditioning.len(), 2 * 2 * 2 * 2, "{conditioning:?}");
    for c in conditioning
        .iter()
        .filter(|c| c["pairing"] == "compensated")
    {
        assert!(
            c["median"].as_f64().unwrap() <= 2.0 && c["worst"].as_f64().unwrap() <= 5.0,
            "{c}"
        );
    }
    assert!(!rows("conditioning_curve").is_empty());
    assert!(dir.join("digits_lost.png").exists());
    for d in rows("drift") {
        if d["space"] == "torus" {
            assert_eq!(d["same_faces"].as_f64(), Some(1.0), "{d}");
            assert!(d["max_position_error"].as_f64().unwrap() <= d["bound"].as_f64().unwrap());
        }
        if let Some(r) = d["worst_bound_ratio"].as_f64() {
            assert!(
                r <= 1.0,
                "a ray's f32 drift exceeds its conditioning bound: {d}"
            );
        }
    }
    for space in ["torus", "seifert-weber"] {
        let budgets: Vec<u64> = rows("auto_budgets")
            .iter()
            .filter(|b| b["space"] == space && b["fog_factor"].as_f64() == Some(3.0))
            .map(|b| b["budget"].as_u64().unwrap())
            .collect();
        assert_eq!(budgets.len(), 3, "{space}: low, medium, high");
        assert!(
            budgets.windows(2).all(|w| w[0] <= w[1]),
            "{space}: {budgets:?}"
        );
    }
    for s in rows("specialisation") {
        assert!(s["differing_pixels"].as_f64().unwrap() < 0.01, "{s}");
        assert!(s["general_uniform_bytes"].as_u64() > s["specialised_uniform_bytes"].as_u64());
    }
    // 2 spaces × the quick mesh sizes (a cube, a torus knot of about 960 triangles).
    let meshes = rows("meshes");
    assert_eq!(meshes.len(), 4);
    for m in &meshes {
        assert!(m["with_mesh_ms"].as_f64().unwrap() > 0.0, "{m}");
        let t = m["triangles"].as_u64().unwrap();
        assert!(t == 12 || (800..=1100).contains(&t), "{m}");
        assert!(m["depth"].as_u64().unwrap() <= 32, "{m}");
    }
    fails_with(
        &["bench", "--quick", "--spaces", "nowhere"],
        "unknown space",
    );
    // The library's members are spaces too, and a bad one says which ones exist.
    fails_with(
        &["bench", "--quick", "--spaces", "torus,census-99"],
        "census-1 to census-10",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn render_stereo_writes_both_eyes_and_names_bad_stereo_options() {
    let dir = temp_dir("stereo");
    let out = dir.join("pair.png");
    let run_ok = run(&[
        "render",
        "torus",
        "--cpu",
        "--stereo",
        "side-by-side",
        "--size",
        "64x24",
        "--crossings",
        "8",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run_ok.status.success(),
        "{}",
        String::from_utf8_lossy(&run_ok.stderr)
    );
    let err = String::from_utf8_lossy(&run_ok.stderr);
    assert!(err.contains("stereo side-by-side: eyes"), "{err}");
    let img = image::open(&out).expect("a PNG").to_rgb8();
    assert_eq!(img.dimensions(), (64, 24));
    let left = image::imageops::crop_imm(&img, 0, 0, 32, 24).to_image();
    let right = image::imageops::crop_imm(&img, 32, 0, 32, 24).to_image();
    assert_ne!(left, right, "the two halves are two eyes");
    fails_with(
        &["render", "torus", "--cpu", "--stereo", "sideways"],
        "unknown stereo mode \"sideways\"",
    );
    // A frame rate to hold: 0 (off) to 1000; anything else is named before a window opens.
    for fps in ["-1", "nan", "inf", "1e308", "1001", "fast"] {
        fails_with(&["walk", "torus", "--fps", fps], "expected frames a second");
    }
    // The headset's options: a snap of 0 (smooth) to 180°, a play area by name, both only
    // with --xr.
    for snap in ["-5", "nan", "181", "left"] {
        fails_with(
            &["walk", "torus", "--xr", "--snap-turn", snap],
            "expected a snap turn from 0 (smooth turning) to 180 degrees",
        );
    }
    fails_with(
        &["walk", "torus", "--xr", "--play-area", "lying"],
        "invalid value 'lying' for '--play-area",
    );
    fails_with(
        &["walk", "torus", "--play-area", "seated"],
        "the following required arguments were not provided",
    );
    fails_with(
        &[
            "render", "torus", "--cpu", "--stereo", "anaglyph", "--ipd", "2",
        ],
        "more than the cell's inradius",
    );
    fails_with(
        &[
            "render", "torus", "--cpu", "--stereo", "anaglyph", "--ipd", "-0.1",
        ],
        "expected a positive number",
    );
}

/// `walk --xr` where no headset can be used (no display here, and a build without the `xr`
/// feature or no OpenXR runtime) says why and falls back to desktop stereo: side by side,
/// rendered offscreen to the PNG it names.
#[test]
fn walk_xr_without_a_runtime_falls_back_to_desktop_stereo() {
    let dir = temp_dir("xr");
    let out = Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(["walk", "torus", "--xr"])
        .current_dir(&dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("the binary runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("no OpenXR support")
            || err.contains("OpenXR runtime")
            || err.contains("OpenXR loader"),
        "{err}"
    );
    assert!(
        err.contains("falling back to desktop stereo: side by side"),
        "{err}"
    );
    let img = image::open(dir.join("curved-spaces.png"))
        .expect("a PNG")
        .to_rgb8();
    let (w, h) = img.dimensions();
    let left = image::imageops::crop_imm(&img, 0, 0, w / 2, h).to_image();
    let right = image::imageops::crop_imm(&img, w / 2, 0, w / 2, h).to_image();
    assert_ne!(left, right, "two eyes side by side");
    std::fs::remove_dir_all(&dir).ok();
}

/// `render --scene` draws a scene file (a different picture from the plain space's), and a
/// bad scene file, or a space named beside `--scene`, gets a clear error.
#[test]
fn render_scene_files_and_name_their_mistakes() {
    let dir = temp_dir("scene");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/torus_globe.toml"
    );
    let with_scene = dir.join("scene.png");
    let plain = dir.join("plain.png");
    for (args, out) in [
        (vec!["render", "--scene", scene], &with_scene),
        (vec!["render", "torus"], &plain),
    ] {
        let mut args = args.clone();
        args.extend(["--cpu", "--size", "64x36", "--out", out.to_str().unwrap()]);
        let o = run(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let (a, b) = (
        image::open(&with_scene).unwrap().to_rgb8(),
        image::open(&plain).unwrap().to_rgb8(),
    );
    let differing = a.pixels().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert!(
        differing > 64 * 36 / 4,
        "the scene file changed only {differing} pixels"
    );

    fails_with(
        &["render", "torus", "--scene", scene],
        "cannot be used with",
    );
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "space = \"torus\"\n\n[[object]]\ntype = \"mesh\"\npath = \"nowhere.glb\"\nsize = 0.2\n",
    )
    .unwrap();
    fails_with(
        &["render", "--cpu", "--scene", bad.to_str().unwrap()],
        "bad.toml:3: mesh not found",
    );
    fails_with(
        &[
            "render",
            "--cpu",
            "--scene",
            dir.join("missing.toml").to_str().unwrap(),
        ],
        "cannot read the scene file",
    );
    fails_with(
        &["render", "--cpu", "--scene", scene, "--time", "soon"],
        "time in seconds",
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Negative numbers are values, not flags: the range check names what is wrong with them.
#[test]
fn negative_numbers_reach_their_range_checks() {
    for (args, expect) in [
        (&["--fov", "-70"][..], "expected an angle between 0 and 180"),
        (&["--time", "-1e308"][..], "expected a time in seconds"),
        (&["--size", "-5x3"][..], "expected WIDTHxHEIGHT"),
        (&["--crossings", "-3"][..], "expected a whole number"),
    ] {
        let mut all = vec!["render", "torus", "--cpu"];
        all.extend(args);
        let out = run(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} accepted");
        assert!(err.contains(expect), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{args:?}: {err}");
    }
    // A negative time in range is a time like any other.
    let dir = temp_dir("negative");
    let png = dir.join("t.png");
    let out = run(&[
        "render",
        "torus",
        "--cpu",
        "--size",
        "16x9",
        "--time",
        "-5",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Directions at the edges of f64 name the direction they point in, and a far look-at
/// point looks the same way as a near one on the same line.
#[test]
fn extreme_directions_and_far_targets_are_directions_too() {
    let along_x = json(&[
        "trace",
        "torus",
        "--dir",
        "1,0,0",
        "--crossings",
        "3",
        "--json",
    ]);
    for dir in ["1e308,0,0", "1e-320,0,0", "5e-324,0,0"] {
        let got = json(&["trace", "torus", "--dir", dir, "--crossings", "3", "--json"]);
        assert_eq!(got, along_x, "--dir {dir}");
    }
    let diagonal = json(&[
        "trace",
        "torus",
        "--dir",
        "1,1,0",
        "--crossings",
        "3",
        "--json",
    ]);
    let huge = json(&[
        "trace",
        "torus",
        "--dir",
        "1e308,1e308,0",
        "--crossings",
        "3",
        "--json",
    ]);
    assert_eq!(huge, diagonal);
    // The user's number is quoted as written, not as a 309-digit expansion.
    let out = run(&["trace", "torus", "--dir", "0,0,0", "--crossings", "1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("(0.0, 0.0, 0.0)"), "{err}");
    let dir = temp_dir("far-look");
    let picture = |target: &str| {
        let png = dir.join(format!("{}.png", target.replace(',', "_")));
        let out = run(&[
            "render",
            "torus",
            "--cpu",
            "--size",
            "32x18",
            "--eye",
            "0,0,0",
            "--look-at",
            target,
            "--out",
            png.to_str().unwrap(),
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        image::open(&png).expect("a PNG").to_rgb8()
    };
    assert_eq!(picture("1e155,0,0"), picture("1,0,0"));
}

/// `info` prints valid JSON whatever the space: a number f64 cannot hold is null with a
/// note, a name longer than the limit is a clear error.
#[test]
fn info_is_valid_json_or_a_clear_error_at_the_edges() {
    let dir = temp_dir("info-edges");
    let exported = run(&["export", "torus"]);
    assert!(exported.status.success());
    let mut record: Value = serde_json::from_slice(&exported.stdout).expect("JSON");
    let s = 2f64.powi(500);
    for face in record["faces"].as_array_mut().unwrap() {
        let offset = face["offset"].as_f64().unwrap();
        face["offset"] = json!(offset * s);
        for row in 0..3 {
            let t = face["pairing"][row][3].as_f64().unwrap();
            face["pairing"][row][3] = json!(t * s);
        }
    }
    let huge = dir.join("huge.json");
    std::fs::write(&huge, serde_json::to_vec(&record).unwrap()).unwrap();
    let info = json(&["info", huge.to_str().unwrap(), "--json"]);
    assert!(info["volume"].is_null(), "{info}");
    assert!(
        info["volume_note"]
            .as_str()
            .unwrap()
            .contains("larger than f64")
    );
    assert!((info["inradius"].as_f64().unwrap() / (0.5 * s) - 1.0).abs() < 1e-14);
    record["name"] = json!("x".repeat(300));
    let long = dir.join("long.json");
    std::fs::write(&long, serde_json::to_vec(&record).unwrap()).unwrap();
    let out = run(&["info", long.to_str().unwrap(), "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("its name is 300 bytes long"), "{err}");
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

/// A scene file's `[start]` gives the field of view too: `render --scene` uses it unless
/// `--fov` says otherwise, so a benchmark view is fully described by its file.
#[test]
fn a_scene_files_start_view_has_its_field_of_view() {
    let dir = temp_dir("scene-fov");
    let scene = dir.join("narrow.toml");
    std::fs::write(
        &scene,
        "space = \"torus\"\n[start]\nposition = [0, 0, 0]\nfov = 30\n",
    )
    .unwrap();
    let picture = |extra: &[&str], name: &str| {
        let png = dir.join(name);
        let mut args = vec![
            "render",
            "--cpu",
            "--size",
            "32x18",
            "--out",
            png.to_str().unwrap(),
        ];
        args.extend(extra);
        let out = run(&args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        image::open(&png).expect("a PNG").to_rgb8()
    };
    let s = scene.to_str().unwrap();
    let from_file = picture(&["--scene", s], "file.png");
    let explicit = picture(&["--scene", s, "--fov", "30"], "explicit.png");
    let wide = picture(&["--scene", s, "--fov", "70"], "wide.png");
    assert_eq!(from_file, explicit);
    assert_ne!(from_file, wide);
}

/// `bench --scene FILE` times a scene file's start view per budget and size, against the
/// trivial material in the same loop, and writes timings.csv with those columns.
#[test]
fn bench_times_any_scene_file() {
    let dir = temp_dir("bench-scene");
    let scene = dir.join("view.toml");
    std::fs::write(
        &scene,
        "space = \"seifert-weber\"\nfog = 2.0\nedges = false\n[start]\nposition = [0, 0, 0]\nfov = 50\n",
    )
    .unwrap();
    let out_dir = dir.join("out");
    let out = run(&[
        "bench",
        "--scene",
        scene.to_str().unwrap(),
        "--budgets",
        "2,4",
        "--sizes",
        "32x18",
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(out_dir.join("timings.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    for column in ["budget", "width", "height", "median_ms", "baseline_ms"] {
        assert!(header.contains(&column), "{column} missing from {header:?}");
    }
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 2, "{csv}");
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for row in &rows {
        assert_eq!(row[col("width")], "32");
        assert!(row[col("median_ms")].parse::<f64>().unwrap() > 0.0);
        assert!(row[col("baseline_ms")].parse::<f64>().unwrap() > 0.0);
    }
    assert!(
        std::fs::read_to_string(out_dir.join("summary.md"))
            .unwrap()
            .contains("| 4 | 32×18 |")
    );
    // A scene file that does not load is an error naming it.
    std::fs::write(&scene, "space = \"klein-bottle\"\n").unwrap();
    let out = run(&[
        "bench",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown space"));
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
fn flights_render_every_frame_resume_and_slice_alike() {
    let dir = temp_dir("flight");
    let file = dir.join("f.toml");
    std::fs::write(
        &file,
        "space = \"torus\"\n\n[[key]]\ntime = 0.0\nposition = [0.3, 0.2, 0.5]\nlook_at = [0.0, 0.0, -1.0]\n\n\
         [[key]]\ntime = 3.0\nposition = [0.3, 0.2, -1.5]\nlook_at = [0.0, 0.0, -3.0]\n",
    )
    .unwrap();
    let (f, whole, part) = (file.to_str().unwrap(), dir.join("whole"), dir.join("part"));
    let args = |out: &std::path::Path| {
        vec![
            "flight".to_string(),
            f.to_string(),
            "--cpu".into(),
            "--size".into(),
            "32x18".into(),
            "--fps".into(),
            "10".into(),
            "--crossings".into(),
            "8".into(),
            "--out".into(),
            out.to_str().unwrap().to_string(),
        ]
    };
    let run_args = |v: Vec<String>| {
        let refs: Vec<&str> = v.iter().map(String::as_str).collect();
        run(&refs)
    };
    let out = run_args(args(&whole));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let frames: Vec<_> = (1..=30)
        .map(|n| whole.join(format!("frame-{n:05}.png")))
        .collect();
    assert!(frames.iter().all(|p| p.exists()), "30 frames");
    assert!(!whole.join("frame-00031.png").exists());
    // Resumed: nothing left to do.
    let out = run_args(args(&whole));
    assert!(String::from_utf8_lossy(&out.stdout).contains("rendered 0 frames"));
    // A slice on another "machine" gives the same files, pixel for pixel.
    let mut sliced = args(&part);
    sliced.extend(["--frames".to_string(), "11..20".to_string()]);
    let out = run_args(sliced);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for n in 1..=30 {
        let p = part.join(format!("frame-{n:05}.png"));
        assert_eq!(p.exists(), (11..=20).contains(&n), "frame {n}");
        if p.exists() {
            assert_eq!(
                std::fs::read(&p).unwrap(),
                std::fs::read(&frames[n - 1]).unwrap()
            );
        }
    }
    // The camera moves: the first and last frames differ.
    assert_ne!(
        std::fs::read(&frames[0]).unwrap(),
        std::fs::read(&frames[29]).unwrap()
    );
    // Mistakes.
    fails_with(&["flight", "missing.toml"], "cannot read flight file");
    std::fs::write(&file, "space = \"torus\"\n").unwrap();
    fails_with(&["flight", f], "at least one [[key]]");
    std::fs::write(
        &file,
        "space = \"torus\"\n[[key]]\ntime = 1.0\nposition = [0,0,0]\nlook_at = [0,0,-1]\n\
         [[key]]\ntime = 0.5\nposition = [0,0,0]\nlook_at = [0,0,-1]\n",
    )
    .unwrap();
    fails_with(&["flight", f], "key 2: time 0.5 does not come after");
    fails_with(&["flight", f, "--fps", "0"], "frames per second");
    fails_with(&["flight", f, "--frames", "5..2"], "frames A..B");
    fails_with(
        &["walk", "--replay", "missing.toml"],
        "cannot read flight file",
    );
    fails_with(&["walk", "torus", "--replay", f], "cannot be used with");
}

/// A scene file's moving object: `render --time` draws it where its motion has taken it (a
/// different picture at 0 and 3 s, and the same as the library's scene at that time), and a
/// velocity that cannot be used is named.
#[test]
fn render_shows_moving_objects_at_their_time() {
    use bevy_curved_spaces::scene::file::load_scene_file;
    use bevy_curved_spaces::trace::{RenderSettings, render};
    use bevy_curved_spaces::view::TraceCamera;
    let dir = temp_dir("moving");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/seifert_weber_knot.toml"
    );
    let mut pictures = Vec::new();
    for time in ["0", "3"] {
        let out = dir.join(format!("t{time}.png"));
        let o = run(&[
            "render",
            "--scene",
            scene,
            "--cpu",
            "--size",
            "64x36",
            "--crossings",
            "6",
            "--time",
            time,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        pictures.push(image::open(&out).unwrap().to_rgb8());
    }
    assert_ne!(pictures[0], pictures[1], "the globe moved");
    // The library's scene at 3 s, from the same start view: the same picture.
    let file = load_scene_file(std::path::Path::new(scene)).unwrap();
    let mut at = file.scene_at(3.0).unwrap();
    at.time = 3.0;
    let camera = TraceCamera {
        frame: file.start.unwrap(),
        fov_y_degrees: file.start_fov.unwrap_or(70.0),
    };
    at.set_avatar_frame(&file.space, camera.frame);
    let cpu = render(
        &file.space,
        &at,
        &camera,
        &RenderSettings {
            width: 64,
            height: 36,
            max_crossings: 6,
        },
    );
    assert_eq!(cpu, pictures[1]);

    fails_with(
        &["render", "torus", "--cpu", "--colour-by", "purple"],
        "invalid value 'purple'",
    );
    fails_with(
        &["render", "torus", "--cpu", "--walls", "1.2"],
        "expected an opening from 0 (solid walls) to 1 (no walls), got `1.2`",
    );
    fails_with(
        &[
            "render",
            "torus",
            "--cpu",
            "--walls",
            "0.5",
            "--wall-opacity",
            "-0.1",
        ],
        "expected an opacity above 0 and at most 1",
    );
    fails_with(
        &["render", "torus", "--cpu", "--wall-opacity", "0.5"],
        "--walls",
    );
    fails_with(
        &["render", "torus", "--cpu", "--centrepiece", "comet"],
        "invalid value 'comet'",
    );
    fails_with(
        &[
            "render",
            "torus",
            "--cpu",
            "--gyroscope",
            "--centrepiece",
            "galaxy",
        ],
        "cannot be used with",
    );
    fails_with(
        &[
            "walk",
            "torus",
            "--record",
            "w.toml",
            "--record-interval",
            "0",
        ],
        "seconds between keys from 0.01 to 10",
    );
    let bad = dir.join("bad.toml");
    for (object, message) in [
        (
            "type = \"tube\"\nfrom = [0, 0, 0]\nto = [0.2, 0, 0]\nradius = 0.1\nvelocity = [1, 0, 0]",
            "velocity",
        ),
        (
            "type = \"ball\"\nradius = 0.1\nvelocity = [nan, 0, 0]",
            "velocity must be finite",
        ),
    ] {
        std::fs::write(&bad, format!("space = \"torus\"\n\n[[object]]\n{object}\n")).unwrap();
        fails_with(
            &[
                "render",
                "--scene",
                bad.to_str().unwrap(),
                "--cpu",
                "--size",
                "8x8",
            ],
            message,
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `render --walls` and `--centrepiece` change the picture (CPU renderer), and the scene
/// file's walls come through unless the command line says otherwise.
#[test]
fn render_draws_walls_and_centrepieces() {
    let dir = temp_dir("render-views");
    let picture = |name: &str, extra: &[&str]| {
        let out = dir.join(format!("{name}.png"));
        let mut args = vec![
            "render",
            "poincare",
            "--cpu",
            "--size",
            "48x27",
            "--crossings",
            "6",
        ];
        args.extend_from_slice(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = run(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        image::open(&out).unwrap().to_rgb8()
    };
    let plain = picture("plain", &[]);
    let walls = picture("walls", &["--walls", "0.4"]);
    let open = picture("open", &["--walls", "1"]);
    let galaxy = picture("galaxy", &["--centrepiece", "galaxy"]);
    let none = picture("none", &["--centrepiece", "none"]);
    let gyroscope = picture("gyroscope", &["--gyroscope"]);
    assert_ne!(plain, walls);
    assert_eq!(plain, open, "fully open windows are no walls");
    assert_ne!(plain, galaxy);
    assert_ne!(plain, none);
    assert_ne!(galaxy, none);
    assert_ne!(gyroscope, none);
    // A scene file's walls, and the command line's over them.
    let scene = format!(
        "{}/assets/scenes/seifert_weber_walls.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let render_scene = |name: &str, extra: &[&str]| {
        let out = dir.join(format!("{name}.png"));
        let mut args = vec![
            "render",
            "--scene",
            &scene,
            "--cpu",
            "--size",
            "48x27",
            "--crossings",
            "6",
        ];
        args.extend_from_slice(extra);
        args.extend(["--out", out.to_str().unwrap()]);
        let o = run(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        image::open(&out).unwrap().to_rgb8()
    };
    let file_walls = render_scene("file", &[]);
    let no_walls = render_scene("file-open", &["--walls", "1"]);
    assert_ne!(file_walls, no_walls);
    std::fs::remove_dir_all(&dir).ok();
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
    fails_with(
        &["light", "bitorus-circle", "--at", "0,0,0"],
        "product spaces",
    );
}
