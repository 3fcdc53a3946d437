//! Spaces given by a group: Curved Spaces' generator files (`.gen`), reading and writing,
//! and the checks that the matrices are isometries of one geometry.
//!
//! A `.gen` file is plain text: `#` starts a comment that runs to the end of the line, an
//! optional UTF-8 byte-order mark may open it, and everything else is numbers, 16 per 4×4
//! matrix, each matrix written row by row. The matrices act on row vectors (`v′ = v·M`),
//! `w` is the fourth coordinate and the basepoint is `(0, 0, 0, 1)`, so the bottom row of a
//! matrix is the image of the basepoint; this crate's matrices act on column vectors and are
//! the transposes. Inverses and the identity need not be listed (they are harmless if they
//! are). A file with no matrices is the 3-sphere. The geometry follows from the matrices:
//! orthogonal (spherical), affine with a rotation part (flat), or preserving
//! `−x² − y² − z² + w²` (hyperbolic).

use super::{Space, SpaceError};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Real, Vector4, max_abs_entry};
use glam::{DMat4, DVec4};
use std::fmt::Write as _;

/// The most matrices a generator file may list.
pub const MAX_GENERATORS: usize = 64;

/// How far a listed matrix may be from an isometry (largest entry of the residual) and still
/// be taken as one; it is then polished to an isometry to the last bit.
pub const ISOMETRY_TOLERANCE: f64 = 1e-6;

/// Why a group could not be read or made into a space.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GroupError {
    #[error("line {line}: `{token}` is not a number")]
    NotANumber { line: usize, token: String },
    #[error("line {line}: `{token}` is not finite")]
    NotFinite { line: usize, token: String },
    #[error(
        "{count} numbers do not make whole 4×4 matrices (16 numbers each, written row by row): \
         {left} left over after matrix {matrices}"
    )]
    PartialMatrix {
        count: usize,
        left: usize,
        matrices: usize,
    },
    #[error("{count} matrices are more than the limit of {max}")]
    TooManyGenerators { count: usize, max: usize },
    #[error(
        "matrix {matrix} is not an isometry of any geometry: its residual is {spherical:.2e} as \
         a rotation of S³, {flat:.2e} as a motion of E³ and {hyperbolic:.2e} as a Lorentz \
         transformation of H³ (at most {tolerance:.0e} is accepted)"
    )]
    NotAnIsometry {
        matrix: usize,
        spherical: f64,
        flat: f64,
        hyperbolic: f64,
        tolerance: f64,
    },
    #[error(
        "the matrices mix geometries: matrix {first} is {first_geometry}, matrix {second} is \
         {second_geometry}"
    )]
    MixedGeometries {
        first: usize,
        first_geometry: &'static str,
        second: usize,
        second_geometry: &'static str,
    },
    #[error(
        "{what} fixes the basepoint (0, 0, 0, 1), so the Dirichlet domain about it is not a \
         fundamental domain; move the basepoint (`--basepoint X,Y,Z`) to a point no element fixes"
    )]
    FixesBasepoint { what: String },
    #[error(
        "the group is not discrete: two of its elements move the basepoint to points only \
         {distance:.2e} apart (the least separation taken as discrete is {limit:.0e})"
    )]
    NotDiscrete { distance: f64, limit: f64 },
    #[error(
        "the group has more than {limit} elements within the distance {radius:.3} of the \
         basepoint that its Dirichlet domain needs: too many to enumerate (the domain is very \
         large, or long and thin)"
    )]
    TooLarge { limit: usize, radius: f64 },
    #[error(
        "the Dirichlet domain does not close up within distance {radius:.3} of the basepoint: \
         the group is not cocompact (a cusped or infinite-volume quotient), or its generators \
         do not generate a lattice of full rank"
    )]
    NotCocompact { radius: f64 },
    #[error(
        "the Dirichlet domain reaches distance π/2 from the basepoint, and the group is {what}; \
         beyond the chart this release draws the 3-sphere, projective space, the lens \
         spaces of groups acting freely and the mirrored lenses of dihedral reflection groups. Move the basepoint (`--basepoint X,Y,Z`) if the \
         group has a point whose domain is smaller"
    )]
    ReachesEquator { what: String },
    #[error(
        "the Dirichlet domain does not close up although every element is known: a face's \
         element has an inverse that bounds no face, or a generator is not a product of the \
         face pairings; the matrices are probably not precise enough to form a group"
    )]
    Unclosed,
    #[error("the Dirichlet domain has {count} faces, more than the limit of {max}")]
    TooManyFaces { count: usize, max: usize },
    #[error("the basepoint {point:?} is not a point of the {geometry} chart")]
    BadBasepoint {
        point: [f64; 3],
        geometry: &'static str,
    },
    #[error("the Dirichlet domain does not validate as a cell: {0}")]
    Invalid(#[from] SpaceError),
}

/// The matrices of a generator file, as column-vector matrices (this crate's convention),
/// with the comment lines at its top (the first is taken as the description).
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratorFile {
    /// The matrices in the file's order, transposed to act on column vectors.
    pub matrices: Vec<DMat4>,
    /// The text of the comment lines before the first number, `#` and leading blanks removed.
    pub comments: Vec<String>,
}

