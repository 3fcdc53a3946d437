//! Bad and extreme input on the command line: a clear error that names the problem, never
//! a panic.

use super::*;

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
