//! Building a cell from its faces and checking it by Poincaré's polyhedron theorem: the
//! vertices, edges and edge cycles are derived from the face planes and the pairings, and each
//! check names the face, edge or vertex at fault ([`SpaceError`]).

use super::{
    Edge, EdgeCycle, Face, FaceSpec, MAX_FACES, SpaceError, VALIDATION_TOLERANCE, dihedral_angle,
};
use crate::geometry::{Geometry, max_abs_entry};
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::f64::consts::TAU;
use std::ops::Range;

pub(super) fn union_find_root(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Faces with unit normals, checked one by one: finite normal, origin inside (in a space of
/// one cell; of several, [`check_cells`] finds the origin in one of them), a plane of the
/// geometry, a pairing with a partner in range that names this face back.
pub(super) fn checked_faces(
    geometry: Geometry,
    specs: &[FaceSpec],
    cells: &[Range<usize>],
) -> Result<Vec<Face>, SpaceError> {
    if let Some(cell) = cells.iter().find(|c| c.len() < 4) {
        return Err(SpaceError::TooFewFaces { count: cell.len() });
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
        if !(offset.is_finite() && (offset > 0.0 || cells.len() > 1)) {
            return Err(SpaceError::OriginNotInside {
                face: i,
                offset: spec.offset,
            });
        }
        if geometry == Geometry::Hyperbolic && offset.abs() >= 1.0 {
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
            cell: 0,
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
pub(super) fn check_vertices(geometry: Geometry, vertices: &[DVec3]) -> Result<(), SpaceError> {
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

/// Finds each face's vertices (among its cell's, `cell_vertices`) and orders them
/// counter-clockwise seen from outside.
pub(super) fn order_face_vertices(
    faces: &mut [Face],
    vertices: &[DVec3],
    cell_vertices: &[Range<usize>],
) -> Result<(), SpaceError> {
    for (i, face) in faces.iter_mut().enumerate() {
        let on: Vec<usize> = cell_vertices[face.cell]
            .clone()
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

/// Edges: consecutive vertices of a face, each shared by exactly two faces, with each
/// cell's Euler characteristic 2 (a cell's vertices are its own, so its edges are too).
pub(super) fn find_edges(
    geometry: Geometry,
    faces: &[Face],
    vertices: &[DVec3],
    points: &[DVec4],
    cells: &[Range<usize>],
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
    for (c, range) in cells.iter().enumerate() {
        let in_cell = |f: usize| faces[f].cell == c;
        let edge_count = sides.iter().filter(|s| in_cell(s[0])).count();
        let vertex_count = faces[range.clone()]
            .iter()
            .flat_map(|f| f.vertices.iter().copied())
            .collect::<std::collections::BTreeSet<_>>()
            .len();
        let euler = vertex_count as i64 - edge_count as i64 + range.len() as i64;
        if euler != 2 {
            return Err(SpaceError::NotAPolyhedron { euler });
        }
    }
    if sides.iter().any(|f| f[1] == usize::MAX) {
        let euler = vertices.len() as i64 - ends.len() as i64 + faces.len() as i64;
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
pub(super) type VertexImages = Vec<Vec<usize>>;

/// Edge cycles: walk the states (edge, face to cross) — crossing face `f` carries edge `e`
/// to an edge `e'` of the partner face, and the walk goes on through the other face at
/// `e'` — until the first state comes back. The dihedral angles met add up to `2π/k`, and
/// the composed pairings are a rotation about the edge of order `k`.
pub(super) fn find_edge_cycles(
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
        let mut crossings = Vec::new();
        // Each state is visited once, so 2E steps always close the cycle.
        for _ in 0..2 * edges.len() {
            if !visited.contains(&e) {
                visited.push(e);
            }
            angle_sum += edges[e].dihedral;
            holonomy = faces[f].pairing * holonomy;
            crossings.push(f);
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
            crossings,
        });
    }
    for (edge, cycle) in edges.iter_mut().zip(cycle_of) {
        edge.cycle = cycle;
    }
    Ok(cycles)
}

/// Vertex cycles: the classes of vertices glued together by the pairings (union–find).
pub(super) fn find_vertex_cycles(
    faces: &[Face],
    count: usize,
    images: &VertexImages,
) -> Vec<Vec<usize>> {
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

/// A chart direction in which the cell is unbounded, if any: one with `n_f · d ≤ 0` for
/// every face. The cone of such directions, when not empty, has an extreme ray along
/// `±(n_i × n_j)` for two faces, so checking those is exact.
pub(super) fn escape_direction(faces: &[Face]) -> Option<DVec3> {
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
pub(super) fn find_vertices(faces: &[Face], tol: f64) -> Vec<DVec3> {
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

pub(super) fn validate_pairings(
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

/// The checks a space of several cells needs beyond each cell's: the cells do not overlap in
/// the chart (a plane separates each pair: a face plane of either, or the plane through an
/// edge of each, the separating-axis test for convex polyhedra), the origin lies in one of
/// them, and the gluings join them all.
pub(super) fn check_cells(
    faces: &[Face],
    cells: &[Range<usize>],
    vertices: &[DVec3],
    cell_vertices: &[Range<usize>],
) -> Result<(), SpaceError> {
    let tol = 1e3 * VALIDATION_TOLERANCE;
    let corners = |c: usize| &vertices[cell_vertices[c].clone()];
    let edges_of = |c: usize| -> Vec<DVec3> {
        let mut out = Vec::new();
        for f in &faces[cells[c].clone()] {
            let n = f.vertices.len();
            for k in 0..n {
                let d = vertices[f.vertices[(k + 1) % n]] - vertices[f.vertices[k]];
                if d.length() > tol {
                    out.push(d.normalize());
                }
            }
        }
        out
    };
    // A direction separates the cells when one's corners all lie at or below the other's
    // along it.
    let separates = |a: &[DVec3], b: &[DVec3], d: DVec3| {
        let (a_lo, a_hi) = a
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(d.dot(*v)), hi.max(d.dot(*v)))
            });
        let (b_lo, b_hi) = b
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(d.dot(*v)), hi.max(d.dot(*v)))
            });
        a_hi <= b_lo + tol || b_hi <= a_lo + tol
    };
    for a in 0..cells.len() {
        for b in a + 1..cells.len() {
            let (pa, pb) = (corners(a), corners(b));
            let by_face = faces[cells[a].clone()]
                .iter()
                .chain(&faces[cells[b].clone()])
                .any(|f| separates(pa, pb, f.normal));
            let by_edges = by_face || {
                let (ea, eb) = (edges_of(a), edges_of(b));
                ea.iter().any(|x| {
                    eb.iter().any(|y| {
                        let d = x.cross(*y);
                        d.length() > 1e-9 && separates(pa, pb, d.normalize())
                    })
                })
            };
            if !by_edges {
                return Err(SpaceError::CellsOverlap { a, b });
            }
        }
    }
    let outside = cells
        .iter()
        .map(|range| {
            faces[range.clone()]
                .iter()
                .map(|f| -f.offset)
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    if !(outside <= VALIDATION_TOLERANCE) {
        return Err(SpaceError::OriginInNoCell { outside });
    }
    let mut parent: Vec<usize> = (0..cells.len()).collect();
    for face in faces {
        let (a, b) = (
            union_find_root(&mut parent, face.cell),
            union_find_root(&mut parent, faces[face.partner].cell),
        );
        parent[a.max(b)] = a.min(b);
    }
    if let Some(cell) = (0..cells.len()).find(|&c| union_find_root(&mut parent, c) != 0) {
        return Err(SpaceError::CellsNotJoined { cell });
    }
    Ok(())
}
