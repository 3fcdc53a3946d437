//! Every numeric command-line option given hostile values.

use super::*;

/// A CPU render of `space` at 16×9 with 4 crossings and `extra` arguments: the cheapest
/// run of the renderer for a hostile option.
fn tiny_render<'a>(space: &'a str, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "render",
        space,
        "--cpu",
        "--size",
        "16x9",
        "--crossings",
        "4",
    ];
    args.extend_from_slice(extra);
    args
}

/// Every numeric option of the command line at 0, negative, NaN, ±inf, 1e308 and 1e-320:
/// a result or an error message, exit status 0 or 1 — never a panic (101) or a signal.
#[test]
fn hostile_numbers_on_the_command_line() {
    let values = ["0", "-1", "nan", "inf", "-inf", "1e308", "1e-320", "-0"];
    let mut outcomes = (0, 0);
    let moving = format!(
        "{}/assets/scenes/seifert_weber_knot.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let nil_scene = format!(
        "{}/assets/scenes/heisenberg_twist.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    for value in values {
        let vec3 = format!("{value},0,0");
        let circle = format!("surface-abABcdCD-circle-{value}");
        let turned = format!("surface-aA-circle-1-turn-{value}");
        let nil = format!("nil-{value}");
        let angle = format!("0.1,0.2,{value}");
        let cases: Vec<Vec<&str>> = vec![
            // Every numeric option of the fluence sum.
            vec!["light", "torus", "--at", &vec3],
            vec!["light", "torus", "--light", &vec3, "--at", "0.1,0,0"],
            vec!["light", "torus", "--at", "0.1,0,0", "--fog", value],
            vec!["light", "torus", "--at", "0.1,0,0", "--reach", value],
            vec!["light", "torus", "--at", "0.1,0,0", "--radius", value],
            vec![
                "light", "torus", "--at", "0.1,0,0", "--reach", "1", "--check", value,
            ],
            vec!["light", "poincare", "--at", "0.1,0,0", "--fog", value],
            // A scene with a moving object at a hostile time.
            vec![
                "render",
                "--scene",
                &moving,
                "--cpu",
                "--size",
                "16x9",
                "--crossings",
                "4",
                "--time",
                value,
            ],
            tiny_render("torus", &["--fov", value]),
            tiny_render("torus", &["--time", value]),
            tiny_render("torus", &["--fog", value]),
            tiny_render("torus", &["--ipd", value, "--stereo", "anaglyph"]),
            vec![
                "render",
                "torus",
                "--cpu",
                "--size",
                "16x9",
                "--crossings",
                value,
            ],
            tiny_render("torus", &["--eye", &vec3, "--look-at", "0.1,0.1,0.1"]),
            // The light's reach and shadow count at hostile numbers, in each geometry.
            tiny_render("torus", &["--light-reach", value]),
            tiny_render("seifert-weber", &["--shadows", value]),
            tiny_render("poincare", &["--light-reach", value, "--shadows", "2"]),
            // Soft shadows: a hostile lamp radius and ray count, in each geometry.
            tiny_render("torus", &["--shadows", "2", "--lamp-radius", value]),
            tiny_render(
                "seifert-weber",
                &[
                    "--shadows",
                    "1",
                    "--lamp-radius",
                    "0.3",
                    "--soft-samples",
                    value,
                ],
            ),
            tiny_render(
                "poincare",
                &[
                    "--shadows",
                    "1",
                    "--soft-samples",
                    "3",
                    "--lamp-radius",
                    value,
                ],
            ),
            // A product space's lamp is a point: a radius is refused.
            tiny_render("bitorus-circle", &["--lamp-radius", value]),
            // A product space's lighting at hostile values.
            tiny_render(
                "bitorus-circle",
                &["--light-reach", value, "--shadows", "2"],
            ),
            tiny_render("sphere-circle-turn", &["--shadows", value]),
            // Walls at a hostile opening and opacity.
            tiny_render("poincare", &["--walls", value]),
            tiny_render(
                "mirrored-cube",
                &["--walls", "0.5", "--wall-opacity", value],
            ),
            vec![
                "walk",
                "torus",
                "--record",
                "fuzz.toml",
                "--record-interval",
                value,
            ],
            vec!["trace", "seifert-weber", "--dir", &vec3, "--crossings", "3"],
            vec![
                "trace",
                "seifert-weber",
                "--from",
                &vec3,
                "--dir",
                "1,0,0",
                "--crossings",
                "3",
            ],
            vec!["trace", "torus", "--dir", "1,0,0", "--distance", value],
            vec!["trace", "torus", "--dir", "1,0,0", "--crossings", value],
            // Nil: a hostile K, direction, start and distance.
            vec!["info", &nil],
            vec!["trace", "nil-3", "--dir", &vec3, "--crossings", "3"],
            vec![
                "trace",
                "nil-50",
                "--from",
                &vec3,
                "--dir",
                "0.3,0.4,0.5",
                "--distance",
                "2",
            ],
            vec!["trace", "nil-1", "--dir", "1,0,0.2", "--distance", value],
            tiny_render("nil-3", &["--eye", &vec3, "--look-at", "0.1,0.2,0"]),
            tiny_render("nil-1", &["--eye", "0.1,0.2,0", "--look-at", &vec3]),
            tiny_render("nil-50", &["--fog", value]),
            vec!["bench", "--quick", "--nil", value],
            // Nil's fluence sum: a hostile lamp, point, fog, reach and check.
            vec!["light", "nil-3", "--light", &vec3, "--at", "0.1,0,0"],
            vec!["light", "nil-1", "--at", &vec3],
            vec!["light", "nil-1", "--at", "0.1,0,0", "--fog", value],
            vec!["light", "nil-1", "--at", "0.1,0,0", "--reach", value],
            vec![
                "light", "nil-1", "--at", "0.1,0,0", "--reach", "1", "--check", value,
            ],
            // Nil's scene file under a hostile fov and fog.
            tiny_render("heisenberg", &["--scene", &nil_scene, "--fov", value]),
            tiny_render("heisenberg", &["--scene", &nil_scene, "--fog", value]),
            // Product spaces: a hostile length, turn, direction and start.
            vec!["info", &circle],
            vec!["info", &turned],
            vec![
                "trace",
                "bitorus-circle",
                "--dir",
                &vec3,
                "--crossings",
                "3",
            ],
            vec![
                "trace",
                "sphere-circle",
                "--from",
                &vec3,
                "--dir",
                "0,1,0.5",
                "--distance",
                "2",
            ],
            vec![
                "trace",
                "projective-plane-circle",
                "--dir",
                "1,0,0.2",
                "--distance",
                value,
            ],
            tiny_render("crosscaps-circle", &["--fog", value]),
            // SL̃(2,R): a hostile fog, field of view, budget, direction, start (base point
            // and angle) and distance.
            tiny_render("unit-tangent-bitorus", &["--fog", value]),
            tiny_render("unit-tangent-bitorus", &["--fov", value]),
            // A hostile eye and point looked at (the inverse exponential map's input).
            tiny_render(
                "unit-tangent-bitorus",
                &["--eye", &vec3, "--look-at", "0,0.5,0"],
            ),
            tiny_render(
                "unit-tangent-bitorus",
                &["--eye", "0,0,0", "--look-at", &vec3],
            ),
            vec![
                "render",
                "unit-tangent-abcdABCD",
                "--cpu",
                "--size",
                "16x9",
                "--crossings",
                value,
            ],
            // SL̃(2,R)'s lamp: a hostile lamp, point, fog, reach and check; its lighting,
            // shadows and walls at hostile values.
            vec![
                "light",
                "unit-tangent-bitorus",
                "--light",
                &vec3,
                "--at",
                "0.1,0,0",
            ],
            vec!["light", "unit-tangent-bitorus-cover-2", "--at", &angle],
            vec![
                "light",
                "unit-tangent-bitorus",
                "--at",
                "0.1,0,0",
                "--fog",
                value,
            ],
            vec![
                "light",
                "unit-tangent-bitorus",
                "--at",
                "0.1,0,0",
                "--reach",
                value,
            ],
            vec![
                "light",
                "unit-tangent-bitorus",
                "--at",
                "0.1,0,0",
                "--reach",
                "1",
                "--check",
                value,
            ],
            tiny_render(
                "unit-tangent-bitorus",
                &["--light-reach", value, "--shadows", "2"],
            ),
            tiny_render("unit-tangent-bitorus-cover-2", &["--shadows", value]),
            tiny_render("unit-tangent-bitorus", &["--lamp-radius", value]),
            tiny_render("unit-tangent-bitorus", &["--walls", value]),
            tiny_render(
                "unit-tangent-bitorus",
                &["--walls", "0.5", "--wall-opacity", value],
            ),
            vec![
                "trace",
                "unit-tangent-bitorus",
                "--dir",
                &vec3,
                "--crossings",
                "3",
            ],
            vec![
                "trace",
                "unit-tangent-abcdABCD",
                "--from",
                &vec3,
                "--dir",
                "0.3,0.4,0.5",
                "--distance",
                "2",
            ],
            vec![
                "trace",
                "unit-tangent-bitorus",
                "--from",
                &angle,
                "--dir",
                "0.6,0,0.8",
                "--crossings",
                "2",
            ],
            vec![
                "trace",
                "unit-tangent-bitorus",
                "--dir",
                "1,0,0.2",
                "--distance",
                value,
                "--precision",
                "f32",
            ],
        ];
        for mut args in cases {
            let out_dir = crate::common::scratch_dir("fuzz-cli");
            let png = out_dir.join("fuzz.png");
            if args[0] == "render" {
                args.extend(["--out", png.to_str().unwrap()]);
            }
            let started = Instant::now();
            let out = std::process::Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
                .args(&args)
                .output()
                .expect("the binary runs");
            let err = String::from_utf8_lossy(&out.stderr);
            match out.status.code() {
                Some(0) => outcomes.0 += 1,
                Some(1 | 2) => {
                    assert!(err.contains("error"), "{args:?}: no message: {err}");
                    outcomes.1 += 1;
                }
                other => panic!("{args:?}: exit {other:?}\n{err}"),
            }
            assert!(started.elapsed().as_secs_f64() < 30.0, "{args:?}: slow");
        }
    }
    eprintln!(
        "command lines: {} ran, {} refused with a message",
        outcomes.0, outcomes.1
    );
}

