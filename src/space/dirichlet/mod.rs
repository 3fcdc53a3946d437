//! The Dirichlet domain of a group about the basepoint `o = (0, 0, 0, 1)`:
//! `D = {x : d(x, o) ≤ d(x, g·o) for every g}`, built as a [`Space`] whose faces are the
//! bisectors that bound it, each paired by the inverse of the element that made it.
//!
//! The method (`docs/groups.md`):
//! 1. Enumerate the group breadth first (products of the generators and their inverses),
//!    keeping the elements that move `o` at most a radius `r`; two elements are the same
//!    when they move `o` to the same point (an element other than the identity that fixes
//!    `o` is an error, as are distinct orbit points closer than [`SEPARATION`]).
//! 2. Cut a large box of the chart by the bisectors, nearest first; a bisector of an element
//!    that moves `o` by more than twice the circumradius `R` of the cut cell misses it, so
//!    the cut stops there. The enumeration radius grows until it is at least `2R`.
//! 3. The cell is validated by Poincaré's polyhedron theorem ([`Space::new`]): it is then a
//!    fundamental domain of the group its pairings generate. Each generator is walked back
//!    into the cell by the pairings; if one does not come back to the identity, the element
//!    it ends at was missed, is added, and the cut starts again. When every generator comes
//!    back, the pairings generate the whole group and the cell is its Dirichlet domain (it
//!    contains the true one and has the same volume).

mod equator;
use equator::equator_space;

use super::exact::{self, Dd3, ExactCell, ExactFace};
use super::group::{
    Generators, GroupError, parse_gen, polish_isometry, polish_isometry_dd, polish_isometry_fast,
};
use super::orbit::OrbitPoints;
use super::{MAX_FACES, Space};
use crate::geometry::{DdMat4, DdVec4, DoubleDouble, Geometry, ORIGIN, Real, max_abs_entry};
use glam::{DMat4, DVec3, DVec4};
use std::collections::HashMap;
use std::path::Path;

/// Orbit points closer than this (geodesic distance; for flat groups, relative to the
/// largest generator translation) but not equal are taken as a sign that the group is not
/// discrete.
pub const SEPARATION: f64 = 1e-4;

/// Orbit points closer than this are the same point (in H³, times `cosh d(o, p)`: the
/// rounding of a product of matrices grows with the size of their entries).
const SAME: f64 = 1e-9;

/// The most elements the enumeration keeps, by default.
pub const DEFAULT_MAX_ELEMENTS: usize = 50_000;

/// The largest enumeration radius: beyond it, orbit points of H³ (`cosh 10 ≈ 11000`) keep
/// too few digits to tell apart from their neighbours; the Dirichlet domains of the census
/// manifolds need about 6. Flat groups, scaled so that their largest generator translation
/// is 1, have long closed up by then.
const MAX_RADIUS: f64 = 10.0;

/// How many times the enumeration radius may grow before the domain is declared not to
/// close up.
const MAX_ATTEMPTS: usize = 12;

/// Half the side of the box of the chart that the bisectors cut: points at the box are at
/// distance `atan 1000 = π/2 − 0.001` in S³; the Klein ball fits in the unit box; flat groups
/// are scaled so that their largest generator translation is 1.
fn box_half_side(geometry: Geometry) -> f64 {
    match geometry {
        Geometry::Spherical => 1e3,
        Geometry::Euclidean => 1e3,
        Geometry::Hyperbolic => 1.0,
    }
}

/// Choices for building a Dirichlet domain.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirichletOptions {
    /// The centre of the domain, as a chart point (default: the origin of the chart).
    pub basepoint: Option<DVec3>,
    /// The most group elements to enumerate before giving up.
    pub max_elements: usize,
    /// Enumerate at least out to this distance from the basepoint (for flat groups, in units
    /// of the largest generator translation): a check that the domain does not change when
    /// more elements are tried. Ignored for the finite groups of S³, which are enumerated
    /// whole.
    pub min_radius: f64,
}

