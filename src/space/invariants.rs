//! Invariants computed from a space's cell and pairings (never typed in): volume, radii,
//! groups, closed geodesics, injectivity radius.

use super::Space;
use super::orbit::OrbitPoints;
use crate::geometry::{Geometry, ORIGIN, max_abs_entry};
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::collections::{BTreeMap, HashMap, VecDeque};

/// Two elements of a deck-group walk are one when they move the centre less than this apart
/// (orbit points of a manifold or orbifold are at least twice the inradius apart).
const SAME_ORBIT_POINT: f64 = 1e-5;

/// An element met again among the axes found (a manifold's group acts freely, so its orbit
/// point names it).
const SAME_AXIS_ELEMENT: f64 = 1e-7;

/// The inradius as a length to size and place things by, at most `cap` in the curved
/// geometries (where the chart or the curvature bounds what fits: S³'s chart reaches only
/// π/2, and the 3-sphere's inradius is π). A flat cell has no length of its own, so there
/// it is the inradius at any size: a cell scaled by 16 gets a scene scaled by 16.
#[must_use]
pub fn inradius_at_most(space: &Space, cap: f64) -> f64 {
    let r = inradius(space);
    if space.geometry == Geometry::Euclidean {
        r
    } else {
        r.min(cap)
    }
}

/// Distance from the centre (chart origin) to the nearest face: the radius of the largest
/// ball about the centre inside the cell.
#[must_use]
pub fn inradius(space: &Space) -> f64 {
    if space.reaches_equator() {
        // Faces as great spheres; the 3-sphere itself has none and contains the ball of
        // radius π.
        return (0..space.faces.len())
            .map(|f| -space.face_distance(f, ORIGIN))
            .fold(std::f64::consts::PI, f64::min);
    }
    // In a space of several cells, the faces of their union (the seams between cells are
    // inside it): the distance to the nearest of their planes that faces the centre, the
    // inradius wherever the union is convex about the centre (as in `torus-two-cells`).
    let multi = space.cells.len() > 1;
    space
        .faces
        .iter()
        .enumerate()
        .filter(|(i, f)| !multi || (!space.is_seam(*i) && f.offset > 0.0))
        .map(|(_, f)| space.geometry.distance_from_ratio(f.offset, 1.0))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from the centre to the farthest vertex.
#[must_use]
pub fn circumradius(space: &Space) -> f64 {
    if space.reaches_equator() {
        // A lens or a hemisphere reaches the great circle or sphere at π/2; the 3-sphere,
        // the antipode.
        return if space.faces.is_empty() {
            std::f64::consts::PI
        } else {
            std::f64::consts::FRAC_PI_2
        };
    }
    (0..space.vertices.len())
        .map(|v| space.geometry.distance(ORIGIN, space.vertex_point(v)))
        .fold(0.0, f64::max)
}

/// The common length of all edges, if they have one (to 1e-9 relative).
#[must_use]
pub fn edge_length(space: &Space) -> Option<f64> {
    if space.edges.is_empty() {
        return None;
    }
    let (lo, hi) = space
        .edges
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), e| {
            (lo.min(e.length), hi.max(e.length))
        });
    (hi - lo <= 1e-9 * hi).then_some(hi)
}

/// Gauss–Legendre nodes and weights on [0, 1] (Newton on the Legendre recurrence).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / dp;
                x -= step;
                if step.abs() < 1e-16 {
                    break;
                }
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            ((1.0 - x) / 2.0, w / 2.0)
        })
        .collect()
}

