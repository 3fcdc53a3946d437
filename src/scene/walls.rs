//! Walls with windows: every face of the cell drawn as a see-through panel with a hole, glued
//! faces in one colour, mirrors in silver. The gluing is then seen at once: a window of one
//! colour leads to the window of the same colour.
//!
//! A wall lies in its face, so a ray meets it exactly where it crosses the face: walls cost
//! nothing between crossings and add no object to intersect. The hole is the face inset by a
//! metric margin: the points of the face at in-plane distance at least `w` from every edge.
//! For a point `X` of face `f` and another face `g` meeting it at the dihedral angle `θ`, the
//! right triangle through the edge gives `S(d(X, plane g)) = S(d_f(X, edge)) · sin θ`
//! (`S` = sin, identity, sinh), so `X` is on the panel (not in the window) exactly when
//! `S(d(X, plane g)) < S(w) · sin θ_fg` for some `g`. Faces whose planes do not meet `f`
//! (parallel in E³, ultraparallel in H³: `sin θ` taken as 0) and faces beyond the polygon
//! give no constraint, so all faces can be tested. The margin is `w = (1 − opening) · ρ_f`
//! with `ρ_f` the face's in-plane inradius: opening 0 leaves no hole, opening 1 no wall.
//!
//! The panels are translucent: crossing one with `through` light left, a ray adds `through ·
//! α · colour` (the panel's colour lit by the angle of incidence and fogged by its distance)
//! and keeps `through · (1 − α)`. A ray whose `through` falls below the fog's cut-off weight
//! stops there (what lies behind changes the pixel by less than the cut-off bound). The
//! shader (`WALLS`) does the same in f32.

use crate::geometry::{Geometry, ORIGIN};
use crate::scene::{Shading, palette};
use crate::space::Space;
use glam::{DVec3, DVec4};

/// The opacity of a wall when none is given: the cells behind still read through three or
/// four walls.
pub const DEFAULT_WALL_OPACITY: f64 = 0.45;

/// A mirror's opacity relative to a wall's: mirrors are drawn lighter, like glass.
pub const MIRROR_OPACITY: f64 = 0.6;

/// A mirror's colour (linear RGB): silver.
pub const MIRROR_COLOUR: DVec3 = DVec3::new(0.78, 0.82, 0.88);

/// The margin `S(w)` standing for a face with no hole (opening 0): larger than any `S(d)`
/// of the cell, finite so that `0 · margin` stays 0 in f32.
const SOLID: f64 = 1e30;

/// How the walls are drawn: how far their windows are open and how much light they stop.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallStyle {
    /// 0: solid walls; 1: no walls (the window fills the face); between, the margin left
    /// round the window is `(1 − opening)` times the face's inradius.
    pub opening: f64,
    /// The share of light a wall stops, in (0, 1] (mirrors stop [`MIRROR_OPACITY`] of it).
    pub opacity: f64,
}

/// A wall setting out of range.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum WallError {
    /// The opening is not in [0, 1].
    #[error("the walls' opening must be between 0 (solid walls) and 1 (no walls), got {0}")]
    Opening(f64),
    /// The opacity is not in (0, 1].
    #[error("the walls' opacity must be above 0 and at most 1, got {0}")]
    Opacity(f64),
}

impl WallStyle {
    /// Walls with windows `opening` open and the default opacity.
    ///
    /// # Errors
    /// The opening is not in [0, 1].
    pub fn new(opening: f64) -> Result<Self, WallError> {
        Self::with_opacity(opening, DEFAULT_WALL_OPACITY)
    }

    /// Walls with windows `opening` open that stop `opacity` of the light.
    ///
    /// # Errors
    /// The opening is not in [0, 1] or the opacity not in (0, 1].
    pub fn with_opacity(opening: f64, opacity: f64) -> Result<Self, WallError> {
        if !(0.0..=1.0).contains(&opening) {
            return Err(WallError::Opening(opening));
        }
        if !(opacity > 0.0 && opacity <= 1.0) {
            return Err(WallError::Opacity(opacity));
        }
        Ok(Self { opening, opacity })
    }
}

/// One face's panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallFace {
    /// The face's covector scaled to a unit normal of the form: `N̂·X̂ = S(signed distance)`
    /// for a point `X̂` of the model.
    pub unit: DVec4,
    /// The panel's colour: one per pair of glued faces ([`palette`] of the pair's rank),
    /// [`MIRROR_COLOUR`] for a mirror.
    pub colour: DVec3,
    /// `S(w)` of the margin `w` round the window (a huge number for a solid wall).
    pub margin: f64,
    /// The share of light the panel stops.
    pub opacity: f64,
    /// Whether the face is a mirror (glued to itself by a reflection).
    pub mirror: bool,
    /// The face's in-plane inradius `ρ_f` (the radius of the largest disc in it).
    pub inradius: f64,
}

