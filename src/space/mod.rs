//! Spaces: a geometry, a convex fundamental polyhedron and one pairing per face, validated
//! by Poincaré's polyhedron theorem when built (`docs/design.md` §2).

pub mod catalog;
mod error;
pub mod file;
pub mod invariants;
pub mod walk;
mod wrap;

pub use catalog::{DEFAULT_SPACE, SEED_SPACES, SeedSpace, seed_space};
pub use error::SpaceError;
pub use walk::{CellWalker, Crossing, Exit, Limit, Trace};
pub use wrap::{Holonomy, MAX_WRAPS_PER_STEP, wrap_into_cell};

use crate::geometry::{Geometry, ORIGIN, max_abs_entry};
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::f64::consts::TAU;

/// The most faces a cell may have (vertex search is cubic in the face count).
pub const MAX_FACES: usize = 128;

/// Relative tolerance for the combinatorial and validation checks.
pub const VALIDATION_TOLERANCE: f64 = 1e-9;

/// How a face is glued: to a partner face by an isometry, which maps this face onto the
/// partner with the cell on the far side (crossing this face applies it to the ray).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pairing {
    /// The partner face.
    pub partner: usize,
    /// The isometry.
    pub matrix: DMat4,
}

/// A face as given to [`Space::new`]: the half-space `normal · x ≤ offset` of the chart and
/// its pairing (`None` is an error, reported as [`SpaceError::MissingPairing`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceSpec {
    /// Outward normal in the chart.
    pub normal: DVec3,
    /// Chart distance of the face plane from the origin.
    pub offset: f64,
    /// Its pairing.
    pub pairing: Option<Pairing>,
}

impl FaceSpec {
    /// A face glued to `partner` by `matrix`.
    #[must_use]
    pub fn paired(normal: DVec3, offset: f64, partner: usize, matrix: DMat4) -> Self {
        Self {
            normal,
            offset,
            pairing: Some(Pairing { partner, matrix }),
        }
    }
}

/// A face of a validated space.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Outward unit normal in the chart.
    pub normal: DVec3,
    /// Chart distance of the face plane from the origin.
    pub offset: f64,
    /// `N = (n, −r)`: `N·X = 0` on the face, `< 0` inside the cell.
    pub covector: DVec4,
    /// The face this one is glued to (itself for a mirror).
    pub partner: usize,
    /// The isometry applied to a ray that leaves the cell through this face.
    pub pairing: DMat4,
    /// The face's vertices, counter-clockwise seen from outside.
    pub vertices: Vec<usize>,
}

impl Face {
    /// Whether this face is a mirror (glued to itself).
    #[must_use]
    pub fn is_mirror(&self, index: usize) -> bool {
        self.partner == index
    }
}

/// An edge of the cell, where two faces meet.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Its end vertices.
    pub vertices: [usize; 2],
    /// The two faces that meet in it.
    pub faces: [usize; 2],
    /// Interior dihedral angle (radians).
    pub dihedral: f64,
    /// Geodesic length.
    pub length: f64,
    /// Index into [`Space::edge_cycles`].
    pub cycle: usize,
}

/// The edges that are glued together into one edge of the space.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeCycle {
    /// Edges of the cell in the order the cycle visits them (each once).
    pub edges: Vec<usize>,
    /// Sum of the dihedral angles met going once around the cycle.
    pub angle_sum: f64,
    /// `k` with `angle_sum = 2π/k` (1 in a manifold; the cone or mirror order otherwise).
    pub order: u32,
}

/// A closed 3-manifold or orbifold of constant curvature, as a validated fundamental cell.
///
/// Only [`Space::new`] makes one (the seed spaces and space files go through it), so every
/// `Space` has passed validation; its parts are read through the methods below.
#[derive(Clone, Debug)]
pub struct Space {
    pub(crate) name: String,
    pub(crate) description: String,
    pub(crate) geometry: Geometry,
    pub(crate) faces: Vec<Face>,
    /// Vertices in the chart.
    pub(crate) vertices: Vec<DVec3>,
    pub(crate) edges: Vec<Edge>,
    pub(crate) edge_cycles: Vec<EdgeCycle>,
    /// Classes of vertices glued together.
    pub(crate) vertex_cycles: Vec<Vec<usize>>,
    /// Every pairing preserves orientation.
    pub(crate) orientable: bool,
    /// No mirrors, every edge cycle of order 1 and spherical vertex links.
    pub(crate) manifold: bool,
}

