//! Finding a space by name: a seed space, a member of a library family, or a file
//! (`.gen` generator file or JSON space file).

use super::catalog::{affine, dodecahedron_normals_exact, dodecahedron_offset_exact};
use super::dirichlet::{DirichletOptions, load_gen_file, space_from_matrices};
use super::exact;
use super::file::load_space_file;
use super::group::parse_gen;
use super::{SEED_SPACES, Space, SpaceError, seed_space};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Real};
use glam::{DMat3, DMat4, DQuat, DVec3, DVec4};
use std::path::Path;

/// Whether `path` names a generator file (by its extension, `.gen`, any case).
#[must_use]
pub fn is_gen_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gen"))
}

/// A seed space or a library family's member by id, else a space file by path (relative to
/// `base`): a `.gen` generator file is made into its group's Dirichlet domain about the
/// basepoint of `options`, anything else is read as a JSON space file. `None` for an id
/// that names none of these but may name a product space (checked between the library and
/// the files).
pub(crate) fn seed_or_library(id: &str) -> Option<Result<Space, String>> {
    if SEED_SPACES.iter().any(|s| s.id == id) {
        return Some(seed_space(id).map_err(|e| e.to_string()));
    }
    library_space(id)
}

/// A space file by path (relative to `base`): `.gen` or JSON.
pub(crate) fn space_file(
    id: &str,
    base: &Path,
    options: &DirichletOptions,
) -> Result<Space, String> {
    let path = base.join(id);
    if is_gen_path(&path) {
        return load_gen_file(&path, options);
    }
    if path.exists() || id.ends_with(".json") {
        return load_space_file(&path).map_err(|e| e.to_string());
    }
    Err(SpaceError::UnknownSpace(id.to_string()).to_string())
}

/// A family of the library, as `curved-spaces list` shows it.
#[derive(Clone, Copy, Debug)]
pub struct Family {
    /// The id, with parameters in capitals (`lens-P-Q`).
    pub pattern: &'static str,
    /// Its geometry.
    pub geometry: Geometry,
    /// One line about it.
    pub summary: &'static str,
    /// Members `list` shows by example.
    pub examples: &'static [&'static str],
}

