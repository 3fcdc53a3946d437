//! What the command line draws: stereo, the headset's fallback, scene files, start views,
//! flights, moving objects, walls and centrepieces.

use super::*;

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