/// The walls of a cell in a style: what the tracers need at a crossing.
#[derive(Clone, Debug, PartialEq)]
pub struct WallPanels {
    /// The geometry.
    pub geometry: Geometry,
    /// Per face.
    pub faces: Vec<WallFace>,
    /// `sin θ_fg` for each pair of faces (row `f`, column `g`; 0 where the planes do not
    /// meet).
    sines: Vec<f64>,
    /// A ray stops once less than this share of light gets through.
    pub stop_below: f64,
    /// Each face's cell in a space of several cells (empty for one): a window is framed
    /// by its own cell's faces.
    cells: Vec<usize>,
}

/// What the walls a ray crossed added to its colour, and the share of light they let through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Veil {
    /// The walls' light, already weighted by what reached them.
    pub colour: DVec3,
    /// The share of light that gets through all of them.
    pub through: f64,
}

impl Veil {
    /// No wall crossed.
    pub const CLEAR: Veil = Veil {
        colour: DVec3::ZERO,
        through: 1.0,
    };

    /// The colour seen through the walls of what lies behind them.
    #[must_use]
    pub fn over(&self, behind: DVec3) -> DVec3 {
        self.colour + self.through * behind
    }
}

/// The walls' colours: one per pair of glued faces ([`palette`] of the pair's rank, pairs
/// numbered in the order of their first face), [`MIRROR_COLOUR`] for a mirror (a face glued
/// to itself by a reflection). The mini-map labels faces in these colours too.
#[must_use]
pub fn wall_colours(partners: &[usize], reflections: &[bool]) -> Vec<DVec3> {
    let n = partners.len();
    let mut rank = vec![usize::MAX; n];
    let mut pairs = 0;
    for f in 0..n {
        let p = partners[f].min(n - 1);
        if rank[f] == usize::MAX {
            rank[f] = pairs;
            rank[p] = pairs;
            pairs += 1;
        }
    }
    (0..n)
        .map(|f| {
            if partners[f] == f && reflections.get(f).copied().unwrap_or(false) {
                MIRROR_COLOUR
            } else {
                palette(rank[f])
            }
        })
        .collect()
}

/// Each face's partner and whether its pairing reverses orientation: what the walls'
/// colours are chosen by ([`wall_colours`]).
#[must_use]
pub fn gluing(space: &Space) -> (Vec<usize>, Vec<bool>) {
    space
        .faces
        .iter()
        .map(|f| (f.partner, f.pairing.determinant() < 0.0))
        .unzip()
}

/// `S⁻¹`: asin, identity, asinh.
fn s_inverse(geometry: Geometry, s: f64) -> f64 {
    match geometry {
        Geometry::Spherical => s.clamp(-1.0, 1.0).asin(),
        Geometry::Euclidean => s,
        Geometry::Hyperbolic => s.asinh(),
    }
}

/// The model point on the ray through `x` (a positive multiple of a point: no sign flip in
/// S³, where a crossing point may lie past the chart's equator).
#[must_use]
pub fn wall_point(geometry: Geometry, x: DVec4) -> DVec4 {
    match geometry {
        Geometry::Spherical => x / x.length(),
        Geometry::Euclidean => x / x.w,
        Geometry::Hyperbolic => x / (-geometry.form(x, x)).sqrt(),
    }
}

/// The covector scaled to unit length in the dual form `B(N, M) = n·m + κ r_N r_M`.
fn unit_covector(geometry: Geometry, n: DVec4) -> DVec4 {
    n / geometry.form(n, n).sqrt()
}

/// The normal vector of a unit covector: `⟨v, X⟩ = N̂·X` for every `X`.
fn normal_vector(geometry: Geometry, n: DVec4) -> DVec4 {
    match geometry {
        Geometry::Euclidean => n.truncate().extend(0.0),
        _ => DVec4::new(n.x, n.y, n.z, geometry.kappa() * n.w),
    }
}

impl WallPanels {
    /// The walls of `space` in `style`, stopping rays as `shading`'s fog cut-off does; `None`
    /// where nothing is drawn (opening 1, or a cell without faces).
    #[must_use]
    pub fn new(space: &Space, style: WallStyle, shading: &Shading) -> Option<Self> {
        let covectors: Vec<DVec4> = space.faces.iter().map(|f| f.covector).collect();
        let (partners, reflections) = gluing(space);
        let cells: Vec<usize> = space.faces.iter().map(|f| f.cell).collect();
        let seams: Vec<bool> = (0..space.faces.len()).map(|f| space.is_seam(f)).collect();
        Self::in_cells(
            space.geometry,
            &covectors,
            &partners,
            &reflections,
            Some((&cells, &seams)),
            style,
            shading,
        )
    }