/// The families of the library beyond the seed spaces, in the order `list` shows them.
pub const FAMILIES: &[Family] = &[
    Family {
        pattern: "three-sphere",
        geometry: Geometry::Spherical,
        summary: "the 3-sphere itself: the trivial group, a cell with no face",
        examples: &["three-sphere"],
    },
    Family {
        pattern: "projective-space",
        geometry: Geometry::Spherical,
        summary: "projective space RP³ = L(2,1): a hemisphere, its equator glued to itself by \
                  the antipodal map (group of order 2)",
        examples: &["projective-space"],
    },
    Family {
        pattern: "lens-P-Q",
        geometry: Geometry::Spherical,
        summary: "lens space L(P,Q), P > Q ≥ 1 coprime, P ≤ 1000: the cyclic group \
                  (z1, z2) -> (ζz1, ζ^Q z2), ζ = e^(2πi/P), of order P (L(P,1) is a lens \
                  reaching π/2)",
        examples: &["lens-5-1", "lens-5-2", "lens-7-2", "lens-12-5"],
    },
    Family {
        pattern: "prism-N",
        geometry: Geometry::Spherical,
        summary: "prism space S³/D*4N, N ≥ 2: the binary dihedral group of order 4N",
        examples: &["prism-2", "prism-3", "prism-6"],
    },
    Family {
        pattern: "binary-tetrahedral",
        geometry: Geometry::Spherical,
        summary: "octahedral space S³/2T: the binary tetrahedral group of order 24",
        examples: &["binary-tetrahedral"],
    },
    Family {
        pattern: "binary-octahedral",
        geometry: Geometry::Spherical,
        summary: "truncated-cube space S³/2O: the binary octahedral group of order 48",
        examples: &["binary-octahedral"],
    },
    Family {
        pattern: "binary-icosahedral",
        geometry: Geometry::Spherical,
        summary: "Poincaré dodecahedral space S³/2I from its group of order 120 (= poincare)",
        examples: &["binary-icosahedral"],
    },
    Family {
        pattern: "mirrored-tetrahedron",
        geometry: Geometry::Spherical,
        summary: "orbifold: an all-right spherical tetrahedron (an orthant of S³) whose four \
                  faces are mirrors; a group of order 16",
        examples: &["mirrored-tetrahedron"],
    },
    Family {
        pattern: "torus-A-B-C",
        geometry: Geometry::Euclidean,
        summary: "3-torus of the A×B×C box lattice (A, B, C > 0, at most 1000 to 1)",
        examples: &["torus-1-1-2", "torus-1-2-3"],
    },
    Family {
        pattern: "half-turn-A-B-C",
        geometry: Geometry::Euclidean,
        summary: "a flat manifold with its lattice stretched to A×B×C (any sides, at most 1000 \
                  to 1): half-turn, hantzsche-wendt, first-amphicosm, second-amphicosm, \
                  first-amphidicosm and second-amphidicosm take -A-B-C; quarter-turn, \
                  third-turn and sixth-turn take -A-C (side of the square or hexagonal \
                  lattice, and height)",
        examples: &["half-turn-1-2-3", "hantzsche-wendt-1-1-2", "third-turn-1-3"],
    },
    Family {
        pattern: "torus-hexagonal",
        geometry: Geometry::Euclidean,
        summary: "3-torus of the hexagonal lattice: a hexagonal prism",
        examples: &["torus-hexagonal"],
    },
    Family {
        pattern: "torus-fcc",
        geometry: Geometry::Euclidean,
        summary: "3-torus of the face-centred cubic lattice: a rhombic dodecahedron",
        examples: &["torus-fcc"],
    },
    Family {
        pattern: "torus-bcc",
        geometry: Geometry::Euclidean,
        summary: "3-torus of the body-centred cubic lattice: a truncated octahedron",
        examples: &["torus-bcc"],
    },
    Family {
        pattern: "first-amphicosm",
        geometry: Geometry::Euclidean,
        summary: "non-orientable flat manifold (Klein space): a glide reflection over a \
                  rectangular lattice (space group Pc)",
        examples: &["first-amphicosm"],
    },
    Family {
        pattern: "second-amphicosm",
        geometry: Geometry::Euclidean,
        summary: "non-orientable flat manifold: a glide reflection over a centred lattice (Cc)",
        examples: &["second-amphicosm"],
    },
    Family {
        pattern: "first-amphidicosm",
        geometry: Geometry::Euclidean,
        summary: "non-orientable flat manifold with holonomy Z2×Z2: a screw and two glides \
                  (Pca2_1)",
        examples: &["first-amphidicosm"],
    },
    Family {
        pattern: "second-amphidicosm",
        geometry: Geometry::Euclidean,
        summary: "non-orientable flat manifold with holonomy Z2×Z2: a screw and two glides \
                  (Pna2_1)",
        examples: &["second-amphidicosm"],
    },
    Family {
        pattern: "census-N",
        geometry: Geometry::Hyperbolic,
        summary: "the N-th smallest closed orientable hyperbolic manifold of SnapPy's census, \
                  N = 1…10 (census-1 = weeks, the smallest known)",
        examples: &["weeks", "census-2", "census-10"],
    },
    Family {
        pattern: "seifert-weber-group",
        geometry: Geometry::Hyperbolic,
        summary: "Seifert–Weber space from its six generators (= seifert-weber)",
        examples: &["seifert-weber-group"],
    },
];

/// The largest lens order P the library builds.
pub const MAX_LENS_ORDER: u32 = 1000;

/// The largest prism parameter N the library builds.
pub const MAX_PRISM: u32 = 250;

/// A census manifold shipped with the crate: SnapPy's name, the file's text and SnapPy's
/// numbers for it (JSON).
#[derive(Clone, Copy, Debug)]
pub struct CensusManifold {
    /// SnapPy's name, e.g. `m003(-3,1)`.
    pub snappy_name: &'static str,
    /// The `.gen` file.
    pub generators: &'static str,
    /// SnapPy's volume, homology, radii and length spectrum.
    pub reference: &'static str,
}

