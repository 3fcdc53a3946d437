//! The SL̃(2,R) spaces on the command line: `info` gives the unit tangent bundle's
//! invariants, `trace` walks its geodesics (the end a model point of `UT H²` in the cell,
//! the vertical speed kept), and words or commands it cannot take are refused with the
//! reason.

use super::*;

fn lorentz(u: &[f64], v: &[f64]) -> f64 {
    u[0] * v[0] + u[1] * v[1] - u[2] * v[2]
}

/// `Z/d + Z + … + Z` (SnapPy's order), `d` left out where it is 1.
fn homology_text(rank: i64, torsion: i64) -> String {
    let mut parts: Vec<String> = Vec::new();
    if torsion > 1 {
        parts.push(format!("Z/{torsion}"));
    }
    parts.extend((0..rank).map(|_| "Z".to_string()));
    parts.join(" + ")
}

#[test]
fn info_gives_the_unit_tangent_bundles_invariants() {
    for (id, word, genus, sheets) in [
        ("unit-tangent-bitorus", "abABcdCD", 2i64, 1i64),
        ("unit-tangent-abcdABCD", "abcdABCD", 2, 1),
        ("unit-tangent-abABcdCDefEF", "abABcdCDefEF", 3, 1),
        ("unit-tangent-bitorus-cover-2", "abABcdCD", 2, 2),
        ("unit-tangent-abABcdCDefEF-cover-2", "abABcdCDefEF", 3, 2),
        ("unit-tangent-abABcdCDefEF-cover-4", "abABcdCDefEF", 3, 4),
    ] {
        let v = json(&["info", id, "--json"]);
        assert_eq!(v["geometry"], "SL2R");
        assert_eq!(v["name"], id);
        assert_eq!(v["word"], word);
        assert_eq!(v["genus"], genus);
        assert_eq!(v["sheets"], sheets);
        let chi = 2 - 2 * genus;
        assert_eq!(v["euler_characteristic"], chi);
        // The fibre 2πN times the area 2π|χ|.
        let volume = 4.0 * std::f64::consts::PI.powi(2) * (sheets * chi.abs()) as f64;
        assert!((v["volume"].as_f64().unwrap() - volume).abs() < 1e-12 * volume);
        // The Euler number of the N-fold cover is χ/N: the fibre's order in H₁.
        assert_eq!(
            v["homology"],
            homology_text(2 * genus, chi.abs() / sheets),
            "{id}"
        );
        assert_eq!(v["faces"], 4 * genus);
        assert_eq!(v["orientable"], true);
        let inj = v["injectivity_radius_at_least"].as_f64().unwrap();
        assert!(inj > 0.5 && inj <= std::f64::consts::PI, "{id}: {inj}");
        if sheets == 1 {
            assert_eq!(v["injectivity_radius"].as_f64(), Some(inj));
        } else {
            assert!(
                v["injectivity_radius"].is_null(),
                "{id}: a cover's is a bound"
            );
        }
    }
}

