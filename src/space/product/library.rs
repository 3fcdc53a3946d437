//! Product spaces by id: `surface-WORD-circle-L` (with an optional `-turn-P`) and the
//! library's aliases; a flat word makes the flat space it is (E²×R is E³), built and
//! validated as every constant-curvature cell is.

use super::{ProductError, ProductSpace};
use crate::geometry::{DoubleDouble, Geometry, Real};
use crate::space::Space;
use crate::space::exact::{self, ExactCell, ExactFace};
use crate::space::homology::{Homology, relations_homology};
use crate::space::surface::{Polygon, SurfaceWord, turn};

/// A named product space of the library.
#[derive(Clone, Copy, Debug)]
pub struct ProductAlias {
    /// Its id.
    pub id: &'static str,
    /// The surface's word.
    pub word: &'static str,
    /// The circle's length.
    pub length: f64,
    /// The turn's order (1: none).
    pub turn: u32,
    /// One line about it.
    pub summary: &'static str,
}

/// The product spaces `curved-spaces list` shows by name.
pub const PRODUCT_ALIASES: &[ProductAlias] = &[
    ProductAlias {
        id: "bitorus-circle",
        word: "abABcdCD",
        length: 2.0,
        turn: 1,
        summary: "H²×R: the genus-2 surface (a 45° octagon) times a circle of length 2",
    },
    ProductAlias {
        id: "bitorus-circle-turn",
        word: "abABcdCD",
        length: 2.0,
        turn: 2,
        summary: "H²×R: the genus-2 surface times a circle, turned by a half turn once round",
    },
    ProductAlias {
        id: "genus-three-circle",
        word: "abABcdCDefEF",
        length: 2.0,
        turn: 1,
        summary: "H²×R: the genus-3 surface (a 30° dodecagon) times a circle of length 2",
    },
    ProductAlias {
        id: "crosscaps-circle",
        word: "aabbcc",
        length: 2.0,
        turn: 1,
        summary: "H²×R: the non-orientable surface of genus 3 (a 120° hexagon) times a circle",
    },
    ProductAlias {
        id: "sphere-circle",
        word: "aA",
        length: std::f64::consts::PI,
        turn: 1,
        summary: "S²×R: S²×S¹, the sphere times a circle of length π",
    },
    ProductAlias {
        id: "sphere-circle-turn",
        word: "aA",
        length: std::f64::consts::PI,
        turn: 4,
        summary: "S²×R: the sphere times a circle, turned by a quarter turn once round",
    },
    ProductAlias {
        id: "projective-plane-circle",
        word: "aa",
        length: std::f64::consts::PI,
        turn: 1,
        summary: "S²×R: the projective plane (a hemisphere) times a circle of length π",
    },
];

/// What an id names among the product spaces: a product space, a flat space (a flat word),
/// or an error naming what is wrong with the id's parts. `None` when the id is not of
/// that form.
pub fn product_space(id: &str) -> Option<Result<ProductOrFlat, String>> {
    let (word, length, turn) = match PRODUCT_ALIASES.iter().find(|a| a.id == id) {
        Some(a) => (a.word.to_string(), a.length, a.turn),
        None => match parse_id(id)? {
            Ok(parts) => parts,
            Err(e) => return Some(Err(e)),
        },
    };
    Some(build(id, &word, length, turn).map_err(|e| format!("{id}: {e}")))
}

/// A product space, or the flat space a flat word makes.
#[derive(Clone, Debug)]
pub enum ProductOrFlat {
    /// H²×R or S²×R.
    Product(Box<ProductSpace>),
    /// E²×R = E³, as a constant-curvature space.
    Flat(Box<Space>),
}

fn build(id: &str, word: &str, length: f64, turn: u32) -> Result<ProductOrFlat, String> {
    match ProductSpace::new(id, word, length, turn) {
        Ok(space) => Ok(ProductOrFlat::Product(Box::new(space))),
        Err(ProductError::Flat { .. }) => {
            flat_space(id, word, length, turn).map(|s| ProductOrFlat::Flat(Box::new(s)))
        }
        Err(e) => Err(e.to_string()),
    }
}

/// `surface-WORD-circle-L[-turn-P]` into its parts; `None` when `id` is not of that form.
fn parse_id(id: &str) -> Option<Result<(String, f64, u32), String>> {
    let rest = id.strip_prefix("surface-")?;
    let usage = "a product space is surface-WORD-circle-L or surface-WORD-circle-L-turn-P \
                 (WORD one letter per side, e.g. abABcdCD; L a positive length; P a whole \
                 number)";
    let Some((word, rest)) = rest.split_once("-circle-") else {
        return Some(Err(format!("{id}: {usage}")));
    };
    let (length, turn) = match rest.split_once("-turn-") {
        Some((l, p)) => (l, Some(p)),
        None => (rest, None),
    };
    let length: f64 = match length.parse() {
        Ok(l) => l,
        Err(_) => {
            return Some(Err(format!(
                "{id}: the length {length:?} is not a number; {usage}"
            )));
        }
    };
    let turn: u32 = match turn.map(str::parse) {
        None => 1,
        Some(Ok(p)) => p,
        Some(Err(_)) => {
            return Some(Err(format!(
                "{id}: the turn {:?} is not a whole number; {usage}",
                turn.unwrap_or_default()
            )));
        }
    };
    Some(Ok((word.to_string(), length, turn)))
}