macro_rules! census {
    ($name:literal, $stem:literal) => {
        CensusManifold {
            snappy_name: $name,
            generators: include_str!(concat!("../../assets/spaces/census/", $stem, ".gen")),
            reference: include_str!(concat!("../../assets/spaces/census/", $stem, ".json")),
        }
    };
}

/// The ten smallest closed orientable hyperbolic manifolds of SnapPy's census, by volume.
pub const CENSUS: [CensusManifold; 10] = [
    census!("m003(-3,1)", "m003_-3_1"),
    census!("m003(-2,3)", "m003_-2_3"),
    census!("m007(3,1)", "m007_3_1"),
    census!("m003(-4,3)", "m003_-4_3"),
    census!("m004(6,1)", "m004_6_1"),
    census!("m004(1,2)", "m004_1_2"),
    census!("m009(4,1)", "m009_4_1"),
    census!("m003(-3,4)", "m003_-3_4"),
    census!("m003(-4,1)", "m003_-4_1"),
    census!("m004(3,2)", "m004_3_2"),
];

fn gcd(a: u32, b: u32) -> u32 {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// The matrix of `x -> a·x·b` on quaternions `x = (x, y, z, w) = w + xi + yj + zk`.
#[must_use]
pub fn quaternion_map(a: DQuat, b: DQuat) -> DMat4 {
    let col = |e: DQuat| DVec4::from(a * e * b);
    DMat4::from_cols(
        col(DQuat::from_xyzw(1.0, 0.0, 0.0, 0.0)),
        col(DQuat::from_xyzw(0.0, 1.0, 0.0, 0.0)),
        col(DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0)),
        col(DQuat::IDENTITY),
    )
}

/// A quaternion `(x, y, z, w) = w + xi + yj + zk` in double-double.
type DdQuat = [DoubleDouble; 4];

/// The Hamilton product in double-double.
fn quat_mul(a: DdQuat, b: DdQuat) -> DdQuat {
    let [ax, ay, az, aw] = a;
    let [bx, by, bz, bw] = b;
    [
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ]
}

/// The unit quaternion along `(x, y, z, w)`, in double-double.
fn unit_quat(q: [f64; 4]) -> DdQuat {
    let q = q.map(DoubleDouble::new);
    let len = q.iter().fold(DoubleDouble::ZERO, |s, x| s + *x * *x).sqrt();
    q.map(|x| x / len)
}

/// The matrix of `x -> a·x·b` on quaternions in double-double, each entry rounded once.
fn quaternion_map_dd(a: DdQuat, b: DdQuat) -> DMat4 {
    let (o, z) = (DoubleDouble::ONE, DoubleDouble::ZERO);
    let basis = [[o, z, z, z], [z, o, z, z], [z, z, o, z], [z, z, z, o]];
    DdMat4(basis.map(|e| DdVec4(quat_mul(quat_mul(a, e), b)))).round_f64()
}

const QUAT_ONE: DdQuat = [
    DoubleDouble::new(0.0),
    DoubleDouble::new(0.0),
    DoubleDouble::new(0.0),
    DoubleDouble::new(1.0),
];

/// Left multiplication by the unit quaternion along `w + xi + yj + zk` (normalised and
/// multiplied out in double-double, rounded once).
fn left(x: f64, y: f64, z: f64, w: f64) -> DMat4 {
    quaternion_map_dd(unit_quat([x, y, z, w]), QUAT_ONE)
}

/// Right multiplication by the unit quaternion along `w + xi + yj + zk`.
fn right_dd(q: DdQuat) -> DMat4 {
    quaternion_map_dd(QUAT_ONE, q)
}

/// `cos + i sin` of `π·p/q` as a unit quaternion.
fn turn_quat(p: i64, q: i64) -> DdQuat {
    let (c, s) = DoubleDouble::cos_sin_pi(p, q);
    [s, DoubleDouble::ZERO, DoubleDouble::ZERO, c]
}

fn translation(v: DVec3) -> DMat4 {
    affine(DMat3::IDENTITY, v)
}

fn diag(x: f64, y: f64, z: f64) -> DMat3 {
    DMat3::from_diagonal(DVec3::new(x, y, z))
}

