//! Cells from closed forms, in double-double, rounded once (`docs/design.md` §2).
//!
//! A cell the crate builds from its definition (the seed spaces; the Dirichlet domains of
//! groups, from the generators' digits) is first built here, in
//! double-double ([`DoubleDouble`], about 32 digits): unit face normals and offsets from
//! square roots of the closed forms, pairings composed from rotations and translations
//! whose cosines and sines are computed to 32 digits (exactly at the multiples of π/2 and
//! π/6). Every number the walkers and the GPU use is then this value **rounded once**: the
//! `f64` faces, pairings and vertices of the [`Space`], and the `f32` copies with their low
//! parts ([`super::CellWalker`] rounds from the same cell). Composing the pairing in `f64`
//! instead rounds at every step and leaves entries several units in the last place off.
//!
//! The double-double cell is kept with the space ([`Space::exact`]): it is what the
//! accuracy reference walks ([`super::accuracy`]), so the reference never takes the `f64`
//! cell's own rounding for the truth.

use super::{FaceSpec, Space, SpaceError};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Real, Vector4};
use glam::{DMat3, DVec3};
use std::sync::Arc;

/// A double-double 3-vector.
pub type Dd3 = [DoubleDouble; 3];

/// A face of a cell in double-double: the half-space `normal · x ≤ offset` of the chart
/// (unit normal) and its pairing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExactFace {
    /// Outward unit normal in the chart.
    pub normal: Dd3,
    /// Chart distance of the face plane from the origin.
    pub offset: DoubleDouble,
    /// The partner face (itself for a mirror).
    pub partner: usize,
    /// The pairing: the isometry applied to a ray that leaves through this face.
    pub pairing: DdMat4,
}

impl ExactFace {
    /// The covector `N = (n, −r)`: `N·X = 0` on the face, `< 0` inside the cell.
    #[must_use]
    pub fn covector(&self) -> DdVec4 {
        DdVec4([self.normal[0], self.normal[1], self.normal[2], -self.offset])
    }
}

/// A cell in double-double, as its closed form gives it.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactCell {
    /// Its geometry.
    pub geometry: Geometry,
    /// Its faces.
    pub faces: Vec<ExactFace>,
}

fn dd(x: f64) -> DoubleDouble {
    DoubleDouble::new(x)
}

/// A vector of `f64`s, exactly.
#[must_use]
pub fn dd3(v: DVec3) -> Dd3 {
    v.to_array().map(dd)
}

/// `v / |v|`.
#[must_use]
pub fn unit(v: Dd3) -> Dd3 {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / len)
}

/// `s · v`.
#[must_use]
pub fn scaled(v: Dd3, s: DoubleDouble) -> Dd3 {
    v.map(|x| x * s)
}

