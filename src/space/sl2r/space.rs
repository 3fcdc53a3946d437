//! The spaces of SL̃(2,R) built so far: the unit tangent bundle `UT Σ = PSL(2,R)/Γ` of a
//! closed orientable hyperbolic surface `Σ` given by its word (the product spaces' regular
//! polygon and side pairings), its cell the polygon times the whole fibre (the fibre closes
//! by itself: `e` turns once round), its only faces the polygon's sides.

use crate::geometry::{DdMat4, DoubleDouble, Geometry, Real};
use crate::space::surface::{Polygon, SurfaceWord, WordError};
use std::f64::consts::PI;

/// A side of the cell: the polygon's side as a covector of the hyperboloid's space
/// (`n·p ≤ 0` inside), the pairing that carries a ray leaving through it (an element of
/// `SO⁺(2,1)`, rows, acting on `(x, y, w)`), and the side it enters through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rSide {
    /// The covector `(cos θ, sin θ, −tanh ρ)` of the side at angle `θ`, inradius `ρ`.
    pub normal: [DoubleDouble; 3],
    /// The pairing, rows.
    pub pairing: [[DoubleDouble; 3]; 3],
    /// The partner side.
    pub partner: usize,
}

/// Why a word gives no unit tangent bundle of SL̃(2,R).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Sl2rError {
    /// The word is not a surface word.
    #[error(transparent)]
    Word(#[from] WordError),
    /// The surface is not hyperbolic.
    #[error(
        "the word {word} is {what}: its unit tangent bundle is {geometry}, not SL̃(2,R) \
         (SL̃(2,R)'s unit tangent bundles are of hyperbolic surfaces: Euler characteristic \
         below 0, e.g. abABcdCD)"
    )]
    NotHyperbolic {
        /// The word.
        word: String,
        /// What the surface is.
        what: &'static str,
        /// The geometry of its unit tangent bundle.
        geometry: &'static str,
    },
    /// A fibre cover's degree is not a whole number dividing the Euler characteristic.
    #[error(
        "unit-tangent-{word}-cover-{n}: {why}; the fibre's N-fold covers of this bundle are \
         N = {divisors} (N divides χ = {chi})"
    )]
    Cover {
        /// The word.
        word: String,
        /// The cover's degree as written.
        n: String,
        /// What is wrong with it.
        why: String,
        /// The degrees there are, listed.
        divisors: String,
        /// The surface's Euler characteristic.
        chi: i64,
    },
    /// The surface is not orientable.
    #[error(
        "the word {word} is a non-orientable surface: its unit tangent bundle is not a \
         quotient of SL̃(2,R) by orientation-preserving isometries; give an orientable word \
         (each letter once lower and once upper case, e.g. abABcdCD)"
    )]
    NotOrientable {
        /// The word.
        word: String,
    },
}

/// `UT Σ` of an orientable hyperbolic surface `Σ`, with the Sasaki metric.
#[derive(Clone, Debug, PartialEq)]
pub struct UnitTangentSpace {
    name: String,
    description: String,
    word: SurfaceWord,
    polygon: Polygon,
    sides: Vec<Sl2rSide>,
    sheets: u32,
}

/// The id's prefix of the unit tangent bundles.
pub const UNIT_TANGENT_PREFIX: &str = "unit-tangent-";

/// The unit tangent bundle an id names (`unit-tangent-WORD`, `unit-tangent-bitorus` =
/// `unit-tangent-abABcdCD`); `None` where the id is not of this family, an error where it
/// is but names no such space.
pub fn sl2r_space(id: &str) -> Option<Result<UnitTangentSpace, Sl2rError>> {
    let rest = id.strip_prefix(UNIT_TANGENT_PREFIX)?;
    let (rest, cover) = match rest.split_once("-cover-") {
        Some((word, n)) => (word, Some(n)),
        None => (rest, None),
    };
    let word = match rest {
        "bitorus" => "abABcdCD",
        w => w,
    };
    let space = match cover {
        None => UnitTangentSpace::new(word),
        Some(n) => cover_degree(word, n).and_then(|n| UnitTangentSpace::cover(word, n)),
    };
    Some(space.map(|mut s| {
        s.name = id.to_string();
        s
    }))
}