/// A library space from its generators, as [`DirichletOptions`] and a name say.
fn from_group(
    id: &str,
    description: &str,
    matrices: &[DMat4],
    basepoint: Option<DVec3>,
) -> Result<Space, String> {
    let options = DirichletOptions {
        basepoint,
        ..DirichletOptions::default()
    };
    space_from_matrices(id, description, matrices, &options).map_err(|e| format!("{id}: {e}"))
}

/// Parses `prefix-A-B-…` into its numbers (`None` if `id` is not of that form).
fn numbers<T: std::str::FromStr>(id: &str, prefix: &str, count: usize) -> Option<Vec<T>> {
    let rest = id.strip_prefix(prefix)?.strip_prefix('-')?;
    let parts: Vec<&str> = rest.split('-').collect();
    if parts.len() != count {
        return None;
    }
    parts.iter().map(|p| p.parse().ok()).collect()
}

/// A member of a library family by id; `None` when `id` names no family (a family member
/// with bad parameters is `Some(Err)` naming the problem).
#[must_use]
pub fn library_space(id: &str) -> Option<Result<Space, String>> {
    let s3 = 0.5 * 3f64.sqrt();
    let built = match id {
        "binary-tetrahedral" => from_group(
            id,
            "Octahedral space S³/2T: the binary tetrahedral group (order 24), by left \
             multiplication by i and (1 + i + j + k)/2.",
            &[left(1.0, 0.0, 0.0, 0.0), left(0.5, 0.5, 0.5, 0.5)],
            None,
        ),
        "binary-octahedral" => from_group(
            id,
            "Truncated-cube space S³/2O: the binary octahedral group (order 48), by left \
             multiplication by (1 + i)/√2 and (1 + i + j + k)/2.",
            &[left(1.0, 0.0, 0.0, 1.0), left(0.5, 0.5, 0.5, 0.5)],
            None,
        ),
        "binary-icosahedral" => {
            let half = DoubleDouble::new(0.5);
            let phi = half * (DoubleDouble::ONE + DoubleDouble::new(5.0).sqrt());
            let z = DoubleDouble::ZERO;
            from_group(
                id,
                "Poincaré dodecahedral space S³/2I: the binary icosahedral group (order 120), \
                 by right multiplication by (1 + i + j + k)/2 and (φ + i/φ + j)/2 (the \
                 handedness of the seed space poincare).",
                &[
                    right_dd([half; 4]),
                    right_dd([half / phi, half, z, half * phi]),
                ],
                None,
            )
        }
        "mirrored-tetrahedron" => {
            // Reflections in four mutually orthogonal hyperplanes of R⁴, each at distance
            // π/6 from the basepoint (their normals are the rows of a Hadamard matrix / 2).
            let normals = [
                DVec4::new(1.0, 1.0, 1.0, -1.0),
                DVec4::new(1.0, -1.0, -1.0, -1.0),
                DVec4::new(-1.0, 1.0, -1.0, -1.0),
                DVec4::new(-1.0, -1.0, 1.0, -1.0),
            ];
            let gens: Vec<DMat4> = normals
                .iter()
                .map(|&n| Geometry::Spherical.reflection(n / n.length()))
                .collect();
            from_group(
                id,
                "An all-right spherical tetrahedron, one orthant of S³, whose four faces are \
                 mirrors: the group of order 16 generated by four orthogonal reflections.",
                &gens,
                None,
            )
        }
        "torus-hexagonal" => from_group(
            id,
            "3-torus of the hexagonal lattice (unit spacing): a hexagonal prism.",
            &[
                translation(DVec3::X),
                translation(DVec3::new(0.5, s3, 0.0)),
                translation(DVec3::Z),
            ],
            None,
        ),
        "torus-fcc" => from_group(
            id,
            "3-torus of the face-centred cubic lattice: a rhombic dodecahedron.",
            &[
                translation(DVec3::new(1.0, 1.0, 0.0)),
                translation(DVec3::new(0.0, 1.0, 1.0)),
                translation(DVec3::new(1.0, 0.0, 1.0)),
            ],
            None,
        ),
        "torus-bcc" => from_group(
            id,
            "3-torus of the body-centred cubic lattice: a truncated octahedron.",
            &[
                translation(DVec3::new(1.0, 1.0, 1.0)),
                translation(DVec3::new(-1.0, 1.0, 1.0)),
                translation(DVec3::new(1.0, -1.0, 1.0)),
            ],
            None,
        ),
        // Space group Pc: the glide (x, y, z) -> (x, −y, z + ½) over a rectangular lattice.
        "first-amphicosm" => from_group(
            id,
            "First amphicosm (Klein space, space group Pc): the glide reflection \
             (x, y, z) -> (x, −y, z + ½) and the translations along x and y.",
            &flat_base("first-amphicosm").expect("a flat family"),
            None,
        ),
        // Cc: the same glide over the C-centred lattice.
        "second-amphicosm" => from_group(
            id,
            "Second amphicosm (space group Cc): the glide reflection (x, y, z) -> \
             (x, −y, z + ½) and the centred lattice of (1, 0, 0) and (½, ½, 0).",
            &flat_base("second-amphicosm").expect("a flat family"),
            None,
        ),
        // Pca2_1: screw (−x, −y, z + ½), glides (x + ½, −y, z) and (½ − x, y, z + ½).
        "first-amphidicosm" => from_group(
            id,
            "First amphidicosm (space group Pca2_1): the screw (x, y, z) -> (−x, −y, z + ½) \
             and the glide (x, y, z) -> (x + ½, −y, z), with the translation along y.",
            &flat_base("first-amphidicosm").expect("a flat family"),
            None,
        ),
        // Pna2_1: screw (−x, −y, z + ½), glides (x + ½, ½ − y, z) and (½ − x, y + ½, z + ½).
        "second-amphidicosm" => from_group(
            id,
            "Second amphidicosm (space group Pna2_1): the screw (x, y, z) -> (−x, −y, z + ½) \
             and the glide (x, y, z) -> (x + ½, ½ − y, z), with the translation along y.",
            &flat_base("second-amphidicosm").expect("a flat family"),
            None,
        ),
        "seifert-weber-group" => seifert_weber_group(id),
        "three-sphere" => from_group(
            id,
            "The 3-sphere itself: the trivial group; light goes round and comes back.",
            &[],
            None,
        ),
        "projective-space" => from_group(
            id,
            "Projective space RP³ = L(2,1): S³ by the antipodal map −I; a hemisphere whose \
             equator is glued to itself.",
            &[-DMat4::IDENTITY],
            None,
        ),
        "weeks" => census_space(id, 1),
        _ => return family_member(id),
    };
    Some(built)
}

