//! The benchmark from the command line: its runs write results that respect their bounds.

use super::*;

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