/// Volume of the cell (= of the space).
///
/// In the chart the volume element is `(1 + κ|x|²)⁻² d³x`. Integrating radially from the
/// centre in closed form, `V = Σ_faces ∫_face g(|x|) r_f / |x|³ dA` with
/// `g(R) = ∫₀^R ρ² (1 + κρ²)⁻² dρ` = `R³/3`, `½(atan R − R/(1+R²))`, `½(R/(1−R²) − atanh R)`.
/// Each face is split into triangles, each triangle into 16, and each of those integrated
/// with a 16×16 Gauss–Legendre rule on the collapsed square: deterministic, and converged to
/// about 1e-13 for the seed spaces (tested against exact volumes).
#[must_use]
pub fn volume(space: &Space) -> f64 {
    if let Some(order) = space.equator_order {
        // The cell is the Dirichlet domain of a group of that order (certified when built).
        return 2.0 * std::f64::consts::PI * std::f64::consts::PI / order as f64;
    }
    let g = space.geometry;
    if g == Geometry::Euclidean {
        return flat_volume(space);
    }
    let radial = |r: f64| match g {
        Geometry::Euclidean => r * r * r / 3.0,
        Geometry::Spherical => 0.5 * (r.atan() - r / (1.0 + r * r)),
        Geometry::Hyperbolic => 0.5 * (r / (1.0 - r * r) - r.atanh()),
    };
    let rule = gauss_legendre(16);
    let mut total = 0.0;
    for face in &space.faces {
        let corners: Vec<DVec3> = face.vertices.iter().map(|&v| space.vertices[v]).collect();
        let centre = corners.iter().sum::<DVec3>() / corners.len() as f64;
        for k in 0..corners.len() {
            let mut triangles = vec![[centre, corners[k], corners[(k + 1) % corners.len()]]];
            for _ in 0..2 {
                triangles = triangles
                    .iter()
                    .flat_map(|&[a, b, c]| {
                        let (ab, bc, ca) = ((a + b) / 2.0, (b + c) / 2.0, (c + a) / 2.0);
                        [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
                    })
                    .collect();
            }
            for [a, b, c] in triangles {
                let area2 = (b - a).cross(c - b).length();
                for &(u, wu) in &rule {
                    for &(w, ww) in &rule {
                        let x = a + u * (b - a) + u * w * (c - b);
                        let r = x.length();
                        total += wu * ww * u * area2 * radial(r) * face.offset / (r * r * r);
                    }
                }
            }
        }
    }
    total
}

/// A flat cell's volume in closed form: the pyramids from the origin over the faces,
/// `V = ⅓ Σ r_f A_f` (exact up to rounding at any scale: nothing is raised past the third
/// power of the cell's size). Infinite only where the volume itself exceeds `f64`.
fn flat_volume(space: &Space) -> f64 {
    // Computed at unit size (a power of two, exact) so that no product overflows.
    let largest = space
        .vertices
        .iter()
        .map(|v| v.abs().max_element())
        .fold(0.0_f64, f64::max);
    let scale = super::power_of_two_near(largest).unwrap_or(1.0);
    let unit: f64 = space
        .faces
        .iter()
        .map(|face| {
            let corners: Vec<DVec3> = face
                .vertices
                .iter()
                .map(|&v| space.vertices[v] / scale)
                .collect();
            let Some(&first) = corners.first() else {
                return 0.0;
            };
            let area: f64 = corners
                .windows(2)
                .skip(1)
                .map(|w| 0.5 * (w[0] - first).cross(w[1] - first).length())
                .sum();
            face.offset / scale * area / 3.0
        })
        .sum();
    unit * scale * scale * scale
}

/// The order of the group generated by the linear parts of a flat space's pairings
/// (its holonomy group), or `None` for other geometries.
#[must_use]
pub fn holonomy_order(space: &Space) -> Option<usize> {
    if space.geometry != Geometry::Euclidean {
        return None;
    }
    let key = |m: &DMat3| m.to_cols_array().map(|x| (x * 1e6).round() as i64);
    let generators: Vec<DMat3> = space
        .faces
        .iter()
        .map(|f| DMat3::from_mat4(f.pairing))
        .collect();
    let mut seen: HashMap<[i64; 9], DMat3> = HashMap::new();
    let mut queue = VecDeque::from([DMat3::IDENTITY]);
    seen.insert(key(&DMat3::IDENTITY), DMat3::IDENTITY);
    while let Some(m) = queue.pop_front() {
        for g in &generators {
            let next = m * *g;
            if seen.len() > 10_000 {
                return None;
            }
            if seen.insert(key(&next), next).is_none() {
                queue.push_back(next);
            }
        }
    }
    Some(seen.len())
}

/// Decides cheaply whether an image `h(cell)` may come within `gap` of the cell, never
/// answering no for one that does. First the orbit bound `d(D, hD) ≥ d(o, ho) − 2R`
/// (`R` the circumradius), then separating planes: if every vertex of `h(D)` lies beyond
/// one face plane of `D` by more than `gap` (or every vertex of `h⁻¹(D)` does), so does all
/// of `h(D)`.
struct Separation {
    geometry: Geometry,
    vertices: Vec<DVec4>,
    /// Face covectors scaled to unit length in the dual form, so `N·X` is `S(distance)`.
    planes: Vec<DVec4>,
    circumradius: f64,
}

impl Separation {
    fn new(space: &Space) -> Self {
        let k = space.geometry.kappa();
        Self {
            geometry: space.geometry,
            vertices: (0..space.vertices.len())
                .map(|v| space.vertex_point(v))
                .collect(),
            planes: space
                .faces
                .iter()
                .filter(|_| space.cells.len() == 1)
                .map(|f| {
                    let n = f.covector;
                    n / (n.truncate().length_squared() + k * n.w * n.w).sqrt()
                })
                .collect(),
            circumradius: circumradius(space),
        }
    }

    fn may_be_within(&self, h: DMat4, gap: f64) -> bool {
        let g = self.geometry;
        if g.distance(ORIGIN, h * ORIGIN) - 2.0 * self.circumradius > gap {
            return false;
        }
        // N·X for a unit X is sin, the distance itself, or sinh of the signed distance.
        let threshold = match g {
            Geometry::Spherical => gap.min(std::f64::consts::FRAC_PI_2).sin(),
            Geometry::Euclidean => gap,
            Geometry::Hyperbolic => gap.sinh(),
        };
        // A cell without vertices (one reaching π/2 in S³) has no separating planes to test,
        // and the union of several cells need not lie behind each face plane.
        if self.vertices.is_empty() || self.planes.is_empty() {
            return true;
        }
        for m in [h, g.inverse(h)] {
            let images: Vec<DVec4> = self
                .vertices
                .iter()
                .map(|&x| g.project_point(m * x))
                .collect();
            for n in &self.planes {
                if images.iter().all(|&x| n.dot(x) > threshold) {
                    return false;
                }
            }
        }
        true
    }
}

/// Every element `h` of the deck group (products of pairings) whose image cell may come
/// within `gap` of the cell (a superset: no element that does is missed), up to `limit`
/// elements; `None` if there are more.
#[must_use]
pub fn elements_near(space: &Space, gap: f64, limit: usize) -> Option<Vec<DMat4>> {
    let generators: Vec<DMat4> = space.faces.iter().map(|f| f.pairing).collect();
    let separation = Separation::new(space);
    let mut seen = OrbitPoints::new(space.geometry, SAME_ORBIT_POINT);
    seen.push(ORIGIN);
    let mut out = vec![DMat4::IDENTITY];
    let mut queue = VecDeque::from([DMat4::IDENTITY]);
    while let Some(m) = queue.pop_front() {
        for generator in &generators {
            let next = m * *generator;
            if !seen.insert(next * ORIGIN) {
                continue;
            }
            if !separation.may_be_within(next, gap) {
                continue;
            }
            out.push(next);
            if out.len() > limit {
                return None;
            }
            queue.push_back(next);
        }
    }
    Some(out)
}

/// The order of a spherical space's deck group, enumerated (`None` for other geometries).
#[must_use]
pub fn group_order(space: &Space) -> Option<usize> {
    (space.geometry == Geometry::Spherical)
        .then(|| elements_near(space, f64::INFINITY, 100_000).map(|e| e.len()))
        .flatten()
}

/// The smallest distance `min_x d(x, h x)` an isometry moves a point (its translation length).
///
/// E³: `|P b|`, `P` the projector onto the fixed vectors of the linear part `A`
/// (the average of `A^k`, `k < 12`, exact for crystallographic holonomy). S³ and H³ (for
/// orientation-preserving `h`): from `tr h = 2(a + b)` and `tr h² = 4(a² + b²) − 4` with
/// `{a, b} = {cos θ₁, cos θ₂}` (S³: displacement `acos max(a,b)`) or `{cosh ℓ, cos θ}`
/// (H³: `ℓ = acosh max(a,b)`).
#[must_use]
pub fn displacement(geometry: Geometry, h: DMat4) -> f64 {
    match geometry {
        Geometry::Euclidean => {
            let a = DMat3::from_mat4(h);
            let mut power = DMat3::IDENTITY;
            let mut sum = DMat3::ZERO;
            for _ in 0..12 {
                sum += power;
                power *= a;
            }
            ((sum * (1.0 / 12.0)) * h.w_axis.truncate()).length()
        }
        _ => {
            let t1 = h.x_axis.x + h.y_axis.y + h.z_axis.z + h.w_axis.w;
            let h2 = h * h;
            let t2 = h2.x_axis.x + h2.y_axis.y + h2.z_axis.z + h2.w_axis.w;
            let sum = t1 / 2.0;
            let squares = t2 / 4.0 + 1.0;
            let diff = (2.0 * squares - sum * sum).max(0.0).sqrt();
            let big = (sum + diff) / 2.0;
            match geometry {
                Geometry::Spherical => big.min(1.0).acos(),
                _ => big.max(1.0).acosh(),
            }
        }
    }
}

/// The most group elements the invariants enumerate before giving up on a quantity.
pub const MAX_ENUMERATED: usize = 500_000;

/// Injectivity radius of a manifold: half its shortest closed geodesic (`None` for orbifolds,
/// or when more than [`MAX_ENUMERATED`] elements would be needed).
#[must_use]
pub fn injectivity_radius(space: &Space) -> Option<f64> {
    if !space.manifold {
        return None;
    }
    if space.equator_order == Some(1) {
        // The 3-sphere: half its shortest closed geodesic, a great circle.
        return Some(std::f64::consts::PI);
    }
    let g = space.geometry;
    // Any pairing bounds the systole from above; the shortest element's axis, moved to meet
    // the cell, moves it by at most that much.
    let bound = space
        .faces
        .iter()
        .enumerate()
        .filter(|(i, _)| !space.is_seam(*i))
        .map(|(_, f)| g.distance(ORIGIN, f.pairing * ORIGIN))
        .fold(f64::INFINITY, f64::min);
    let elements = elements_near(space, bound + 1e-9, MAX_ENUMERATED)?;
    elements
        .iter()
        .skip(1)
        .map(|&h| displacement(g, h))
        .min_by(f64::total_cmp)
        .map(|s| s / 2.0)
}

/// A closed geodesic length with the number of distinct (unoriented, primitive) closed
/// geodesics of that length.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct GeodesicLength {
    /// The length.
    pub length: f64,
    /// Distinct unoriented primitive closed geodesics of this length.
    pub count: usize,
}

