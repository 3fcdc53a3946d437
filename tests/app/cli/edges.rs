//! The command line at the edges of its input, where it was once silently wrong: every answer
//! is a number (no `null` in the JSON, no `inf` or `NaN` in the text), a walk never ends
//! without a crossing, its distance or a stated reason, a bound holds, and an error path
//! exits with its own code. A fuzz of the same classes closes the file.

use super::*;
use std::process::Stdio;

/// The error message of a command that must be refused (exit 1).
fn refused(args: &[&str]) -> String {
    let out = run(args);
    assert_eq!(out.status.code(), Some(1), "{args:?} was not refused");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Where a JSON value holds a `null` or a non-finite number that nothing explains: the
/// paths, empty when every answer is a number.
fn nulls(v: &Value, path: &str, out: &mut Vec<String>) {
    match v {
        Value::Null => out.push(path.to_string()),
        Value::Number(n) if !n.as_f64().is_some_and(f64::is_finite) => out.push(path.to_string()),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                nulls(x, &format!("{path}[{i}]"), out);
            }
        }
        Value::Object(m) => {
            for (k, x) in m {
                // `check` is null when none was asked for; a volume too large for f64 is
                // null with a note that says so.
                let explained = k == "check" || k == "volume" && m.contains_key("volume_note");
                if !(explained && x.is_null()) {
                    nulls(x, &format!("{path}.{k}"), out);
                }
            }
        }
        _ => {}
    }
}

fn assert_all_numbers(v: &Value, what: &str) {
    let mut found = Vec::new();
    nulls(v, "", &mut found);
    assert!(found.is_empty(), "{what}: null at {found:?}\n{v}");
}

#[test]
fn points_past_the_chart_are_given_in_the_model_with_the_reason() {
    for (space, dir) in [
        ("projective-plane-circle", "1,1,0"),
        ("surface-abab-circle-2", "1,1,0"),
        ("sphere-circle", "1,0.3,0.1"),
        ("three-sphere", "1,0,0.2"),
        ("projective-space", "1,0,0.3"),
    ] {
        for precision in ["f64", "f32"] {
            let args = [
                "trace",
                space,
                "--dir",
                dir,
                "--crossings",
                "3",
                "--precision",
                precision,
                "--json",
            ];
            let out = run(&args);
            // A walk that crosses no face says so (three-sphere); every other one answers.
            let v: Value = serde_json::from_slice(&out.stdout).unwrap();
            assert_all_numbers(&v, &format!("{args:?}"));
            let items = v["crossings"].as_array().unwrap().iter().chain([&v["end"]]);
            for item in items {
                let has_point = item.get("point").is_some();
                let off = item.get("off_chart").is_some();
                assert!(has_point != off, "{args:?}: {item}");
                if off {
                    assert!(item["model"].as_array().is_some_and(|m| m.len() == 4));
                }
            }
            if space == "three-sphere" {
                assert_eq!(out.status.code(), Some(1));
                assert!(
                    v["end"]["stopped"]
                        .as_str()
                        .unwrap()
                        .contains("meets no face")
                );
            } else {
                assert!(out.status.success(), "{args:?}");
            }
        }
    }
    // The projective plane's antipodal gluing puts its crossings on the equator.
    let v = json(&[
        "trace",
        "projective-plane-circle",
        "--dir",
        "1,1,0",
        "--crossings",
        "3",
        "--json",
    ]);
    assert!(
        v["crossings"][0]["off_chart"]
            .as_str()
            .unwrap()
            .contains("equator")
    );
}

