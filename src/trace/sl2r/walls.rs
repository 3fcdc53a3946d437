//! Walls with windows in the cell of `UT Σ`: each side drawn as a see-through panel with a
//! window, met exactly where a ray crosses it (the walk solves each crossing to the last
//! bit), as in the other families ([`crate::scene::walls`]).
//!
//! A side of the cell is a band: a side of the polygon times the whole fibre, a circle, so
//! it has edges only along the polygon's corners. Its window is the middle of the band, the
//! whole fibre high: the points whose base point lies within `(1 − w)` of the side's half
//! length from the side's midpoint, measured along the side (`w` the margin's share:
//! `1 − opening`). A pairing is an isometry of `H²` carrying a side's midpoint to its
//! partner's, so the window of a side is carried onto its partner's: one window, seen from
//! both sides. Glued sides share a colour.

use super::Sl2rScene;
use crate::scene::walls::{Veil, WallStyle, wall_colours};
use crate::space::sl2r::UnitTangentSpace;
use crate::space::sl2r::flow::{Sl2rRay, lorentz};
use glam::DVec3;

/// The walls of a unit tangent bundle's cell in a style.
#[derive(Clone, Debug, PartialEq)]
pub struct Sl2rWalls {
    /// Per side: its pair's colour.
    pub colours: Vec<DVec3>,
    /// Per side: the unit tangent along it at its midpoint, `(−sin θ, cos θ, 0)`.
    pub along: Vec<[f64; 3]>,
    /// Per side: its unit outward normal, `(cosh ρ cos θ, cosh ρ sin θ, sinh ρ)` (a tangent
    /// vector at each of its points).
    pub normals: Vec<[f64; 3]>,
    /// How far along a side from its midpoint the window reaches (`−1` for solid walls).
    pub window: f64,
    /// The share of light a panel stops.
    pub opacity: f64,
    /// A ray stops once less than this share of light gets through.
    pub stop_below: f64,
}

impl Sl2rWalls {
    /// The walls of `space` in `style`; `None` where nothing is drawn (opening 1). Rays stop
    /// behind walls that let less than `stop_below` of the light through.
    #[must_use]
    pub fn new(space: &UnitTangentSpace, style: WallStyle, stop_below: f64) -> Option<Self> {
        if style.opening >= 1.0 {
            return None;
        }
        let sides = space.sides();
        let n = sides.len();
        let partners: Vec<usize> = sides.iter().map(|s| s.partner).collect();
        let rho = space.inradius();
        // The half length of a side: cosh R = cosh ρ cosh(L/2) in the right triangle of the
        // centre, a side's midpoint and its vertex.
        let half = (space.circumradius().cosh() / rho.cosh()).acosh();
        let angle = |f: usize| std::f64::consts::TAU * f as f64 / n as f64;
        Some(Self {
            colours: wall_colours(&partners, &vec![false; n]),
            along: (0..n)
                .map(|f| [-angle(f).sin(), angle(f).cos(), 0.0])
                .collect(),
            normals: (0..n)
                .map(|f| {
                    let (s, c) = angle(f).sin_cos();
                    [rho.cosh() * c, rho.cosh() * s, rho.sinh()]
                })
                .collect(),
            window: if style.opening <= 0.0 {
                -1.0
            } else {
                style.opening * half
            },
            opacity: style.opacity,
            stop_below,
        })
    }

    /// Whether the base point `p` of side `face` is on the panel rather than in its window:
    /// its distance along the side from the midpoint, `asinh ⟨p, t⟩`, past the window's
    /// reach.
    #[must_use]
    pub fn on_panel(&self, face: usize, p: [f64; 3]) -> bool {
        lorentz(p, self.along[face]).asinh().abs() > self.window
    }

    /// The panel's colour lit by the angle at which the ray `at` (on the side) meets it: the
    /// side's normal in the body frame is `(⟨N, e⟩, ⟨N, e⊥⟩, 0)`.
    #[must_use]
    pub fn lit_colour(&self, face: usize, at: &Sl2rRay<f64>) -> DVec3 {
        let [e, f, _] = at.frame;
        let n = self.normals[face];
        let normal = DVec3::new(lorentz(n, e), lorentz(n, f), 0.0);
        let facing = normal.dot(DVec3::from_array(at.velocity)).abs().min(1.0);
        (self.colours[face] * (0.55 + 0.45 * facing)).min(DVec3::ONE)
    }

    /// Adds the wall a ray meets crossing `face` at `at` (on the side), `distance` from the
    /// eye, to the veil. Returns whether enough light still gets through to go on.
    pub fn cross(
        &self,
        veil: &mut Veil,
        scene: &Sl2rScene,
        face: usize,
        at: &Sl2rRay<f64>,
        distance: f64,
    ) -> bool {
        if self.on_panel(face, at.frame[2]) {
            let fog = (-distance / scene.fog_distance).exp();
            let seen = fog * self.lit_colour(face, at) + (1.0 - fog) * scene.fog_colour;
            veil.colour += veil.through * self.opacity * seen;
            veil.through *= 1.0 - self.opacity;
        }
        veil.through >= self.stop_below
    }
}