impl Default for DirichletOptions {
    fn default() -> Self {
        Self {
            basepoint: None,
            max_elements: DEFAULT_MAX_ELEMENTS,
            min_radius: 0.0,
        }
    }
}

/// One element of the group.
#[derive(Clone, Copy, Debug)]
struct Element {
    matrix: DMat4,
    /// Where it moves the basepoint.
    point: DVec4,
    /// `d(o, g·o)`.
    distance: f64,
    /// Length of the shortest word found for it.
    word: usize,
    /// The element it was found from and the move that made it (`parent · move`).
    from: Option<(usize, usize)>,
}

/// The elements found so far, found again by their orbit points.
struct Orbit {
    geometry: Geometry,
    elements: Vec<Element>,
    points: OrbitPoints,
}

impl Orbit {
    fn new(geometry: Geometry) -> Self {
        let mut orbit = Self {
            geometry,
            elements: Vec::new(),
            points: OrbitPoints::new(geometry, SEPARATION),
        };
        orbit.push(Element {
            matrix: DMat4::IDENTITY,
            point: ORIGIN,
            distance: 0.0,
            word: 0,
            from: None,
        });
        orbit
    }

    fn push(&mut self, e: Element) -> usize {
        let i = self.points.push(e.point);
        self.elements.push(e);
        i
    }

    /// The element whose orbit point is nearest `p`, if one is within [`SEPARATION`].
    fn nearest(&self, p: DVec4) -> Option<(usize, f64)> {
        self.points.nearest(p)
    }

    /// Adds `matrix` unless it is already known; `Ok(true)` when it is new.
    fn insert(
        &mut self,
        matrix: DMat4,
        word: usize,
        from: Option<(usize, usize)>,
    ) -> Result<bool, GroupError> {
        let point = matrix.w_axis;
        let distance = self.geometry.distance(ORIGIN, point);
        if let Some((i, d)) = self.nearest(point) {
            if d >= SAME * point.w.abs().max(1.0) {
                return Err(GroupError::NotDiscrete {
                    distance: d,
                    limit: SEPARATION,
                });
            }
            let known = self.elements[i].matrix;
            let size = 1.0 + max_abs_entry(&matrix.to_cols_array());
            if max_abs_entry(&(known - matrix).to_cols_array()) > 1e-6 * size {
                let what = if word <= 1 {
                    "a generator".to_string()
                } else {
                    format!("an element of the group (a product of {word} generators)")
                };
                return Err(GroupError::FixesBasepoint { what });
            }
            return Ok(false);
        }
        self.push(Element {
            matrix,
            point,
            distance,
            word,
            from,
        });
        Ok(true)
    }
}

/// Breadth-first enumeration of the elements that move `o` at most `radius` (every element
/// when `radius` is infinite, for the finite groups of S³).
fn enumerate(
    geometry: Geometry,
    moves: &[DMat4],
    radius: f64,
    limit: usize,
) -> Result<Orbit, GroupError> {
    let mut orbit = Orbit::new(geometry);
    let mut frontier = vec![0usize];
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for &e in &frontier {
            let (m, word) = (orbit.elements[e].matrix, orbit.elements[e].word);
            for (k, &g) in moves.iter().enumerate() {
                let product = polish_isometry_fast(geometry, m * g);
                if geometry.distance(ORIGIN, product.w_axis) > radius {
                    continue;
                }
                if orbit.insert(product, word + 1, Some((e, k)))? {
                    next.push(orbit.elements.len() - 1);
                    if orbit.elements.len() > limit {
                        return Err(GroupError::TooLarge { limit, radius });
                    }
                }
            }
        }
        frontier = next;
    }
    Ok(orbit)
}

/// The bisector of `o` and `p` as a chart half-space `n·x ≤ r` with `|n| = 1`, or `None`
/// when it lies at infinity in the chart (`p = −o` in S³).
fn bisector(geometry: Geometry, p: DVec4) -> Option<(DVec3, f64)> {
    let (n, r) = match geometry {
        Geometry::Spherical => (p.truncate(), 1.0 - p.w),
        Geometry::Euclidean => {
            let t = p.truncate() / p.w;
            (t, 0.5 * t.length_squared())
        }
        Geometry::Hyperbolic => (p.truncate(), p.w - 1.0),
    };
    let len = n.length();
    (len > 1e-12 * (1.0 + r.abs())).then(|| (n / len, r / len))
}

