//! Bringing a frame that left the cell back in through the faces it is past: the rule the
//! player, the stereo eyes and the headset share (`docs/design.md` §3).

use super::Space;
use glam::DMat4;

/// Most faces a single wrap may cross (through an edge or a vertex a few are needed).
pub const MAX_WRAPS_PER_STEP: usize = 32;

/// Brings a frame back into the cell: while its position is past a face by more than
/// `margin`, applies the pairing of the face it is farthest past. Returns the new frame
/// (re-orthonormalized) and the faces crossed, in order.
#[must_use]
pub fn wrap_into_cell(space: &Space, frame: DMat4, margin: f64) -> (DMat4, Vec<usize>) {
    let mut f = frame;
    let mut crossed = Vec::new();
    for _ in 0..MAX_WRAPS_PER_STEP {
        // Beyond the chart (a cell reaching π/2 in S³) the point is not divided by `w`: its
        // unit covectors give the sine of the distance past each face.
        let p = if space.reaches_equator() {
            f.w_axis / f.w_axis.length()
        } else {
            f.w_axis / f.w_axis.w
        };
        // In a space of several cells: past the faces of the cell it is nearest, leaving out
        // the seams between cells (the point is in the union of the cells, or past a face of
        // the union: never moved by a seam's identity).
        let cell = &space.cells[space.cell_containing(p)];
        let (face, outside) = cell
            .clone()
            .filter(|&i| space.cells.len() == 1 || !space.is_seam(i))
            .map(|i| (i, space.faces[i].covector.dot(p)))
            .fold((0, f64::NEG_INFINITY), |a, b| if b.1 > a.1 { b } else { a });
        if !(outside > margin) {
            break;
        }
        f = space.faces[face].pairing * f;
        crossed.push(face);
    }
    (frame_on_model(space, f), crossed)
}

/// A frame of `space` made orthonormal on the model again. Past the equator of S³ a point
/// is not its antipode (the 3-sphere): in a cell that reaches the equator the frame's point
/// is only scaled back to unit length, never turned into the hemisphere `w ≥ 0` without
/// its axes.
#[must_use]
pub fn frame_on_model(space: &Space, frame: DMat4) -> DMat4 {
    let g = space.geometry;
    if space.reaches_equator() {
        g.orthonormalize_frame_at(frame, frame.w_axis / frame.w_axis.length())
    } else {
        g.orthonormalize_frame(frame)
    }
}

/// The face crossings of a frame since it entered the space (a player's is a component).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Holonomy {
    /// Faces crossed so far.
    pub crossings: u64,
    /// The product of the pairings applied, latest on the left: `F_now = matrix · F_unwrapped`.
    pub matrix: DMat4,
    /// The face crossed last.
    pub last_face: Option<usize>,
    /// The height the pairings added along a product space's fibre (the top's and bottom's
    /// shifts; 0 in constant curvature): a product frame's cover position is
    /// `matrix⁻¹` applied to its surface part, this subtracted from its height.
    pub fibre_shift: f64,
}

impl Default for Holonomy {
    fn default() -> Self {
        Self {
            crossings: 0,
            matrix: DMat4::IDENTITY,
            last_face: None,
            fibre_shift: 0.0,
        }
    }
}

impl Holonomy {
    /// Records a crossing through `face` with pairing `g`.
    pub fn record(&mut self, face: usize, g: DMat4) {
        self.crossings += 1;
        self.matrix = g * self.matrix;
        self.last_face = Some(face);
    }

    /// Records a crossing a frame made on its way back into the cell (its face, pairing and
    /// fibre shift: [`super::FrameSpace::wrap_frame`]).
    pub fn record_crossing(&mut self, crossing: &super::FrameCrossing) {
        self.record(crossing.face, crossing.pairing);
        self.fibre_shift += crossing.fibre_shift;
    }
}