/// The fixed point at infinity that `h` pushes points towards (chart point on the unit
/// sphere), by repeated squaring.
fn attracting_point(h: DMat4) -> DVec3 {
    let mut m = h;
    for _ in 0..12 {
        m = m * m;
        let scale = max_abs_entry(&m.to_cols_array());
        m *= 1.0 / scale;
    }
    let p = m * ORIGIN;
    p.truncate() / p.w
}

/// The primitive closed geodesics of a hyperbolic manifold up to `max_length`, grouped by
/// length (to 1e-6), computed from the group: closed geodesics are the conjugacy classes of
/// primitive elements up to inversion, and their lengths the translation lengths of the
/// elements (from the traces, [`displacement`]).
///
/// Every class has members whose axes meet the cell; such a member moves the cell by at
/// most its length, so [`elements_near`] finds them all. The members whose axes meet the
/// cell (or pass within 1e-7 of it) are joined into classes by conjugating with the face
/// pairings (an axis leaving the cell through a face continues as the axis of the
/// conjugate by that face's pairing) and with their inverses; a member that is the `k`-th
/// power of another is not primitive. No ray is traced, so axes through edges and vertices
/// count like any other.
///
/// Empty for spaces other than hyperbolic manifolds; `None` when more than
/// [`MAX_ENUMERATED`] elements would have to be enumerated (a cell with very short closed
/// geodesics).
#[must_use]
pub fn closed_geodesics(space: &Space, max_length: f64) -> Option<Vec<GeodesicLength>> {
    let axes = axes_meeting_cell(space, max_length)?;
    let n = axes.elements.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let find = |m: DMat4| axes.find(m);
    let pairings: Vec<(DMat4, DMat4)> = space
        .faces
        .iter()
        .map(|f| (f.pairing, space.faces[f.partner].pairing))
        .collect();
    let mut primitive = vec![true; n];
    for i in 0..n {
        let (h, length) = (axes.elements[i], axes.lengths[i]);
        let mut join = |j: usize| {
            let (a, b) = (
                super::validate::union_find_root(&mut parent, i),
                super::validate::union_find_root(&mut parent, j),
            );
            parent[a.max(b)] = a.min(b);
        };
        if let Some(j) = find(space.geometry.inverse(h)) {
            join(j);
        }
        for &(p, p_inv) in &pairings {
            if let Some(j) = find(p * h * p_inv) {
                join(j);
            }
        }
        let mut power = h;
        for k in 2.. {
            if k as f64 * length > max_length + 1e-6 {
                break;
            }
            power *= h;
            if let Some(j) = find(power) {
                primitive[j] = false;
            }
        }
    }
    let mut class_length: BTreeMap<usize, f64> = BTreeMap::new();
    for (i, &is_primitive) in primitive.iter().enumerate() {
        let root = super::validate::union_find_root(&mut parent, i);
        if is_primitive && axes.lengths[i] <= max_length + 1e-9 {
            class_length.entry(root).or_insert(axes.lengths[i]);
        }
    }
    let mut lengths: Vec<f64> = class_length.into_values().collect();
    lengths.sort_by(f64::total_cmp);
    Some(group_lengths(&lengths))
}

