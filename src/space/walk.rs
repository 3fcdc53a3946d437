//! Walking geodesics through the cell, face to face (`docs/design.md` §3).
//!
//! The walk is generic over precision ([`Vector4`]): double-double is the reference
//! ([`super::accuracy`]), `f64` what the CPU computes, `f32` what the GPU computes, and
//! running them side by side measures what each costs.

use super::Space;
use super::exact::ExactCell;
use crate::geometry::{DdMat4, Geometry, Ray, Real, Vector4};
use glam::{DMat4, DVec4};

/// Where a ray leaves the cell through a face: the ratio `T = num/den = S(t)/C(t)` of the
/// exit point along the ray (`X ∝ p + T v`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exit<R> {
    /// The face left through.
    pub face: usize,
    /// `−N·p`, clamped to ≥ 0 (the point is inside or on the face).
    pub num: R,
    /// `N·v > 0`.
    pub den: R,
}

impl<R: Real> Exit<R> {
    /// The chart ratio `T` of the exit point.
    #[must_use]
    pub fn ratio(&self) -> R {
        self.num / self.den
    }
}

/// The cell's faces and pairings in one precision, ready to walk rays.
#[derive(Clone, Debug)]
pub struct CellWalker<V: Vector4> {
    /// The geometry.
    pub geometry: Geometry,
    /// Face covectors `N_f`: the cell is `N_f·X ≤ 0`.
    pub covectors: Vec<V>,
    /// Face pairings, rounded to this precision.
    pub pairings: Vec<V::Matrix>,
    /// What rounding each pairing to this precision left out (zero in `f64`): the pairing
    /// is applied as `pairings + pairings_lo`, compensated.
    pub pairings_lo: Vec<V::Matrix>,
    /// Each face's partner.
    pub partners: Vec<usize>,
    /// Apply pairings compensated (the default); `false` gives the plain product, which
    /// loses up to a digit in curved cells, for comparison (the benchmark reports both).
    pub compensated: bool,
    /// The longest step as a chart ratio, for the cells of S³ whose chords can pass π/2
    /// ([`Space::walks_in_steps`]: the exit ratio sees only faces met within π/2): a ray
    /// that meets no face within `T = 1` (π/4) takes a step of π/4 without crossing
    /// ([`NO_FACE`]). `None` elsewhere, where every segment in the cell is shorter than π/2.
    pub step_cap: Option<f64>,
    /// The cell each face bounds, for a space of several cells ([`Space::cells`]); empty
    /// for one cell. A walk searches the exit among its cell's faces only: after a crossing
    /// the cell of the face entered, at the start the cell that holds the ray's point.
    pub face_cells: Vec<usize>,
    /// Which faces are seams between cells ([`Space::is_seam`]); empty for one cell.
    pub seams: Vec<bool>,
}

/// A double-double matrix rounded once to `V`, and what that rounding left out (rounded
/// once too): the `hi`/`lo` pair a compensated pairing is applied with.
pub(crate) fn rounded_with_rest<V: Vector4>(m: &DdMat4) -> (V::Matrix, V::Matrix) {
    let (hi, lo) = m.parts();
    let r = V::matrix_from_f64_pair(hi, lo);
    // What the matrix used leaves out: nothing for double-double, which holds `m` itself
    // (rounding it to f64 here once made the reference apply `m` plus its own low part).
    let (h2, l2) = (*m - V::matrix_to_dd(&r)).parts();
    (r, V::matrix_from_f64_pair(h2, l2))
}

/// Records the crossings a walk hands out (`walk` runs it with a visitor) as a [`Trace`].
pub(crate) fn record<V: Copy>(
    walk: impl FnOnce(&mut dyn FnMut(&Crossing<V>) -> bool) -> (Ray<V>, f64),
) -> Trace<V> {
    let mut crossings = Vec::new();
    let (end, distance) = walk(&mut |c| {
        crossings.push(*c);
        true
    });
    Trace {
        crossings,
        end,
        distance,
    }
}

/// The face of an [`Exit`] that is a step without crossing (see [`CellWalker::step_cap`]).
pub const NO_FACE: usize = usize::MAX;

/// How many steps without crossing a walk by [`Limit::Crossings`] takes in a row before it
/// stops: sixteen steps of π/4 go twice round S³.
pub const MAX_STEPS_WITHOUT_CROSSING: usize = 16;

/// One face crossing of a traced ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing<V> {
    /// The face the ray left through.
    pub face: usize,
    /// The cell it entered (that of the partner face; 0 in a space of one cell).
    pub cell: usize,
    /// Cumulative geodesic distance from the start to the crossing.
    pub distance: f64,
    /// The ray after the pairing, on the partner face.
    pub ray: Ray<V>,
}