fn cross(a: Dd3, b: Dd3) -> Dd3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot3(a: Dd3, b: Dd3) -> DoubleDouble {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `x ↦ A x + b` in the Euclidean model (`a` by rows).
#[must_use]
pub fn affine(a: [Dd3; 3], b: Dd3) -> DdMat4 {
    let z = DoubleDouble::ZERO;
    DdMat4(std::array::from_fn(|j| {
        if j == 3 {
            DdVec4([b[0], b[1], b[2], DoubleDouble::ONE])
        } else {
            DdVec4([a[0][j], a[1][j], a[2][j], z])
        }
    }))
}

/// The rotation with cosine `c` and sine `s` about the geodesic through the origin with
/// unit chart direction `axis` (right-hand rule; every geometry).
#[must_use]
pub fn rotation(axis: Dd3, c: DoubleDouble, s: DoubleDouble) -> DdMat4 {
    let one_c = DoubleDouble::ONE - c;
    let z = DoubleDouble::ZERO;
    DdMat4(std::array::from_fn(|j| {
        if j == 3 {
            return DdVec4([z, z, z, DoubleDouble::ONE]);
        }
        let mut e = [z; 3];
        e[j] = DoubleDouble::ONE;
        let turned = cross(axis, e);
        DdVec4(std::array::from_fn(|i| {
            if i == 3 {
                z
            } else {
                c * e[i] + s * turned[i] + one_c * axis[j] * axis[i]
            }
        }))
    }))
}

/// Translation along the geodesic through the origin with unit chart direction `u`, by the
/// distance whose `C` and `S` are `c` and `s` (curved geometries; see
/// [`Geometry::translation`]).
#[must_use]
pub fn translation(geometry: Geometry, u: Dd3, c: DoubleDouble, s: DoubleDouble) -> DdMat4 {
    let k = dd(geometry.kappa());
    let z = DoubleDouble::ZERO;
    let c1 = c - DoubleDouble::ONE;
    DdMat4(std::array::from_fn(|j| {
        if j == 3 {
            return DdVec4([s * u[0], s * u[1], s * u[2], c]);
        }
        DdVec4(std::array::from_fn(|i| {
            let e = if i == j { DoubleDouble::ONE } else { z };
            if i == 3 {
                -(k * s * u[j])
            } else {
                e + c1 * u[j] * u[i]
            }
        }))
    }))
}

/// The translation across a face at chart distance `r` onto the opposite one: twice the
/// inradius `ρ` along `u`, with `C(2ρ)` and `S(2ρ)` from `r = tan ρ` (S³) or `tanh ρ`
/// (H³) directly, so no inverse trigonometric function is rounded.
#[must_use]
pub fn double_inradius_translation(geometry: Geometry, u: Dd3, r: DoubleDouble) -> DdMat4 {
    let one = DoubleDouble::ONE;
    let r2 = r * r;
    let two_r = r + r;
    let (c, s) = match geometry {
        Geometry::Spherical => ((one - r2) / (one + r2), two_r / (one + r2)),
        Geometry::Hyperbolic => ((one + r2) / (one - r2), two_r / (one - r2)),
        Geometry::Euclidean => return affine(identity3(), scaled(u, two_r)),
    };
    translation(geometry, u, c, s)
}

/// The 3×3 identity, by rows.
#[must_use]
pub fn identity3() -> [Dd3; 3] {
    let (o, z) = (DoubleDouble::ONE, DoubleDouble::ZERO);
    [[o, z, z], [z, o, z], [z, z, o]]
}

/// Reflection in the plane `N·X = 0` of the covector `N = (n, −r)` (see
/// [`Geometry::reflection`]).
#[must_use]
pub fn reflection(geometry: Geometry, covector: DdVec4) -> DdMat4 {
    let n = covector.0;
    let m = DdVec4([n[0], n[1], n[2], dd(geometry.kappa()) * n[3]]);
    let scale = dd(2.0) / (0..4).fold(DoubleDouble::ZERO, |a, i| a + n[i] * m.0[i]);
    DdMat4(std::array::from_fn(|j| {
        let mut e = DdVec4::default();
        e.0[j] = DoubleDouble::ONE;
        e - m.scale(scale * n[j])
    }))
}

/// The inverse of an isometry: `G gᵀ G` (S³, H³), `(Aᵀ, −Aᵀ b)` (E³).
#[must_use]
pub fn inverse(geometry: Geometry, g: &DdMat4) -> DdMat4 {
    match geometry {
        Geometry::Euclidean => {
            let a: [Dd3; 3] = std::array::from_fn(|i| std::array::from_fn(|j| g.at(j, i)));
            let b = [g.at(0, 3), g.at(1, 3), g.at(2, 3)];
            let back = std::array::from_fn(|i| -dot3(a[i], b));
            affine(a, back)
        }
        _ => {
            let k = dd(geometry.kappa());
            let t = g.transpose();
            DdMat4(std::array::from_fn(|j| {
                DdVec4(std::array::from_fn(|i| {
                    let f = |x: usize| if x == 3 { k } else { DoubleDouble::ONE };
                    f(i) * t.at(i, j) * f(j)
                }))
            }))
        }
    }
}

/// The solution `x` of `n_i · x = r_i` for three faces (Cramer's rule in double-double).
fn meet(planes: [(Dd3, DoubleDouble); 3]) -> Dd3 {
    let rows = planes.map(|(n, _)| n);
    let det = dot3(rows[0], cross(rows[1], rows[2]));
    std::array::from_fn(|k| {
        let mut m = rows;
        for (i, row) in m.iter_mut().enumerate() {
            row[k] = planes[i].1;
        }
        dot3(m[0], cross(m[1], m[2])) / det
    })
}

/// Below this share of a vector's or matrix's largest entry, an entry of a closed-form
/// cell is zero: double-double cannot tell it from zero (sums that cancel exactly leave
/// about 2⁻¹⁰⁴), and such an entry must round to zero, not to a tiny number.
const NOISE: f64 = 1.0 / (1u128 << 90) as f64;

/// A vector with its entries below [`NOISE`] set to zero.
fn snap_zeros(v: Dd3) -> Dd3 {
    let size = v.iter().fold(0.0_f64, |m, x| m.max(x.abs().to_f64()));
    v.map(|x| {
        if x.abs().to_f64() < size * NOISE {
            DoubleDouble::ZERO
        } else {
            x
        }
    })
}

impl Space {
    /// Builds and validates a space from its cell in double-double: every face number,
    /// pairing and vertex of the space is the double-double value rounded once to `f64`,
    /// and the cell itself is kept ([`Space::exact`]) for the walkers' lower precisions and
    /// for the accuracy reference. Validation is [`Space::new`]'s, on the rounded cell.
    pub fn from_exact(
        name: impl Into<String>,
        description: impl Into<String>,
        cell: ExactCell,
    ) -> Result<Self, SpaceError> {
        let mut cell = cell;
        for face in &mut cell.faces {
            face.normal = snap_zeros(face.normal);
            let size = face.pairing.max_abs();
            for col in &mut face.pairing.0 {
                for x in &mut col.0 {
                    if x.abs().to_f64() < size * NOISE {
                        *x = DoubleDouble::ZERO;
                    }
                }
            }
        }
        let round3 = |v: Dd3| DVec3::from_array(v.map(DoubleDouble::round_f64));
        let specs: Vec<FaceSpec> = cell
            .faces
            .iter()
            .map(|f| {
                FaceSpec::paired(
                    round3(f.normal),
                    f.offset.round_f64(),
                    f.partner,
                    f.pairing.round_f64(),
                )
            })
            .collect();
        let mut space = Self::new(name, description, cell.geometry, &specs)?;
        for (face, exact) in space.faces.iter_mut().zip(&cell.faces) {
            face.normal = round3(exact.normal);
            face.offset = exact.offset.round_f64();
            face.covector = exact.covector().round_f64();
            face.pairing = exact.pairing.round_f64();
        }
        // Each vertex from the three of its faces that meet it most squarely.
        for v in 0..space.vertices.len() {
            let on: Vec<usize> = (0..space.faces.len())
                .filter(|&f| space.faces[f].vertices.contains(&v))
                .collect();
            let mut best: Option<([usize; 3], f64)> = None;
            for a in 0..on.len() {
                for b in a + 1..on.len() {
                    for c in b + 1..on.len() {
                        let [x, y, z] = [on[a], on[b], on[c]].map(|f| space.faces[f].normal);
                        let det = DMat3::from_cols(x, y, z).determinant().abs();
                        if best.is_none_or(|(_, d)| det > d) {
                            best = Some(([on[a], on[b], on[c]], det));
                        }
                    }
                }
            }
            if let Some((three, _)) = best {
                let planes = three.map(|f| (cell.faces[f].normal, cell.faces[f].offset));
                space.vertices[v] = round3(snap_zeros(meet(planes)));
            }
        }
        space.exact = Some(Arc::new(cell));
        Ok(space)
    }

    /// The cell in double-double, when the space was built from one ([`Space::from_exact`]):
    /// the seed spaces (from their closed forms) and the Dirichlet domains of groups (from
    /// their generators' digits as given). `None` for JSON space files, whose `f64` numbers
    /// are their own truth, and for cells that reach the equator of S³.
    #[must_use]
    pub fn exact(&self) -> Option<&ExactCell> {
        self.exact.as_deref()
    }
}
