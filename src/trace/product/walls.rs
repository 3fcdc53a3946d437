//! Walls with windows in a product cell: each face drawn as a see-through panel with a
//! hole, glued faces in one colour (the sides by their letters, the top with the bottom),
//! met exactly where a ray crosses the face, as in the constant-curvature cells
//! ([`crate::scene::walls`]).
//!
//! A side face is the side's segment times the circle: a flat strip. A point of it is in
//! the window when it is at least the margin `w` from the face's edges: along the side from
//! both corners (`h − d(X, M)`, with `M` the side's midpoint and `h` half its length) and
//! along the fibre from the top and the bottom (`L/2 − |z|`). The top and bottom are the
//! polygon: a point is in the window when it is at least `w` from every side's line. The
//! margin is `(1 − opening)` times the face's in-plane inradius (`min(h, L/2)` for a side,
//! the polygon's inradius for the top and bottom). The whole sphere has no edge: its top
//! and bottom keep a window of radius `opening · π` about the cell's centre.

use super::{ProductScene, base, base_form, surface_distance};
use crate::geometry::Geometry;
use crate::scene::walls::{Veil, WallStyle, wall_colours};
use crate::space::product::{ProductSpace, ProductWalker};
use glam::{DVec3, DVec4};

/// One face's panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProductWall {
    /// The panel's colour (one per pair of glued faces).
    pub colour: DVec3,
    /// The margin `w` round the window (a distance); infinite for a solid wall.
    pub margin: f64,
    /// A side's midpoint on the surface (unused for the top and bottom).
    pub midpoint: DVec4,
    /// Half a side's length (unused for the top and bottom).
    pub half_side: f64,
}

/// The walls of a product cell in a style.
#[derive(Clone, Debug, PartialEq)]
pub struct ProductWalls {
    geometry: Geometry,
    /// The sides' unit covectors (`−N·X̂ = S(distance inside)`).
    covectors: Vec<DVec4>,
    half_length: f64,
    /// Per face: the sides, then the top and the bottom.
    pub faces: Vec<ProductWall>,
    /// The share of light a panel stops.
    pub opacity: f64,
    /// A ray stops once less than this share of light gets through.
    pub stop_below: f64,
}

impl ProductWalls {
    /// The walls of `space` in `style`; `None` where nothing is drawn (opening 1). Rays
    /// stop behind walls that let less than `stop_below` of the light through.
    #[must_use]
    pub fn new(space: &ProductSpace, style: WallStyle, stop_below: f64) -> Option<Self> {
        if style.opening >= 1.0 {
            return None;
        }
        let g = space.base();
        let walker = ProductWalker::<DVec4>::new(space);
        let n = walker.covectors.len();
        let polygon = space.polygon();
        let mut partners: Vec<usize> = walker.partners.clone();
        partners.extend([n + 1, n]);
        let colours = wall_colours(&partners, &vec![false; n + 2]);
        let inradius = space.base_inradius();
        let circumradius = crate::geometry::Real::to_f64(polygon.circumradius);
        let half = 0.5 * space.length();
        let margin = |r: f64| {
            if style.opening <= 0.0 {
                f64::INFINITY
            } else {
                (1.0 - style.opening) * r
            }
        };
        let at = |radius: f64, angle: f64| {
            let (c, s) = g.cs(radius);
            DVec4::new(s * angle.cos(), s * angle.sin(), 0.0, c)
        };
        let mut faces: Vec<ProductWall> = (0..n)
            .map(|k| {
                let angle = std::f64::consts::TAU * k as f64 / n as f64;
                let midpoint = at(inradius, angle);
                let corner = at(circumradius, angle - std::f64::consts::PI / n as f64);
                let half_side = surface_distance(g, midpoint, corner);
                ProductWall {
                    colour: colours[k],
                    margin: margin(half_side.min(half)),
                    midpoint,
                    half_side,
                }
            })
            .collect();
        let cap = if n == 0 {
            // No edge: the window is a cap about the centre (the margin field holds its
            // radius).
            style.opening * std::f64::consts::PI
        } else {
            margin(inradius)
        };
        for k in [n, n + 1] {
            faces.push(ProductWall {
                colour: colours[k],
                margin: cap,
                midpoint: DVec4::W,
                half_side: 0.0,
            });
        }
        let covectors = walker
            .covectors
            .iter()
            .map(|c| {
                let norm = (c.x * c.x + c.y * c.y + g.kappa() * c.w * c.w).abs().sqrt();
                *c / norm
            })
            .collect();
        Some(Self {
            geometry: g,
            covectors,
            half_length: half,
            faces,
            opacity: style.opacity,
            stop_below,
        })
    }

    /// Whether the point `x` of face `face` (on the model) is on the panel rather than in
    /// its window.
    #[must_use]
    pub fn on_panel(&self, face: usize, x: DVec4) -> bool {
        let g = self.geometry;
        let n = self.covectors.len();
        let wall = &self.faces[face];
        if face < n {
            let along = wall.half_side - surface_distance(g, x, wall.midpoint);
            let up = self.half_length - x.z.abs();
            return along.min(up) < wall.margin;
        }
        if n == 0 {
            return surface_distance(g, x, DVec4::W) > wall.margin;
        }
        let xb = base(x);
        let unit = xb / (g.kappa() * base_form(g, xb, xb)).abs().sqrt();
        self.covectors.iter().any(|c| {
            let s = -c.dot(unit);
            let d = match g {
                Geometry::Spherical => s.clamp(-1.0, 1.0).asin(),
                _ => s.asinh(),
            };
            d < wall.margin
        })
    }

    /// The panel's colour lit by the angle at which the unit tangent `v` meets it.
    #[must_use]
    pub fn lit_colour(&self, face: usize, v: DVec4) -> DVec3 {
        let facing = match self.covectors.get(face) {
            Some(c) => c.dot(v).abs(),
            None => v.z.abs(),
        }
        .min(1.0);
        (self.faces[face].colour * (0.55 + 0.45 * facing)).min(DVec3::ONE)
    }

    /// Adds the wall a ray meets entering the cell through `face` at `x` with unit tangent
    /// `v`, `distance` from the eye, to the veil (glued faces are congruent and share a
    /// colour and a margin, so the face entered stands for the one left). Returns whether
    /// enough light still gets through to go on.
    pub fn cross(
        &self,
        veil: &mut Veil,
        scene: &ProductScene,
        face: usize,
        x: DVec4,
        v: DVec4,
        distance: f64,
    ) -> bool {
        if self.on_panel(face, x) {
            let fog = (-distance / scene.fog_distance).exp();
            let seen = fog * self.lit_colour(face, v) + (1.0 - fog) * scene.fog_colour;
            veil.colour += veil.through * self.opacity * seen;
            veil.through *= 1.0 - self.opacity;
        }
        veil.through >= self.stop_below
    }
}
