//! Invariants computed from a space's cell and pairings (never typed in): volume, radii,
//! groups, closed geodesics, injectivity radius.

use super::Space;
use crate::geometry::Ray;
use crate::geometry::{Geometry, ORIGIN, max_abs_entry};
use crate::space::{CellWalker, Limit};
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::collections::{BTreeMap, HashMap, VecDeque};

/// Distance from the centre (chart origin) to the nearest face: the radius of the largest
/// ball about the centre inside the cell.
#[must_use]
pub fn inradius(space: &Space) -> f64 {
    space
        .faces
        .iter()
        .map(|f| space.geometry.distance_from_ratio(f.offset, 1.0))
        .fold(f64::INFINITY, f64::min)
}

/// Distance from the centre to the farthest vertex.
#[must_use]
pub fn circumradius(space: &Space) -> f64 {
    (0..space.vertices.len())
        .map(|v| space.geometry.distance(ORIGIN, space.vertex_point(v)))
        .fold(0.0, f64::max)
}

/// The common length of all edges, if they have one (to 1e-9 relative).
#[must_use]
pub fn edge_length(space: &Space) -> Option<f64> {
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

/// Orbit points of distinct elements are at least twice the inradius apart, so a coarse
/// grid tells them apart.
fn orbit_key(p: DVec4) -> [i64; 4] {
    p.to_array().map(|x| (x * 1e5).round() as i64)
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
    let mut seen: HashMap<[i64; 4], ()> = HashMap::new();
    seen.insert(orbit_key(ORIGIN), ());
    let mut out = vec![DMat4::IDENTITY];
    let mut queue = VecDeque::from([DMat4::IDENTITY]);
    while let Some(m) = queue.pop_front() {
        for generator in &generators {
            let next = m * *generator;
            let key = orbit_key(next * ORIGIN);
            if seen.contains_key(&key) {
                continue;
            }
            seen.insert(key, ());
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
    let g = space.geometry;
    // Any pairing bounds the systole from above; the shortest element's axis, moved to meet
    // the cell, moves it by at most that much.
    let bound = space
        .faces
        .iter()
        .map(|f| g.distance(ORIGIN, f.pairing * ORIGIN))
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
/// length (to 1e-6). Every closed geodesic is the axis of a deck element whose axis meets the
/// cell, and such an element moves the cell by at most its length, so enumerating the
/// elements near the cell finds them all. Each is traced through the cell by the reference
/// tracer: its cyclic sequence of exit faces (up to orientation) tells distinct geodesics
/// apart, and a periodic sequence marks a power of a shorter one.
///
/// Empty for spaces other than hyperbolic manifolds; `None` when more than
/// [`MAX_ENUMERATED`] elements would have to be enumerated (a cell with very short closed
/// geodesics).
#[must_use]
pub fn closed_geodesics(space: &Space, max_length: f64) -> Option<Vec<GeodesicLength>> {
    if space.geometry != Geometry::Hyperbolic || !space.manifold {
        return Some(Vec::new());
    }
    let g = space.geometry;
    let elements = elements_near(space, max_length + 1e-9, MAX_ENUMERATED)?;
    let walker = CellWalker::<DVec4>::new(space);
    let partners: Vec<usize> = space.faces.iter().map(|f| f.partner).collect();
    let mut found: BTreeMap<Vec<usize>, f64> = BTreeMap::new();
    for &h in elements.iter().skip(1) {
        let length = displacement(g, h);
        if !(length <= max_length + 1e-9) {
            continue;
        }
        let ahead = attracting_point(h);
        let behind = attracting_point(g.inverse(h));
        let d = ahead - behind;
        // Clip the axis (a chart segment between its ends at infinity) to the cell.
        let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
        for f in &space.faces {
            let (a, b) = (f.normal.dot(d), f.offset - f.normal.dot(behind));
            if a > 0.0 {
                hi = hi.min(b / a);
            } else if a < 0.0 {
                lo = lo.max(b / a);
            } else if b < 0.0 {
                hi = -1.0;
            }
        }
        if hi - lo < 1e-9 {
            continue;
        }
        let mid = behind + d * ((lo + hi) / 2.0);
        let point = g.project_point(mid.extend(1.0));
        let Ok(tangent) = g.tangent_from_chart(point, d) else {
            continue;
        };
        let trace = walker.trace(Ray { point, tangent }, Limit::Distance(length));
        let closes = g.distance(trace.end.point, point) < 1e-6
            && g.form(trace.end.tangent, tangent) > 1.0 - 1e-9;
        let faces: Vec<usize> = trace.crossings.iter().map(|c| c.face).collect();
        if !closes || faces.is_empty() || minimal_period(&faces) < faces.len() {
            continue;
        }
        let reversed: Vec<usize> = faces.iter().rev().map(|&f| partners[f]).collect();
        let key = canonical_rotation(&faces).min(canonical_rotation(&reversed));
        found.entry(key).or_insert(length);
    }
    let mut lengths: Vec<f64> = found.into_values().collect();
    lengths.sort_by(f64::total_cmp);
    Some(group_lengths(&lengths))
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

fn minimal_period(seq: &[usize]) -> usize {
    (1..=seq.len())
        .find(|&p| {
            seq.len().is_multiple_of(p)
                && (0..seq.len()).all(|i| seq[i] == seq[(i + p) % seq.len()])
        })
        .unwrap_or(seq.len())
}

fn canonical_rotation(seq: &[usize]) -> Vec<usize> {
    (0..seq.len())
        .map(|r| {
            seq[r..]
                .iter()
                .chain(&seq[..r])
                .copied()
                .collect::<Vec<_>>()
        })
        .min()
        .unwrap_or_default()
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
