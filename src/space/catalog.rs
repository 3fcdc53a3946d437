//! The seed spaces, each built in code from its definition and validated.
//!
//! Each is built in double-double from its closed form and rounded once
//! ([`super::exact`]): the `f64` numbers of a seed space are the correctly rounded values of
//! the exact ones.
//!
//! Twists are right-handed: a face's pairing rotates by the twist angle about the face's
//! outward normal (counter-clockwise seen from outside the face), after translating the
//! face onto its partner. The other sense gives the mirror-image space.

use super::exact::{self, Dd3, ExactCell, ExactFace, dd3, identity3, scaled, unit};
use super::{Space, SpaceError};
use crate::geometry::{DdMat4, DoubleDouble, Geometry, Real};
use glam::{DMat3, DMat4, DVec3};

/// The seed space shown when nothing else is chosen.
pub const DEFAULT_SPACE: &str = "seifert-weber";

/// A named space of the catalog.
#[derive(Clone, Copy, Debug)]
pub struct SeedSpace {
    /// The CLI id.
    pub id: &'static str,
    /// One line about it.
    pub summary: &'static str,
    build: fn() -> Result<Space, SpaceError>,
}

impl SeedSpace {
    /// Builds and validates the space.
    pub fn build(&self) -> Result<Space, SpaceError> {
        (self.build)()
    }
}

/// Every seed space, in the order `curved-spaces list` shows them.
pub const SEED_SPACES: &[SeedSpace] = &[
    SeedSpace {
        id: "torus",
        summary: "3-torus: a unit cube with opposite faces glued by translations",
        build: torus,
    },
    SeedSpace {
        id: "torus-two-cells",
        summary: "3-torus again, cut into two half-cubes: a space of two cells",
        build: torus_two_cells,
    },
    SeedSpace {
        id: "half-turn",
        summary: "flat manifold: cube, the z faces glued with a half turn",
        build: || turned_cube("half-turn", 2),
    },
    SeedSpace {
        id: "quarter-turn",
        summary: "flat manifold: cube, the z faces glued with a quarter turn",
        build: || turned_cube("quarter-turn", 4),
    },
    SeedSpace {
        id: "third-turn",
        summary: "flat manifold: hexagonal prism, the z faces glued with a third turn",
        build: || turned_prism("third-turn", 3),
    },
    SeedSpace {
        id: "sixth-turn",
        summary: "flat manifold: hexagonal prism, the z faces glued with a sixth turn",
        build: || turned_prism("sixth-turn", 6),
    },
    SeedSpace {
        id: "hantzsche-wendt",
        summary: "flat manifold with holonomy Z2×Z2: a rhombic dodecahedron (Dirichlet domain)",
        build: hantzsche_wendt,
    },
    SeedSpace {
        id: "mirrored-cube",
        summary: "flat orbifold: a cube whose six faces are mirrors",
        build: mirrored_cube,
    },
    SeedSpace {
        id: "seifert-weber",
        summary: "hyperbolic manifold: 72° dodecahedron, opposite faces glued with a 3π/5 twist",
        build: seifert_weber,
    },
    SeedSpace {
        id: "mirrored-dodecahedron",
        summary: "hyperbolic orbifold: right-angled dodecahedron whose faces are mirrors",
        build: mirrored_dodecahedron,
    },
    SeedSpace {
        id: "poincare",
        summary: "spherical manifold: 120° dodecahedron, opposite faces glued with a π/5 twist",
        build: poincare,
    },
];

/// Builds a seed space by its id.
pub fn seed_space(id: &str) -> Result<Space, SpaceError> {
    SEED_SPACES
        .iter()
        .find(|s| s.id == id)
        .ok_or_else(|| SpaceError::UnknownSpace(id.to_string()))?
        .build()
}

/// `x ↦ A x + b` as a 4×4 matrix of the Euclidean model.
#[must_use]
pub fn affine(a: DMat3, b: DVec3) -> DMat4 {
    let mut m = DMat4::from_mat3(a);
    m.w_axis = b.extend(1.0);
    m
}

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::new(x)
}

/// Faces `n·x ≤ ½` for the given unit normals, each glued to the face with the opposite
/// normal by the unit translation along `−n` (so a ray leaving through `+x` comes back at
/// `−x`).
fn translated_faces(normals: &[Dd3]) -> Vec<ExactFace> {
    let round = |n: &Dd3| DVec3::from_array(n.map(DoubleDouble::round_f64));
    normals
        .iter()
        .map(|n| {
            let partner = normals
                .iter()
                .position(|m| (round(m) + round(n)).length() < 1e-12)
                .unwrap_or(usize::MAX);
            ExactFace {
                normal: *n,
                offset: dd(0.5),
                partner,
                pairing: exact::affine(identity3(), n.map(|x| -x)),
            }
        })
        .collect()
}

