//! Why a space was rejected: each error names the face, edge or vertex at fault.

use thiserror::Error;

/// A space that fails Poincaré's polyhedron theorem (or is malformed) is rejected with one of
/// these, never drawn wrongly.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SpaceError {
    #[error("a cell needs at least 4 faces to be bounded, this one has {count}")]
    TooFewFaces { count: usize },
    #[error("a cell may have at most {max} faces, this one has {count}")]
    TooManyFaces { count: usize, max: usize },
    #[error("face {face}: normal {normal:?} has zero length or is not finite")]
    BadNormal { face: usize, normal: [f64; 3] },
    #[error(
        "face {face}: offset {offset} must be positive and finite (the chart origin has to lie strictly inside the cell)"
    )]
    OriginNotInside { face: usize, offset: f64 },
    #[error(
        "face {face}: the plane n·x = {offset} misses hyperbolic space (in the Klein model it needs offset < 1)"
    )]
    PlaneMissesSpace { face: usize, offset: f64 },
    #[error(
        "face {face} has no pairing: give it a partner face and an isometry, or make it a mirror"
    )]
    MissingPairing { face: usize },
    #[error("face {face} is paired with face {partner}, but there are only {count} faces")]
    PartnerOutOfRange {
        face: usize,
        partner: usize,
        count: usize,
    },
    #[error(
        "face {face} names face {partner} as its partner, but face {partner} names face {back}"
    )]
    PartnerNotMutual {
        face: usize,
        partner: usize,
        back: usize,
    },
    #[error(
        "face {face} is a redundant inequality: it touches the cell in {vertices} vertices, not a polygon"
    )]
    DegenerateFace { face: usize, vertices: usize },
    #[error(
        "the faces do not close the cell: it is unbounded in chart direction {direction:?}. Is a face missing?"
    )]
    NotBounded { direction: [f64; 3] },
    #[error(
        "the faces do not form a convex polyhedron (V − E + F = {euler}, expected 2, or an edge with one face)"
    )]
    NotAPolyhedron { euler: i64 },
    #[error(
        "vertex at chart point {point:?} lies on or beyond the sphere at infinity: only compact hyperbolic cells are supported"
    )]
    IdealVertex { point: [f64; 3] },
    #[error(
        "vertex at chart point {point:?} is not in the open hemisphere w > 0 of the spherical chart"
    )]
    VertexOutsideChart { point: [f64; 3] },
    #[error("the pairing of face {face} is not an isometry of the geometry (defect {defect:.3e})")]
    NotAnIsometry { face: usize, defect: f64 },
    #[error(
        "the pairings of faces {face} and {partner} are not inverse to each other (defect {defect:.3e}){}",
        if face == partner { "; a mirror's pairing must be an involution" } else { "" }
    )]
    NotInverse {
        face: usize,
        partner: usize,
        defect: f64,
    },
    #[error(
        "the pairing of face {face} does not map it onto face {partner} with the cell on the far side: {reason}"
    )]
    FaceNotMapped {
        face: usize,
        partner: usize,
        reason: String,
    },
    #[error(
        "edge cycle through edges {edges} has angle sum {angle_sum_deg:.6}°, which is not 360°/k for a whole k"
    )]
    EdgeAngleSum { edges: String, angle_sum_deg: f64 },
    #[error(
        "edge cycle through edges {edges}: going once around it gives an isometry of order other than {order} (defect {defect:.3e}), so the cells do not close up around the edge"
    )]
    EdgeHolonomy {
        edges: String,
        order: u32,
        defect: f64,
    },
    #[error(
        "the vertex links are not spheres: Euler characteristic {chi} (V {vertex_cycles} − E {edge_cycles} + F {face_pairs} − 1) should be 0 for a manifold"
    )]
    VertexLinks {
        chi: i64,
        vertex_cycles: usize,
        edge_cycles: usize,
        face_pairs: usize,
    },
    #[error("unknown space `{0}`; `curved-spaces list` shows the known ones")]
    UnknownSpace(String),
}