/// The end is a point of `UT H²` (`p` on the hyperboloid, `e` a unit tangent there) whose
/// base point is in the polygon, the body velocity is unit and keeps its vertical part, and
/// the f32 walk crosses the same sides.
#[test]
fn trace_walks_an_sl2r_geodesic_to_a_model_point_in_the_cell() {
    let dir = [0.6, 0.3, 0.5];
    let n: f64 = dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2];
    let args = [
        "trace",
        "unit-tangent-bitorus",
        "--dir",
        "0.6,0.3,0.5",
        "--crossings",
        "12",
        "--json",
    ];
    let v = json(&args);
    let crossings = v["crossings"].as_array().unwrap();
    assert_eq!(crossings.len(), 12, "{v}");
    let end = &v["end"];
    let m: Vec<f64> = end["model"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let (p, e) = (&m[0..3], &m[3..6]);
    assert!((lorentz(p, p) + 1.0).abs() < 1e-12 && p[2] > 0.0, "{m:?}");
    assert!((lorentz(e, e) - 1.0).abs() < 1e-12, "{m:?}");
    assert!(lorentz(e, p).abs() < 1e-12, "{m:?}");
    let d: Vec<f64> = end["direction"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((d.iter().map(|x| x * x).sum::<f64>() - 1.0).abs() < 1e-14);
    assert!(
        (d[2] - 0.5 / n.sqrt()).abs() < 1e-15,
        "the vertical speed changed: {d:?}"
    );
    // In the octagon: within its circumradius of the centre (cosh R = cot(π/8) cot(π/8)).
    let cosh_r = (1.0 / (std::f64::consts::PI / 8.0).tan()).powi(2);
    assert!(p[2] <= cosh_r + 1e-9, "{p:?} is outside the octagon");
    let mut f32_args = args.to_vec();
    f32_args.extend(["--precision", "f32"]);
    let v32 = json(&f32_args);
    let sides = |v: &Value| -> Vec<i64> {
        v["crossings"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["side"].as_i64().unwrap())
            .collect()
    };
    assert_eq!(sides(&v32), sides(&v));
}

#[test]
fn the_fibre_is_a_closed_geodesic_inside_the_cell() {
    fails_with(
        &[
            "trace",
            "unit-tangent-bitorus",
            "--dir",
            "0,0,1",
            "--crossings",
            "1",
        ],
        "stays inside the cell for ever",
    );
    // Walked by distance it goes round: back to the start after 2π.
    let v = json(&[
        "trace",
        "unit-tangent-bitorus",
        "--dir",
        "0,0,1",
        "--distance",
        "6.283185307179586",
        "--json",
    ]);
    let m = v["end"]["model"].as_array().unwrap();
    let want = [0.0, 0.0, 1.0, 1.0, 0.0, 0.0];
    for (x, w) in m.iter().zip(want) {
        assert!((x.as_f64().unwrap() - w).abs() < 1e-14, "{m:?}");
    }
}

#[test]
fn words_and_commands_it_cannot_take_are_refused_with_the_reason() {
    fails_with(&["info", "unit-tangent-abAB"], "flat");
    fails_with(&["info", "unit-tangent-aA"], "spherical");
    fails_with(&["info", "unit-tangent-aabb"], "non-orientable");
    fails_with(
        &["info", "unit-tangent-abABcdCD-cover-3"],
        "3 does not divide χ = -2",
    );
    fails_with(
        &["info", "unit-tangent-abABcdCD-cover-0"],
        "N = 0 is no cover",
    );
    fails_with(&["info", "unit-tangent-abAB-cover-2"], "flat");
    fails_with(&["info", "unit-tangent-ab"], "");
    // walk refuses by the table what it cannot do (before it would open a window).
    fails_with(
        &["walk", "unit-tangent-bitorus", "--colour-by", "holonomy"],
        "not in the SL̃(2,R) spaces",
    );
    for extra in [&["--colour-by", "holonomy"][..], &["--time", "1"]] {
        let mut args = vec!["render", "unit-tangent-bitorus", "--cpu", "--size", "16x9"];
        args.extend_from_slice(extra);
        fails_with(&args, "SL̃(2,R)");
    }
    // The lamp is a point, and its images are summed below the injectivity radius.
    let light = [
        "light",
        "unit-tangent-bitorus",
        "--light",
        "0,0,0",
        "--at",
        "0.1,0,0",
    ];
    fails_with(
        &[&light[..], &["--radius", "0.1"]].concat(),
        "lamp is a point",
    );
    fails_with(
        &[&light[..], &["--reach", "5"]].concat(),
        "within 3 at most",
    );
    fails_with(
        &[&light[..], &["--check", "4"]].concat(),
        "within 3 at most",
    );
    fails_with(
        &[
            "render",
            "unit-tangent-bitorus",
            "--cpu",
            "--lamp-radius",
            "0.2",
        ],
        "lamp is a point",
    );
    let list = String::from_utf8(run(&["list"]).stdout).unwrap();
    assert!(list.contains("unit-tangent-WORD"), "{list}");
}

/// `light` sums the lamp's images along the shortest geodesics within the reach: the JSON
/// names the geometry, and the sum is the same from either end (the two points swapped), in
/// the bundle and in a cover.
#[test]
fn light_sums_the_lamps_images_the_same_from_either_end() {
    for space in ["unit-tangent-bitorus", "unit-tangent-bitorus-cover-2"] {
        let sum = |lamp: &str, at: &str| {
            json(&[
                "light", space, "--light", lamp, "--at", at, "--reach", "2.5", "--json",
            ])
        };
        let there = sum("-0.3,0.4,0.3", "0.8,0.1,-1");
        let back = sum("0.8,0.1,-1", "-0.3,0.4,0.3");
        assert_eq!(there["geometry"], "SL2R");
        assert_eq!(there["reach"], 2.5);
        let (a, b) = (
            there["exact"].as_f64().unwrap(),
            back["exact"].as_f64().unwrap(),
        );
        assert!(
            a > 0.0 && (a - b).abs() < 1e-9 * a,
            "{space}: {a} against {b}"
        );
        assert_eq!(there["images"], back["images"]);
        assert!(there["tail"].as_f64().unwrap() > 0.0);
    }
}

/// `render --cpu` draws the default scene: straight ahead the centre's pale pillar, in front
/// of the fog.
#[test]
fn render_cpu_draws_the_fibre_tubes() {
    let dir = temp_dir("sl2r-render");
    let out = dir.join("bitorus.png");
    let run_out = run(&[
        "render",
        "unit-tangent-bitorus",
        "--cpu",
        "--size",
        "64x36",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run_out.status.success(),
        "{}",
        String::from_utf8_lossy(&run_out.stderr)
    );
    let image = image::open(&out).expect("a PNG").to_rgb8();
    assert_eq!(image.dimensions(), (64, 36));
    let centre = image.get_pixel(32, 18).0;
    // The default scene's fog, written as computed (no gamma curve).
    let fog = [0.55f64, 0.6, 0.7].map(|c| (255.0 * c).round() as u8);
    assert_ne!(centre, fog, "the centre pixel is fog");
    // The pale pillar: red and green alike, unlike the fog's blue tint.
    assert!(
        (i32::from(centre[0]) - i32::from(centre[1])).abs() <= 6,
        "{centre:?}"
    );
    let distinct: std::collections::HashSet<[u8; 3]> = image.pixels().map(|p| p.0).collect();
    assert!(
        distinct.len() > 50,
        "a flat picture: {} colours",
        distinct.len()
    );
}

/// The example scene file renders with the CPU reference and on the GPU: straight ahead its
/// red tube.
#[test]
fn the_example_scene_file_renders_on_the_cpu() {
    let scene = format!(
        "{}/assets/scenes/unit_tangent_ring.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let dir = temp_dir("sl2r-scene");
    let out = dir.join("ring.png");
    let run_out = run(&[
        "render",
        "--scene",
        &scene,
        "--cpu",
        "--size",
        "48x27",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run_out.status.success(),
        "{}",
        String::from_utf8_lossy(&run_out.stderr)
    );
    let gpu_out = dir.join("ring-gpu.png");
    let gpu_run = run(&[
        "render",
        "--scene",
        &scene,
        "--size",
        "48x27",
        "--out",
        gpu_out.to_str().unwrap(),
    ]);
    assert!(
        gpu_run.status.success(),
        "{}",
        String::from_utf8_lossy(&gpu_run.stderr)
    );
    for path in [&out, &gpu_out] {
        let image = image::open(path).expect("a PNG").to_rgb8();
        let centre = image.get_pixel(24, 13).0;
        assert!(
            centre[0] > centre[1] + 30 && centre[0] > centre[2] + 30,
            "{}: not the red tube ahead: {centre:?}",
            path.display()
        );
    }
}

/// The teaching views tint by the crossings or the last side crossed: the pictures differ
/// from the plain one and from each other.
#[test]
fn the_teaching_views_tint_the_copies() {
    let dir = temp_dir("sl2r-views");
    let picture = |extra: &[&str], name: &str| {
        let out = dir.join(name);
        let mut args = vec![
            "render",
            "unit-tangent-bitorus",
            "--cpu",
            "--size",
            "64x36",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let o = run(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        image::open(&out).expect("a PNG").to_rgb8()
    };
    let plain = picture(&[], "plain.png");
    let crossings = picture(&["--colour-by", "crossings"], "crossings.png");
    let face = picture(&["--colour-by", "face"], "face.png");
    assert_ne!(plain, crossings);
    assert_ne!(plain, face);
    assert_ne!(crossings, face);
}

/// `--eye x,y,θ --look-at x,y,θ` places the camera and turns it along the shortest geodesic
/// to the point (the ball stack, where the picture is the stack's orange); a point too far
/// for the inverse exponential map and a point on the eye are refused with the reason.
#[test]
fn render_looks_at_a_point_by_the_inverse_exponential_map() {
    let dir = temp_dir("sl2r-look-at");
    let out = dir.join("stack.png");
    // The stack's middle ball: half the inradius (1.5286) towards side 2, e at angle 0.
    let y = (0.5f64 * 1.528_570_919_480_998_2).sinh();
    let target = format!("0,{y},0");
    let run_out = run(&[
        "render",
        "unit-tangent-bitorus",
        "--cpu",
        "--size",
        "32x18",
        "--eye",
        "-0.2,0,0",
        "--look-at",
        &target,
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        run_out.status.success(),
        "{}",
        String::from_utf8_lossy(&run_out.stderr)
    );
    let image = image::open(&out).expect("a PNG").to_rgb8();
    let [r, g, b] = image.get_pixel(16, 9).0;
    assert!(
        r > g && g > b && r > 100,
        "the centre of the view is not the orange ball: {r},{g},{b}"
    );
    for (look_at, says) in [
        ("10,10,0", "injectivity radius"),
        ("-0.2,0,0", "own position"),
    ] {
        fails_with(
            &[
                "render",
                "unit-tangent-bitorus",
                "--cpu",
                "--size",
                "16x9",
                "--eye",
                "-0.2,0,0",
                "--look-at",
                look_at,
            ],
            says,
        );
    }
}

/// An SL̃(2,R) flight's first frame is the view from its first key (the same picture as
/// `render --eye --look-at`), the example flight flies through a side on the GPU's twin (the
/// CPU here), and keys too far apart are refused with the reason.
#[test]
fn flights_fly_through_unit_tangent_bundles() {
    let dir = temp_dir("sl2r-flight");
    let flight = dir.join("flight.toml");
    std::fs::write(
        &flight,
        "space = \"unit-tangent-bitorus\"\nfov = 60\n[[key]]\ntime = 0.0\n\
         position = [-0.6, 0.0, 0.0]\nlook_at = [0.0, 0.84, 0.0]\n[[key]]\ntime = 1.0\n\
         position = [0.2, 0.5, 0.3]\nlook_at = [0.0, 1.2, 0.5]\n",
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
            "unit-tangent-bitorus",
            "--eye",
            "-0.6,0,0",
            "--look-at",
            "0,0.84,0",
            "--fov",
            "60",
        ],
    );
    assert_eq!(flown, rendered);
    assert!(dir.join("frames/frame-00002.png").exists());
    let example = format!(
        "{}/assets/flights/unit_tangent_past_the_stack.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let _ = cpu_picture(&dir, "example", &["flight", &example, "--fps", "1"]);
    assert!(dir.join("example/frame-00004.png").exists());
    let far = dir.join("far.toml");
    std::fs::write(
        &far,
        "space = \"unit-tangent-bitorus\"\n[[key]]\ntime = 0.0\nposition = [0, 0, 0]\n\
         look_at = [0.5, 0, 0]\n[[key]]\ntime = 1.0\nposition = [20, 0, 0]\n\
         look_at = [21, 0, 0]\n",
    )
    .expect("write");
    fails_with(&["flight", far.to_str().unwrap()], "add keys between");
    fails_with(
        &["walk", "--replay", far.to_str().unwrap()],
        "add keys between",
    );
}

/// `walk --xr` takes an SL̃(2,R) space: without a runtime it says so and falls back to
/// desktop stereo (here, without a display, a stereo picture of the space).
#[test]
fn the_headset_mode_takes_unit_tangent_bundles() {
    let dir = temp_dir("sl2r-xr");
    let said = crate::products::walk_without_display(
        &dir,
        &["walk", "unit-tangent-bitorus", "--xr", "--crossings", "8"],
    );
    assert!(said.contains("falling back to desktop stereo"), "{said}");
    let picture = image::open(dir.join("curved-spaces.png"))
        .expect("a picture")
        .to_rgb8();
    // Side by side: the two halves are the two eyes, not the same picture.
    let (w, h) = picture.dimensions();
    let half = |x0: u32| image::imageops::crop_imm(&picture, x0, 0, w / 2, h).to_image();
    assert_ne!(half(0), half(w / 2), "{said}");
}

/// `--walls` draws the sides: solid opaque walls hide every copy past the first side, so the
/// picture changes wherever a ray left the cell before meeting a tube.
#[test]
fn render_walls_hide_what_lies_past_the_sides() {
    let dir = temp_dir("sl2r-walls");
    let picture = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let mut args = vec!["render", "unit-tangent-bitorus", "--cpu", "--size", "48x27"];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", out.to_str().unwrap()]);
        let done = run(&args);
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
        image::open(&out).expect("a PNG").to_rgb8()
    };
    let open = picture("open.png", &[]);
    let walled = picture("walled.png", &["--walls", "0", "--wall-opacity", "1"]);
    let changed = open
        .pixels()
        .zip(walled.pixels())
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 48 * 27 / 5, "only {changed} pixels changed");
    // The centre's pillar stands inside the cell: no wall before it.
    assert_eq!(open.get_pixel(24, 13), walled.get_pixel(24, 13));
}