/// Outward normals of the cube's faces, in the order +x, −x, +y, −y, +z, −z.
pub const CUBE_NORMALS: [DVec3; 6] = [
    DVec3::X,
    DVec3::NEG_X,
    DVec3::Y,
    DVec3::NEG_Y,
    DVec3::Z,
    DVec3::NEG_Z,
];

fn euclidean(faces: Vec<ExactFace>) -> ExactCell {
    ExactCell {
        geometry: Geometry::Euclidean,
        faces,
    }
}

fn torus() -> Result<Space, SpaceError> {
    Space::from_exact(
        "torus",
        "The 3-torus E³/Z³: a unit cube whose opposite faces are glued by translations.",
        euclidean(translated_faces(&CUBE_NORMALS.map(dd3))),
    )
}

/// The 3-torus of [`torus`] cut by the plane `x = 0` into two half-cubes, each a cell: the
/// cut is a seam (the halves glued by the identity), the other faces glued as the cube's.
/// Everything the space is (volume, homology, closed geodesics, its pictures) is the
/// torus's; only the walk crosses the seam as well.
fn torus_two_cells() -> Result<Space, SpaceError> {
    use super::FaceSpec;
    let shift = |v: DVec3| DMat4::from_translation(v);
    // Faces of the cell at x ≤ 0 (0..6) then of the cell at x ≥ 0 (6..12): +x, −x, +y,
    // −y, +z, −z in each.
    let half = |sign: f64, first: usize, other: usize| {
        vec![
            if sign < 0.0 {
                FaceSpec::paired(DVec3::X, 0.0, other + 1, DMat4::IDENTITY)
            } else {
                FaceSpec::paired(DVec3::X, 0.5, other + 1, shift(DVec3::NEG_X))
            },
            if sign < 0.0 {
                FaceSpec::paired(DVec3::NEG_X, 0.5, other, shift(DVec3::X))
            } else {
                FaceSpec::paired(DVec3::NEG_X, 0.0, other, DMat4::IDENTITY)
            },
            FaceSpec::paired(DVec3::Y, 0.5, first + 3, shift(DVec3::NEG_Y)),
            FaceSpec::paired(DVec3::NEG_Y, 0.5, first + 2, shift(DVec3::Y)),
            FaceSpec::paired(DVec3::Z, 0.5, first + 5, shift(DVec3::NEG_Z)),
            FaceSpec::paired(DVec3::NEG_Z, 0.5, first + 4, shift(DVec3::Z)),
        ]
    };
    Space::new_cells(
        "torus-two-cells",
        "The 3-torus E³/Z³ as two cells: a unit cube cut into two half-cubes at x = 0, glued \
         to each other across the cut (a seam) and across the x faces, each to itself across \
         the y and z faces.",
        Geometry::Euclidean,
        &[half(-1.0, 0, 6), half(1.0, 6, 0)],
    )
}

/// Glues the face at `z = −½` onto `z = +½` by a rotation of `2π/turns` about the z axis
/// followed by the unit translation in z; the face at `z = +½` gets the inverse.
fn screw_z(faces: &mut [ExactFace], top: usize, bottom: usize, turns: u32) {
    let (c, s) = DoubleDouble::cos_sin_pi(2, i64::from(turns));
    let z = DoubleDouble::ZERO;
    let o = DoubleDouble::ONE;
    let up = exact::affine([[c, -s, z], [s, c, z], [z, z, o]], [z, z, o]);
    faces[bottom].partner = top;
    faces[bottom].pairing = up;
    faces[top].partner = bottom;
    faces[top].pairing = exact::inverse(Geometry::Euclidean, &up);
}

fn turned_cube(name: &str, turns: u32) -> Result<Space, SpaceError> {
    let mut faces = translated_faces(&CUBE_NORMALS.map(dd3));
    screw_z(&mut faces, 4, 5, turns);
    Space::from_exact(
        name,
        format!(
            "A unit cube: x and y faces glued by translations, the z faces by a 1/{turns} turn \
             about the z axis and a unit translation."
        ),
        euclidean(faces),
    )
}

fn turned_prism(name: &str, turns: u32) -> Result<Space, SpaceError> {
    let mut normals: Vec<Dd3> = (0..6)
        .map(|k| {
            let (c, s) = DoubleDouble::cos_sin_pi(k, 3);
            [c, s, DoubleDouble::ZERO]
        })
        .collect();
    normals.extend([DVec3::Z, DVec3::NEG_Z].map(dd3));
    let mut faces = translated_faces(&normals);
    screw_z(&mut faces, 6, 7, turns);
    Space::from_exact(
        name,
        format!(
            "A hexagonal prism: opposite sides glued by unit translations, the z faces by a \
             1/{turns} turn about the z axis and a unit translation."
        ),
        euclidean(faces),
    )
}

