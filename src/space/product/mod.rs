//! The product geometries H²×R and S²×R: a closed surface (from its word,
//! [`super::surface`]) times a circle of length `L`, optionally turned by `2π/P` once round
//! the circle (`docs/surfaces.md`).
//!
//! A point is a 4-vector `(x, y, z, w)`: `(x, y, w)` on the surface's model
//! (`x² + y² + κw² = κ`, the centre `(0, 0, 1)`) and `z` the height along the fibre; the
//! chart is `(x/w, y/w, z)`. A unit tangent `(vx, vy, vz, vw)` splits into the base part of
//! speed `λ` and the fibre speed `μ = vz`, `λ² + μ² = 1`. The geodesic is exact: its shadow
//! on the surface is the surface geodesic at speed `λ`, `p(t) = C(λt) p + S(λt)/λ · v`, and
//! its height `z + μt`. The cell is the polygon times `[−L/2, L/2]`: its side faces are the
//! polygon's sides times the fibre (totally geodesic, met where the shadow crosses the
//! side's line, a ratio as in the constant-curvature walk), and its top and bottom are the
//! slices `z = ±L/2`, met at `t = (±L/2 − z)/μ`. Leaving through a side applies the
//! polygon's pairing (a 4×4 matrix that fixes `z`); leaving through the top applies
//! `(p, z) ↦ (R⁻¹p, z − L)`, `R` the turn, and the bottom its inverse.

pub mod accuracy;
mod library;
pub mod motion;
mod walk;

pub use library::{PRODUCT_ALIASES, ProductAlias, ProductOrFlat, product_space};
pub use walk::{ProductExit, ProductWalker};

use super::exact::ExactFace;
use super::surface::{Polygon, SurfaceWord, WordError, turn};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, Ray, Real};
use glam::DVec4;
use std::sync::Arc;

/// The largest turn order `P`.
pub const MAX_TURN: u32 = 64;

/// Why a product space cannot be built.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProductError {
    /// The word is not a closed surface.
    #[error(transparent)]
    Word(#[from] WordError),
    /// The circle's length is not a positive finite number whose half is a normal one.
    #[error(
        "the circle's length L = {0:?} must be a finite number of at least 4.4502e-308 (the cell \
         reaches L/2 above and below its centre, and that half must be a positive number)"
    )]
    BadLength(f64),
    /// The turn order is out of range.
    #[error("the turn -turn-{0} must be a whole number from 1 to {MAX_TURN}")]
    BadTurn(u32),
    /// The turn does not carry the polygon's gluing to itself.
    #[error(
        "a turn by 2π/{turn} does not carry the gluing of {word} to itself: it must move each \
         side to a side glued the same way to the turned partner (the word has {sides} sides)"
    )]
    TurnNotSymmetry {
        turn: u32,
        word: String,
        sides: usize,
    },
    /// A flat word: its product is a flat space.
    #[error(
        "{word} is a flat surface (Euler characteristic 0): its product with a circle is a flat \
         space, built as one (`Space`)"
    )]
    Flat { word: String },
}

/// Whether `length` can be a product's circle: finite, and half of it a positive normal
/// number (a subnormal or zero half-height would make a cell of no height, crossed at
/// distance 0 for ever).
#[must_use]
pub fn valid_length(length: f64) -> bool {
    length.is_finite() && 0.5 * length >= f64::MIN_POSITIVE
}

/// A closed 3-manifold (or, with a non-orientable surface, still a manifold) of the product
/// geometry H²×R or S²×R, as its cell: the surface's polygon times an interval.
#[derive(Clone, Debug)]
pub struct ProductSpace {
    pub(crate) name: String,
    pub(crate) description: String,
    pub(crate) word: SurfaceWord,
    pub(crate) polygon: Arc<Polygon>,
    pub(crate) length: f64,
    pub(crate) turn: u32,
}

