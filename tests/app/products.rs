//! The product spaces (H²×R, S²×R) through the command line: `walk` without a display
//! renders instead, `flight` renders a product flight on the CPU and the GPU alike, `bench
//! --products` measures them, and what they do not take yet is named.

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    let _gpu = ["render", "walk", "bench", "flight"]
        .iter()
        .any(|c| args.first() == Some(c) && !args.contains(&"--cpu"))
        .then(crate::common::gpu_lock);
    Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(args)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("the binary runs")
}

fn ok(args: &[&str]) -> String {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

fn fails_with(args: &[&str], needle: &str) {
    let out = run(args);
    assert!(!out.status.success(), "{args:?} should fail");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(needle), "{args:?}: `{err}` lacks `{needle}`");
    assert!(!err.contains("panicked"), "{err}");
}

fn flight_file() -> String {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/flights/bitorus_through_a_side.toml"
    )
    .into()
}

#[test]
fn product_flights_render_alike_on_the_cpu_and_the_gpu() {
    let dir = crate::common::scratch_dir("products-flight");
    let (cpu, gpu) = (dir.join("cpu"), dir.join("gpu"));
    let file = flight_file();
    for (out, extra) in [(&cpu, Some("--cpu")), (&gpu, None)] {
        let mut args = vec![
            "flight",
            file.as_str(),
            "--size",
            "64x36",
            "--fps",
            "1",
            "--frames",
            "1..2",
            "--crossings",
            "24",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let said = ok(&args);
        assert!(said.contains("bitorus-circle (H2xR)"), "{said}");
    }
    for n in 1..=2 {
        let name = format!("frame-{n:05}.png");
        let a = image::open(cpu.join(&name)).expect("CPU frame").to_rgb8();
        let b = image::open(gpu.join(&name)).expect("GPU frame").to_rgb8();
        assert_eq!(a.dimensions(), (64, 36));
        let differing = a
            .pixels()
            .zip(b.pixels())
            .filter(|(p, q)| (0..3).any(|k| p.0[k].abs_diff(q.0[k]) > 10))
            .count();
        assert!(
            differing <= 23,
            "frame {n}: {differing} of 2304 pixels differ"
        );
        // Not an empty picture: the scene's objects show.
        let distinct: std::collections::BTreeSet<[u8; 3]> = a.pixels().map(|p| p.0).collect();
        assert!(distinct.len() > 20, "frame {n}: {} colours", distinct.len());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Pixels of two pictures differing by more than 10 in a channel.
fn differing(a: &image::RgbImage, b: &image::RgbImage) -> usize {
    assert_eq!(a.dimensions(), b.dimensions());
    a.pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|k| p.0[k].abs_diff(q.0[k]) > 10))
        .count()
}

#[test]
fn product_scene_files_render_alike_on_the_cpu_and_the_gpu_in_mono_and_stereo() {
    let dir = crate::common::scratch_dir("products-scene");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/bitorus_pillars.toml"
    );
    for stereo in ["mono", "side-by-side"] {
        let mut pictures = Vec::new();
        for cpu in [true, false] {
            let out = dir.join(format!("{stereo}-{cpu}.png"));
            let mut args = vec![
                "render",
                "--scene",
                scene,
                "--size",
                "64x36",
                "--crossings",
                "24",
                "--stereo",
                stereo,
                "--out",
                out.to_str().unwrap(),
            ];
            if cpu {
                args.push("--cpu");
            }
            let said = ok(&args);
            assert!(said.contains("bitorus-circle (H2xR)"), "{said}");
            assert_eq!(said.contains("eyes 0.04"), stereo != "mono", "{said}");
            pictures.push(image::open(&out).expect("a picture").to_rgb8());
        }
        let d = differing(&pictures[0], &pictures[1]);
        assert!(d <= 23, "{stereo}: {d} of 2304 pixels differ");
        let distinct: std::collections::BTreeSet<[u8; 3]> =
            pictures[0].pixels().map(|p| p.0).collect();
        assert!(distinct.len() > 20, "{stereo}: {} colours", distinct.len());
    }
    // The scene file's view, not the space's default one.
    let default = dir.join("default.png");
    ok(&[
        "render",
        "bitorus-circle",
        "--size",
        "64x36",
        "--crossings",
        "24",
        "--cpu",
        "--out",
        default.to_str().unwrap(),
    ]);
    let default = image::open(&default).unwrap().to_rgb8();
    let from_file = image::open(dir.join("mono-true.png")).unwrap().to_rgb8();
    assert!(differing(&default, &from_file) > 500);
    // --eye and --look-at move the camera as a scene file's [start] would; --time has
    // nothing to turn.
    let moved = dir.join("moved.png");
    ok(&[
        "render",
        "--scene",
        scene,
        "--eye",
        "0.3,0,0",
        "--look-at",
        "-0.5,0.2,0",
        "--size",
        "64x36",
        "--crossings",
        "24",
        "--cpu",
        "--out",
        moved.to_str().unwrap(),
    ]);
    let moved = image::open(&moved).unwrap().to_rgb8();
    assert!(differing(&moved, &from_file) > 500);
    fails_with(
        &[
            "render",
            "--scene",
            scene,
            "--eye",
            "0,0,0",
            "--look-at",
            "0,0,0",
            "--cpu",
        ],
        "nothing to look towards",
    );
    // A ball with a velocity: `--time` moves it (the GPU drawing what the CPU does), and a
    // time that cannot be flown is refused.
    let moving = dir.join("moving.toml");
    std::fs::write(
        &moving,
        "space = \"bitorus-circle\"\n[start]\nposition = [0.0, 0.0, 0.0]\nlook_at = [1.0, 0.0, 0.0]\n\
         [[object]]\ntype = \"ball\"\nposition = [0.4, 0.0, 0.0]\nradius = 0.15\n\
         colour = [1.0, 0.2, 0.2]\nvelocity = [0.0, 0.25, 0.0]\n",
    )
    .unwrap();
    let moving = moving.to_str().unwrap();
    let picture = |time: &str, cpu: bool| {
        let out = dir.join(format!("moving-{time}-{cpu}.png"));
        let mut args = vec![
            "render",
            "--scene",
            moving,
            "--time",
            time,
            "--size",
            "64x36",
            "--crossings",
            "16",
            "--out",
            out.to_str().unwrap(),
        ];
        if cpu {
            args.push("--cpu");
        }
        ok(&args);
        image::open(&out).expect("a picture").to_rgb8()
    };
    let (start, later) = (picture("0", true), picture("1.5", true));
    assert!(
        differing(&start, &later) > 20,
        "the ball moved: {} pixels changed",
        differing(&start, &later)
    );
    let gpu = picture("1.5", false);
    assert!(differing(&gpu, &later) <= 23, "{}", differing(&gpu, &later));
    fails_with(
        &["render", "--scene", moving, "--time", "1e9", "--cpu"],
        "motion steps",
    );
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "space = \"bitorus-circle\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0.95]\nradius = 0.2\n",
    )
    .unwrap();
    fails_with(
        &["render", "--scene", bad.to_str().unwrap(), "--cpu"],
        "bad.toml:2: the ball at [0.0, 0.0, 0.95] does not fit in the cell",
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_teaching_views_colour_product_spaces_alike_on_the_cpu_and_the_gpu() {
    let dir = crate::common::scratch_dir("products-colour-by");
    // The bitorus's pairings turn by multiples of 45°, which lie between the holonomy
    // view's 30° bins: f32 and f64 may round such a tie either way. The far copies, lit by
    // every image of the lamp, are bright enough for such a tie to show (48 pixels of
    // 2304 lit by the nearest copy, 96 by every image, in a run on lavapipe).
    for (mode, most) in [("crossings", 23), ("face", 23), ("holonomy", 120)] {
        let mut pictures = Vec::new();
        for cpu in [true, false] {
            let out = dir.join(format!("{mode}-{cpu}.png"));
            let mut args = vec![
                "render",
                "bitorus-circle",
                "--colour-by",
                mode,
                "--size",
                "64x36",
                "--crossings",
                "24",
                "--out",
                out.to_str().unwrap(),
            ];
            if cpu {
                args.push("--cpu");
            }
            ok(&args);
            pictures.push(image::open(&out).expect("a picture").to_rgb8());
        }
        let d = differing(&pictures[0], &pictures[1]);
        assert!(d <= most, "{mode}: {d} of 2304 pixels differ");
    }
    // Each view tints the picture its own way.
    let read = |m: &str| {
        image::open(dir.join(format!("{m}-true.png")))
            .unwrap()
            .to_rgb8()
    };
    assert!(differing(&read("crossings"), &read("face")) > 200);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `curved-spaces ARGS` in `dir` with no display (and no OpenXR runtime): it must succeed;
/// returns what it said.
pub(crate) fn walk_without_display(dir: &std::path::Path, args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_curved-spaces"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env("XR_RUNTIME_JSON", dir.join("no-runtime.json"))
        .output()
        .expect("runs");
    let said = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(out.status.success(), "{args:?}: {said}");
    said
}

#[test]
fn walking_a_product_space_without_a_display_renders_it() {
    let dir = crate::common::scratch_dir("products-walk");
    let said = walk_without_display(
        &dir,
        &["walk", "projective-plane-circle", "--crossings", "16"],
    );
    assert!(said.contains("no display found"), "{said}");
    assert!(dir.join("curved-spaces.png").exists(), "{said}");
    // The headset mode works here too: without a runtime it says so and falls back to
    // desktop stereo (here, without a display, a stereo picture).
    let said = walk_without_display(
        &dir,
        &[
            "walk",
            "projective-plane-circle",
            "--xr",
            "--crossings",
            "8",
        ],
    );
    assert!(said.contains("falling back to desktop stereo"), "{said}");
    // Without a window the options of a walk do nothing, and it says so.
    let said = walk_without_display(
        &dir,
        &[
            "walk",
            "projective-plane-circle",
            "--record",
            "walk.toml",
            "--crossings",
            "8",
        ],
    );
    assert!(said.contains("--record does nothing"), "{said}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_products_measures_speed_against_error() {
    let dir = crate::common::scratch_dir("products-bench");
    let said = ok(&[
        "bench",
        "--quick",
        "--products",
        "projective-plane-circle,crosscaps-circle",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(said.contains("crossings a pixel"), "{said}");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("bench.json")).unwrap()).unwrap();
    let rows = json["report"]["products"].as_array().unwrap().clone();
    assert_eq!(rows.len(), 2, "{rows:?}");
    for r in &rows {
        let f = |k: &str| r[k].as_f64().unwrap_or(f64::NAN);
        assert!(
            f("tracer_ms") > 0.0 && f("reference_ms") > 0.0 && f("ratio") > 0.0,
            "{r}"
        );
        assert!(f("crossings_per_pixel") >= 1.0, "{r}");
        assert!(f("crossings_per_pixel") <= f("budget"), "{r}");
        assert!(f("differing_pixels") < 0.01, "{r}");
        // The f32 walk stays within the accuracy target relative to its conditioning.
        assert!(f("f32_median") <= 2.0 && f("f32_worst") <= 5.0, "{r}");
    }
    let csv = std::fs::read_to_string(dir.join("products.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(
        std::fs::read_to_string(dir.join("summary.md"))
            .unwrap()
            .contains("Product spaces")
    );
    fails_with(&["bench", "--products", "nowhere"], "not a product space");
    fails_with(
        &["bench", "--products", "surface-abAB-circle-1"],
        "flat space",
    );
    fails_with(
        &["bench", "--products", "surface-abc-circle-1"],
        "surface-abc-circle-1",
    );
    let _ = std::fs::remove_dir_all(&dir);
}