/// Hostile ids of the SL̃(2,R) family: empty, short, flat, spherical, non-orientable and
/// over-long words, broken cover suffixes, odd letters: an error that names the problem.
#[test]
fn hostile_unit_tangent_ids_are_refused_with_a_message() {
    let long = "ab".repeat(40);
    let words = [
        "",
        "a",
        "ab",
        "aA",
        "abAB",
        "aabb",
        "abcabc",
        "abABcdCD-cover-",
        "abABcdCD-cover-x",
        "abABcdCD-cover-0",
        "abABcdCD-cover-3",
        "abABcdCD-cover--2",
        "abABcdCD-cover-99999999999999999999999",
        "abABcdCDefEF-cover-8",
        "abAB-cover-2",
        "-cover-2",
        "ab AB",
        "äbÄB",
        long.as_str(),
        "abABcdCD\u{7}",
    ];
    for word in words {
        let id = format!("unit-tangent-{word}");
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
            .args(["info", &id])
            .output()
            .expect("the binary runs");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{id}: {err}");
        assert!(err.contains("error"), "{id}: no message: {err}");
    }
}

/// Hostile torus-bundle ids (Sol's, `space::sol::TorusBundle`): every entry at 0, ±1, huge,
/// non-numbers, doubled and dangling dashes, odd characters — a bundle with a finite
/// eigenvalue and lattice, or an error that names the id or the gluing; never a panic.
#[test]
fn hostile_torus_bundle_ids_are_a_bundle_or_a_message() {
    use bevy_curved_spaces::space::sol::TorusBundle;
    let entries = [
        "0",
        "1",
        "-1",
        "2",
        "-3",
        "10000",
        "-10001",
        "99999999999999999999",
        "nan",
        "inf",
        "1e3",
        "",
        "-",
        "--2",
        "2.0",
        "ä",
        " 1",
    ];
    let (mut bundles, mut refused) = (0, 0);
    for a in entries {
        for b in ["1", "-1", "0", a] {
            for d in ["1", "2", a] {
                let id = format!("torus-bundle-{a}-{b}-1-{d}");
                match TorusBundle::from_id(&id).expect("a torus bundle id") {
                    Ok(bundle) => {
                        bundles += 1;
                        assert!(
                            bundle.lambda > 1.0
                                && bundle.tau.is_finite()
                                && bundle.q.iter().flatten().all(|x| x.is_finite()),
                            "{id}: {bundle:?}"
                        );
                    }
                    Err(e) => {
                        refused += 1;
                        let e = e.to_string();
                        assert!(e.contains(&id) || e.contains("gluing"), "{id}: {e}");
                    }
                }
            }
        }
    }
    assert!(
        bundles > 0 && refused > 0,
        "{bundles} bundles, {refused} refused"
    );
}