impl ProductSpace {
    /// The surface of `word` times a circle of length `length`, turned by `2π/turn` once
    /// round it (`turn` 1: no turn).
    pub fn new(
        name: impl Into<String>,
        word: &str,
        length: f64,
        turn: u32,
    ) -> Result<Self, ProductError> {
        let word = SurfaceWord::parse(word)?;
        if !valid_length(length) {
            return Err(ProductError::BadLength(length));
        }
        if !(1..=MAX_TURN).contains(&turn) {
            return Err(ProductError::BadTurn(turn));
        }
        if word.geometry() == Geometry::Euclidean {
            return Err(ProductError::Flat {
                word: word.word.clone(),
            });
        }
        // The sphere and the hemisphere are glued the same way all round (identity, the
        // antipodal map): every turn commutes with that.
        let uniform = word.geometry() == Geometry::Spherical && word.corners_per_vertex() <= 2;
        if !uniform && !word.turn_is_symmetry(turn) {
            return Err(ProductError::TurnNotSymmetry {
                turn,
                word: word.word.clone(),
                sides: word.side_count(),
            });
        }
        let polygon = Arc::new(Polygon::of(&word));
        let description = format!(
            "{} ({}) times a circle of length {length}{}",
            word.common_name(),
            word.word,
            if turn > 1 {
                format!(", turned by 2π/{turn} once round it")
            } else {
                String::new()
            }
        );
        Ok(Self {
            name: name.into(),
            description,
            word,
            polygon,
            length,
            turn,
        })
    }

    /// The space's name.
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// A one-line description.
    #[must_use]
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The surface's geometry: [`Geometry::Hyperbolic`] for H²×R, [`Geometry::Spherical`]
    /// for S²×R.
    #[must_use]
    pub fn base(&self) -> Geometry {
        self.polygon.geometry
    }

    /// `H2xR` or `S2xR`.
    #[must_use]
    pub fn geometry_name(&self) -> &'static str {
        match self.base() {
            Geometry::Hyperbolic => "H2xR",
            _ => "S2xR",
        }
    }

    /// The surface's word.
    #[must_use]
    pub fn word(&self) -> &SurfaceWord {
        &self.word
    }

    /// The surface's polygon in double-double.
    #[must_use]
    pub fn polygon(&self) -> &Polygon {
        &self.polygon
    }

    /// The circle's length `L`.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.length
    }

    /// The turn's order `P` (1: none).
    #[must_use]
    pub fn turn(&self) -> u32 {
        self.turn
    }

    /// The surface's area by Gauss–Bonnet, `2π|χ|`.
    #[must_use]
    pub fn base_area(&self) -> f64 {
        std::f64::consts::TAU * self.word.euler_characteristic().unsigned_abs() as f64
    }

    /// The volume: the surface's area times `L`.
    #[must_use]
    pub fn volume(&self) -> f64 {
        self.base_area() * self.length
    }

    /// Whether the space is orientable (the surface is; the turn preserves orientation).
    #[must_use]
    pub fn orientable(&self) -> bool {
        self.word.orientable()
    }

    /// The number of the cell's faces: the side faces, then the top and the bottom.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.side_faces().len() + 2
    }

    /// The side faces as the walk uses them: the polygon's sides, or for the hemisphere one
    /// face (the equator, every side of which is glued by the antipodal map), or none for
    /// the sphere.
    #[must_use]
    pub fn side_faces(&self) -> Vec<ExactFace> {
        let sides = &self.polygon.sides;
        if self.hemisphere() {
            let z = DoubleDouble::ZERO;
            vec![ExactFace {
                normal: [z, z, z],
                offset: DoubleDouble::new(f64::INFINITY),
                partner: 0,
                pairing: sides[0].pairing,
            }]
        } else {
            sides.clone()
        }
    }

    /// Whether the base is the hemisphere (a projective plane of S²).
    #[must_use]
    pub fn hemisphere(&self) -> bool {
        self.base() == Geometry::Spherical && self.word.corners_per_vertex() == 2
    }

    /// The unit covector of a side face in the model (`N·X ≤ 0` inside), in double-double:
    /// `(C(ρ)·n, 0, −S(ρ))` for a side at chart offset `S/C` (the equator `(0, 0, 0, −1)`).
    #[must_use]
    pub fn side_covector(&self, face: &ExactFace) -> DdVec4 {
        let one = DoubleDouble::ONE;
        if !face.offset.is_finite() {
            return DdVec4([
                DoubleDouble::ZERO,
                DoubleDouble::ZERO,
                DoubleDouble::ZERO,
                -one,
            ]);
        }
        let k = DoubleDouble::new(self.base().kappa());
        // n·x ≤ r·w with |n| = 1: scale (n, −r) to unit length in the dual form.
        let r = face.offset;
        let len = (one + k * r * r).sqrt();
        DdVec4([
            face.normal[0] / len,
            face.normal[1] / len,
            DoubleDouble::ZERO,
            -r / len,
        ])
    }

    /// The top's pairing `R⁻¹` (the bottom's is `R`), fixing `z`; the height shift is
    /// applied by the walk.
    #[must_use]
    pub fn top_pairing(&self) -> DdMat4 {
        turn(-2, i64::from(self.turn))
    }

    /// How far the model point `p` is outside the cell: the largest of the side faces'
    /// `N·X` of the unit base point and `|z| − L/2` (negative inside).
    #[must_use]
    pub fn outside_by(&self, p: DVec4) -> f64 {
        let g = self.base();
        let base = DVec4::new(p.x, p.y, 0.0, p.w);
        let norm = (g.kappa() * g.form(base, base))
            .abs()
            .sqrt()
            .max(f64::MIN_POSITIVE);
        let base = base / norm;
        self.side_faces()
            .iter()
            .map(|f| self.side_covector(f).round_f64().dot(base))
            .fold(p.z.abs() - 0.5 * self.length, f64::max)
    }

    /// The cell's centre `(0, 0, 0, 1)`.
    #[must_use]
    pub fn centre(&self) -> DVec4 {
        DVec4::W
    }
}