/// The degree `N` of `unit-tangent-WORD-cover-N` as written, checked against the word's
/// Euler characteristic (a word that is no hyperbolic surface reports that instead).
fn cover_degree(word: &str, n: &str) -> Result<u32, Sl2rError> {
    let surface = UnitTangentSpace::new(word)?;
    let chi = surface.word.euler_characteristic();
    let divisors: Vec<String> = (1..=chi.unsigned_abs())
        .filter(|d| chi.unsigned_abs() % d == 0)
        .map(|d| d.to_string())
        .collect();
    let refuse = |why: String| Sl2rError::Cover {
        word: word.to_string(),
        n: n.to_string(),
        why,
        divisors: divisors.join(", "),
        chi,
    };
    let degree = match n.parse::<u64>() {
        Ok(0) => return Err(refuse("N = 0 is no cover".to_string())),
        Ok(d) => d,
        Err(_) if n.is_empty() => return Err(refuse("the degree N is missing".to_string())),
        Err(_) if n.bytes().all(|b| b.is_ascii_digit()) => {
            return Err(refuse(format!("{n} sheets are far more than χ allows")));
        }
        Err(_) => {
            return Err(refuse(format!(
                "`{}` is not a whole number of sheets",
                n.escape_debug()
            )));
        }
    };
    if chi.unsigned_abs() % degree != 0 {
        return Err(refuse(format!(
            "{degree} does not divide χ = {chi}, so the surface group has no lift to the \
             {degree}-fold cover of the fibre"
        )));
    }
    Ok(degree as u32)
}

/// The 3×3 part of a product space's pairing that acts on `H²` (`(x, y, w)`: the model's
/// coordinates 0, 1 and 3), rows.
fn surface_part(m: &DdMat4) -> [[DoubleDouble; 3]; 3] {
    let idx = [0, 1, 3];
    // DdMat4 is by columns: entry (row r, column c) is m.0[c].0[r].
    idx.map(|r| idx.map(|c| m.0[c].0[r]))
}

impl UnitTangentSpace {
    /// The unit tangent bundle of the surface of `word`; an error says why a word has none.
    pub fn new(word: &str) -> Result<Self, Sl2rError> {
        let word = SurfaceWord::parse(word)?;
        if !word.orientable() {
            return Err(Sl2rError::NotOrientable {
                word: word.word.clone(),
            });
        }
        match word.geometry() {
            Geometry::Hyperbolic => {}
            Geometry::Euclidean => {
                return Err(Sl2rError::NotHyperbolic {
                    word: word.word.clone(),
                    what: "flat (Euler characteristic 0)",
                    geometry: "flat: the torus's is the 3-torus, E³",
                });
            }
            Geometry::Spherical => {
                return Err(Sl2rError::NotHyperbolic {
                    word: word.word.clone(),
                    what: "spherical (Euler characteristic above 0)",
                    geometry: "spherical: the sphere's is the projective space RP³, S³",
                });
            }
        }
        let polygon = Polygon::of(&word);
        let z = DoubleDouble::ZERO;
        let sides = polygon
            .sides
            .iter()
            .map(|f| Sl2rSide {
                normal: [f.normal[0], f.normal[1], z - f.offset],
                pairing: surface_part(&f.pairing),
                partner: f.partner,
            })
            .collect();
        let genus = (2 - word.euler_characteristic()) / 2;
        Ok(Self {
            name: format!("{UNIT_TANGENT_PREFIX}{}", word.word),
            description: format!(
                "the unit tangent bundle of the genus-{genus} surface {} (SL̃(2,R)): its \
                 {}-gon times the fibre, a circle of length 2π",
                word.word,
                word.side_count()
            ),
            word,
            polygon,
            sides,
            sheets: 1,
        })
    }

    /// The fibre's `N`-fold cover of the unit tangent bundle of `word` (`N` dividing `χ`):
    /// the fibre closes after `2πN`; the cell is the polygon times `Λ ∈ (−πN, πN]` (see
    /// [`super::cover`]). `N = 1` is `UT Σ`.
    pub fn cover(word: &str, sheets: u32) -> Result<Self, Sl2rError> {
        let mut space = Self::new(word)?;
        if sheets == 1 {
            return Ok(space);
        }
        cover_degree(word, &sheets.to_string())?;
        let genus = space.genus();
        space.name = format!("{UNIT_TANGENT_PREFIX}{}-cover-{sheets}", space.word.word);
        space.description = format!(
            "the {sheets}-fold fibre cover of the unit tangent bundle of the genus-{genus} \
             surface {} (SL̃(2,R)): its {}-gon times the fibre, a circle of length {sheets}·2π \
             (the cell's top and bottom at ±{sheets}π glued)",
            space.word.word,
            space.word.side_count()
        );
        space.sheets = sheets;
        Ok(space)
    }

    /// The fibre cover's degree `N` (1 for `UT Σ`).
    #[must_use]
    pub fn sheets(&self) -> u32 {
        self.sheets
    }

    /// The space's id: `unit-tangent-WORD` (or the alias it was named by).
    #[must_use]
    pub fn name(&self) -> &str {
        &self.name
    }