    /// [`WallPanels::new`] from the cell's face covectors, partners and which pairings
    /// reverse orientation.
    #[must_use]
    pub fn from_parts(
        geometry: Geometry,
        covectors: &[DVec4],
        partners: &[usize],
        reflections: &[bool],
        style: WallStyle,
        shading: &Shading,
    ) -> Option<Self> {
        Self::in_cells(
            geometry,
            covectors,
            partners,
            reflections,
            None,
            style,
            shading,
        )
    }

    /// [`WallPanels::from_parts`] for faces that bound several cells: `cells` gives each
    /// face's cell and whether it is a seam ([`Space::is_seam`]). A face's window is framed
    /// by the faces of its own cell only, and nothing is drawn on a seam (no face of the
    /// space).
    #[must_use]
    pub fn in_cells(
        geometry: Geometry,
        covectors: &[DVec4],
        partners: &[usize],
        reflections: &[bool],
        cells: Option<(&[usize], &[bool])>,
        style: WallStyle,
        shading: &Shading,
    ) -> Option<Self> {
        let (cells, seams) = cells.unwrap_or((&[], &[]));
        if covectors.is_empty() || style.opening >= 1.0 {
            return None;
        }
        let n = covectors.len();
        // A face without a (valid) partner counts as glued to itself.
        let partners: Vec<usize> = (0..n)
            .map(|f| partners.get(f).copied().filter(|&p| p < n).unwrap_or(f))
            .collect();
        let units: Vec<DVec4> = covectors
            .iter()
            .map(|&c| unit_covector(geometry, c))
            .collect();
        let mut sines = vec![0.0; n * n];
        for f in 0..n {
            for g in 0..n {
                let same_cell = cells.is_empty() || cells[f] == cells[g];
                if f != g && same_cell {
                    let c = geometry.form(units[f], units[g]);
                    sines[f * n + g] = (1.0 - c * c).max(0.0).sqrt();
                }
            }
        }
        let inradii: Vec<f64> = (0..n)
            .map(|f| face_inradius(geometry, &units, &sines, f))
            .collect();
        let colours = wall_colours(&partners, reflections);
        let faces = (0..n)
            .map(|f| {
                let partner = partners[f];
                let mirror = partner == f && reflections.get(f).copied().unwrap_or(false);
                // Glued faces are congruent: one margin for both, so the window matches.
                let inradius = inradii[f].min(inradii[partner]);
                let margin = if style.opening <= 0.0 {
                    SOLID
                } else {
                    geometry.s((1.0 - style.opening) * inradius)
                };
                let seam = seams.get(f).copied().unwrap_or(false);
                WallFace {
                    unit: units[f],
                    colour: colours[f],
                    margin,
                    opacity: if seam {
                        0.0
                    } else {
                        style.opacity * if mirror { MIRROR_OPACITY } else { 1.0 }
                    },
                    mirror,
                    inradius,
                }
            })
            .collect();
        Some(Self {
            geometry,
            faces,
            sines,
            stop_below: shading.cutoff_weight,
            cells: cells.to_vec(),
        })
    }

    /// `sin θ_fg`: 0 where the planes of faces `f` and `g` do not meet.
    #[must_use]
    pub fn sine(&self, f: usize, g: usize) -> f64 {
        self.sines[f * self.faces.len() + g]
    }

    /// Whether the point `x` of face `f` (a model point, [`wall_point`]) is on the panel
    /// rather than in its window.
    #[must_use]
    pub fn on_panel(&self, f: usize, x: DVec4) -> bool {
        let margin = self.faces[f].margin;
        let same_cell = |g: usize| self.cells.is_empty() || self.cells[g] == self.cells[f];
        self.faces
            .iter()
            .enumerate()
            .any(|(g, face)| g != f && same_cell(g) && -face.unit.dot(x) < margin * self.sine(f, g))
    }

    /// The panel's lit colour where a ray with tangent `v` (at the crossing point, any
    /// length) crosses face `f`, before the fog: walls are brighter seen face on, mirrors at a
    /// grazing angle.
    #[must_use]
    pub fn lit_colour(&self, f: usize, v: DVec4) -> DVec3 {
        let face = &self.faces[f];
        let facing = (face.unit.dot(v) / self.geometry.form(v, v).sqrt())
            .abs()
            .min(1.0);
        let light = if face.mirror {
            0.55 + 0.45 * (1.0 - facing)
        } else {
            0.55 + 0.45 * facing
        };
        (face.colour * light).min(DVec3::ONE)
    }