/// The same counts as [`closed_geodesics`] by an independent route, without conjugacy
/// classes: the axes of the members of a class cut the closed geodesic into the pieces that
/// lie in the cell, so their chords in the cell add up to its length `ℓ` (twice, counting
/// each element's inverse). A chord in a face is shared by the two cells on its sides, and
/// one along an edge by the cells around it, so each is weighted by one over that number.
/// The powers `h^k` of a geodesic's element have the same axes; so, with `C(λ)` half the
/// weighted chord sum of all elements of length `λ`, the primitive count is
/// `n(λ) = (C(λ) − Σ_{k ≥ 2} (λ/k) n(λ/k)) / λ`. Returned as real numbers: that they are
/// whole is part of the check.
#[must_use]
pub fn closed_geodesics_by_chords(space: &Space, max_length: f64) -> Option<Vec<(f64, f64)>> {
    let axes = axes_meeting_cell(space, max_length)?;
    let mut sums: Vec<(f64, f64)> = Vec::new();
    let mut order: Vec<usize> = (0..axes.elements.len()).collect();
    order.sort_by(|&a, &b| axes.lengths[a].total_cmp(&axes.lengths[b]));
    for i in order {
        let (l, chord) = (axes.lengths[i], axes.chords[i]);
        match sums.last_mut() {
            Some(last) if (l - last.0).abs() < 1e-6 => last.1 += chord / 2.0,
            _ => sums.push((l, chord / 2.0)),
        }
    }
    let mut primitive: Vec<(f64, f64)> = Vec::new();
    for &(lambda, c) in &sums {
        let mut rest = c;
        for &(l, n) in &primitive {
            let k = (lambda / l).round();
            if k >= 2.0 && (lambda - k * l).abs() < 1e-6 {
                rest -= l * n;
            }
        }
        let n = rest / lambda;
        if n.abs() > 1e-6 {
            primitive.push((lambda, n));
        }
    }
    Some(primitive)
}