/// How far to trace.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Limit {
    /// Stop after this many face crossings.
    Crossings(usize),
    /// Stop at this geodesic distance.
    Distance(f64),
}

/// A traced ray: its crossings and where it stopped.
#[derive(Clone, Debug, PartialEq)]
pub struct Trace<V> {
    /// Its face crossings, in order.
    pub crossings: Vec<Crossing<V>>,
    /// The ray where tracing stopped (inside the cell).
    pub end: Ray<V>,
    /// Cumulative distance at the end.
    pub distance: f64,
}

/// What a walk does next, as a family's walker answers it ([`CellWalk::next_exit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NextExit<E> {
    /// Leave through this exit (a face, or a step without crossing, [`NO_FACE`]).
    Exit(E),
    /// No face lies ahead, ever: the geodesic stays in the cell (a great circle of S³ that
    /// meets no face, a level ray round a sphere with no sides). A walk by distance goes its
    /// whole length at once; a walk by crossings ends.
    NoFaceAhead,
    /// The ray is degenerate (a zero or non-finite tangent): the walk ends where it is.
    Degenerate,
}

/// The walk of a geometry family through its cell, the contract the walk loop is written
/// once over ([`CellWalk::walk`], [`CellWalk::trace`]), in any precision `V`: where a ray
/// leaves the cell, how far that is, how it crosses, how it moves inside. The
/// constant-curvature walker ([`CellWalker`]) and the product walker
/// ([`super::product::ProductWalker`]) implement it; each family's exit carries what its
/// crossing needs (a chart ratio, a distance).
pub trait CellWalk<V: Vector4> {
    /// Where a ray leaves the cell.
    type Exit: Copy;

    /// The ray put back onto the model (a ray on it to rounding kept bit for bit).
    #[must_use]
    fn on_model(&self, ray: Ray<V>) -> Ray<V>;

    /// The next exit of a walk that has taken `steps` steps in a row without crossing, the
    /// face `skip` just entered; or why there is none.
    #[must_use]
    fn next_exit(&self, ray: &Ray<V>, skip: Option<usize>, steps: usize) -> NextExit<Self::Exit>;

    /// The face an exit leaves through ([`NO_FACE`] for a step without crossing).
    #[must_use]
    fn exit_face(exit: &Self::Exit) -> usize;

    /// The geodesic length from the ray's point to its exit.
    #[must_use]
    fn exit_length(&self, exit: &Self::Exit) -> f64;

    /// The ray moved to its exit and through the face's pairing, back on the model.
    #[must_use]
    fn through(&self, ray: &Ray<V>, exit: &Self::Exit) -> Ray<V>;

    /// The ray moved by `t` along its geodesic, inside the cell, back on the model.
    #[must_use]
    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V>;

    /// The face to skip after crossing `exit` (the partner entered through).
    #[must_use]
    fn skip_after(&self, exit: &Self::Exit) -> Option<usize>;

    /// The cell a crossing through `exit` entered, `ray` the ray after it: a family whose
    /// spaces are one cell keeps the default, 0.
    #[must_use]
    fn cell_after(&self, ray: &Ray<V>, exit: &Self::Exit) -> usize {
        let _ = (ray, exit);
        0
    }

    /// Walks a ray through the cell until the limit, handing each crossing to `visit`
    /// (`false` stops). Returns where it stopped and the distance walked.
    ///
    /// A step without crossing is no crossing to count or visit. The walk ends short of its
    /// limit only where the ray meets no face again ([`NextExit::NoFaceAhead`], for a walk by
    /// crossings) or is degenerate; a caller tells this from the crossings it was handed.
    fn walk(
        &self,
        start: Ray<V>,
        limit: Limit,
        mut visit: impl FnMut(&Crossing<V>) -> bool,
    ) -> (Ray<V>, f64)
    where
        Self: Sized,
    {
        let mut ray = self.on_model(start);
        let mut count = 0usize;
        let mut distance = 0.0;
        let mut skip = None;
        let mut steps = 0usize;
        let max_crossings = match limit {
            Limit::Crossings(n) => n,
            Limit::Distance(_) => usize::MAX,
        };
        while count < max_crossings {
            let exit = match self.next_exit(&ray, skip, steps) {
                NextExit::Exit(exit) => exit,
                NextExit::NoFaceAhead => {
                    if let Limit::Distance(d) = limit {
                        return (self.moved_by(&ray, d - distance), d);
                    }
                    break;
                }
                NextExit::Degenerate => break,
            };
            let length = self.exit_length(&exit);
            if let Limit::Distance(d) = limit
                && distance + length >= d
            {
                return (self.moved_by(&ray, d - distance), d);
            }
            ray = self.through(&ray, &exit);
            distance += length;
            skip = self.skip_after(&exit);
            let face = Self::exit_face(&exit);
            if face == NO_FACE {
                steps += 1;
                continue;
            }
            steps = 0;
            count += 1;
            if !visit(&Crossing {
                face,
                cell: self.cell_after(&ray, &exit),
                distance,
                ray,
            }) {
                break;
            }
        }
        (ray, distance)
    }