/// A convex polyhedron of the chart: its vertices, each with the planes it lies on.
struct Polyhedron {
    points: Vec<DVec3>,
    planes: Vec<Vec<u32>>,
}

/// Plane ids below this are the box's six sides.
const BOX_PLANES: u32 = 6;

impl Polyhedron {
    fn cube(l: f64) -> Self {
        let mut points = Vec::new();
        let mut planes = Vec::new();
        for i in 0..8u32 {
            let s = |bit: u32| if i & (1 << bit) != 0 { 1.0 } else { -1.0 };
            points.push(DVec3::new(s(0), s(1), s(2)) * l);
            // Plane 2a is the side +axis a, 2a + 1 the side −axis a.
            planes.push(
                (0..3)
                    .map(|a| 2 * a + u32::from(i & (1 << a) == 0))
                    .collect(),
            );
        }
        Self { points, planes }
    }

    /// Cuts by `n·x ≤ r`; whether anything was cut off.
    fn cut(&mut self, id: u32, n: DVec3, r: f64) -> bool {
        let eps = |x: DVec3| 1e-10 * (1.0 + x.length());
        let s: Vec<f64> = self.points.iter().map(|&x| n.dot(x) - r).collect();
        let out = |i: usize| s[i] > eps(self.points[i]);
        let inside = |i: usize| s[i] < -eps(self.points[i]);
        if !(0..s.len()).any(out) {
            return false;
        }
        let mut points = Vec::new();
        let mut planes: Vec<Vec<u32>> = Vec::new();
        let mut add = |x: DVec3, p: Vec<u32>, points: &mut Vec<DVec3>| {
            if let Some(k) = points
                .iter()
                .position(|&y: &DVec3| (y - x).length() < 1e-9 * (1.0 + x.length()))
            {
                for id in p {
                    if !planes[k].contains(&id) {
                        planes[k].push(id);
                    }
                }
            } else {
                points.push(x);
                planes.push(p);
            }
        };
        for i in 0..s.len() {
            if inside(i) {
                add(self.points[i], self.planes[i].clone(), &mut points);
            } else if !out(i) {
                let mut p = self.planes[i].clone();
                p.push(id);
                add(self.points[i], p, &mut points);
            }
        }
        for i in (0..s.len()).filter(|&i| inside(i)) {
            for j in (0..s.len()).filter(|&j| out(j)) {
                let shared: Vec<u32> = self.planes[i]
                    .iter()
                    .copied()
                    .filter(|p| self.planes[j].contains(p))
                    .collect();
                if shared.len() < 2 {
                    continue;
                }
                let t = s[i] / (s[i] - s[j]);
                let x = self.points[i] + (self.points[j] - self.points[i]) * t;
                let mut p = shared;
                p.push(id);
                add(x, p, &mut points);
            }
        }
        for p in &mut planes {
            p.sort_unstable();
        }
        self.points = points;
        self.planes = planes;
        true
    }

    /// Whether a side of the box is still a face (the cut cell is not bounded by bisectors).
    fn touches_box(&self) -> bool {
        (0..BOX_PLANES).any(|b| self.planes.iter().filter(|p| p.contains(&b)).count() >= 3)
    }

    /// The planes with three vertices or more: the faces.
    fn faces(&self) -> Vec<u32> {
        let mut count: HashMap<u32, usize> = HashMap::new();
        for p in &self.planes {
            for &id in p {
                *count.entry(id).or_default() += 1;
            }
        }
        let mut faces: Vec<u32> = count
            .into_iter()
            .filter(|&(id, c)| id >= BOX_PLANES && c >= 3)
            .map(|(id, _)| id)
            .collect();
        faces.sort_unstable();
        faces
    }
}

