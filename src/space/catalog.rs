//! The seed spaces, each built in code from its definition and validated.
//!
//! Twists are right-handed: a face's pairing rotates by the twist angle about the face's
//! outward normal (counter-clockwise seen from outside the face), after translating the
//! face onto its partner. The other sense gives the mirror-image space.

use super::{FaceSpec, Pairing, Space, SpaceError};
use crate::geometry::Geometry;
use glam::{DMat3, DMat4, DVec3};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

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

/// Faces `n·x ≤ ½` for the given normals, each glued to the face with the opposite normal
/// by the unit translation along `−n` (so a ray leaving through `+x` comes back at `−x`).
fn translated_faces(normals: &[DVec3]) -> Vec<FaceSpec> {
    normals
        .iter()
        .map(|&n| {
            let partner = normals
                .iter()
                .position(|&m| (m + n).length() < 1e-12)
                .unwrap_or(usize::MAX);
            FaceSpec::paired(n, 0.5, partner, affine(DMat3::IDENTITY, -n))
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

fn torus() -> Result<Space, SpaceError> {
    Space::new(
        "torus",
        "The 3-torus E³/Z³: a unit cube whose opposite faces are glued by translations.",
        Geometry::Euclidean,
        &translated_faces(&CUBE_NORMALS),
    )
}

/// Glues the face at `z = −½` onto `z = +½` by a rotation of `2π/turns` about the z axis
/// followed by the unit translation in z; the face at `z = +½` gets the inverse.
fn screw_z(faces: &mut [FaceSpec], top: usize, bottom: usize, turns: u32) {
    let up = affine(DMat3::from_rotation_z(2.0 * PI / turns as f64), DVec3::Z);
    faces[bottom].pairing = Some(Pairing {
        partner: top,
        matrix: up,
    });
    faces[top].pairing = Some(Pairing {
        partner: bottom,
        matrix: Geometry::Euclidean.inverse(up),
    });
}

fn turned_cube(name: &str, turns: u32) -> Result<Space, SpaceError> {
    let mut faces = translated_faces(&CUBE_NORMALS);
    screw_z(&mut faces, 4, 5, turns);
    Space::new(
        name,
        format!(
            "A unit cube: x and y faces glued by translations, the z faces by a 1/{turns} turn \
             about the z axis and a unit translation."
        ),
        Geometry::Euclidean,
        &faces,
    )
}

fn turned_prism(name: &str, turns: u32) -> Result<Space, SpaceError> {
    let mut normals: Vec<DVec3> = (0..6)
        .map(|k| {
            let a = k as f64 * PI / 3.0;
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    normals.extend([DVec3::Z, DVec3::NEG_Z]);
    let mut faces = translated_faces(&normals);
    screw_z(&mut faces, 6, 7, turns);
    Space::new(
        name,
        format!(
            "A hexagonal prism: opposite sides glued by unit translations, the z faces by a \
             1/{turns} turn about the z axis and a unit translation."
        ),
        Geometry::Euclidean,
        &faces,
    )
}

fn hantzsche_wendt() -> Result<Space, SpaceError> {
    let e = Geometry::Euclidean;
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
    let mut normals = Vec::new();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        for (si, sj) in [(1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            let mut n = DVec3::ZERO;
            n[i] = si;
            n[j] = sj;
            normals.push(n * FRAC_1_SQRT_2);
        }
    }
    let faces: Vec<FaceSpec> = normals
        .iter()
        .map(|&n| {
            // The neighbour cell across this face is h(D) with h(0) = 2·(1/√2)·n.
            let across = n * 2.0 * FRAC_1_SQRT_2;
            let pairing = words
                .iter()
                .find(|h| (h.w_axis.truncate() - across).length() < 1e-12)
                .map(|h| {
                    let g = e.inverse(*h);
                    let back = g.w_axis.truncate();
                    let partner = normals
                        .iter()
                        .position(|m| (*m * 2.0 * FRAC_1_SQRT_2 - back).length() < 1e-12)
                        .unwrap_or(usize::MAX);
                    Pairing { partner, matrix: g }
                });
            FaceSpec {
                normal: n,
                offset: FRAC_1_SQRT_2,
                pairing,
            }
        })
        .collect();
    Space::new(
        "hantzsche-wendt",
        "The Hantzsche–Wendt manifold, generated by α(x,y,z) = (x+1, 1−y, −z), \
         β(x,y,z) = (−x, y+1, 1−z), γ(x,y,z) = (1−x, −y, z+1); the cell is its Dirichlet \
         domain about the origin, a rhombic dodecahedron.",
        e,
        &faces,
    )
}

fn mirror_faces(geometry: Geometry, normals: &[DVec3], offset: f64) -> Vec<FaceSpec> {
    normals
        .iter()
        .enumerate()
        .map(|(i, &n)| FaceSpec::paired(n, offset, i, geometry.reflection(n.extend(-offset))))
        .collect()
}

fn mirrored_cube() -> Result<Space, SpaceError> {
    Space::new(
        "mirrored-cube",
        "A unit cube whose six faces are mirrors: a flat orbifold (a room of mirrors).",
        Geometry::Euclidean,
        &mirror_faces(Geometry::Euclidean, &CUBE_NORMALS, 0.5),
    )
}

/// The twelve outward face normals of the regular dodecahedron, `n(f+6) = −n(f)`.
#[must_use]
pub fn dodecahedron_normals() -> [DVec3; 12] {
    let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let half = [
        DVec3::new(0.0, 1.0, phi),
        DVec3::new(0.0, -1.0, phi),
        DVec3::new(1.0, phi, 0.0),
        DVec3::new(-1.0, phi, 0.0),
        DVec3::new(phi, 0.0, 1.0),
        DVec3::new(phi, 0.0, -1.0),
    ];
    let s = (1.0 + phi * phi).sqrt();
    std::array::from_fn(|f| if f < 6 { half[f] / s } else { -half[f - 6] / s })
}

/// Chart distance of the faces of a regular dodecahedron with the given dihedral angle.
///
/// Adjacent faces have `n·m = c = 1/√5`; the dihedral angle satisfies
/// `cos α = −(c + κ r²)/(1 + κ r²)` (see [`super::dihedral_angle`]), so
/// `r² = −(c + cos α) / (κ (1 + cos α))`.
#[must_use]
pub fn dodecahedron_offset(geometry: Geometry, dihedral: f64) -> f64 {
    let c = 1.0 / 5.0_f64.sqrt();
    let k = geometry.kappa();
    (-(c + dihedral.cos()) / (k * (1.0 + dihedral.cos()))).sqrt()
}

/// A regular dodecahedron with opposite faces glued by the translation along the line through
/// the two face centres composed with a right-handed `twist` about it.
pub fn twisted_dodecahedron(
    name: &str,
    description: &str,
    geometry: Geometry,
    dihedral: f64,
    twist: f64,
) -> Result<Space, SpaceError> {
    let r = dodecahedron_offset(geometry, dihedral);
    let normals = dodecahedron_normals();
    let centre = geometry.project_point((normals[0] * r).extend(1.0));
    let inradius = geometry.distance(crate::geometry::ORIGIN, centre);
    let faces: Vec<FaceSpec> = normals
        .iter()
        .enumerate()
        .map(|(f, &n)| {
            let g = geometry.rotation(n, twist) * geometry.translation(-n, 2.0 * inradius);
            FaceSpec::paired(n, r, (f + 6) % 12, g)
        })
        .collect();
    Space::new(name, description, geometry, &faces)
}

fn seifert_weber() -> Result<Space, SpaceError> {
    twisted_dodecahedron(
        "seifert-weber",
        "The Seifert–Weber dodecahedral space: a hyperbolic regular dodecahedron with dihedral \
         angle 72°, each face glued to the opposite one with a right-handed 3π/5 twist.",
        Geometry::Hyperbolic,
        2.0 * PI / 5.0,
        3.0 * PI / 5.0,
    )
}

fn poincare() -> Result<Space, SpaceError> {
    twisted_dodecahedron(
        "poincare",
        "The Poincaré dodecahedral space S³/2I: a spherical regular dodecahedron with dihedral \
         angle 120°, each face glued to the opposite one with a right-handed π/5 twist.",
        Geometry::Spherical,
        2.0 * PI / 3.0,
        PI / 5.0,
    )
}

fn mirrored_dodecahedron() -> Result<Space, SpaceError> {
    let g = Geometry::Hyperbolic;
    Space::new(
        "mirrored-dodecahedron",
        "A hyperbolic right-angled regular dodecahedron whose twelve faces are mirrors.",
        g,
        &mirror_faces(g, &dodecahedron_normals(), dodecahedron_offset(g, PI / 2.0)),
    )
}