#[test]
fn a_walk_in_the_three_sphere_follows_its_great_circle_past_the_equator() {
    // Past π/2 a point of S³ is not its antipode: at distance 3 along x it is (sin 3, 0, 0,
    // cos 3), with w < 0.
    let v = json(&[
        "trace",
        "three-sphere",
        "--dir",
        "1,0,0",
        "--distance",
        "3",
        "--json",
    ]);
    let model: Vec<f64> = v["end"]["model"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let want = [3f64.sin(), 0.0, 0.0, 3f64.cos()];
    for (a, b) in model.iter().zip(want) {
        assert!((a - b).abs() < 1e-12, "{model:?} against {want:?}");
    }
}

#[test]
fn a_long_circle_is_crossed_and_a_huge_direction_is_a_direction() {
    let v = json(&[
        "trace",
        "surface-aA-circle-100",
        "--dir",
        "1,2,3",
        "--crossings",
        "3",
        "--json",
    ]);
    let crossings = v["crossings"].as_array().unwrap();
    assert_eq!(crossings.len(), 3);
    let rise = 3.0 / 14f64.sqrt();
    let first = crossings[0]["distance"].as_f64().unwrap();
    assert!((first - 50.0 / rise).abs() < 1e-9, "{first}");
    assert_eq!(crossings[0]["face"], "top");
    let huge = run(&[
        "trace",
        "bitorus-circle",
        "--dir",
        "1e200,0,1e200",
        "--crossings",
        "4",
    ]);
    let unit = run(&[
        "trace",
        "bitorus-circle",
        "--dir",
        "1,0,1",
        "--crossings",
        "4",
    ]);
    assert!(huge.status.success());
    assert_eq!(huge.stdout, unit.stdout);
}

#[test]
fn circles_of_no_height_are_refused_and_huge_ones_say_what_overflows() {
    let e = refused(&["info", "surface-abABcdCD-circle-5e-324"]);
    assert!(e.contains("5e-324") && e.contains("4.4502e-308"), "{e}");
    let v = json(&["info", "surface-abABcdCD-circle-1e308", "--json"]);
    assert!(v["volume"].is_null());
    assert!(
        v["volume_note"]
            .as_str()
            .unwrap()
            .contains("larger than f64")
    );
    // Two crossings of a circle of 1e308 are farther than f64 holds: said, not null.
    let out = run(&[
        "trace",
        "surface-aA-circle-1e308",
        "--dir",
        "0.5,0.3,0.4",
        "--crossings",
        "3",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_all_numbers(&v, "circle 1e308");
    assert!(
        v["end"]["stopped"]
            .as_str()
            .unwrap()
            .contains("larger than f64")
    );
}

#[test]
fn the_documented_maximum_walk_runs_in_constant_memory() {
    // A million crossings, streamed: under a 1 GiB address-space limit (once 2.4 GiB).
    let bin = env!("CARGO_BIN_EXE_curved-spaces");
    let status = Command::new("bash")
        .args([
            "-c",
            &format!(
                "ulimit -v 1048576 && exec {bin} trace bitorus-circle --dir 1,2,3 \
                 --crossings 1000000 --json"
            ),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
}

#[test]
fn the_light_is_a_number_or_a_reason() {
    // Past 1.3e154 a chart point of S³ once became the zero vector, "inside" every cell.
    let e = refused(&["light", "poincare", "--at", "1e160,0,0"]);
    assert!(e.contains("outside"), "{e}");
    let e = refused(&["light", "torus", "--at", "0.1,0,0", "--radius", "1e-160"]);
    assert!(e.contains("1e-150"), "{e}");
    // A long fog in E³: the tail overflows, and the message names the fog, not a reach.
    for args in [
        vec!["light", "torus", "--at", "0.1,0,0", "--fog", "1e308"],
        vec![
            "light", "torus", "--at", "0.1,0,0", "--fog", "1e308", "--reach", "1",
        ],
    ] {
        let e = refused(&args);
        assert!(
            e.contains("--fog") && !e.contains("reach must"),
            "{args:?}: {e}"
        );
    }
    for args in [
        vec![
            "light", "poincare", "--at", "0.1,0,0", "--fog", "1e307", "--json",
        ],
        vec![
            "light", "torus", "--at", "0.1,0,0", "--reach", "5e-324", "--json",
        ],
        vec![
            "light", "torus", "--at", "0.1,0,0", "--radius", "1e-150", "--json",
        ],
        vec![
            "light", "torus", "--at", "0.1,0,0", "--radius", "1e300", "--json",
        ],
    ] {
        let out = run(&args);
        match out.status.code() {
            Some(0) => assert_all_numbers(
                &serde_json::from_slice(&out.stdout).unwrap(),
                &format!("{args:?}"),
            ),
            Some(1) => assert!(String::from_utf8_lossy(&out.stderr).contains("error")),
            other => panic!("{args:?}: exit {other:?}"),
        }
    }
}

#[test]
fn the_bound_holds_in_thick_fog_and_the_default_reach_makes_it_useful() {
    let v = json(&[
        "light",
        "seifert-weber",
        "--at",
        "0.2,0.1,0",
        "--fog",
        "6",
        "--reach",
        "2",
        "--check",
        "3",
        "--json",
    ]);
    let gap = v["check"]["difference"].as_f64().unwrap().abs();
    let bound = v["bound"].as_f64().unwrap() + v["check"]["bound"].as_f64().unwrap();
    assert!(gap <= bound, "off by {gap}, bound {bound}");
    // Without --reach: the bound is within 1 % of the total, or a note says why not.
    for space in ["torus", "half-turn", "seifert-weber", "weeks"] {
        let v = json(&["light", space, "--at", "0.1,0.05,0", "--json"]);
        assert_all_numbers(&v, space);
        let (bound, total) = (v["bound"].as_f64().unwrap(), v["total"].as_f64().unwrap());
        if bound > 0.01 * total {
            let note = v["bound_note"]
                .as_str()
                .unwrap_or_else(|| panic!("{space}: {v}"));
            assert!(note.contains("not within 1 %"), "{note}");
        }
        if space == "torus" {
            assert!(bound <= 0.01 * total, "torus: {bound} of {total}");
        }
    }
}

#[test]
fn a_refused_gpu_scene_exits_with_its_own_code_every_time() {
    // `run` takes the GPU for a render, one user at a time.
    let dir = temp_dir("many-balls");
    let mut text = String::from("space = \"torus\"\n");
    for i in 0..5000 {
        let t = f64::from(i) / 5000.0;
        text.push_str(&format!(
            "\n[[object]]\ntype = \"ball\"\nposition = [{:.4}, {:.4}, {:.4}]\nradius = 0.005\n",
            0.9 * (t - 0.5),
            0.4 * (t * 7.0).sin(),
            0.4 * (t * 13.0).cos()
        ));
    }
    let scene = dir.join("balls.toml");
    std::fs::write(&scene, text).unwrap();
    let png = dir.join("balls.png");
    for attempt in 0..4 {
        let out = run(&[
            "render",
            "--scene",
            scene.to_str().unwrap(),
            "--size",
            "16x9",
            "--out",
            png.to_str().unwrap(),
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "attempt {attempt}: {err}");
        assert!(err.contains("uniform data"), "{err}");
    }
}

/// The fuzz classes of this file: chart points at the model's edge, long and short fibres,
/// overflowing directions and lengths, tiny and huge lamp radii, fog and reach, in the
/// constant-curvature and the product spaces. Each run
/// exits 0 with every JSON answer a number, or 1 with an error message.
#[test]
fn edges_of_the_input_are_numbers_or_reasons() {
    let edge_numbers = [
        "1e154", "1.4e154", "1e160", "1e300", "1e307", "1.7e308", "1e-150", "1e-160", "5e-324",
        "2.3e-308",
    ];
    let mut cases: Vec<Vec<String>> = Vec::new();
    let s = |x: &str| x.to_string();
    for x in edge_numbers {
        let point = format!("{x},0,0");
        let dir = format!("{x},1,{x}");
        for space in [
            "poincare",
            "three-sphere",
            "lens-5-2",
            "torus",
            "seifert-weber",
        ] {
            cases.push(vec![
                s("light"),
                s(space),
                s("--at"),
                point.clone(),
                s("--json"),
            ]);
        }
        for space in ["bitorus-circle", "sphere-circle"] {
            cases.push(vec![
                s("light"),
                s(space),
                s("--at"),
                point.clone(),
                s("--json"),
            ]);
            for option in ["--fog", "--reach"] {
                cases.push(vec![
                    s("light"),
                    s(space),
                    s("--at"),
                    s("0.1,0,0"),
                    s(option),
                    s(x),
                    s("--json"),
                ]);
            }
        }
        for option in ["--fog", "--reach", "--radius"] {
            for space in ["torus", "poincare", "seifert-weber"] {
                cases.push(vec![
                    s("light"),
                    s(space),
                    s("--at"),
                    s("0.1,0,0"),
                    s(option),
                    s(x),
                    s("--json"),
                ]);
            }
        }
        for space in [
            format!("surface-aA-circle-{x}"),
            format!("surface-aa-circle-{x}"),
            format!("surface-abABcdCD-circle-{x}"),
        ] {
            cases.push(vec![s("info"), space.clone(), s("--json")]);
            cases.push(vec![
                s("trace"),
                space,
                s("--dir"),
                s("0.5,0.3,0.4"),
                s("--crossings"),
                s("3"),
                s("--json"),
            ]);
        }
        for space in ["bitorus-circle", "projective-plane-circle", "three-sphere"] {
            cases.push(vec![
                s("trace"),
                s(space),
                s("--dir"),
                dir.clone(),
                s("--crossings"),
                s("3"),
                s("--json"),
            ]);
            cases.push(vec![
                s("trace"),
                s(space),
                s("--from"),
                point.clone(),
                s("--dir"),
                s("1,0,0"),
                s("--distance"),
                s("2"),
                s("--json"),
            ]);
        }
    }
    let (mut answered, mut refused_count) = (0, 0);
    for args in &cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        match out.status.code() {
            Some(0) => {
                answered += 1;
                let v: Value =
                    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{args:?}: {e}"));
                assert_all_numbers(&v, &format!("{args:?}"));
            }
            Some(1 | 2) => {
                refused_count += 1;
                assert!(err.contains("error"), "{args:?}: no message: {err}");
                // A stated stop still prints numbers only.
                if let Ok(v) = serde_json::from_slice::<Value>(&out.stdout) {
                    assert_all_numbers(&v, &format!("{args:?}"));
                }
            }
            other => panic!("{args:?}: exit {other:?}\n{err}"),
        }
    }
    eprintln!(
        "edges of the input: {} cases, {answered} answered, {refused_count} refused",
        cases.len()
    );
}

/// `scripts/run.sh` (a plain `cargo run`) and `scripts/test.sh` (`cargo test`) share one
/// build of Bevy only if every crate both use gets the same features: the tests'
/// dependencies must not turn on a feature that a plain build leaves off.
#[test]
fn running_and_testing_share_one_build() {
    let tree = |edges: &str| -> std::collections::BTreeMap<String, String> {
        let out = Command::new(env!("CARGO"))
            .args([
                "tree",
                "--offline",
                "-e",
                edges,
                "-f",
                "{p}|{f}",
                "--prefix",
                "none",
                "--no-dedupe",
            ])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .filter_map(|l| l.split_once('|'))
            .map(|(p, f)| (p.trim_end_matches(" (*)").to_string(), f.to_string()))
            .collect()
    };
    let plain = tree("normal,build");
    let tests = tree("normal,build,dev");
    let differ: Vec<String> = plain
        .iter()
        .filter(|(p, _)| !p.starts_with("bevy_curved_spaces"))
        .filter_map(|(p, f)| {
            let g = tests.get(p)?;
            (g != f).then(|| format!("{p}: [{f}] in a plain build, [{g}] in the tests'"))
        })
        .collect();
    assert!(
        differ.is_empty(),
        "name these features in Cargo.toml's [dependencies]:\n{}",
        differ.join("\n")
    );
}
