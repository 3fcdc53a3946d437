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
            _ => surface_systole(self, limit)?,
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

/// How far a surface isometry (a 4×4 matrix fixing `z`) moves the points of H² at least:
/// `cosh a = (tr − det)/2` of its 3×3 part (a translation, or a glide reflection with
/// `det = −1`); 0 for an elliptic one.
fn surface_displacement(h: &glam::DMat4) -> f64 {
    let m = glam::DMat3::from_cols(
        glam::DVec3::new(h.x_axis.x, h.x_axis.y, h.x_axis.w),
        glam::DVec3::new(h.y_axis.x, h.y_axis.y, h.y_axis.w),
        glam::DVec3::new(h.w_axis.x, h.w_axis.y, h.w_axis.w),
    );
    let det = m.determinant().signum();
    let trace = m.x_axis.x + m.y_axis.y + m.z_axis.z;
    let c = 0.5 * (trace - det);
    if c > 1.0 { c.acosh() } else { 0.0 }
}

/// The systole of a hyperbolic surface of the product: the shortest translation among the
/// elements of its group, enumerated breadth first by the side pairings while they move
/// the centre at most [`systole_search_radius`]. The products are taken in double-double:
/// in f64 a word's rounding grows like the product of its letters' sizes, and a relation's
/// partial products (which close up into the identity) would come out as tiny translations.
///
/// The breadth-first search finds every element within the radius: the polygon is the
/// Dirichlet domain of its centre `c` (each side is the bisector of `c` and the neighbour's
/// centre), so any `h ≠ 1` has a side pairing `s` with `d(c, h s c) < d(c, h c)`, a parent
/// nearer the centre.
fn surface_systole(space: &ProductSpace, limit: usize) -> Option<f64> {
    let inradius = space.polygon.inradius.to_f64();
    let glides = !space.word.orientable();
    systole_within(space, limit, |best| {
        systole_search_radius(best, inradius, glides)
    })
}

/// The systole, searching the elements that move the centre at most `radius_for(best)`,
/// `best` the shortest translation found so far.
fn systole_within(
    space: &ProductSpace,
    limit: usize,
    radius_for: impl Fn(f64) -> f64,
) -> Option<f64> {
    use crate::geometry::DdMat4;
    use crate::space::group::polish_isometry_dd;
    use crate::space::orbit::OrbitPoints;
    let g = Geometry::Hyperbolic;
    let moves: Vec<DdMat4> = space.polygon.sides.iter().map(|s| s.pairing).collect();
    let radius = |h: &glam::DMat4| g.distance(glam::DVec4::W, h.w_axis);
    // The generators' translations bound the systole from above.
    let mut best = moves
        .iter()
        .map(|m| surface_displacement(&m.round_f64()))
        .filter(|&a| a > 1e-9)
        .fold(f64::INFINITY, f64::min);
    let mut seen = OrbitPoints::new(g, 1e-7);
    seen.insert(glam::DVec4::W);
    let mut frontier = vec![DdMat4::IDENTITY];
    let mut count = 1usize;
    while !frontier.is_empty() {
        let reach = radius_for(best) + 1e-9;
        let mut next = Vec::new();
        for h in &frontier {
            for m in &moves {
                let e = polish_isometry_dd(g, &(*h * *m));
                let rounded = e.round_f64();
                if radius(&rounded) > reach || !seen.insert(rounded.w_axis) {
                    continue;
                }
                count += 1;
                if count > limit {
                    return None;
                }
                let a = surface_displacement(&rounded);
                if a > 1e-9 {
                    best = best.min(a);
                }
                next.push(e);
            }
        }
        frontier = next;
    }
    Some(best)
}

/// How far from the polygon's centre `c` the search for a closed geodesic of length at most
/// `length` must look, on a surface tiled by regular polygons of inradius `r`.
///
/// Every geodesic line comes within `r` of some polygon's centre: the discs of radius `r`
/// inscribed in the polygons touch at the sides' midpoints, and what they leave uncovered
/// is one bounded star round each vertex, joined to the next only at a midpoint, where the
/// one line that stays outside both touching discs is the side's own. So the axis of a
/// shortest element, conjugated to bring that centre to `c`, passes within `δ ≤ r` of `c`,
/// and an element translating by `a` along an axis at distance `δ` moves `c` by `d` with
/// `sinh(d/2) = cosh δ sinh(a/2)`, or for a glide reflection (which also flips `c` across
/// the axis) `cosh(d/2) = cosh δ cosh(a/2)`. This is `2r` less a little than the older
/// bound `a + 2R` (`R` the circumradius, much larger than `r` for many-sided polygons with
/// thin corners): a 52-gon's search visits hundreds of elements instead of tens of thousands.
fn systole_search_radius(length: f64, r: f64, glides: bool) -> f64 {
    let half = 0.5 * length;
    let translation = 2.0 * (r.cosh() * half.sinh()).asinh();
    if glides {
        translation.max(2.0 * (r.cosh() * half.cosh()).acosh())
    } else {
        translation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The search within the inradius bound finds the systole that the older, wider search
    /// (the systole plus twice the circumradius) finds, orientable words and not.
    #[test]
    fn the_narrower_systole_search_finds_the_same_systole() {
        for word in [
            "abABcdCD",
            "abABcdCDefEF",
            "aabbcc",
            "abcdABCD",
            "aabbccdd",
            "aabcBC",
        ] {
            let Some(Ok(ProductOrFlat::Product(space))) =
                product_space(&format!("surface-{word}-circle-2"))
            else {
                panic!("{word} is not a product");
            };
            let circumradius = space.polygon.circumradius.to_f64();
            let wide = systole_within(&space, 1_000_000, |best| best + 2.0 * circumradius).unwrap();
            let narrow = surface_systole(&space, 1_000_000).unwrap();
            assert!(
                (wide - narrow).abs() < 1e-9,
                "{word}: {narrow} against {wide}"
            );
        }
    }
}