/// Parses the text of a `.gen` file (no geometry checks yet: see [`Generators::new`]).
pub fn parse_gen(text: &str) -> Result<GeneratorFile, GroupError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut numbers = Vec::new();
    let mut comments = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let (data, comment) = match line.find('#') {
            Some(k) => (&line[..k], Some(&line[k + 1..])),
            None => (line, None),
        };
        for token in data.split_whitespace() {
            let x: f64 = token.parse().map_err(|_| GroupError::NotANumber {
                line: i + 1,
                token: token.chars().take(40).collect(),
            })?;
            if !x.is_finite() {
                return Err(GroupError::NotFinite {
                    line: i + 1,
                    token: token.chars().take(40).collect(),
                });
            }
            numbers.push(x);
            if numbers.len() > 16 * MAX_GENERATORS {
                return Err(GroupError::TooManyGenerators {
                    count: numbers.len().div_ceil(16),
                    max: MAX_GENERATORS,
                });
            }
        }
        if let Some(c) = comment
            && numbers.is_empty()
        {
            let c = c.trim();
            if !c.is_empty() {
                comments.push(c.to_string());
            }
        }
    }
    if numbers.len() % 16 != 0 {
        return Err(GroupError::PartialMatrix {
            count: numbers.len(),
            left: numbers.len() % 16,
            matrices: numbers.len() / 16,
        });
    }
    let matrices = numbers
        .chunks_exact(16)
        // Row by row of the row-vector matrix M is column by column of Mᵀ.
        .map(DMat4::from_cols_slice)
        .collect();
    Ok(GeneratorFile { matrices, comments })
}

/// Generators of a group of isometries of one geometry, each polished to an isometry.
#[derive(Clone, Debug, PartialEq)]
pub struct Generators {
    /// The geometry they act on.
    pub geometry: Geometry,
    /// The generators (column-vector convention), without the identity.
    pub matrices: Vec<DMat4>,
}

/// How far `g` is from an isometry of each geometry (S³, E³, H³).
fn residuals(g: DMat4) -> [f64; 3] {
    let flat = {
        let bottom = (g.row(3) - DVec4::W).abs().max_element();
        bottom.max(Geometry::Euclidean.isometry_defect(g))
    };
    // A Lorentz matrix that swaps the two sheets of the hyperboloid is no isometry of H³.
    let hyperbolic = if g.w_axis.w > 0.0 {
        Geometry::Hyperbolic.isometry_defect(g)
    } else {
        f64::INFINITY
    };
    [Geometry::Spherical.isometry_defect(g), flat, hyperbolic]
}

/// The isometry of `geometry` nearest `g` (Gram–Schmidt of its columns in the form,
/// starting from the image of the basepoint, which is kept on its ray), computed in
/// double-double and rounded once: the result is the correctly rounded value of the
/// isometry that polishing `g`'s digits as given makes.
#[must_use]
pub fn polish_isometry(geometry: Geometry, g: DMat4) -> DMat4 {
    polish_isometry_dd(geometry, &DdMat4::from_f64(g)).round_f64()
}

/// [`polish_isometry`] in `f64` throughout: for the many products of a group enumeration,
/// whose survivors are polished again in double-double where they become face pairings.
#[must_use]
pub(crate) fn polish_isometry_fast(geometry: Geometry, g: DMat4) -> DMat4 {
    match geometry {
        Geometry::Euclidean => {
            let mut c = [g.x_axis, g.y_axis, g.z_axis].map(|v| v.truncate());
            for _ in 0..2 {
                for i in 0..3 {
                    let mut v = c[i];
                    for done in &c[..i] {
                        v -= *done * v.dot(*done);
                    }
                    c[i] = v.normalize();
                }
            }
            DMat4::from_cols(
                c[0].extend(0.0),
                c[1].extend(0.0),
                c[2].extend(0.0),
                g.w_axis.truncate().extend(1.0),
            )
        }
        _ => {
            let form = |a: DVec4, b: DVec4| geometry.form(a, b);
            let w = g.w_axis / (geometry.kappa() * form(g.w_axis, g.w_axis)).sqrt();
            let mut cols = [g.x_axis, g.y_axis, g.z_axis];
            for i in 0..3 {
                let mut v = cols[i] - w * (form(cols[i], w) / form(w, w));
                for done in &cols[..i] {
                    v -= *done * form(v, *done);
                }
                cols[i] = v / form(v, v).sqrt();
            }
            DMat4::from_cols(cols[0], cols[1], cols[2], w)
        }
    }
}