    /// Traces a ray through the cell until the limit, recording each crossing.
    #[must_use]
    fn trace(&self, start: Ray<V>, limit: Limit) -> Trace<V>
    where
        Self: Sized,
    {
        record(|visit| self.walk(start, limit, visit))
    }
}

impl<V: Vector4> CellWalk<V> for CellWalker<V> {
    type Exit = Exit<V::Real>;

    fn on_model(&self, ray: Ray<V>) -> Ray<V> {
        CellWalker::normalized(self, ray)
    }

    /// Sixteen steps of π/4 in a row without a face go twice round S³: the great circle
    /// meets no face.
    fn next_exit(&self, ray: &Ray<V>, skip: Option<usize>, steps: usize) -> NextExit<Self::Exit> {
        if steps >= MAX_STEPS_WITHOUT_CROSSING {
            return NextExit::NoFaceAhead;
        }
        match self.exit(ray, skip) {
            Some(exit) => NextExit::Exit(exit),
            None => NextExit::Degenerate,
        }
    }

    fn exit_face(exit: &Self::Exit) -> usize {
        exit.face
    }

    fn exit_length(&self, exit: &Self::Exit) -> f64 {
        self.geometry
            .distance_from_ratio(exit.num, exit.den)
            .to_f64()
    }

    fn through(&self, ray: &Ray<V>, exit: &Self::Exit) -> Ray<V> {
        self.crossed(ray, exit)
    }

    fn moved_by(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        self.advance(ray, t)
    }

    fn skip_after(&self, exit: &Self::Exit) -> Option<usize> {
        self.entered(exit)
    }

    fn cell_after(&self, ray: &Ray<V>, exit: &Self::Exit) -> usize {
        self.entered_cell(ray, exit)
    }
}

impl<V: Vector4> CellWalker<V> {
    /// The walker of a space in the precision `V`.
    #[must_use]
    pub fn new(space: &Space) -> Self {
        let mut walker = if let Some(cell) = space.exact() {
            Self::from_exact(cell)
        } else {
            let covectors: Vec<_> = space.faces.iter().map(|f| f.covector).collect();
            let pairings: Vec<_> = space.faces.iter().map(|f| f.pairing).collect();
            let partners: Vec<_> = space.faces.iter().map(|f| f.partner).collect();
            Self::from_parts(space.geometry, &covectors, &pairings, partners)
        };
        if space.walks_in_steps() {
            walker.step_cap = Some(1.0);
        }
        if space.cells.len() > 1 {
            walker.face_cells = space.faces.iter().map(|f| f.cell).collect();
            walker.seams = (0..space.faces.len()).map(|f| space.is_seam(f)).collect();
        }
        walker
    }

    /// A walker from a cell in double-double: every covector and pairing entry rounded
    /// once to `V`, and the pairings' low parts what that rounding left out (so the `f64`
    /// walker too applies its pairings to about 32 digits).
    #[must_use]
    pub fn from_exact(cell: &ExactCell) -> Self {
        let (pairings, pairings_lo) = cell
            .faces
            .iter()
            .map(|f| rounded_with_rest::<V>(&f.pairing))
            .unzip();
        Self {
            geometry: cell.geometry,
            covectors: cell
                .faces
                .iter()
                .map(|f| {
                    let (hi, lo) = f.covector().parts();
                    V::from_f64_pair(hi, lo)
                })
                .collect(),
            pairings,
            pairings_lo,
            partners: cell.faces.iter().map(|f| f.partner).collect(),
            compensated: true,
            step_cap: None,
            face_cells: Vec::new(),
            seams: Vec::new(),
        }
    }