impl Space {
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

    /// Its geometry.
    #[must_use]
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// The cell's faces with their pairings.
    #[must_use]
    pub fn faces(&self) -> &[Face] {
        &self.faces
    }

    /// The cell's vertices in the chart.
    #[must_use]
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// The cell's edges.
    #[must_use]
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The edge cycles: the cell's edges glued into one edge of the space.
    #[must_use]
    pub fn edge_cycles(&self) -> &[EdgeCycle] {
        &self.edge_cycles
    }

    /// Classes of vertices glued together.
    #[must_use]
    pub fn vertex_cycles(&self) -> &[Vec<usize>] {
        &self.vertex_cycles
    }

    /// Whether every pairing preserves orientation.
    #[must_use]
    pub fn orientable(&self) -> bool {
        self.orientable
    }

    /// Whether the space is a manifold: no mirrors, every edge cycle of order 1 and
    /// spherical vertex links.
    #[must_use]
    pub fn manifold(&self) -> bool {
        self.manifold
    }
}

fn union_find_root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

impl Space {
    /// Builds and validates a space. Faces are half-spaces of the chart around the origin.
    ///
    /// Validation (Poincaré's polyhedron theorem): the faces bound a compact convex
    /// polyhedron; every pairing is an isometry; partners are mutual and their pairings
    /// inverse (a mirror's is an involution); each pairing maps its face onto the partner
    /// face, vertices onto vertices, with the cell on the far side; every edge cycle has
    /// angle sum `2π/k` and going once around it is an isometry of order `k`; for a
    /// manifold the vertex links are spheres (Euler characteristic 0).
    pub fn new(
        name: impl Into<String>,
        description: impl Into<String>,
        geometry: Geometry,
        specs: &[FaceSpec],
    ) -> Result<Self, SpaceError> {
        let mut faces = checked_faces(geometry, specs)?;
        if let Some(direction) = escape_direction(&faces) {
            return Err(SpaceError::NotBounded {
                direction: direction.to_array(),
            });
        }
        let vertices = find_vertices(&faces, VALIDATION_TOLERANCE);
        check_vertices(geometry, &vertices)?;
        order_face_vertices(&mut faces, &vertices)?;
        let points: Vec<DVec4> = vertices
            .iter()
            .map(|&v| geometry.project_point(v.extend(1.0)))
            .collect();
        let mut edges = find_edges(geometry, &faces, &vertices, &points)?;
        let images = validate_pairings(geometry, &faces, &vertices, &points)?;
        let edge_cycles = find_edge_cycles(geometry, &faces, &mut edges, &points, &images)?;
        let vertex_cycles = find_vertex_cycles(&faces, vertices.len(), &images);

        let has_mirror = faces.iter().enumerate().any(|(i, f)| f.is_mirror(i));
        let orientable = faces.iter().all(|f| f.pairing.determinant() > 0.0);
        let face_pairs = faces
            .iter()
            .enumerate()
            .filter(|(i, f)| f.partner >= *i)
            .count();
        let chi = vertex_cycles.len() as i64 - edge_cycles.len() as i64 + face_pairs as i64 - 1;
        let cone_edges = edge_cycles.iter().any(|c| c.order > 1);
        if !has_mirror && !cone_edges && chi != 0 {
            return Err(SpaceError::VertexLinks {
                chi,
                vertex_cycles: vertex_cycles.len(),
                edge_cycles: edge_cycles.len(),
                face_pairs,
            });
        }
        Ok(Self {
            name: name.into(),
            description: description.into(),
            geometry,
            faces,
            vertices,
            edges,
            edge_cycles,
            vertex_cycles,
            orientable,
            manifold: !has_mirror && !cone_edges,
        })
    }

