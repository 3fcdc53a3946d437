//! Why a space was rejected: each error names the face, edge or vertex at fault.

use thiserror::Error;

/// A space that fails Poincaré's polyhedron theorem (or is malformed) is rejected with one of
/// these, never drawn wrongly.
// The fields of a variant are the values its message names.
#[allow(missing_docs)]
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpaceError {
    /// A cell needs at least 4 faces to be bounded, this one has `count`.
    #[error("a cell needs at least 4 faces to be bounded, this one has {count}")]
    TooFewFaces { count: usize },
    /// A cell may have at most `max` faces, this one has `count`.
    #[error("a cell may have at most {max} faces, this one has {count}")]
    TooManyFaces { count: usize, max: usize },
    /// Face `face`: normal `normal` has zero length or is not finite.
    #[error("face {face}: normal {normal:?} has zero length or is not finite")]
    BadNormal { face: usize, normal: [f64; 3] },
    /// Face `face`: offset `offset` must be positive and finite (the chart origin has to lie strictly inside the cell).
    #[error(
        "face {face}: offset {offset} must be positive and finite (the chart origin has to lie strictly inside the cell)"
    )]
    OriginNotInside { face: usize, offset: f64 },
    /// Face `face`: the plane n·x = `offset` misses hyperbolic space (in the Klein model it needs offset < 1).
    #[error(
        "face {face}: the plane n·x = {offset} misses hyperbolic space (in the Klein model it needs offset < 1)"
    )]
    PlaneMissesSpace { face: usize, offset: f64 },
    /// Face `face` has no pairing: give it a partner face and an isometry, or make it a mirror.
    #[error(
        "face {face} has no pairing: give it a partner face and an isometry, or make it a mirror"
    )]
    MissingPairing { face: usize },
    /// Face `face` is paired with face `partner`, but there are only `count` faces.
    #[error("face {face} is paired with face {partner}, but there are only {count} faces")]
    PartnerOutOfRange {
        face: usize,
        partner: usize,
        count: usize,
    },
    /// Face `face` names face `partner` as its partner, but face `partner` names face `back`.
    #[error(
        "face {face} names face {partner} as its partner, but face {partner} names face {back}"
    )]
    PartnerNotMutual {
        face: usize,
        partner: usize,
        back: usize,
    },
    /// Face `face` is a redundant inequality: it touches the cell in `vertices` vertices, not a polygon.
    #[error(
        "face {face} is a redundant inequality: it touches the cell in {vertices} vertices, not a polygon"
    )]
    DegenerateFace { face: usize, vertices: usize },
    /// The faces do not close the cell: it is unbounded in chart direction `direction`. Is a face missing?.
    #[error(
        "the faces do not close the cell: it is unbounded in chart direction {direction:?}. Is a face missing?"
    )]
    NotBounded { direction: [f64; 3] },
    /// The faces do not form a convex polyhedron (V − E + F = `euler`, expected 2, or an edge with one face).
    #[error(
        "the faces do not form a convex polyhedron (V − E + F = {euler}, expected 2, or an edge with one face)"
    )]
    NotAPolyhedron { euler: i64 },
    /// Vertex at chart point `point` lies on or beyond the sphere at infinity: only compact hyperbolic cells are supported.
    #[error(
        "vertex at chart point {point:?} lies on or beyond the sphere at infinity: only compact hyperbolic cells are supported"
    )]
    IdealVertex { point: [f64; 3] },
    /// Vertex at chart point `point` is not in the open hemisphere w > 0 of the spherical chart.
    #[error(
        "vertex at chart point {point:?} is not in the open hemisphere w > 0 of the spherical chart"
    )]
    VertexOutsideChart { point: [f64; 3] },
    /// The pairing of face `face` is not an isometry of the geometry (defect `defect`).
    #[error("the pairing of face {face} is not an isometry of the geometry (defect {defect:.3e})")]
    NotAnIsometry { face: usize, defect: f64 },
    /// The pairings of faces `face` and `partner` are not inverse to each other (defect `defect`)….
    #[error(
        "the pairings of faces {face} and {partner} are not inverse to each other (defect {defect:.3e}){}",
        if face == partner { "; a mirror's pairing must be an involution" } else { "" }
    )]
    NotInverse {
        face: usize,
        partner: usize,
        defect: f64,
    },
    /// The pairing of face `face` does not map it onto face `partner` with the cell on the far side: `reason`.
    #[error(
        "the pairing of face {face} does not map it onto face {partner} with the cell on the far side: {reason}"
    )]
    FaceNotMapped {
        face: usize,
        partner: usize,
        reason: String,
    },
    /// Edge cycle through edges `edges` has angle sum `angle_sum_deg`°, which is not 360°/k for a whole k.
    #[error(
        "edge cycle through edges {edges} has angle sum {angle_sum_deg:.6}°, which is not 360°/k for a whole k"
    )]
    EdgeAngleSum { edges: String, angle_sum_deg: f64 },
    /// Edge cycle through edges `edges`: going once around it gives an isometry of order other than `order` (defect `defect`), so the cells do not close up around the edge.
    #[error(
        "edge cycle through edges {edges}: going once around it gives an isometry of order other than {order} (defect {defect:.3e}), so the cells do not close up around the edge"
    )]
    EdgeHolonomy {
        edges: String,
        order: u32,
        defect: f64,
    },
    /// The vertex links are not spheres: Euler characteristic `chi` (V `vertex_cycles` − E `edge_cycles` + F `face_pairs` − C `cells`) should be 0 for a manifold.
    #[error(
        "the vertex links are not spheres: Euler characteristic {chi} (V {vertex_cycles} − E {edge_cycles} + F {face_pairs} − C {cells}) should be 0 for a manifold"
    )]
    VertexLinks {
        chi: i64,
        vertex_cycles: usize,
        edge_cycles: usize,
        face_pairs: usize,
        cells: usize,
    },
    /// Cells `a` and `b` overlap in the chart: no plane separates them.
    #[error(
        "cells {a} and {b} overlap in the chart (no plane separates them): the cells of a space must meet only in faces, edges and vertices"
    )]
    CellsOverlap { a: usize, b: usize },
    /// The chart origin lies in no cell.
    #[error(
        "the chart origin lies in no cell (it is {outside:.3e} outside the nearest): the origin is where a space is entered and its scene centred"
    )]
    OriginInNoCell { outside: f64 },
    /// Cell `cell` is glued to none of the cells before it: the space falls apart.
    #[error(
        "no gluing joins cell {cell} to cell 0: the cells must be glued into one connected space"
    )]
    CellsNotJoined { cell: usize },
    /// No seed space has this id and no space file is at this path.
    #[error("unknown space `{0}`; `curved-spaces list` shows the known ones")]
    UnknownSpace(String),
}
