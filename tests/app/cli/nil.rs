//! The Nil spaces on the command line: `info`, `trace`, `render`, scene files, `flight` and
//! `light` take them, bad ids and bad files get a clear error, and what is not written for
//! Nil yet says so.

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
        &["light", "nil-3", "--at", "0,0,0", "--radius", "0.1"][..],
        &["export", "nil-3"][..],
        &[
            "render",
            "nil-3",
            "--cpu",
            "--size",
            "16x9",
            "--colour-by",
            "holonomy",
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

/// A scene file of a Nil space draws its own objects from its start view: the view aimed at
/// its ball sees the ball's colour in the middle, and `--eye --look-at` from the same place
/// draws the same picture as the file's `[start]`.
#[test]
fn render_draws_a_nil_scene_file() {
    let dir = temp_dir("nil-scene");
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "space = \"nil-3\"\nedges = false\nfog = 2.0\n[start]\nposition = [0.0, -0.4, 0.02]\n\
         look_at = [1.0, 0.1, 0.0]\nfov = 60\n[[object]]\ntype = \"ball\"\n\
         position = [1.0, 0.1, 0.0]\nradius = 0.12\ncolour = [0.9, 0.1, 0.1]\n",
    )
    .expect("write");
    let path = scene.to_str().unwrap();
    let file = cpu_picture(&dir, "file.png", &["render", "--scene", path]);
    let [r, g, b] = file.get_pixel(20, 12).0;
    assert!(r > 2 * g.max(b) && r > 30, "the middle is {r},{g},{b}");
    let aimed = cpu_picture(
        &dir,
        "aimed.png",
        &[
            "render",
            "--scene",
            path,
            "--eye",
            "0,-0.4,0.02",
            "--look-at",
            "1,0.1,0",
            "--fov",
            "60",
        ],
    );
    assert_eq!(file, aimed, "the file's start view is --eye --look-at's");
    // The example scene loads and draws.
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/assets/scenes/heisenberg_twist.toml"
    );
    let picture = cpu_picture(&dir, "example.png", &["render", "--scene", example]);
    let mut colours: Vec<[u8; 3]> = picture.pixels().map(|p| p.0).collect();
    colours.sort_unstable();
    colours.dedup();
    assert!(colours.len() > 100, "only {} colours", colours.len());
}

#[test]
fn bad_nil_scene_files_get_errors_that_name_the_line() {
    let dir = temp_dir("nil-bad-scenes");
    let cases = [
        ("space = \"nil-0\"\n", ":1: ", "the K of nil-K"),
        (
            "space = \"nil-2\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0]\nradius = 0.7\n",
            ":2: ",
            "at most 0.5",
        ),
        (
            "space = \"nil-2\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0]\nradius = 0.1\nvelocity = [inf, 0, 0]\n",
            ":2: ",
            "velocity must be finite",
        ),
        (
            "space = \"nil-2\"\n[[object]]\ntype = \"fibre\"\nposition = [0, 0]\nradios = 0.1\n",
            "",
            "radius",
        ),
        (
            "space = \"nil-2\"\n[[light]]\nposition = [0, 0, 0]\n[[light]]\nposition = [0.1, 0, 0]\n",
            ":4: ",
            "one light",
        ),
        (
            "space = \"nil-2\"\n[start]\nposition = [0, 0, 0]\nlook_at = [0, 0, 0]\n",
            ":2: ",
            "looks at its own position",
        ),
        (
            "space = \"nil-2\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 1e300]\nradius = 0.1\n",
            ":2: ",
            "within 10⁶",
        ),
        (
            "space = \"nil-1000\"\n[[object]]\ntype = \"ball\"\nposition = [0, 0, 0]\nradius = 0.5\n",
            ":2: ",
            "more than 400 objects",
        ),
        (
            "space = \"nil-2\"\nfog = -1\n",
            ":2: ",
            "fog distance must be a positive",
        ),
    ];
    for (i, (text, line, needle)) in cases.iter().enumerate() {
        let scene = dir.join(format!("bad-{i}.toml"));
        std::fs::write(&scene, text).expect("write");
        let path = scene.to_str().unwrap();
        fails_with(
            &["render", "--scene", path, "--cpu", "--size", "16x9"],
            &format!("{path}{line}"),
        );
        fails_with(
            &["render", "--scene", path, "--cpu", "--size", "16x9"],
            needle,
        );
    }
}

