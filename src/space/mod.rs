//! Spaces: a geometry, a convex fundamental polyhedron and one pairing per face, validated
//! by Poincaré's polyhedron theorem when built (`docs/design.md` §2).

pub mod accuracy;
pub mod catalog;
pub mod contract;
pub mod dirichlet;
mod error;
pub mod exact;
pub mod family;
pub mod file;
pub mod group;
pub mod homology;
pub mod invariants;
pub mod library;
pub mod motion;
pub mod nil;
pub mod orbit;
pub mod product;
pub mod roots;
pub mod sl2r;
pub mod sol;
pub mod surface;
mod validate;
pub mod walk;
mod wrap;

pub use catalog::{DEFAULT_SPACE, SEED_SPACES, SeedSpace, seed_space};
pub use contract::{FamilySpace, FrameCrossing, FrameMotion, FrameSpace};
pub use error::SpaceError;
pub use family::{AnySpace, Family, Feature, Unsupported, resolve_space};
pub use walk::{CellWalk, CellWalker, Crossing, Exit, Limit, NextExit, Trace};
pub use wrap::{Holonomy, MAX_WRAPS_PER_STEP, frame_on_model, wrap_into_cell};

use crate::geometry::{Geometry, ORIGIN};
use glam::{DMat4, DVec3, DVec4};
use std::ops::Range;
use validate::{
    check_cells, check_vertices, checked_faces, escape_direction, find_edge_cycles, find_edges,
    find_vertex_cycles, find_vertices, order_face_vertices, validate_pairings,
};

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

/// The power of two nearest the largest face distance of a flat cell, when every offset
/// and translation is finite (otherwise the checks report the bad face).
fn flat_scale(specs: &[FaceSpec]) -> Option<f64> {
    let largest = specs.iter().map(|f| f.offset.abs()).fold(0.0_f64, f64::max);
    let finite = specs
        .iter()
        .all(|f| f.offset.is_finite() && f.pairing.is_none_or(|p| p.matrix.is_finite()));
    if finite {
        power_of_two_near(largest)
    } else {
        None
    }
}

/// The power of two nearest `x` (positive and finite), by which a flat cell can be scaled
/// exactly; `None` for any other `x`.
pub(crate) fn power_of_two_near(x: f64) -> Option<f64> {
    (x > 0.0 && x.is_finite())
        .then(|| 2f64.powi(x.log2().round() as i32))
        .filter(|s| s.is_finite() && *s > 0.0)
}

impl FaceSpec {
    /// The face of a flat cell scaled by `factor` (offset and the pairing's translation).
    fn scaled(&self, factor: f64) -> Self {
        let mut f = *self;
        f.offset *= factor;
        if let Some(p) = &mut f.pairing {
            let t = p.matrix.w_axis.truncate() * factor;
            p.matrix.w_axis = t.extend(p.matrix.w_axis.w);
        }
        f
    }

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
    /// The cell the face bounds ([`Space::cells`]; 0 in a space of one cell).
    pub cell: usize,
}

impl Face {
    /// Whether this face is a mirror: glued to itself by the reflection in it, which fixes
    /// the face point by point. A face glued to itself by another map is not a mirror: the
    /// hemisphere of projective space has one face, its equator, glued to itself by the
    /// antipodal map, which moves every point of it (a free action: RP³ is a manifold).
    #[must_use]
    pub fn is_mirror(&self, index: usize) -> bool {
        self.partner == index && fixes_hyperplane(&self.pairing, self.covector)
    }
}

