//! The Nil spaces on the command line: `info` and `trace` take them, bad ids get a clear
//! error, and the commands that draw say that Nil's pictures are not drawn yet.

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
        &["render", "nil-3", "--cpu", "--size", "16x9"][..],
        &["light", "nil-3", "--at", "0,0,0"][..],
        &["export", "nil-3"][..],
    ] {
        fails_with(args, "not in the Nil spaces");
    }
}