/// Geodesic distance from `o` of a chart point.
fn chart_radius(geometry: Geometry, x: DVec3) -> f64 {
    let l = x.length();
    match geometry {
        Geometry::Spherical => l.atan(),
        Geometry::Euclidean => l,
        Geometry::Hyperbolic => {
            if l < 1.0 {
                l.atanh()
            } else {
                f64::INFINITY
            }
        }
    }
}

/// The cell cut from the box by the bisectors of the orbit's elements, nearest first.
struct Cut {
    polyhedron: Polyhedron,
    /// Elements (indices into the orbit) whose bisectors are faces.
    faces: Vec<usize>,
    circumradius: f64,
}

fn cut_domain(orbit: &Orbit) -> Cut {
    let geometry = orbit.geometry;
    let mut order: Vec<usize> = (1..orbit.elements.len()).collect();
    order.sort_by(|&a, &b| {
        orbit.elements[a]
            .distance
            .total_cmp(&orbit.elements[b].distance)
    });
    let mut poly = Polyhedron::cube(box_half_side(geometry));
    let radius = |poly: &Polyhedron| {
        poly.points
            .iter()
            .map(|&x| chart_radius(geometry, x))
            .fold(0.0, f64::max)
    };
    let mut circumradius = radius(&poly);
    for &i in &order {
        let e = &orbit.elements[i];
        // The bisector lies at distance d/2 from o: beyond the cell once d/2 > R.
        if e.distance > 2.0 * circumradius * (1.0 + 1e-9) + 1e-12 {
            break;
        }
        let Some((n, r)) = bisector(geometry, e.point) else {
            continue;
        };
        if poly.cut(BOX_PLANES + i as u32, n, r) {
            circumradius = radius(&poly);
        }
    }
    let faces = poly
        .faces()
        .into_iter()
        .map(|id| (id - BOX_PLANES) as usize)
        .collect();
    Cut {
        polyhedron: poly,
        faces,
        circumradius,
    }
}

/// What stops a cut from becoming a space, before the validator sees it.
enum Attempt {
    Space(Box<Space>),
    /// Enumerate further (a larger radius, or this missed element added to the moves).
    Grow(Option<DMat4>),
}