    /// A walker from faces given directly (`f64` covectors and pairings, each face's
    /// partner), for cells that are not a validated [`Space`], such as a billiard of mirrors.
    #[must_use]
    pub fn from_parts(
        geometry: Geometry,
        covectors: &[DVec4],
        pairings: &[DMat4],
        partners: Vec<usize>,
    ) -> Self {
        Self {
            geometry,
            covectors: covectors.iter().map(|&c| V::from_f64(c)).collect(),
            pairings: pairings.iter().map(|&m| V::matrix_from_f64(m)).collect(),
            pairings_lo: pairings
                .iter()
                .map(|&m| V::matrix_from_f64(m - V::matrix_to_f64(&V::matrix_from_f64(m))))
                .collect(),
            partners,
            compensated: true,
            step_cap: None,
            face_cells: Vec::new(),
            seams: Vec::new(),
        }
    }

    /// The partner of the face an exit left through, to skip next; none after a step
    /// without crossing.
    #[must_use]
    pub fn entered(&self, exit: &Exit<V::Real>) -> Option<usize> {
        (exit.face != NO_FACE).then(|| self.partners[exit.face])
    }

    /// Applies face `face`'s pairing to `x`, compensated
    /// ([`Vector4::transform_compensated`]).
    #[inline]
    #[must_use]
    pub fn apply_pairing(&self, face: usize, x: V) -> V {
        // Flat pairings are rotations and translations with small entries: nothing cancels,
        // and the plain product is already at the limit (docs/performance.md).
        if self.compensated && self.geometry != Geometry::Euclidean {
            V::transform_compensated(&self.pairings[face], &self.pairings_lo[face], x)
        } else {
            self.pairings[face] * x
        }
    }

    /// The exit face: the smallest positive `T = −(N·p)/(N·v)` among faces with `N·v > 0`.
    ///
    /// `skip` is the face the ray just entered through: a geodesic meets a plane at most once
    /// (within a hemisphere in S³), so it cannot leave through it, and skipping it makes a
    /// ray that starts exactly on that face robust against rounding. Returns `None` only for
    /// a degenerate ray (zero or non-finite tangent).
    #[must_use]
    pub fn exit(&self, ray: &Ray<V>, skip: Option<usize>) -> Option<Exit<V::Real>> {
        let zero = V::Real::ZERO;
        let mut best: Option<Exit<V::Real>> = None;
        let cell = self.cell_of(ray, skip);
        for (f, n) in self.covectors.iter().enumerate() {
            if Some(f) == skip || cell.is_some_and(|c| self.face_cells[f] != c) {
                continue;
            }
            let den = n.dot(ray.tangent);
            if !(den > zero) {
                continue;
            }
            let num = (-n.dot(ray.point)).max(zero);
            // num/den < best.num/best.den without dividing.
            let better = best.is_none_or(|b| num * b.den < b.num * den);
            if better {
                best = Some(Exit { face: f, num, den });
            }
        }
        if let Some(cap) = self.step_cap {
            let cap = V::Real::from_f64(cap);
            if best.is_none_or(|b| b.num > cap * b.den) {
                return Some(Exit {
                    face: NO_FACE,
                    num: cap,
                    den: V::Real::ONE,
                });
            }
        }
        best
    }

    /// The cell a walk is in, in a space of several cells (`None` for one): that of the face
    /// just entered (`skip`), else the one whose faces the ray's point is least outside of.
    #[must_use]
    pub fn cell_of(&self, ray: &Ray<V>, skip: Option<usize>) -> Option<usize> {
        if self.face_cells.is_empty() {
            return None;
        }
        if let Some(f) = skip {
            return Some(self.face_cells[f]);
        }
        // A cell's faces are a run: one pass, no allocation (this runs at every start).
        let mut best: Option<(usize, V::Real)> = None;
        let mut f = 0;
        while f < self.face_cells.len() {
            let cell = self.face_cells[f];
            let mut outside = V::Real::from_f64(f64::NEG_INFINITY);
            while f < self.face_cells.len() && self.face_cells[f] == cell {
                outside = outside.max(self.covectors[f].dot(ray.point));
                f += 1;
            }
            if best.is_none_or(|(_, least)| outside < least) {
                best = Some((cell, outside));
            }
        }
        best.map(|(cell, _)| cell)
    }

    /// The cell a walk enters through `exit`'s face (0 in a space of one cell, and the
    /// cell it is in after a step without crossing).
    #[must_use]
    pub fn entered_cell(&self, ray_after: &Ray<V>, exit: &Exit<V::Real>) -> usize {
        self.cell_of(ray_after, self.entered(exit)).unwrap_or(0)
    }

    /// Moves the ray to its exit point and applies the face's pairing; returns the new ray
    /// (re-normalized onto the model) and the geodesic length of the segment.
    ///
    /// Exit point `X ∝ (N·v) p − (N·p) v`, tangent `γ' ∝ κ (N·p) p + (N·v) v`; the pairing
    /// is applied compensated ([`Self::apply_pairing`]), the one step where the plain
    /// arithmetic lost digits beyond the problem's conditioning.
    #[must_use]
    pub fn cross(&self, ray: &Ray<V>, exit: &Exit<V::Real>) -> (Ray<V>, V::Real) {
        let length = self.geometry.distance_from_ratio(exit.num, exit.den);
        (self.crossed(ray, exit), length)
    }