    /// One line about it.
    #[must_use]
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The injectivity radius of `UT Σ`, `min(π, sys/2)` with `sys` the surface's systole;
    /// `None` when the surface group is too large to search (more than `limit` elements).
    /// For a fibre cover it is a lower bound (a geodesic loop of the cover is one of `UT Σ`,
    /// and the conjugate radius is the same): whether the shortest loop over the systole
    /// closes in the cover depends on the sheets it climbs.
    ///
    /// Why: the sectional curvature of this metric lies in `[−7/4, 1/4]` (Milnor's formulas
    /// for the structure constants `[B₁, B₂] = −R`, `[R, B₁] = B₂`, `[R, B₂] = −B₁`), so no
    /// geodesic has a conjugate point before `π/√(1/4) = 2π`, and the injectivity radius is
    /// half the shortest closed geodesic. A closed geodesic is the axis of a deck element:
    /// one over a non-trivial surface element moves points at least as far as its shadow on
    /// `H²` moves, its translation length, and the tangent lift of the surface's systole is a
    /// closed geodesic of exactly that length; a power `zᵏ` of the fibre's loop moves every
    /// point by the same distance, and the only geodesics from a point back to its fibre turned
    /// by `2π` are the fibre itself (a geodesic whose base point circles returns after its
    /// period `2π/√(2c² − 1)` turned by `2π(2c/√(2c² − 1) − 1) ≥ 2π`, equal only at `c = 1`),
    /// so `z` moves points by `2π`.
    #[must_use]
    pub fn injectivity_radius(&self, limit: usize) -> Option<f64> {
        let systole = crate::space::surface::systole(&self.word, &self.polygon, limit)?;
        Some((0.5 * systole).min(PI))
    }

    /// The frame reached from the centre's frame (`p = (0, 0, 1)`, `e = (1, 0, 0)`, the
    /// viewer's axes the body frame) along the body direction `offset` by its length.
    #[must_use]
    pub fn frame_from_centre(&self, offset: glam::DVec3) -> glam::DMat4 {
        use crate::space::FrameSpace;
        let start = glam::DMat4::from_cols(
            glam::DVec4::new(1.0, 0.0, 0.0, 1.0),
            glam::DVec4::new(0.0, 1.0, 0.0, 0.0),
            glam::DVec4::new(0.0, 0.0, 1.0, 0.0),
            glam::DVec4::new(0.0, 0.0, 1.0, 1.0),
        );
        self.step_frame(
            start,
            &crate::space::contract::FrameMotion {
                translation: offset,
                rotation: glam::DVec3::ZERO,
                level: false,
            },
        )
    }

    /// The surface's word.
    #[must_use]
    pub fn word(&self) -> &SurfaceWord {
        &self.word
    }

    /// The sides of the cell, in the word's order.
    #[must_use]
    pub fn sides(&self) -> &[Sl2rSide] {
        &self.sides
    }

    /// The polygon's inradius.
    #[must_use]
    pub fn inradius(&self) -> f64 {
        self.polygon.inradius.hi
    }

    /// The polygon's circumradius (the distance from its centre to its vertices).
    #[must_use]
    pub fn circumradius(&self) -> f64 {
        self.polygon.circumradius.hi
    }

    /// The polygon's vertices on the hyperboloid, vertex `k` between sides `k − 1` and `k`
    /// (side `k` is centred on the direction at angle `2πk/n`).
    #[must_use]
    pub fn vertices(&self) -> Vec<[f64; 3]> {
        let n = self.sides.len();
        let r = self.circumradius();
        (0..n)
            .map(|k| {
                let phi = (2.0 * k as f64 - 1.0) * PI / n as f64;
                [r.sinh() * phi.cos(), r.sinh() * phi.sin(), r.cosh()]
            })
            .collect()
    }

    /// The surface's genus `g` (`χ = 2 − 2g`).
    #[must_use]
    pub fn genus(&self) -> u64 {
        ((2 - self.word.euler_characteristic()) / 2) as u64
    }

    /// The volume: the fibre's length `2πN` times the surface's area `2π|χ|`.
    #[must_use]
    pub fn volume(&self) -> f64 {
        4.0 * PI
            * PI
            * f64::from(self.sheets)
            * self.word.euler_characteristic().unsigned_abs() as f64
    }

    /// `H₁`, from the presentation: the side pairs' generators and the fibre's loop `z`
    /// (central); the vertex cycle's relation is the surface word (each generator once
    /// forwards and once backwards, so nothing when abelian) times `z^{−m/N}`, `m` its
    /// central turn ([`Self::euler_turns`], `±χ`): `Z^{2g} + Z/(|χ|/N)` (`Z/(2g − 2)` for
    /// `UT Σ_g`).
    #[must_use]
    pub fn homology(&self) -> crate::space::homology::Homology {
        let generators = 2 * self.genus() as usize;
        let n = i64::from(self.sheets);
        let relations: Vec<Vec<i128>> = self
            .euler_turns()
            .into_iter()
            .map(|m| {
                let mut row = vec![0; generators + 1];
                row[generators] = i128::from(-m / n);
                row
            })
            .collect();
        crate::space::homology::from_relations(&relations, generators + 1)
    }
}