fn hantzsche_wendt() -> Result<Space, SpaceError> {
    let e = Geometry::Euclidean;
    // Every entry of the group's matrices is a small integer: exact in f64, so the word
    // search runs in f64; only the normals and offsets (1/√2) need double-double.
    let generators = [
        affine(
            DMat3::from_diagonal(DVec3::new(1.0, -1.0, -1.0)),
            DVec3::new(1.0, 1.0, 0.0),
        ),
        affine(
            DMat3::from_diagonal(DVec3::new(-1.0, 1.0, -1.0)),
            DVec3::new(0.0, 1.0, 1.0),
        ),
        affine(
            DMat3::from_diagonal(DVec3::new(-1.0, -1.0, 1.0)),
            DVec3::new(1.0, 0.0, 1.0),
        ),
    ];
    let mut letters: Vec<DMat4> = generators.to_vec();
    letters.extend(generators.iter().map(|&g| e.inverse(g)));
    // Words of length ≤ 3 reach every element moving the origin to a nearest neighbour.
    let mut words = vec![DMat4::IDENTITY];
    let mut frontier = vec![DMat4::IDENTITY];
    for _ in 0..3 {
        frontier = frontier
            .iter()
            .flat_map(|w| letters.iter().map(move |l| *w * *l))
            .collect();
        words.extend(&frontier);
    }
    // The twelve directions (±1, ±1, 0) and their permutations (integer vectors).
    let mut directions = Vec::new();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        for (si, sj) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let mut n = DVec3::ZERO;
            n[i] = si;
            n[j] = sj;
            directions.push(n);
        }
    }
    let half_root2 = dd(0.5).sqrt();
    let faces: Vec<ExactFace> = directions
        .iter()
        .map(|&d| {
            // The neighbour cell across this face is h(D) with h(0) = d.
            let (partner, pairing) = words
                .iter()
                .find(|h| (h.w_axis.truncate() - d).length() < 1e-12)
                .map(|h| {
                    let g = e.inverse(*h);
                    let back = g.w_axis.truncate();
                    let partner = directions
                        .iter()
                        .position(|m| (*m - back).length() < 1e-12)
                        .unwrap_or(usize::MAX);
                    (partner, DdMat4::from_f64(g))
                })
                .unwrap_or((usize::MAX, DdMat4::IDENTITY));
            ExactFace {
                normal: scaled(dd3(d), half_root2),
                offset: half_root2,
                partner,
                pairing,
            }
        })
        .collect();
    Space::from_exact(
        "hantzsche-wendt",
        "The Hantzsche–Wendt manifold, generated by α(x,y,z) = (x+1, 1−y, −z), \
         β(x,y,z) = (−x, y+1, 1−z), γ(x,y,z) = (1−x, −y, z+1); the cell is its Dirichlet \
         domain about the origin, a rhombic dodecahedron.",
        euclidean(faces),
    )
}

/// Mirrors at chart distance `offset` with the given unit normals.
fn mirror_faces(geometry: Geometry, normals: &[Dd3], offset: DoubleDouble) -> Vec<ExactFace> {
    normals
        .iter()
        .enumerate()
        .map(|(i, &normal)| {
            let face = ExactFace {
                normal,
                offset,
                partner: i,
                pairing: DdMat4::IDENTITY,
            };
            ExactFace {
                pairing: exact::reflection(geometry, face.covector()),
                ..face
            }
        })
        .collect()
}

fn mirrored_cube() -> Result<Space, SpaceError> {
    Space::from_exact(
        "mirrored-cube",
        "A unit cube whose six faces are mirrors: a flat orbifold (a room of mirrors).",
        euclidean(mirror_faces(
            Geometry::Euclidean,
            &CUBE_NORMALS.map(dd3),
            dd(0.5),
        )),
    )
}

/// The twelve outward unit face normals of the regular dodecahedron in double-double,
/// `n(f+6) = −n(f)`: `(0, ±1, ±φ)` and its cyclic permutations over `√(1 + φ²)`.
#[must_use]
pub fn dodecahedron_normals_exact() -> [Dd3; 12] {
    let phi = (dd(1.0) + dd(5.0).sqrt()) / dd(2.0);
    let (o, z) = (DoubleDouble::ONE, DoubleDouble::ZERO);
    let half = [
        [z, o, phi],
        [z, -o, phi],
        [o, phi, z],
        [-o, phi, z],
        [phi, z, o],
        [phi, z, -o],
    ];
    std::array::from_fn(|f| {
        let n = unit(half[f % 6]);
        if f < 6 { n } else { n.map(|x| -x) }
    })
}