/// The Dirichlet domain of the group generated by `generators`, validated as a space.
pub fn dirichlet_space(
    name: &str,
    description: &str,
    generators: &Generators,
    options: &DirichletOptions,
) -> Result<Space, GroupError> {
    let geometry = generators.geometry;
    let mut gens = generators.matrices.clone();
    if let Some(b) = options.basepoint {
        let point = match geometry {
            Geometry::Euclidean if b.is_finite() => Some(b.extend(1.0)),
            Geometry::Euclidean => None,
            _ => geometry.from_chart(b).ok(),
        }
        .ok_or(GroupError::BadBasepoint {
            point: b.to_array(),
            geometry: geometry.name(),
        })?;
        let t = geometry.translation_to(point);
        let t_inv = geometry.inverse(t);
        for g in &mut gens {
            *g = polish_isometry(geometry, t_inv * *g * t);
        }
    }
    // Flat groups are cut at the scale of their largest translation, and scaled back.
    let scale = if geometry == Geometry::Euclidean {
        gens.iter()
            .map(|g| g.w_axis.truncate().length())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE)
    } else {
        1.0
    };
    for g in &mut gens {
        if geometry == Geometry::Euclidean {
            g.w_axis = (g.w_axis.truncate() / scale).extend(1.0);
        }
    }
    let mut moves: Vec<DMat4> = Vec::new();
    for &g in &gens {
        moves.push(g);
        moves.push(polish_isometry(geometry, geometry.inverse(g)));
    }
    let reach = moves
        .iter()
        .map(|g| geometry.distance(ORIGIN, g.w_axis))
        .fold(0.0, f64::max);
    let finite = geometry == Geometry::Spherical;
    let mut radius = if finite {
        f64::INFINITY
    } else {
        2.0 * reach + 1.0
    };
    let mut last_error = None;
    // Whether some cut so far was bounded: if none was when the enumeration grows too
    // large, the domain does not close up.
    let mut ever_bounded = false;
    for _ in 0..MAX_ATTEMPTS {
        radius = radius.max(options.min_radius);
        if !finite && radius > MAX_RADIUS {
            return Err(GroupError::NotCocompact {
                radius: MAX_RADIUS * scale,
            });
        }
        let orbit = match enumerate(geometry, &moves, radius, options.max_elements) {
            Err(GroupError::TooLarge { .. }) if !ever_bounded => {
                return Err(GroupError::NotCocompact {
                    radius: radius * scale,
                });
            }
            other => other?,
        };
        let cut = cut_domain(&orbit);
        let bounded = !cut.polyhedron.touches_box()
            && (geometry != Geometry::Hyperbolic || cut.circumradius.is_finite());
        if !bounded {
            if finite {
                return equator_space(name, description, &orbit);
            }
            radius *= 1.6;
            continue;
        }
        ever_bounded = true;
        // Every element whose bisector can be a face moves o at most 2R, and reaching them
        // by products may pass a little further out.
        let needed = 2.0 * cut.circumradius + reach;
        if !finite && radius < needed {
            radius = needed * 1.05;
            continue;
        }
        let groups = Moves {
            geometry,
            moves: &moves,
            scale,
        };
        match attempt(name, description, &groups, &orbit, &cut, &gens) {
            Ok(Attempt::Space(space)) => return Ok(*space),
            Ok(Attempt::Grow(_)) if finite => {
                // Every element is known already: the numbers do not make a group.
                return Err(GroupError::Unclosed);
            }
            Ok(Attempt::Grow(missed)) => {
                if let Some(m) = missed {
                    moves.push(m);
                    moves.push(polish_isometry(geometry, geometry.inverse(m)));
                }
                radius *= 1.3;
            }
            Err(e) => {
                if finite {
                    return Err(e);
                }
                last_error = Some(e);
                radius *= 1.3;
            }
        }
    }
    Err(last_error.unwrap_or(GroupError::NotCocompact {
        radius: radius * scale,
    }))
}

/// The moves an enumeration multiplied by, for recomputing its elements in double-double.
struct Moves<'a> {
    geometry: Geometry,
    moves: &'a [DMat4],
    /// A flat group's cut scale (its translations are divided by it).
    scale: f64,
}

impl Moves<'_> {
    /// Element `i` of the orbit as the exact product of the moves that found it (each
    /// move's `f64` digits taken as given), polished to an isometry in double-double.
    fn exact(&self, orbit: &Orbit, i: usize) -> DdMat4 {
        let mut product = DdMat4::IDENTITY;
        let mut at = i;
        // parent · move, so the moves multiply on the right, last found last.
        let mut word = Vec::new();
        while let Some((parent, k)) = orbit.elements[at].from {
            word.push(k);
            at = parent;
        }
        for &k in word.iter().rev() {
            product = product * DdMat4::from_f64(self.moves[k]);
        }
        polish_isometry_dd(self.geometry, &product)
    }
}

/// The bisector of the origin and the model point `p` in double-double, as a unit normal
/// and chart offset (see [`bisector`]).
fn bisector_dd(geometry: Geometry, p: DdVec4) -> Option<(Dd3, DoubleDouble)> {
    let xyz = [p.0[0], p.0[1], p.0[2]];
    let one = DoubleDouble::ONE;
    let (n, r) = match geometry {
        Geometry::Spherical => (xyz, one - p.0[3]),
        Geometry::Euclidean => {
            let t = xyz.map(|x| x / p.0[3]);
            let half = DoubleDouble::new(0.5);
            (t, half * (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]))
        }
        Geometry::Hyperbolic => (xyz, p.0[3] - one),
    };
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    (len.to_f64() > 1e-12 * (1.0 + r.abs().to_f64())).then(|| (n.map(|x| x / len), r / len))
}