/// A scene file's moving ball is drawn where it has flown: `render --time` moves it, a
/// flight's frames show it moving, and a ball too fast to follow is refused by name.
#[test]
fn moving_balls_fly_through_nil() {
    let dir = temp_dir("nil-moving");
    let scene = dir.join("moving.toml");
    std::fs::write(
        &scene,
        "space = \"nil-1\"\nedges = false\n[start]\nposition = [0.0, -0.4, 0.0]\n\
         look_at = [0.0, 0.0, 0.0]\n[[object]]\ntype = \"ball\"\nposition = [0.0, 0.0, 0.0]\n\
         radius = 0.1\ncolour = [0.9, 0.2, 0.2]\nvelocity = [0.25, 0.0, 0.0]\n",
    )
    .expect("write");
    let path = scene.to_str().unwrap();
    let at =
        |t: &str, name: &str| cpu_picture(&dir, name, &["render", "--scene", path, "--time", t]);
    let start = at("0", "t0.png");
    let later = at("1", "t1.png");
    // At 0 the ball is dead ahead; a second later it has moved off the middle to the right.
    let middle = |image: &image::RgbImage| image.get_pixel(20, 12).0;
    let [r, g, b] = middle(&start);
    assert!(r > 2 * g.max(b) && r > 30, "at 0 the middle is {r},{g},{b}");
    assert_ne!(middle(&start), middle(&later), "the ball did not move");
    let right = |image: &image::RgbImage| {
        image
            .enumerate_pixels()
            .filter(|(x, _, p)| *x > 20 && p.0[0] > 2 * p.0[1].max(p.0[2]) && p.0[0] > 30)
            .count()
    };
    assert!(right(&later) > right(&start), "the ball did not move right");
    let fast = dir.join("fast.toml");
    std::fs::write(
        &fast,
        std::fs::read_to_string(&scene)
            .unwrap()
            .replace("velocity = [0.25, 0.0, 0.0]", "velocity = [1e9, 0.0, 0.0]"),
    )
    .expect("write");
    fails_with(
        &[
            "render",
            "--scene",
            fast.to_str().unwrap(),
            "--time",
            "1",
            "--cpu",
            "--size",
            "16x9",
        ],
        "at 1 s",
    );
}

/// A Nil flight's first frame is the view from its first key (the same picture as
/// `render --eye --look-at`), and a key beyond the box is reached by flying there; keys
/// too far, a replayed flight and a recorded one name what is wrong.
#[test]
fn flights_fly_through_nil() {
    let dir = temp_dir("nil-flight");
    let flight = dir.join("flight.toml");
    std::fs::write(
        &flight,
        "space = \"nil-3\"\nfov = 60\n[[key]]\ntime = 0.0\nposition = [0.1, -0.4, 0.05]\n\
         look_at = [0.0, 0.0, 0.0]\n[[key]]\ntime = 1.0\nposition = [1.2, 0.3, 0.1]\n\
         look_at = [2.0, 0.5, 0.0]\n",
    )
    .expect("write");
    let flown = cpu_picture(
        &dir,
        "frames",
        &["flight", flight.to_str().unwrap(), "--fps", "2"],
    );
    let rendered = cpu_picture(
        &dir,
        "key.png",
        &[
            "render",
            "nil-3",
            "--eye",
            "0.1,-0.4,0.05",
            "--look-at",
            "0,0,0",
            "--fov",
            "60",
        ],
    );
    assert_eq!(flown, rendered);
    assert!(dir.join("frames/frame-00002.png").exists());
    let far = dir.join("far.toml");
    std::fs::write(
        &far,
        "space = \"nil-50\"\n[[key]]\ntime = 0.0\nposition = [0.0, 0.0, 40.0]\nlook_at = [0.1, 0.0, 0.0]\n",
    )
    .expect("write");
    fails_with(
        &["flight", far.to_str().unwrap()],
        "more than 1000 face crossings",
    );
    fails_with(
        &["walk", "--replay", far.to_str().unwrap()],
        "more than 1000 face crossings",
    );
}

/// `light` sums the lamp's images along the shortest geodesics with Nil's falloff, the rest
/// by its mean: the mean stands in for the images between two reaches to within 2 %.
#[test]
fn light_sums_a_nil_lamps_images() {
    let at = |reach: &str, check: &str| {
        json(&[
            "light",
            "nil-1",
            "--light",
            "0,0,0.1",
            "--at",
            "0.3,0.2,0",
            "--reach",
            reach,
            "--check",
            check,
            "--json",
        ])
    };
    let v = at("1", "2");
    assert_eq!(v["geometry"], "Nil");
    let (exact, tail, total) = (
        v["exact"].as_f64().unwrap(),
        v["tail"].as_f64().unwrap(),
        v["total"].as_f64().unwrap(),
    );
    assert!(exact > 0.0 && tail > 0.0 && (exact + tail - total).abs() < 1e-12 * total);
    assert!(v["images"].as_u64().unwrap() >= 1);
    let longer = &v["check"];
    assert!(longer["images"].as_u64().unwrap() > v["images"].as_u64().unwrap());
    let off = longer["difference"].as_f64().unwrap() / total;
    assert!(off.abs() < 0.02, "the tail's mean is off by {off}");
    // A start outside the box is brought in by the lattice: the same light.
    let moved = json(&[
        "light",
        "nil-1",
        "--light",
        "1,0,0.1",
        "--at",
        "0.3,1.2,-0.15",
        "--reach",
        "1",
        "--json",
    ]);
    assert!((moved["total"].as_f64().unwrap() - total).abs() < 1e-9 * total);
    fails_with(
        &["light", "nil-1", "--light", "0,0,0", "--at", "0,0,2e6"],
        "not a chart point",
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