    /// The model point of vertex `v`.
    #[must_use]
    pub fn vertex_point(&self, v: usize) -> DVec4 {
        self.geometry.project_point(self.vertices[v].extend(1.0))
    }

    /// The largest `N·X / X.w` over the faces: how far a point is outside the cell
    /// (negative inside).
    #[must_use]
    pub fn outside_by(&self, p: DVec4) -> f64 {
        let p = p / p.w;
        self.faces
            .iter()
            .map(|f| f.covector.dot(p))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Signed geodesic distance from the model point `p` to face `f`'s plane (positive
    /// outside the cell): `S(d) = N̂·X` with the covector normalised to a unit vector of the
    /// form (`asin`, identity, `asinh` of it).
    #[must_use]
    pub fn face_distance(&self, f: usize, p: DVec4) -> f64 {
        let face = &self.faces[f];
        let (n, r) = (face.normal.length(), face.offset);
        let p = self.geometry.project_point(p);
        match self.geometry {
            Geometry::Euclidean => face.covector.dot(p / p.w) / n,
            Geometry::Spherical => (face.covector.dot(p) / (n * n + r * r).sqrt())
                .clamp(-1.0, 1.0)
                .asin(),
            Geometry::Hyperbolic => (face.covector.dot(p) / (n * n - r * r).sqrt()).asinh(),
        }
    }

    /// Whether any face is a mirror.
    #[must_use]
    pub fn has_mirrors(&self) -> bool {
        self.faces.iter().enumerate().any(|(i, f)| f.is_mirror(i))
    }

    /// The centre of the cell: the chart origin.
    #[must_use]
    pub fn centre(&self) -> DVec4 {
        ORIGIN
    }
}

/// Faces with unit normals, checked one by one: finite normal, origin inside, a plane of the
/// geometry, a pairing with a partner in range that names this face back.
fn checked_faces(geometry: Geometry, specs: &[FaceSpec]) -> Result<Vec<Face>, SpaceError> {
    if specs.len() < 4 {
        return Err(SpaceError::TooFewFaces { count: specs.len() });
    }
    if specs.len() > MAX_FACES {
        return Err(SpaceError::TooManyFaces {
            count: specs.len(),
            max: MAX_FACES,
        });
    }
    let mut faces = Vec::with_capacity(specs.len());
    for (i, spec) in specs.iter().enumerate() {
        let len = spec.normal.length();
        if !(len.is_finite() && len > 0.0) {
            return Err(SpaceError::BadNormal {
                face: i,
                normal: spec.normal.to_array(),
            });
        }
        let offset = spec.offset / len;
        if !(offset.is_finite() && offset > 0.0) {
            return Err(SpaceError::OriginNotInside {
                face: i,
                offset: spec.offset,
            });
        }
        if geometry == Geometry::Hyperbolic && offset >= 1.0 {
            return Err(SpaceError::PlaneMissesSpace { face: i, offset });
        }
        let pairing = spec.pairing.ok_or(SpaceError::MissingPairing { face: i })?;
        if pairing.partner >= specs.len() {
            return Err(SpaceError::PartnerOutOfRange {
                face: i,
                partner: pairing.partner,
                count: specs.len(),
            });
        }
        let normal = spec.normal / len;
        faces.push(Face {
            normal,
            offset,
            covector: normal.extend(-offset),
            partner: pairing.partner,
            pairing: pairing.matrix,
            vertices: Vec::new(),
        });
    }
    for (i, face) in faces.iter().enumerate() {
        let back = faces[face.partner].partner;
        if back != i {
            return Err(SpaceError::PartnerNotMutual {
                face: i,
                partner: face.partner,
                back,
            });
        }
    }
    Ok(faces)
}

/// Vertices must be proper points of the geometry's chart.
fn check_vertices(geometry: Geometry, vertices: &[DVec3]) -> Result<(), SpaceError> {
    for v in vertices {
        if !v.is_finite() {
            return Err(SpaceError::VertexOutsideChart {
                point: v.to_array(),
            });
        }
        if geometry == Geometry::Hyperbolic && v.length_squared() >= 1.0 - VALIDATION_TOLERANCE {
            return Err(SpaceError::IdealVertex {
                point: v.to_array(),
            });
        }
    }
    Ok(())
}

/// Finds each face's vertices and orders them counter-clockwise seen from outside.
fn order_face_vertices(faces: &mut [Face], vertices: &[DVec3]) -> Result<(), SpaceError> {
    for (i, face) in faces.iter_mut().enumerate() {
        let on: Vec<usize> = (0..vertices.len())
            .filter(|&v| {
                (face.normal.dot(vertices[v]) - face.offset).abs() <= 10.0 * VALIDATION_TOLERANCE
            })
            .collect();
        if on.len() < 3 {
            return Err(SpaceError::DegenerateFace {
                face: i,
                vertices: on.len(),
            });
        }
        let centre = on.iter().map(|&v| vertices[v]).sum::<DVec3>() / on.len() as f64;
        let e1 = (vertices[on[0]] - centre).normalize();
        let e2 = face.normal.cross(e1);
        let angle = |v: usize| {
            let d = vertices[v] - centre;
            d.dot(e2).atan2(d.dot(e1))
        };
        let mut sorted = on;
        sorted.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
        face.vertices = sorted;
    }
    Ok(())
}

/// Edges: consecutive vertices of a face, each shared by exactly two faces, with the
/// polyhedron's Euler characteristic 2.
fn find_edges(
    geometry: Geometry,
    faces: &[Face],
    vertices: &[DVec3],
    points: &[DVec4],
) -> Result<Vec<Edge>, SpaceError> {
    let mut ends: Vec<[usize; 2]> = Vec::new();
    let mut sides: Vec<[usize; 2]> = Vec::new();
    for (i, face) in faces.iter().enumerate() {
        let n = face.vertices.len();
        for k in 0..n {
            let (a, b) = (face.vertices[k], face.vertices[(k + 1) % n]);
            let key = [a.min(b), a.max(b)];
            match ends.iter().position(|&x| x == key) {
                Some(e) => sides[e][1] = i,
                None => {
                    ends.push(key);
                    sides.push([i, usize::MAX]);
                }
            }
        }
    }
    let euler = vertices.len() as i64 - ends.len() as i64 + faces.len() as i64;
    if euler != 2 || sides.iter().any(|f| f[1] == usize::MAX) {
        return Err(SpaceError::NotAPolyhedron { euler });
    }
    Ok(ends
        .iter()
        .zip(&sides)
        .map(|(&[a, b], &f)| Edge {
            vertices: [a, b],
            faces: f,
            dihedral: dihedral_angle(geometry, faces[f[0]].covector, faces[f[1]].covector),
            length: geometry.distance(points[a], points[b]),
            cycle: usize::MAX,
        })
        .collect())
}

/// Where each face's pairing sends that face's vertices: `images[f][v]` (only meaningful for
/// the vertices `v` of face `f`).
type VertexImages = Vec<Vec<usize>>;

/// Edge cycles: walk the states (edge, face to cross) — crossing face `f` carries edge `e`
/// to an edge `e'` of the partner face, and the walk goes on through the other face at
/// `e'` — until the first state comes back. The dihedral angles met add up to `2π/k`, and
/// the composed pairings are a rotation about the edge of order `k`.
fn find_edge_cycles(
    geometry: Geometry,
    faces: &[Face],
    edges: &mut [Edge],
    points: &[DVec4],
    images: &VertexImages,
) -> Result<Vec<EdgeCycle>, SpaceError> {
    let edge_of = |a: usize, b: usize| {
        edges
            .iter()
            .position(|e| e.vertices == [a.min(b), a.max(b)])
    };
    let label = |cycle: &[usize]| {
        cycle
            .iter()
            .map(|&e| format!("{}–{}", edges[e].vertices[0], edges[e].vertices[1]))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut cycles: Vec<EdgeCycle> = Vec::new();
    let mut cycle_of = vec![usize::MAX; edges.len()];
    for start in 0..edges.len() {
        if cycle_of[start] != usize::MAX {
            continue;
        }
        let (mut e, mut f) = (start, edges[start].faces[0]);
        let mut visited = Vec::new();
        let mut angle_sum = 0.0;
        let mut holonomy = DMat4::IDENTITY;
        // Each state is visited once, so 2E steps always close the cycle.
        for _ in 0..2 * edges.len() {
            if !visited.contains(&e) {
                visited.push(e);
            }
            angle_sum += edges[e].dihedral;
            holonomy = faces[f].pairing * holonomy;
            let [a, b] = edges[e].vertices;
            let partner = faces[f].partner;
            let Some(next) =
                edge_of(images[f][a], images[f][b]).filter(|&n| edges[n].faces.contains(&partner))
            else {
                return Err(SpaceError::FaceNotMapped {
                    face: f,
                    partner,
                    reason: format!("edge {a}–{b} does not map onto an edge of the partner face"),
                });
            };
            e = next;
            f = if edges[e].faces[0] == partner {
                edges[e].faces[1]
            } else {
                edges[e].faces[0]
            };
            if e == start && f == edges[start].faces[0] {
                break;
            }
        }
        let k = (TAU / angle_sum).round();
        if !(k >= 1.0 && (angle_sum * k - TAU).abs() < 1e-7) {
            return Err(SpaceError::EdgeAngleSum {
                edges: label(&visited),
                angle_sum_deg: angle_sum.to_degrees(),
            });
        }
        let order = k as u32;
        let power = (0..order).fold(DMat4::IDENTITY, |m, _| m * holonomy);
        // Going round once must also fix the edge itself (be a rotation about it).
        let [a, b] = edges[start].vertices;
        let defect = max_abs_entry(&(power - DMat4::IDENTITY).to_cols_array())
            .max(geometry.distance(holonomy * points[a], points[a]))
            .max(geometry.distance(holonomy * points[b], points[b]));
        if !(defect <= 1e-7) {
            return Err(SpaceError::EdgeHolonomy {
                edges: label(&visited),
                order,
                defect,
            });
        }
        for &v in &visited {
            cycle_of[v] = cycles.len();
        }
        cycles.push(EdgeCycle {
            edges: visited,
            angle_sum,
            order,
        });
    }
    for (edge, cycle) in edges.iter_mut().zip(cycle_of) {
        edge.cycle = cycle;
    }
    Ok(cycles)
}

/// Vertex cycles: the classes of vertices glued together by the pairings (union–find).
fn find_vertex_cycles(faces: &[Face], count: usize, images: &VertexImages) -> Vec<Vec<usize>> {
    let mut parent: Vec<usize> = (0..count).collect();
    for (i, face) in faces.iter().enumerate() {
        for &v in &face.vertices {
            let (a, b) = (
                union_find_root(&mut parent, v),
                union_find_root(&mut parent, images[i][v]),
            );
            parent[a.max(b)] = a.min(b);
        }
    }
    let mut cycles: Vec<Vec<usize>> = Vec::new();
    let mut class_of = vec![usize::MAX; count];
    for v in 0..count {
        let root = union_find_root(&mut parent, v);
        if class_of[root] == usize::MAX {
            class_of[root] = cycles.len();
            cycles.push(Vec::new());
        }
        cycles[class_of[root]].push(v);
    }
    cycles
}

/// Interior dihedral angle between two face planes: `cos α = −B(N, M)/√(B(N,N) B(M,M))`
/// with `B(N, M) = n·m + κ r_N r_M` the form on covectors dual to ⟨,⟩.
#[must_use]
pub fn dihedral_angle(geometry: Geometry, a: DVec4, b: DVec4) -> f64 {
    let k = geometry.kappa();
    let form = |x: DVec4, y: DVec4| x.truncate().dot(y.truncate()) + k * x.w * y.w;
    let c = -form(a, b) / (form(a, a) * form(b, b)).sqrt();
    c.clamp(-1.0, 1.0).acos()
}

/// A chart direction in which the cell is unbounded, if any: one with `n_f · d ≤ 0` for
/// every face. The cone of such directions, when not empty, has an extreme ray along
/// `±(n_i × n_j)` for two faces, so checking those is exact.
fn escape_direction(faces: &[Face]) -> Option<DVec3> {
    let escapes = |d: DVec3| faces.iter().all(|f| f.normal.dot(d) <= 1e-12);
    if faces
        .windows(2)
        .all(|w| w[0].normal.cross(w[1].normal).length() < 1e-12)
    {
        return Some(faces[0].normal.any_orthonormal_vector());
    }
    for (i, a) in faces.iter().enumerate() {
        for b in &faces[i + 1..] {
            let d = a.normal.cross(b.normal);
            if d.length() < 1e-12 {
                continue;
            }
            let d = d.normalize();
            for d in [d, -d] {
                if escapes(d) {
                    return Some(d);
                }
            }
        }
    }
    None
}

/// All points where three or more face planes meet inside every other half-space.
fn find_vertices(faces: &[Face], tol: f64) -> Vec<DVec3> {
    let mut out: Vec<DVec3> = Vec::new();
    let n = faces.len();
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let m =
                    DMat3::from_cols(faces[i].normal, faces[j].normal, faces[k].normal).transpose();
                if m.determinant().abs() < 1e-9 {
                    continue;
                }
                let x = m.inverse() * DVec3::new(faces[i].offset, faces[j].offset, faces[k].offset);
                if faces.iter().all(|f| f.normal.dot(x) <= f.offset + tol)
                    && !out.iter().any(|v| (*v - x).length() < 1e3 * tol)
                {
                    out.push(x);
                }
            }
        }
    }
    out
}