/// [`polish_isometry`] in double-double.
#[must_use]
pub fn polish_isometry_dd(geometry: Geometry, g: &DdMat4) -> DdMat4 {
    let [x, y, z, w] = g.0;
    match geometry {
        Geometry::Euclidean => {
            // The linear part orthonormalised (twice, for the last bit), handedness kept;
            // the translation as given.
            let linear = |v: DdVec4| DdVec4([v.0[0], v.0[1], v.0[2], DoubleDouble::ZERO]);
            let mut c = [linear(x), linear(y), linear(z)];
            for _ in 0..2 {
                for i in 0..3 {
                    let mut v = c[i];
                    for done in &c[..i] {
                        v = v - done.scale(v.dot(*done));
                    }
                    c[i] = v.scale(DoubleDouble::ONE / v.dot(v).sqrt());
                }
            }
            let mut t = w;
            t.0[3] = DoubleDouble::ONE;
            DdMat4([c[0], c[1], c[2], t])
        }
        _ => {
            let form = |a: DdVec4, b: DdVec4| geometry.form(a, b);
            let k = DoubleDouble::new(geometry.kappa());
            // Normalised in the form, never flipped (−I is an element of S³ groups).
            let w = w.scale(DoubleDouble::ONE / (k * form(w, w)).sqrt());
            let mut cols = [x, y, z];
            for i in 0..3 {
                let mut v = cols[i] - w.scale(form(cols[i], w) / form(w, w));
                for done in &cols[..i] {
                    v = v - done.scale(form(v, *done));
                }
                cols[i] = v.scale(DoubleDouble::ONE / form(v, v).sqrt());
            }
            DdMat4([cols[0], cols[1], cols[2], w])
        }
    }
}

impl Generators {
    /// Finds the geometry of the matrices and polishes each to an isometry of it. The
    /// identity is dropped. No matrices at all is the trivial group of S³.
    pub fn new(matrices: &[DMat4]) -> Result<Self, GroupError> {
        if matrices.len() > MAX_GENERATORS {
            return Err(GroupError::TooManyGenerators {
                count: matrices.len(),
                max: MAX_GENERATORS,
            });
        }
        let mut geometry: Option<(usize, Geometry)> = None;
        let mut kept = Vec::new();
        for (i, &g) in matrices.iter().enumerate() {
            if !g.is_finite() {
                return Err(GroupError::NotAnIsometry {
                    matrix: i + 1,
                    spherical: f64::INFINITY,
                    flat: f64::INFINITY,
                    hyperbolic: f64::INFINITY,
                    tolerance: ISOMETRY_TOLERANCE,
                });
            }
            let scale = max_abs_entry(&(g - DMat4::IDENTITY).to_cols_array());
            if scale <= 1e-12 {
                continue;
            }
            let r = residuals(g);
            let fits: Vec<Geometry> = [
                Geometry::Spherical,
                Geometry::Euclidean,
                Geometry::Hyperbolic,
            ]
            .into_iter()
            .zip(r)
            .filter(|(_, r)| *r <= ISOMETRY_TOLERANCE)
            .map(|(geo, _)| geo)
            .collect();
            match fits.len() {
                0 => {
                    return Err(GroupError::NotAnIsometry {
                        matrix: i + 1,
                        spherical: r[0],
                        flat: r[1],
                        hyperbolic: r[2],
                        tolerance: ISOMETRY_TOLERANCE,
                    });
                }
                1 => {}
                // An isometry of two geometries is a rotation about the basepoint.
                _ => {
                    return Err(GroupError::FixesBasepoint {
                        what: format!("matrix {}", i + 1),
                    });
                }
            }
            let geo = fits[0];
            match geometry {
                None => geometry = Some((i, geo)),
                Some((first, first_geo)) if first_geo != geo => {
                    return Err(GroupError::MixedGeometries {
                        first: first + 1,
                        first_geometry: first_geo.name(),
                        second: i + 1,
                        second_geometry: geo.name(),
                    });
                }
                Some(_) => {}
            }
            kept.push(polish_isometry(geo, g));
        }
        Ok(Self {
            geometry: geometry.map_or(Geometry::Spherical, |(_, g)| g),
            matrices: kept,
        })
    }
}

/// A space's face pairings as a `.gen` file (one matrix per pair of faces and per mirror),
/// with its name, description and geometry in comments. Reading it back gives the
/// Dirichlet domain of the same group about the same basepoint.
#[must_use]
pub fn write_gen(space: &Space) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "#\t{}", space.name());
    if !space.description().is_empty() {
        for line in space.description().lines() {
            let _ = writeln!(out, "#\t{line}");
        }
    }
    let _ = writeln!(
        out,
        "#\t{} geometry; written by bevy_curved_spaces: one face pairing per pair of faces,\n\
         #\tas 4×4 matrices acting on row vectors (v' = v·M), basepoint (0, 0, 0, 1).",
        space.geometry().name()
    );
    for (i, face) in space.faces().iter().enumerate() {
        // A seam between two cells is glued by the identity: no generator.
        if face.partner < i || space.is_seam(i) {
            continue;
        }
        out.push('\n');
        let m = face.pairing.to_cols_array();
        for row in m.chunks_exact(4) {
            // The shortest decimal that reads back as the same f64: every entry as stored,
            // rounded once (a fixed 17 decimals kept too few digits of small entries).
            let line: Vec<String> = row.iter().map(|x| format!("{x:>22}")).collect();
            let _ = writeln!(out, "{}", line.join(" "));
        }
    }
    out
}
