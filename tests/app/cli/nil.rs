//! The Nil spaces on the command line: `info`, `trace` and `render` take them, bad ids get
//! a clear error, and what is not written for Nil yet says so.

use super::*;

#[test]
fn info_gives_the_lattices_invariants() {
    for k in [1u32, 3, 50] {
        let v = json(&["info", &format!("nil-{k}"), "--json"]);
        assert_eq!(v["geometry"], "Nil");
        assert_eq!(v["k"], k);
        let kf = f64::from(k);
        assert!((v["volume"].as_f64().unwrap() - 1.0 / kf).abs() < 1e-15);
        // Half the shortest translation: the centre's 1/K (at most the side's 1).
        let inj = v["injectivity_radius"].as_f64().unwrap();
        assert!((inj - 0.5 / kf).abs() < 1e-15, "nil-{k}: {inj}");
        let h1 = v["homology"].as_str().unwrap();
        if k == 1 {
            assert_eq!(h1, "Z + Z");
        } else {
            assert!(
                h1.contains(&format!("Z/{k}")) && h1.matches('Z').count() == 3,
                "{h1}"
            );
        }
    }
    assert_eq!(json(&["info", "heisenberg", "--json"])["name"], "nil-1");
}

/// A vertical ray climbs straight through the top, once per box height; a start outside
/// the box is brought in by the lattice first; the end direction is the body velocity.
#[test]
fn trace_walks_a_nil_geodesic() {
    let v = json(&[
        "trace",
        "nil-4",
        "--dir",
        "0,0,1",
        "--distance",
        "1",
        "--json",
    ]);
    let crossings = v["crossings"].as_array().unwrap();
    // From the origin, the top at 1/8, then every 1/4: 1/8, 3/8, 5/8, 7/8.
    assert_eq!(crossings.len(), 4, "{v}");
    for (i, c) in crossings.iter().enumerate() {
        let want = (2.0 * i as f64 + 1.0) / 8.0;
        assert!(
            (c["distance"].as_f64().unwrap() - want).abs() < 1e-15,
            "{c}"
        );
        assert_eq!(c["face"], "top");
    }
    assert_eq!(v["end"]["direction"], json!([0.0, 0.0, 1.0]));
    let moved = json(&[
        "trace",
        "nil-1",
        "--from",
        "3.25,-1.5,7",
        "--dir",
        "1,0,0",
        "--crossings",
        "1",
        "--json",
    ]);
    let first = &moved["crossings"][0];
    assert_eq!(first["face"], "x = +1/2");
    // The start (3.25, -1.5, 7) is brought to x = 0.25: the first side 0.25 away.
    assert!(
        (first["distance"].as_f64().unwrap() - 0.25).abs() < 1e-15,
        "{first}"
    );
}

#[test]
fn bad_nil_ids_and_drawing_commands_get_clear_errors() {
    for bad in [
        "nil-0", "nil--1", "nil-1.5", "nil-1e9", "nil-", "nil-+3", "nil-1001",
    ] {
        fails_with(
            &["info", bad],
            "the K of nil-K must be a whole number from 1 to 1000",
        );
    }
    for args in [
        &["light", "nil-3", "--at", "0,0,0"][..],
        &["export", "nil-3"][..],
        &[
            "render", "nil-3", "--cpu", "--size", "16x9", "--walls", "0.5",
        ][..],
        &[
            "render",
            "nil-3",
            "--cpu",
            "--size",
            "16x9",
            "--colour-by",
            "crossings",
        ][..],
        &[
            "render",
            "nil-3",
            "--cpu",
            "--size",
            "16x9",
            "--lamp-radius",
            "0.5",
            "--shadows",
            "1",
        ][..],
    ] {
        fails_with(args, "not in the Nil spaces");
    }
    fails_with(
        &[
            "render",
            "nil-3",
            "--cpu",
            "--size",
            "16x9",
            "--eye",
            "0,0,0",
            "--look-at",
            "0,0,0",
        ],
        "looks at its own position",
    );
}

#[test]
fn files_naming_a_nil_space_get_clear_errors() {
    let dir = temp_dir("nil-files");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, "space = \"nil-3\"\n").expect("write");
    fails_with(
        &[
            "render",
            "--scene",
            scene.to_str().unwrap(),
            "--cpu",
            "--size",
            "16x9",
        ],
        "constant-curvature geometries only",
    );
    let flight = dir.join("flight.toml");
    std::fs::write(
        &flight,
        "space = \"nil-3\"\n[[key]]\ntime = 0.0\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.1, 0.0, 0.0]\n[[key]]\ntime = 1.0\nposition = [0.2, 0.0, 0.0]\nlook_at = [0.3, 0.0, 0.0]\n",
    )
    .expect("write");
    fails_with(
        &["flight", flight.to_str().unwrap()],
        "not in the Nil spaces",
    );
    fails_with(
        &["walk", "--replay", flight.to_str().unwrap()],
        "not in the Nil spaces",
    );
}

#[test]
fn render_draws_the_default_scene_with_the_cpu_reference() {
    let dir = temp_dir("nil-render");
    let out = dir.join("nil-1.png");
    let path = out.to_str().expect("a UTF-8 path");
    let output = run(&["render", "nil-1", "--cpu", "--size", "48x27", "--out", path]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("wrote"), "{stdout}");
    let image = image::open(&out).expect("a PNG").to_rgb8();
    assert_eq!(image.dimensions(), (48, 27));
    // The picture shows objects (not all fog): many distinct colours.
    let mut colours: Vec<[u8; 3]> = image.pixels().map(|p| p.0).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 100, "only {} colours", colours.len());
    // Aimed at the centrepiece (a white ball), the middle pixel is grey, not the fog.
    let aimed = dir.join("aimed.png");
    let path = aimed.to_str().expect("a UTF-8 path");
    let output = run(&[
        "render",
        "nil-1",
        "--cpu",
        "--size",
        "49x27",
        "--eye",
        "0.3,-0.4,0.2",
        "--look-at",
        "0,0,0",
        "--out",
        path,
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let image = image::open(&aimed).expect("a PNG").to_rgb8();
    let [r, g, b] = image.get_pixel(24, 13).0;
    assert!(
        r > 40 && r.abs_diff(b) < 16 && r.abs_diff(g) < 16,
        "the middle is {r},{g},{b}"
    );
}