fn validate_pairings(
    geometry: Geometry,
    faces: &[Face],
    vertices: &[DVec3],
    points: &[DVec4],
) -> Result<VertexImages, SpaceError> {
    let tol = VALIDATION_TOLERANCE;
    let mut images = vec![vec![usize::MAX; vertices.len()]; faces.len()];
    for (i, face) in faces.iter().enumerate() {
        let g = face.pairing;
        let defect = geometry.isometry_defect(g);
        if !(defect < tol) {
            return Err(SpaceError::NotAnIsometry { face: i, defect });
        }
        let partner = &faces[face.partner];
        let defect = max_abs_entry(&(partner.pairing * g - DMat4::IDENTITY).to_cols_array());
        if !(defect < tol) {
            return Err(SpaceError::NotInverse {
                face: i,
                partner: face.partner,
                defect,
            });
        }
        // The pulled-back partner plane must be this face's plane, with the cell outside:
        // N' ∘ g = −λ N, λ > 0.
        let pulled = g.transpose() * partner.covector;
        let lambda = -pulled.dot(face.covector) / face.covector.length_squared();
        let off_plane = (pulled + lambda * face.covector).length() / pulled.length();
        if !(lambda > 0.0 && off_plane < tol) {
            let reason = if off_plane < tol {
                "it keeps the cell on the same side of the partner face".to_string()
            } else {
                format!("the image of the face plane misses the partner's plane by {off_plane:.3e}")
            };
            return Err(SpaceError::FaceNotMapped {
                face: i,
                partner: face.partner,
                reason,
            });
        }
        for &v in &face.vertices {
            let image = geometry.to_chart(g * points[v]);
            let hit = partner
                .vertices
                .iter()
                .copied()
                .find(|&w| (vertices[w] - image).length() < 1e3 * tol);
            let Some(w) = hit else {
                return Err(SpaceError::FaceNotMapped {
                    face: i,
                    partner: face.partner,
                    reason: format!(
                        "vertex {v} at {:?} goes to {:?}, which is no vertex of the partner face",
                        vertices[v].to_array(),
                        image.to_array()
                    ),
                });
            };
            images[i][v] = w;
        }
    }
    Ok(images)
}