/// The members of the families with parameters.
fn family_member(id: &str) -> Option<Result<Space, String>> {
    if let Some(v) = numbers::<u32>(id, "lens", 2) {
        return Some(lens(id, v[0], v[1]));
    }
    if let Some(v) = numbers::<u32>(id, "prism", 1) {
        return Some(prism(id, v[0]));
    }
    if let Some(v) = numbers::<usize>(id, "census", 1) {
        return Some(census_space(id, v[0]));
    }
    if let Some(v) = numbers::<f64>(id, "torus", 3) {
        return Some(box_torus(id, v[0], v[1], v[2]));
    }
    flat_member(id)
}

/// The generators of a flat manifold's group at unit lattice size: each family's linear
/// parts are diagonal, or rotations about z, so stretching the axes conjugates the group
/// into another of the same kind.
fn flat_base(name: &str) -> Option<Vec<DMat4>> {
    let s3 = 0.5 * 3f64.sqrt();
    // A turn of 1/n about z (its cosine and sine rounded once) and a rise of 1/n.
    let screw = |n: i64| {
        let (c, s) = DoubleDouble::cos_sin_pi(2, n);
        let (c, s) = (c.round_f64(), s.round_f64());
        let rise = DoubleDouble::new(1.0) / DoubleDouble::new(n as f64);
        affine(
            DMat3::from_cols_array(&[c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0]),
            DVec3::Z * rise.round_f64(),
        )
    };
    let square = [translation(DVec3::X), translation(DVec3::Y)];
    let hexagonal = [translation(DVec3::X), translation(DVec3::new(0.5, s3, 0.0))];
    Some(match name {
        "half-turn" => vec![square[0], square[1], screw(2)],
        "quarter-turn" => vec![square[0], square[1], screw(4)],
        "third-turn" => vec![hexagonal[0], hexagonal[1], screw(3)],
        "sixth-turn" => vec![hexagonal[0], hexagonal[1], screw(6)],
        // P2₁2₁2₁: three screws along parallels of the axes that do not meet.
        "hantzsche-wendt" => vec![
            affine(diag(1.0, -1.0, -1.0), DVec3::new(0.5, 0.5, 0.0)),
            affine(diag(-1.0, 1.0, -1.0), DVec3::new(0.0, 0.5, 0.5)),
            affine(diag(-1.0, -1.0, 1.0), DVec3::new(0.5, 0.0, 0.5)),
        ],
        "first-amphicosm" => vec![
            square[0],
            square[1],
            affine(diag(1.0, -1.0, 1.0), DVec3::Z * 0.5),
        ],
        "second-amphicosm" => vec![
            square[0],
            translation(DVec3::new(0.5, 0.5, 0.0)),
            affine(diag(1.0, -1.0, 1.0), DVec3::Z * 0.5),
        ],
        "first-amphidicosm" => vec![
            affine(diag(-1.0, -1.0, 1.0), DVec3::Z * 0.5),
            affine(diag(1.0, -1.0, 1.0), DVec3::X * 0.5),
            square[1],
        ],
        "second-amphidicosm" => vec![
            affine(diag(-1.0, -1.0, 1.0), DVec3::Z * 0.5),
            affine(diag(1.0, -1.0, 1.0), DVec3::new(0.5, 0.5, 0.0)),
            square[1],
        ],
        _ => return None,
    })
}