/// Makes the space of a bounded cut, and checks that its pairings generate the group.
///
/// The cell's numbers are computed in double-double from the moves' digits and rounded
/// once ([`Space::from_exact`]): each face pairing is the exact product of the moves along
/// the word that found it, polished, and each face the bisector of its exact orbit point.
fn attempt(
    name: &str,
    description: &str,
    moves: &Moves,
    orbit: &Orbit,
    cut: &Cut,
    gens: &[DMat4],
) -> Result<Attempt, GroupError> {
    let (geometry, scale) = (moves.geometry, moves.scale);
    if cut.faces.len() > MAX_FACES {
        return Err(GroupError::TooManyFaces {
            count: cut.faces.len(),
            max: MAX_FACES,
        });
    }
    let mut faces = Vec::with_capacity(cut.faces.len());
    for &i in &cut.faces {
        let e = &orbit.elements[i];
        let inverse = polish_isometry(geometry, geometry.inverse(e.matrix));
        let Some((j, _)) = orbit.nearest(inverse.w_axis) else {
            return Ok(Attempt::Grow(None));
        };
        let Some(partner) = cut.faces.iter().position(|&f| f == j) else {
            return Ok(Attempt::Grow(None));
        };
        let element = moves.exact(orbit, i);
        let Some((normal, offset)) = bisector_dd(geometry, element.0[3]) else {
            return Ok(Attempt::Grow(None));
        };
        let mut pairing = polish_isometry_dd(geometry, &exact::inverse(geometry, &element));
        let s = DoubleDouble::new(scale);
        if geometry == Geometry::Euclidean {
            for x in &mut pairing.0[3].0[..3] {
                *x = *x * s;
            }
        }
        faces.push(ExactFace {
            normal,
            offset: offset * s,
            partner,
            pairing,
        });
    }
    let space = Space::from_exact(name, description, ExactCell { geometry, faces })?;
    // Walk each generator's image of o back into the cell by the pairings.
    for &g in gens {
        let mut g = g;
        if geometry == Geometry::Euclidean {
            g.w_axis = (g.w_axis.truncate() * scale).extend(1.0);
        }
        let mut element = g;
        for _ in 0..10_000 {
            let x = element.w_axis;
            let (f, s) = space
                .faces()
                .iter()
                .enumerate()
                .map(|(f, face)| {
                    let x = if geometry == Geometry::Spherical {
                        x
                    } else {
                        x / x.w
                    };
                    (f, face.covector.dot(x))
                })
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((0, f64::NEG_INFINITY));
            if s <= 1e-9 {
                break;
            }
            element = polish_isometry_fast(geometry, space.faces()[f].pairing * element);
        }
        let d = geometry.distance(ORIGIN, element.w_axis);
        if d > 1e-7
            * if geometry == Geometry::Euclidean {
                scale
            } else {
                1.0
            }
        {
            let mut missed = element;
            if geometry == Geometry::Euclidean {
                missed.w_axis = (missed.w_axis.truncate() / scale).extend(1.0);
            }
            return Ok(Attempt::Grow(Some(missed)));
        }
    }
    Ok(Attempt::Space(Box::new(space)))
}

/// Reads a `.gen` file and builds the Dirichlet domain of its group.
pub fn load_gen_file(path: &Path, options: &DirichletOptions) -> Result<Space, String> {
    let name = path.display().to_string();
    let text = crate::files::read_text(path, crate::files::MAX_SPACE_FILE_BYTES)
        .map_err(|e| format!("cannot read generator file {name}: {e}"))?;
    let file = parse_gen(&text).map_err(|e| format!("generator file {name}: {e}"))?;
    let stem = path
        .file_stem()
        .map_or_else(|| name.clone(), |s| s.to_string_lossy().into_owned());
    let description = file.comments.first().cloned().unwrap_or_default();
    space_from_matrices(&stem, &description, &file.matrices, options)
        .map_err(|e| format!("generator file {name}: {e}"))
}

/// The space of the group generated by `matrices` (column-vector convention).
pub fn space_from_matrices(
    name: &str,
    description: &str,
    matrices: &[DMat4],
    options: &DirichletOptions,
) -> Result<Space, GroupError> {
    let generators = Generators::new(matrices)?;
    dirichlet_space(name, description, &generators, options)
}