/// The twelve outward face normals of the regular dodecahedron, `n(f+6) = −n(f)`
/// (each component correctly rounded).
#[must_use]
pub fn dodecahedron_normals() -> [DVec3; 12] {
    dodecahedron_normals_exact().map(|n| DVec3::from_array(n.map(DoubleDouble::round_f64)))
}

/// Chart distance of the faces of a regular dodecahedron whose dihedral angle has cosine
/// `cos_dihedral`, in double-double (see [`dodecahedron_offset`]).
#[must_use]
pub fn dodecahedron_offset_exact(geometry: Geometry, cos_dihedral: DoubleDouble) -> DoubleDouble {
    let c = DoubleDouble::ONE / dd(5.0).sqrt();
    let k = dd(geometry.kappa());
    (-(c + cos_dihedral) / (k * (DoubleDouble::ONE + cos_dihedral))).sqrt()
}

/// Chart distance of the faces of a regular dodecahedron with the given dihedral angle.
///
/// Adjacent faces have `n·m = c = 1/√5`; the dihedral angle satisfies
/// `cos α = −(c + κ r²)/(1 + κ r²)` (see [`super::dihedral_angle`]), so
/// `r² = −(c + cos α) / (κ (1 + cos α))`.
#[must_use]
pub fn dodecahedron_offset(geometry: Geometry, dihedral: f64) -> f64 {
    let (_, cos) = dd(dihedral).sin_cos();
    dodecahedron_offset_exact(geometry, cos).round_f64()
}

/// A regular dodecahedron (dihedral angle with cosine `cos_dihedral`) whose opposite faces
/// are glued by the translation along the line through the two face centres composed with
/// a right-handed twist of cosine and sine `twist`, in double-double.
fn twisted_dodecahedron_exact(
    geometry: Geometry,
    cos_dihedral: DoubleDouble,
    twist: (DoubleDouble, DoubleDouble),
) -> ExactCell {
    let r = dodecahedron_offset_exact(geometry, cos_dihedral);
    let normals = dodecahedron_normals_exact();
    let faces = normals
        .iter()
        .enumerate()
        .map(|(f, &n)| {
            let back = n.map(|x| -x);
            ExactFace {
                normal: n,
                offset: r,
                partner: (f + 6) % 12,
                pairing: exact::rotation(n, twist.0, twist.1)
                    * exact::double_inradius_translation(geometry, back, r),
            }
        })
        .collect();
    ExactCell { geometry, faces }
}

/// A regular dodecahedron with opposite faces glued by the translation along the line through
/// the two face centres composed with a right-handed `twist` about it (built in
/// double-double from the two angles as given, and rounded once).
pub fn twisted_dodecahedron(
    name: &str,
    description: &str,
    geometry: Geometry,
    dihedral: f64,
    twist: f64,
) -> Result<Space, SpaceError> {
    let (_, cos_dihedral) = dd(dihedral).sin_cos();
    let (s, c) = dd(twist).sin_cos();
    Space::from_exact(
        name,
        description,
        twisted_dodecahedron_exact(geometry, cos_dihedral, (c, s)),
    )
}

fn seifert_weber() -> Result<Space, SpaceError> {
    Space::from_exact(
        "seifert-weber",
        "The Seifert–Weber dodecahedral space: a hyperbolic regular dodecahedron with dihedral \
         angle 72°, each face glued to the opposite one with a right-handed 3π/5 twist.",
        twisted_dodecahedron_exact(
            Geometry::Hyperbolic,
            DoubleDouble::cos_sin_pi(2, 5).0,
            DoubleDouble::cos_sin_pi(3, 5),
        ),
    )
}

fn poincare() -> Result<Space, SpaceError> {
    Space::from_exact(
        "poincare",
        "The Poincaré dodecahedral space S³/2I: a spherical regular dodecahedron with dihedral \
         angle 120°, each face glued to the opposite one with a right-handed π/5 twist.",
        twisted_dodecahedron_exact(
            Geometry::Spherical,
            DoubleDouble::cos_sin_pi(2, 3).0,
            DoubleDouble::cos_sin_pi(1, 5),
        ),
    )
}

fn mirrored_dodecahedron() -> Result<Space, SpaceError> {
    let g = Geometry::Hyperbolic;
    let right_angle = DoubleDouble::cos_sin_pi(1, 2).0;
    Space::from_exact(
        "mirrored-dodecahedron",
        "A hyperbolic right-angled regular dodecahedron whose twelve faces are mirrors.",
        ExactCell {
            geometry: g,
            faces: mirror_faces(
                g,
                &dodecahedron_normals_exact(),
                dodecahedron_offset_exact(g, right_angle),
            ),
        },
    )
}