/// Whether the linear map `m` of R⁴ fixes every point of the hyperplane `N·X = 0`: it
/// moves none of the three basis vectors of the hyperplane (each `e_k` with its `N` part
/// taken out, the one most along `N` left out) by more than a rounding error.
fn fixes_hyperplane(m: &DMat4, covector: DVec4) -> bool {
    let n2 = covector.length_squared();
    if !(n2 > 0.0 && n2.is_finite()) {
        return false;
    }
    let along = covector.abs().max_position();
    let largest = m.to_cols_array().iter().fold(0.0f64, |a, x| a.max(x.abs()));
    (0..4).filter(|&k| k != along).all(|k| {
        let v = DVec4::AXES[k] - covector * (covector[k] / n2);
        (*m * v - v).length() <= 1e-9 * v.length().max(largest)
    })
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
    /// The faces crossed going once around the cycle, in order: the product of their
    /// pairings, to the power `order`, is the identity (a relation of the group).
    pub crossings: Vec<usize>,
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
    /// For a spherical cell that reaches distance π/2 from its centre (built from its
    /// finite group, [`Space::reaches_equator`]): the group's order.
    pub(crate) equator_order: Option<usize>,
    /// The cell in double-double, for a space built from a closed form
    /// ([`Space::from_exact`]).
    pub(crate) exact: Option<std::sync::Arc<exact::ExactCell>>,
    /// The cells, each a run of faces ([`Space::cells`]).
    pub(crate) cells: Vec<Range<usize>>,
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

    /// Whether the cell is a spherical one that reaches distance π/2 from its centre, beyond
    /// the gnomonic chart: the 3-sphere itself (no face), projective space (a hemisphere with
    /// one face) or a lens space L(P, 1) (a lens whose two faces meet in a great circle with no
    /// vertex). Such a cell is built from its finite group ([`dirichlet`]) and certified by
    /// it rather than by Poincaré's theorem; its faces are great spheres given by their
    /// covectors, walks never divide by `w`, and rays are walked in steps of at most π/4
    /// (`docs/groups.md`).
    #[must_use]
    pub fn reaches_equator(&self) -> bool {
        self.equator_order.is_some()
    }

    /// Whether a ray can run more than π/2 inside the cell before it meets a face, so that
    /// the walk must go in steps of at most π/4: the exit ratio `−(N·p)/(N·v)` finds only
    /// the faces a ray meets within π/2 (where `N·v > 0`). That is every spherical cell
    /// whose diameter passes π/2 — its circumradius passes π/4, as in `lens-7-2` (1.16),
    /// `prism-3` or the mirrored tetrahedron, whose walks once ended in the middle of the
    /// cell — and every cell that reaches the equator.
    #[must_use]
    pub fn walks_in_steps(&self) -> bool {
        self.reaches_equator()
            || self.geometry == Geometry::Spherical
                && invariants::circumradius(self) > std::f64::consts::FRAC_PI_4 - 1e-9
    }

    /// A spherical cell that reaches distance π/2, from its faces' covectors (unit in R⁴,
    /// the cell `N·X ≤ 0`), partners and pairings, and the order of its group (the only
    /// constructor of such a cell; its callers have the whole group in hand).
    pub(crate) fn equator_cell(
        name: &str,
        description: &str,
        faces: Vec<(DVec4, usize, DMat4)>,
        order: usize,
    ) -> Self {
        let faces: Vec<Face> = faces
            .into_iter()
            .map(|(covector, partner, pairing)| {
                let n = covector.truncate();
                let (normal, offset) = if n.length() > 1e-12 {
                    (n / n.length(), -covector.w / n.length())
                } else {
                    (DVec3::ZERO, f64::INFINITY)
                };
                Face {
                    normal,
                    offset,
                    covector,
                    partner,
                    pairing,
                    vertices: Vec::new(),
                    cell: 0,
                }
            })
            .collect();
        let mirrors = faces
            .iter()
            .enumerate()
            .filter(|(i, f)| f.is_mirror(*i))
            .count();
        // A mirrored lens: two mirrors meeting in one great circle at the lens's angle α
        // (the angle between the outward normals is π − α); once round the edge crosses
        // both, angle sum 2α, and the relation is the product of the two reflections to
        // the power π/α.
        let edge_cycles = if faces.len() == 2 && mirrors == 2 {
            let alpha = std::f64::consts::PI
                - faces[0]
                    .covector
                    .dot(faces[1].covector)
                    .clamp(-1.0, 1.0)
                    .acos();
            let angle_sum = 2.0 * alpha;
            vec![EdgeCycle {
                edges: Vec::new(),
                angle_sum,
                order: (std::f64::consts::TAU / angle_sum).round() as u32,
                crossings: vec![0, 1],
            }]
        // A lens: the two faces meet in one great circle, glued to itself `order` times
        // around (angle sum 2π); the relation is the pairing to the power `order`.
        } else if faces.len() == 2 {
            vec![EdgeCycle {
                edges: Vec::new(),
                angle_sum: std::f64::consts::TAU,
                order: 1,
                crossings: vec![0; order],
            }]
        } else {
            Vec::new()
        };
        let orientable = faces.iter().all(|f| f.pairing.determinant() > 0.0);
        // One cell of every face (a range, not the list of its indices).
        #[allow(clippy::single_range_in_vec_init)]
        let cells = vec![0..faces.len()];
        Self {
            cells,
            name: name.to_string(),
            description: description.to_string(),
            geometry: Geometry::Spherical,
            faces,
            vertices: Vec::new(),
            edges: Vec::new(),
            edge_cycles,
            vertex_cycles: Vec::new(),
            orientable,
            manifold: mirrors == 0,
            equator_order: Some(order),
            exact: None,
        }
    }
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
        Self::new_cells(name, description, geometry, &[specs.to_vec()])
    }

    /// Builds and validates a space of several cells, each a convex polyhedron given by its
    /// faces as for [`Space::new`]; faces are numbered through the cells in order (the first
    /// cell's, then the second's), and a pairing's partner may be a face of another cell.
    ///
    /// The cells lie in one chart without overlapping, the chart origin in one of them, and
    /// the gluings join them all into one space. Where two cells meet in the chart, their
    /// faces are glued by the identity: a *seam* ([`Space::is_seam`]), which a ray crosses
    /// without seeing it. The validation is [`Space::new`]'s, with the edge cycles and vertex
    /// cycles running through every cell and the Euler characteristic counting the cells.
    pub fn new_cells(
        name: impl Into<String>,
        description: impl Into<String>,
        geometry: Geometry,
        cells: &[Vec<FaceSpec>],
    ) -> Result<Self, SpaceError> {
        let specs: Vec<FaceSpec> = cells.iter().flatten().copied().collect();
        let mut ranges = Vec::with_capacity(cells.len());
        let mut start = 0;
        for cell in cells {
            ranges.push(start..start + cell.len());
            start += cell.len();
        }
        // A flat cell has no scale of its own, and the checks' tolerances are in chart
        // units: build it at unit size (scaled by the power of two nearest its largest face
        // distance, which is exact) and scale the result back.
        if geometry == Geometry::Euclidean
            && let Some(scale) = flat_scale(&specs)
            && scale != 1.0
        {
            let scaled: Vec<FaceSpec> = specs.iter().map(|f| f.scaled(1.0 / scale)).collect();
            let mut space = Self::build(name, description, geometry, &scaled, ranges)?;
            space.scale_flat(scale);
            return Ok(space);
        }
        Self::build(name, description, geometry, &specs, ranges)
    }

    /// Multiplies a flat space's lengths by `scale` (a power of two: exact).
    fn scale_flat(&mut self, scale: f64) {
        for face in &mut self.faces {
            face.offset *= scale;
            face.covector = face.normal.extend(-face.offset);
            let t = face.pairing.w_axis.truncate() * scale;
            face.pairing.w_axis = t.extend(1.0);
        }
        for v in &mut self.vertices {
            *v *= scale;
        }
        for e in &mut self.edges {
            e.length *= scale;
        }
    }

    fn build(
        name: impl Into<String>,
        description: impl Into<String>,
        geometry: Geometry,
        specs: &[FaceSpec],
        cells: Vec<Range<usize>>,
    ) -> Result<Self, SpaceError> {
        let mut faces = checked_faces(geometry, specs, &cells)?;
        let mut vertices = Vec::new();
        let mut cell_vertices = Vec::with_capacity(cells.len());
        for (c, range) in cells.iter().enumerate() {
            if let Some(direction) = escape_direction(&faces[range.clone()]) {
                return Err(SpaceError::NotBounded {
                    direction: direction.to_array(),
                });
            }
            let found = find_vertices(&faces[range.clone()], VALIDATION_TOLERANCE);
            let first = vertices.len();
            vertices.extend(found);
            cell_vertices.push(first..vertices.len());
            for face in &mut faces[range.clone()] {
                face.cell = c;
            }
        }
        check_vertices(geometry, &vertices)?;
        order_face_vertices(&mut faces, &vertices, &cell_vertices)?;
        if cells.len() > 1 {
            check_cells(&faces, &cells, &vertices, &cell_vertices)?;
        }
        let points: Vec<DVec4> = vertices
            .iter()
            .map(|&v| geometry.project_point(v.extend(1.0)))
            .collect();
        let mut edges = find_edges(geometry, &faces, &vertices, &points, &cells)?;
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
        let chi = vertex_cycles.len() as i64 - edge_cycles.len() as i64 + face_pairs as i64
            - cells.len() as i64;
        let cone_edges = edge_cycles.iter().any(|c| c.order > 1);
        if !has_mirror && !cone_edges && chi != 0 {
            return Err(SpaceError::VertexLinks {
                chi,
                vertex_cycles: vertex_cycles.len(),
                edge_cycles: edge_cycles.len(),
                face_pairs,
                cells: cells.len(),
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
            equator_order: None,
            exact: None,
            cells,
        })
    }

    /// The cells, each as the run of face indices that bound it: one cell for every space
    /// but those built by [`Space::new_cells`]. A walk leaves the cell it is in through one
    /// of that cell's faces and enters the cell of the partner face.
    #[must_use]
    pub fn cells(&self) -> &[Range<usize>] {
        &self.cells
    }

    /// Whether face `f` is a seam: glued by the identity to a face of another cell, where
    /// two cells meet in the chart. A ray goes through it unchanged; walls, images and
    /// the default scene's edges leave it out, as it is no face of the space's fundamental
    /// domain (the union of the cells).
    #[must_use]
    pub fn is_seam(&self, f: usize) -> bool {
        let face = &self.faces[f];
        face.cell != self.faces[face.partner].cell
            && crate::geometry::max_abs_entry(&(face.pairing - DMat4::IDENTITY).to_cols_array())
                <= 1e-12
    }

    /// The cell that holds the chart point of the model point `p` (the one it is least
    /// outside of, for a point on a seam or just past a face).
    #[must_use]
    pub fn cell_containing(&self, p: DVec4) -> usize {
        if self.cells.len() == 1 {
            return 0;
        }
        let p = p / p.w;
        (0..self.cells.len())
            .map(|c| (c, self.outside_cell(c, p)))
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
            .0
    }

    /// The largest `N·X` over the faces of cell `c` for a chart point `X` (`w = 1`).
    fn outside_cell(&self, c: usize, p: DVec4) -> f64 {
        self.faces[self.cells[c].clone()]
            .iter()
            .map(|f| f.covector.dot(p))
            .fold(f64::NEG_INFINITY, f64::max)
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
        if self.reaches_equator() {
            // Beyond the chart: N·X of the unit point, the sine of the distance past the face.
            let p = p / p.length();
            return self
                .faces
                .iter()
                .map(|f| f.covector.dot(p))
                .fold(f64::NEG_INFINITY, f64::max);
        }
        let p = p / p.w;
        // Outside the union of the cells by as little as the nearest cell.
        (0..self.cells.len())
            .map(|c| self.outside_cell(c, p))
            .fold(f64::INFINITY, f64::min)
    }

    /// Signed geodesic distance from the model point `p` to face `f`'s plane (positive
    /// outside the cell): `S(d) = N̂·X` with the covector normalised to a unit vector of the
    /// form (`asin`, identity, `asinh` of it).
    #[must_use]
    pub fn face_distance(&self, f: usize, p: DVec4) -> f64 {
        let face = &self.faces[f];
        let (n, r) = (face.normal.length(), face.offset);
        match self.geometry {
            Geometry::Euclidean => {
                let p = self.geometry.project_point(p);
                face.covector.dot(p / p.w) / n
            }
            // The covector's length in R⁴ (√(n² + r²) for a chart face; a face at π/2 has
            // no chart offset). The point is normalised without the chart's sign flip.
            Geometry::Spherical => (face.covector.dot(p / p.length()) / face.covector.length())
                .clamp(-1.0, 1.0)
                .asin(),
            Geometry::Hyperbolic => {
                let p = self.geometry.project_point(p);
                (face.covector.dot(p) / (n * n - r * r).sqrt()).asinh()
            }
        }
    }

    /// How far the model point `p` lies outside the cell, as a signed geodesic distance
    /// past the face it is farthest past (negative inside), with that face; in a space of
    /// several cells, outside the cell it is nearest.
    #[must_use]
    pub fn past_face(&self, p: DVec4) -> (usize, f64) {
        self.cells
            .iter()
            .map(|cell| {
                cell.clone()
                    .map(|f| (f, self.face_distance(f, p)))
                    .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a })
            })
            .fold((0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a })
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

/// Interior dihedral angle between two face planes: `cos α = −B(N, M)/√(B(N,N) B(M,M))`
/// with `B(N, M) = n·m + κ r_N r_M` the form on covectors dual to ⟨,⟩.
#[must_use]
pub fn dihedral_angle(geometry: Geometry, a: DVec4, b: DVec4) -> f64 {
    let k = geometry.kappa();
    let form = |x: DVec4, y: DVec4| x.truncate().dot(y.truncate()) + k * x.w * y.w;
    let c = -form(a, b) / (form(a, a) * form(b, b)).sqrt();
    c.clamp(-1.0, 1.0).acos()
}