/// Elements of translation length at most `max_length` whose axes meet the cell, with
/// their lengths and the weighted lengths of their chords in the cell.
struct Axes {
    elements: Vec<DMat4>,
    lengths: Vec<f64>,
    chords: Vec<f64>,
    /// Where each element moves the centre.
    points: OrbitPoints,
}

impl Axes {
    /// The element equal to `m` (by where it moves the centre: a manifold's group acts
    /// freely), if it is one of these.
    fn find(&self, m: DMat4) -> Option<usize> {
        self.points.nearest(m * ORIGIN).map(|(i, _)| i)
    }
}

fn axes_meeting_cell(space: &Space, max_length: f64) -> Option<Axes> {
    let mut axes = Axes {
        elements: Vec::new(),
        lengths: Vec::new(),
        chords: Vec::new(),
        points: OrbitPoints::new(Geometry::Hyperbolic, SAME_AXIS_ELEMENT),
    };
    if space.geometry != Geometry::Hyperbolic || !space.manifold {
        return Some(axes);
    }
    let g = space.geometry;
    let elements = elements_near(space, max_length + 1e-9, MAX_ENUMERATED)?;
    for &h in elements.iter().skip(1) {
        let length = displacement(g, h);
        if !(length <= max_length + 1e-9) {
            continue;
        }
        let ahead = attracting_point(h);
        let behind = attracting_point(g.inverse(h));
        // Its chords through each cell, each weighted by the cells that share it.
        let mut meets = false;
        let mut chords = 0.0;
        for cell in space.cells() {
            let Some((a, b, faces)) = chord(space, cell.clone(), behind, ahead) else {
                continue;
            };
            meets = true;
            let weight = match faces.as_slice() {
                [] => 1.0,
                [_] => 0.5,
                [f, h, ..] => {
                    // Along an edge: shared by the cells around its cycle.
                    let cycle = space
                        .edges
                        .iter()
                        .find(|e| e.faces.contains(f) && e.faces.contains(h))
                        .map_or(1, |e| space.edge_cycles[e.cycle].edges.len());
                    1.0 / cycle as f64
                }
            };
            chords += weight * g.distance(a, b);
        }
        if !meets {
            continue;
        }
        axes.elements.push(h);
        axes.lengths.push(length);
        axes.chords.push(chords);
        axes.points.push(h * ORIGIN);
    }
    Some(axes)
}