    /// The ray of [`Self::cross`] without the segment's length (the walk has taken it
    /// already, [`CellWalk::exit_length`]).
    fn crossed(&self, ray: &Ray<V>, exit: &Exit<V::Real>) -> Ray<V> {
        let g = self.geometry;
        let k = V::Real::from_f64(g.kappa());
        let (num, den) = (exit.num, exit.den);
        let at_face = ray.point.scale(den) + ray.tangent.scale(num);
        let tangent = ray.point.scale(-k * num) + ray.tangent.scale(den);
        if exit.face == NO_FACE {
            let point = self.onto_model(at_face);
            let tangent = g.unit_tangent(point, tangent);
            return Ray { point, tangent };
        }
        let point = self.onto_model(self.apply_pairing(exit.face, at_face));
        let tangent = g.unit_tangent(point, self.apply_pairing(exit.face, tangent));
        Ray { point, tangent }
    }

    /// The ray moved by `t` along its geodesic (within the cell), re-normalized.
    #[must_use]
    pub fn advance(&self, ray: &Ray<V>, t: f64) -> Ray<V> {
        let g = self.geometry;
        let (point, tangent) = g.geodesic(ray.point, ray.tangent, t);
        let point = self.onto_model(point);
        let tangent = g.unit_tangent(point, tangent);
        Ray { point, tangent }
    }

    /// A point put back onto the model. In a cell walked in steps ([`Self::step_cap`]:
    /// those that reach the equator among them) a point of S³ is only scaled to unit
    /// length, never turned to its antipode as [`Geometry::project_point`] turns it into
    /// the hemisphere `w ≥ 0`:
    /// there the 3-sphere's points past the equator are other points than their antipodes,
    /// and where a point and its antipode are one (projective space, on its equator face)
    /// the tangent would have to turn with it, so a turn of the point alone sent the ray
    /// back the way it came. Bit for bit `project_point` where `w ≥ 0`.
    fn onto_model(&self, p: V) -> V {
        if self.step_cap.is_some() && self.geometry == Geometry::Spherical {
            p.scale(V::Real::ONE / p.dot(p).sqrt())
        } else {
            self.geometry.project_point(p)
        }
    }

    /// The ray put back onto the model if it is off it: the point projected, the tangent
    /// made tangent there and of unit length. The crossing formulas assume a unit tangent
    /// (in S³ and H³ the exit tangent `κ (N·p) p + (N·v) v` is wrong for any other length),
    /// so every walk starts with this. A ray already on the model to rounding is kept bit
    /// for bit.
    #[must_use]
    pub fn normalized(&self, ray: Ray<V>) -> Ray<V> {
        let g = self.geometry;
        let tolerance = V::Real::from_f64(64.0) * V::Real::EPSILON;
        let one = V::Real::ONE;
        // Forms of vectors with entries of size w are known to ε·w² only.
        let w = ray.point.w().abs().max(one);
        let scaled = tolerance * w * w;
        let v = ray.tangent;
        let (off_model, off_tangent) = match g {
            Geometry::Euclidean => (
                (ray.point.w() - one).abs() > tolerance,
                v.w().abs() > tolerance,
            ),
            _ => (
                (g.form(ray.point, ray.point) - V::Real::from_f64(g.kappa())).abs() > scaled,
                g.form(ray.point, v).abs() > scaled,
            ),
        };
        let off_unit = off_tangent || !((g.form(v, v) - one).abs() <= scaled);
        if !off_model && !off_unit {
            return ray;
        }
        let point = g.project_point(ray.point);
        Ray {
            point,
            tangent: g.unit_tangent(point, ray.tangent),
        }
    }

    /// Walks a ray through the cell until the limit ([`CellWalk::walk`], the one walk loop).
    pub fn walk(
        &self,
        start: Ray<V>,
        limit: Limit,
        visit: impl FnMut(&Crossing<V>) -> bool,
    ) -> (Ray<V>, f64) {
        CellWalk::walk(self, start, limit, visit)
    }

    /// Traces a ray through the cell until the limit, recording each crossing
    /// ([`CellWalk::trace`]).
    #[must_use]
    pub fn trace(&self, start: Ray<V>, limit: Limit) -> Trace<V> {
        CellWalk::trace(self, start, limit)
    }
}