/// A ray from the centre with unit chart direction `d`: base speed `|d.xy|`, fibre speed
/// `d.z` (the convention of the product spaces' CLI and tests).
#[must_use]
pub fn ray_from_centre(d: glam::DVec3) -> Ray<DVec4> {
    let d = d.normalize();
    Ray {
        point: DVec4::W,
        tangent: DVec4::new(d.x, d.y, d.z, 0.0),
    }
}

/// A ray at the chart point `x = (x/w, y/w, z)` with chart direction `d`: the base part of
/// the direction is taken along the surface's chart (straight lines are geodesics there)
/// and the height part along the fibre, each at the speed the chart says, then the tangent
/// is scaled to unit length.
pub fn chart_ray(base: Geometry, x: glam::DVec3, d: glam::DVec3) -> Result<Ray<DVec4>, String> {
    let g = base;
    let p = chart_point(base, x)?;
    // Any finite non-zero direction names one, however large or small its entries: scaled
    // by its largest entry before its length is taken (`1e200` would overflow it).
    let largest = d.abs().max_element();
    if !(d.is_finite() && largest > 0.0) {
        return Err(format!(
            "the direction {:?} is not usable: give three finite numbers, not all 0",
            d.to_array()
        ));
    }
    let d = d / largest;
    let base_point = DVec4::new(p.x, p.y, 0.0, p.w);
    let vb = g
        .tangent_from_chart(base_point, glam::DVec3::new(d.x, d.y, 0.0))
        .ok();
    let horizontal = glam::DVec2::new(d.x, d.y).length() / d.length();
    let vertical = d.z / d.length();
    let tangent = match vb {
        Some(v) => v * horizontal + DVec4::Z * vertical,
        None => DVec4::Z * vertical.signum(),
    };
    Ok(Ray { point: p, tangent })
}

/// The model point `[x, y, z, w]` of the chart point `x = (x/w, y/w, z)`: the surface's
/// chart point (gnomonic or Klein) and a height, as `trace --from`, `light` and `render
/// --eye` take it.
pub fn chart_point(base: Geometry, x: glam::DVec3) -> Result<DVec4, String> {
    if !x.z.is_finite() {
        return Err(format!("the height {} is not a finite number", x.z));
    }
    let p = base
        .from_chart(glam::DVec3::new(x.x, x.y, 0.0))
        .map_err(|e| e.to_string())?;
    Ok(DVec4::new(p.x, p.y, x.z, p.w))
}