/// A flat manifold with a stretched lattice: `NAME-A-B-C` (axes stretched by A, B, C) or,
/// for the screws of order 3, 4 and 6 about z, `NAME-A-C` (the plane lattice by A, the
/// height by C).
fn flat_member(id: &str) -> Option<Result<Space, String>> {
    for name in [
        "half-turn",
        "hantzsche-wendt",
        "first-amphicosm",
        "second-amphicosm",
        "first-amphidicosm",
        "second-amphidicosm",
        "quarter-turn",
        "third-turn",
        "sixth-turn",
    ] {
        let planar = matches!(name, "quarter-turn" | "third-turn" | "sixth-turn");
        let sides = if planar {
            numbers::<f64>(id, name, 2).map(|v| [v[0], v[0], v[1]])
        } else {
            numbers::<f64>(id, name, 3).map(|v| [v[0], v[1], v[2]])
        };
        let Some([a, b, c]) = sides else {
            continue;
        };
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        if !(lo > 0.0 && hi.is_finite() && hi <= 1000.0 * lo) {
            let form = if planar { "A-C" } else { "A-B-C" };
            return Some(Err(format!(
                "{id}: {name}-{form} needs positive finite sizes at most 1000 to 1"
            )));
        }
        // S g S⁻¹ in double-double, rounded once.
        let diag_dd = |d: [f64; 3]| {
            let mut m = DdMat4::IDENTITY;
            for (i, x) in d.iter().enumerate() {
                m.0[i].0[i] = DoubleDouble::new(*x);
            }
            m
        };
        let stretch = diag_dd([a, b, c]);
        let one = DoubleDouble::ONE;
        let mut squeeze = DdMat4::IDENTITY;
        for (i, x) in [a, b, c].iter().enumerate() {
            squeeze.0[i].0[i] = one / DoubleDouble::new(*x);
        }
        let gens: Vec<DMat4> = flat_base(name)?
            .into_iter()
            .map(|g| (stretch * DdMat4::from_f64(g) * squeeze).round_f64())
            .collect();
        return Some(from_group(
            id,
            &format!("The {name} flat manifold, its lattice stretched to {a}×{b}×{c}."),
            &gens,
            None,
        ));
    }
    None
}