/// The part of the chart line from `behind` to `ahead` (points at infinity) in the cell,
/// widened by 1e-7: its end points in the model and the faces it lies in (`None` if it
/// misses the cell).
fn chord(
    space: &Space,
    cell: std::ops::Range<usize>,
    behind: DVec3,
    ahead: DVec3,
) -> Option<(DVec4, DVec4, Vec<usize>)> {
    let d = ahead - behind;
    // The parameter interval inside the cell widened by `slack`, over the faces not in
    // `skip`.
    let interval = |slack: f64, skip: &[usize]| {
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for (i, f) in space.faces.iter().enumerate() {
            if skip.contains(&i) || !cell.contains(&i) {
                continue;
            }
            let (a, b) = (f.normal.dot(d), f.offset + slack - f.normal.dot(behind));
            if a > 0.0 {
                hi = hi.min(b / a);
            } else if a < 0.0 {
                lo = lo.max(b / a);
            } else if b < 0.0 {
                return None;
            }
        }
        (lo <= hi).then_some((lo, hi))
    };
    // Widened for membership: an axis along a face or an edge must not be lost to rounding.
    let slack = 1e-7;
    let (wide_lo, wide_hi) = interval(slack, &[])?;
    let (pa, pb) = (behind + d * wide_lo, behind + d * wide_hi);
    let lies_in: Vec<usize> = space
        .faces
        .iter()
        .enumerate()
        .filter(|(i, f)| {
            cell.contains(i)
                && f.normal.dot(d).abs() <= 1e-6 * d.length()
                && (f.normal.dot(pa) - f.offset).abs() < 2.0 * slack
                && (f.normal.dot(pb) - f.offset).abs() < 2.0 * slack
        })
        .map(|(i, _)| i)
        .collect();
    // The exact interval, leaving out the planes the line lies in (there the quotient of
    // two roundings would cut it anywhere).
    let (lo, hi) = interval(0.0, &lies_in).unwrap_or((wide_lo, wide_lo));
    let g = space.geometry;
    let point = |x: DVec3| g.project_point(x.extend(1.0));
    Some((point(behind + d * lo), point(behind + d * hi), lies_in))
}