    /// Adds the wall a ray meets leaving the cell through face `f` at `at_face` (any positive
    /// multiple of the exit point), with tangent `v` there (any length), `distance` from the
    /// eye, to the veil. Returns whether enough light still gets through to go on.
    pub fn cross(
        &self,
        veil: &mut Veil,
        shading: &Shading,
        f: usize,
        at_face: DVec4,
        v: DVec4,
        distance: f64,
    ) -> bool {
        let x = wall_point(self.geometry, at_face);
        if self.on_panel(f, x) {
            let fog = (-distance / shading.fog_distance).exp();
            let seen = fog * self.lit_colour(f, v) + (1.0 - fog) * shading.fog_colour;
            let alpha = self.faces[f].opacity;
            veil.colour += veil.through * alpha * seen;
            veil.through *= 1.0 - alpha;
        }
        veil.through >= self.stop_below
    }
}

/// The in-plane inradius of face `f`: the largest `ρ` such that a point of the face lies at
/// in-plane distance `ρ` from every edge, found by a compass search over the face's plane
/// (geodesic polar coordinates about the foot of the perpendicular from the centre) from a
/// grid of starts. The function maximised, `min_g S(d(X, plane g)) / sin θ_fg`, is `S` of
/// the distance to the nearest edge line.
fn face_inradius(geometry: Geometry, units: &[DVec4], sines: &[f64], f: usize) -> f64 {
    let n = units.len();
    let unit = units[f];
    let normal = normal_vector(geometry, unit);
    // The foot of the perpendicular from the origin; a face through the origin's antipode
    // direction (S³, a face at π/2) has its foot anywhere on it: take the origin moved along
    // a tangent of the plane.
    let foot_raw = ORIGIN - unit.dot(ORIGIN) * normal;
    let foot = if foot_raw.length() > 1e-9 {
        wall_point(geometry, foot_raw)
    } else {
        DVec4::X
    };
    // Two orthonormal tangents of the face's plane at the foot.
    let mut basis: Vec<DVec4> = Vec::new();
    for axis in [DVec4::X, DVec4::Y, DVec4::Z, DVec4::W] {
        let mut t = geometry.project_tangent(foot, axis);
        if geometry == Geometry::Euclidean {
            t.w = 0.0;
        }
        t -= geometry.form(t, normal) * normal;
        for b in &basis {
            t -= geometry.form(t, *b) * *b;
        }
        let len2 = geometry.form(t, t);
        if len2 > 1e-12 {
            basis.push(t / len2.sqrt());
        }
        if basis.len() == 2 {
            break;
        }
    }
    if basis.len() < 2 {
        return 0.0;
    }
    let point = |a: f64, b: f64| -> DVec4 {
        let r = (a * a + b * b).sqrt();
        if r == 0.0 {
            return foot;
        }
        let dir = (basis[0] * a + basis[1] * b) / r;
        wall_point(geometry, geometry.geodesic(foot, dir, r).0)
    };
    let height = |a: f64, b: f64| -> f64 {
        let x = point(a, b);
        (0..n)
            .filter(|&g| g != f && sines[f * n + g] > 1e-9)
            .map(|g| -units[g].dot(x) / sines[f * n + g])
            .fold(f64::INFINITY, f64::min)
    };
    // Far enough to cover any face of a cell (the chart distance is what matters in S³,
    // where distances stay below π).
    let reach = match geometry {
        Geometry::Spherical => 1.5,
        _ => 4.0,
    };
    let mut best = (f64::NEG_INFINITY, 0.0, 0.0);
    let steps = 8;
    for i in -steps..=steps {
        for j in -steps..=steps {
            let (a, b) = (
                reach * f64::from(i) / f64::from(steps),
                reach * f64::from(j) / f64::from(steps),
            );
            let h = height(a, b);
            if h > best.0 {
                best = (h, a, b);
            }
        }
    }
    let (mut h, mut a, mut b) = best;
    let mut step = reach / f64::from(steps);
    // A pattern search halves its step when no move helps: ~30 halvings, each after a few
    // moves; the cap only guards against a creeping ridge.
    for _ in 0..4096 {
        if step <= 1e-9 {
            break;
        }
        let mut moved = false;
        for (da, db) in [
            (1.0, 0.0),
            (-1.0, 0.0),
            (0.0, 1.0),
            (0.0, -1.0),
            (0.7, 0.7),
            (-0.7, 0.7),
            (0.7, -0.7),
            (-0.7, -0.7),
        ] {
            let (na, nb) = (a + step * da, b + step * db);
            let nh = height(na, nb);
            if nh > h {
                (h, a, b) = (nh, na, nb);
                moved = true;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    if h.is_finite() {
        s_inverse(geometry, h.max(0.0))
    } else {
        0.0
    }
}