/// A flat word times a circle: the polygon's sides times the fibre and the two slices
/// `z = ±L/2`, glued by the polygon's pairings and by the translation by `L` with the
/// turn, as a constant-curvature space built in double-double.
fn flat_space(id: &str, word: &str, length: f64, turn_order: u32) -> Result<Space, String> {
    let parsed = SurfaceWord::parse(word).map_err(|e| e.to_string())?;
    let n = parsed.side_count();
    if !(1..=super::MAX_TURN).contains(&turn_order) {
        return Err(ProductError::BadTurn(turn_order).to_string());
    }
    if turn_order > 1 && !parsed.turn_is_symmetry(turn_order) {
        return Err(ProductError::TurnNotSymmetry {
            turn: turn_order,
            word: word.to_string(),
            sides: n,
        }
        .to_string());
    }
    if !super::valid_length(length) {
        return Err(ProductError::BadLength(length).to_string());
    }
    let polygon = Polygon::of(&parsed);
    let mut faces: Vec<ExactFace> = polygon.sides.clone();
    let half = DoubleDouble::new(length) * DoubleDouble::new(0.5);
    let z = DoubleDouble::ZERO;
    let one = DoubleDouble::ONE;
    // Top: (p, z) ↦ (R⁻¹ p, z − L); bottom its inverse.
    let r_inv = turn(-2, i64::from(turn_order));
    let shift = |dz: DoubleDouble| exact::affine(exact::identity3(), [z, z, dz]);
    let up = shift(-DoubleDouble::new(length)) * r_inv;
    let down = exact::inverse(Geometry::Euclidean, &up);
    faces.push(ExactFace {
        normal: [z, z, one],
        offset: half,
        partner: n + 1,
        pairing: up,
    });
    faces.push(ExactFace {
        normal: [z, z, -one],
        offset: half,
        partner: n,
        pairing: down,
    });
    let description = format!(
        "{} ({word}) times a circle of length {length}{}: a flat space",
        parsed.common_name(),
        if turn_order > 1 {
            format!(", turned by 2π/{turn_order} once round it")
        } else {
            String::new()
        }
    );
    Space::from_exact(
        id,
        description,
        ExactCell {
            geometry: Geometry::Euclidean,
            faces,
        },
    )
    .map_err(|e| e.to_string())
}

impl ProductSpace {
    /// The first homology: generators the letters and the circle, relations each vertex
    /// cycle of the polygon (its crossings add up to zero) and the turn (it carries each
    /// side's generator to the turned side's).
    #[must_use]
    pub fn homology(&self) -> Homology {
        let word = &self.word;
        let letters = word.letter_generators().len();
        let generators = letters + 1;
        let mut relations = Vec::new();
        // The sphere's two sides are glued by the identity: its vertex cycles say a = 0.
        {
            for crossed in &word.cycle_crossings {
                let mut row = vec![0i128; generators];
                for &side in crossed {
                    let (g, sign) = word.generator_of(side);
                    row[g] += sign;
                }
                relations.push(row);
            }
            let n = word.side_count();
            let p = self.turn as usize;
            if p > 1 {
                let step = n / p;
                for &first in &word.letter_generators() {
                    let mut row = vec![0i128; generators];
                    let (g, s) = word.generator_of(first);
                    let (h, t) = word.generator_of((first + step) % n);
                    row[g] -= s;
                    row[h] += t;
                    relations.push(row);
                }
            }
        }
        relations_homology(&relations, generators)
    }

    /// The injectivity radius: half the shortest closed geodesic, and at most π in S²×R
    /// (where geodesics along the surface meet their conjugate points). A closed geodesic
    /// is the axis of a deck transformation `(h, z ↦ z + mL)`; its length is
    /// `√(a(h)² + (mL)²)` with `a(h)` how far `h` moves the surface's points at least. With
    /// `m ≠ 0` the shortest is the fibre through the centre (the turn fixes it), `L`; with
    /// `m = 0` it is the surface's systole, found among the surface group's elements that
    /// move the centre at most the systole's bound plus twice the circumradius (a shortest
    /// element has a conjugate whose axis meets the cell). `None` when more than `limit`
    /// elements would be needed.
    #[must_use]
    pub fn injectivity_radius(&self, limit: usize) -> Option<f64> {
        let g = self.base();
        let l = self.length;
        let systole = match g {
            Geometry::Spherical if self.hemisphere() => std::f64::consts::PI,
            Geometry::Spherical => f64::INFINITY,
            _ => crate::space::surface::systole(&self.word, &self.polygon, limit)?,
        };
        let shortest = systole.min(l);
        let conjugate = if g == Geometry::Spherical {
            std::f64::consts::PI
        } else {
            f64::INFINITY
        };
        Some((0.5 * shortest).min(conjugate))
    }

    /// The surface's Euler characteristic.
    #[must_use]
    pub fn euler_characteristic(&self) -> i64 {
        self.word.euler_characteristic()
    }

    /// A length of the cell's size: the smaller of the polygon's inradius and half the
    /// circle. Walking speeds, eye distances and flight keys' positions are in this unit.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.base_inradius().min(0.5 * self.length)
    }

    /// The inradius of the surface's polygon (its distance from the centre to a side; π for
    /// the sphere, π/2 for the hemisphere).
    #[must_use]
    pub fn base_inradius(&self) -> f64 {
        if self.polygon.sides.is_empty() {
            std::f64::consts::PI
        } else {
            self.polygon.inradius.to_f64()
        }
    }
}