/// Sorted lengths grouped into (length, count) to 1e-6.
fn group_lengths(lengths: &[f64]) -> Vec<GeodesicLength> {
    let mut out: Vec<GeodesicLength> = Vec::new();
    for &l in lengths {
        match out.last_mut() {
            Some(last) if (l - last.length).abs() < 1e-6 => last.count += 1,
            _ => out.push(GeodesicLength {
                length: l,
                count: 1,
            }),
        }
    }
    out
}

/// Closed geodesics are listed up to this length.
pub const GEODESIC_SPECTRUM_LENGTH: f64 = 3.5;

/// A face as `curved-spaces info` reports it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct FaceSummary {
    /// Outward unit normal in the chart.
    pub normal: [f64; 3],
    /// Chart distance of the face plane from the origin.
    pub offset: f64,
}

/// An edge cycle as `curved-spaces info` reports it.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct EdgeCycleSummary {
    /// How many edges of the cell the cycle glues together.
    pub edges: usize,
    /// Sum of their dihedral angles (radians).
    pub angle_sum: f64,
}

/// Everything `curved-spaces info` reports, computed from the space.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Invariants {
    /// The space's name.
    pub name: String,
    /// Its geometry.
    pub geometry: Geometry,
    /// Its faces.
    pub faces: Vec<FaceSummary>,
    /// How many cells it is made of ([`Space::cells`]).
    pub cells: usize,
    /// Its volume.
    pub volume: f64,
    /// Radius of the largest ball around the cell's centre inside the cell.
    pub inradius: f64,
    /// Distance from the centre to the farthest vertex.
    pub circumradius: f64,
    /// The edges' length, if they all have one.
    pub edge_length: Option<f64>,
    /// The edge cycles.
    pub edge_cycles: Vec<EdgeCycleSummary>,
    /// Number of vertex classes.
    pub vertex_cycles: usize,
    /// Whether every pairing preserves orientation.
    pub orientable: bool,
    /// Whether it is a manifold (not only an orbifold).
    pub manifold: bool,
    /// Order of the holonomy group (flat spaces).
    pub holonomy_order: Option<usize>,
    /// Order of the fundamental group (spherical spaces).
    pub group_order: Option<usize>,
    /// The first homology group (the fundamental or orbifold group made abelian), in
    /// SnapPy's notation (`Z/5 + Z/5`).
    pub homology: String,
    /// `null` when the enumeration would be too large.
    pub closed_geodesics: Option<Vec<GeodesicLength>>,
    /// Half the shortest closed geodesic (manifolds).
    pub injectivity_radius: Option<f64>,
}

impl Invariants {
    /// Computes every invariant (the closed geodesics take a fraction of a second for
    /// Seifert–Weber in a release build).
    #[must_use]
    pub fn compute(space: &Space) -> Self {
        Self {
            name: space.name.clone(),
            geometry: space.geometry,
            faces: space
                .faces
                .iter()
                .map(|f| FaceSummary {
                    normal: f.normal.to_array(),
                    offset: f.offset,
                })
                .collect(),
            cells: space.cells.len(),
            volume: volume(space),
            inradius: inradius(space),
            circumradius: circumradius(space),
            edge_length: edge_length(space),
            edge_cycles: space
                .edge_cycles
                .iter()
                .map(|c| EdgeCycleSummary {
                    edges: c.edges.len(),
                    angle_sum: c.angle_sum,
                })
                .collect(),
            vertex_cycles: space.vertex_cycles.len(),
            orientable: space.orientable,
            manifold: space.manifold,
            holonomy_order: holonomy_order(space),
            group_order: group_order(space),
            homology: super::homology::first_homology(space).to_string(),
            closed_geodesics: closed_geodesics(space, GEODESIC_SPECTRUM_LENGTH),
            injectivity_radius: injectivity_radius(space),
        }
    }
}