fn lens(id: &str, p: u32, q: u32) -> Result<Space, String> {
    if !((2..=MAX_LENS_ORDER).contains(&p) && (1..p).contains(&q)) || p == 2 {
        return Err(format!(
            "{id}: a lens space lens-P-Q needs 1 ≤ Q < P ≤ {MAX_LENS_ORDER}, P ≥ 3 \
             (L(2,1) is projective-space)"
        ));
    }
    if gcd(p, q) != 1 {
        return Err(format!(
            "{id}: P = {p} and Q = {q} have the common factor {}, so the group does not act \
             freely; choose coprime P and Q",
            gcd(p, q)
        ));
    }
    // (z1, z2) -> (ζ z1, ζ^q z2) for x = z1 + z2 j is x -> e^{iα} x e^{iβ} with α + β = 2π/p,
    // α − β = 2πq/p.
    let g = quaternion_map_dd(
        turn_quat(i64::from(1 + q), i64::from(p)),
        turn_quat(1 - i64::from(q), i64::from(p)),
    );
    // The basepoint with |z1| = |z2|: there the orbit is spread over both circles.
    from_group(
        id,
        &format!(
            "Lens space L({p},{q}): S³ by the cyclic group of order {p} generated by (z1, z2) -> (ζz1, ζ^{q}z2), ζ = e^(2πi/{p})."
        ),
        &[g],
        Some(DVec3::new(0.0, 1.0, 0.0)),
    )
}

fn prism(id: &str, n: u32) -> Result<Space, String> {
    if !(2..=MAX_PRISM).contains(&n) {
        return Err(format!(
            "{id}: a prism space prism-N needs 2 ≤ N ≤ {MAX_PRISM}"
        ));
    }
    from_group(
        id,
        &format!(
            "Prism space S³/D*{}: the binary dihedral group of order {}, by left \
             multiplication by e^(iπ/{n}) and j.",
            4 * n,
            4 * n
        ),
        &[
            quaternion_map_dd(turn_quat(1, i64::from(n)), QUAT_ONE),
            left(0.0, 1.0, 0.0, 0.0),
        ],
        None,
    )
}

fn box_torus(id: &str, a: f64, b: f64, c: f64) -> Result<Space, String> {
    let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
    if !(lo > 0.0 && hi.is_finite() && hi <= 1000.0 * lo) {
        return Err(format!(
            "{id}: a box torus torus-A-B-C needs positive finite sides at most 1000 to 1"
        ));
    }
    from_group(
        id,
        &format!("3-torus of the {a}×{b}×{c} box lattice."),
        &[
            translation(DVec3::X * a),
            translation(DVec3::Y * b),
            translation(DVec3::Z * c),
        ],
        None,
    )
}

fn census_space(id: &str, n: usize) -> Result<Space, String> {
    let Some(m) = n.checked_sub(1).and_then(|i| CENSUS.get(i)) else {
        return Err(format!(
            "{id}: the library ships census-1 to census-{}; export others with \
             scripts/snappy-export.py",
            CENSUS.len()
        ));
    };
    let file = parse_gen(m.generators).map_err(|e| format!("{id}: {e}"))?;
    from_group(
        id,
        &format!(
            "{}: closed orientable hyperbolic manifold no. {n} of SnapPy's census, from the \
             face pairings of its Dirichlet domain.",
            m.snappy_name
        ),
        &file.matrices,
        None,
    )
}

/// Seifert–Weber space from its definition: the six pairings of opposite faces of the
/// regular dodecahedron with dihedral angle 2π/5, each a translation through the face by
/// twice the inradius after a 3π/5 turn about the face's axis (clockwise seen from outside
/// the face, so that its inverse, the face pairing, turns counter-clockwise as the seed's
/// does).
fn seifert_weber_group(id: &str) -> Result<Space, String> {
    let g = Geometry::Hyperbolic;
    let cos_dihedral = DoubleDouble::cos_sin_pi(2, 5).0;
    let r = dodecahedron_offset_exact(g, cos_dihedral);
    let (c, s) = DoubleDouble::cos_sin_pi(-3, 5);
    let gens: Vec<DMat4> = dodecahedron_normals_exact()[..6]
        .iter()
        .map(|&n| {
            (exact::double_inradius_translation(g, n, r) * exact::rotation(n, c, s)).round_f64()
        })
        .collect();
    from_group(
        id,
        "Seifert–Weber space from its six generators: translation across opposite faces of \
         the 72° hyperbolic dodecahedron with a 3π/5 twist.",
        &gens,
        None,
    )
}
