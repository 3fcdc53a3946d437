//! Walls with windows in the box of `nil-K`: each pair of glued faces drawn as one
//! see-through panel with a hole, met exactly where a ray crosses the face (the walk solves
//! each crossing to the last bit), as in the other families ([`crate::scene::walls`]).
//!
//! A side is glued to its partner by a shear (`A⁻¹` takes `(½, y, z)` to `(−½, y, z − y/2)`
//! and a power of `C`), so a window cut the same way in both sides' chart coordinates would
//! not be one window: the panel of a pair is defined on one face of it, the one at `−½`
//! (and the bottom for the top and bottom pair), and a ray crossing the other face is
//! judged where it comes in there. A point of that face is in the window when it is at least
//! the margin `w` from the face's edges in the chart (`½ − |y|` and `h − |z|` on a side,
//! `½ − |x|` and `½ − |y|` on the bottom), `w = (1 − opening)` times the face's half width
//! (`min(½, h)` on a side, `½` on the bottom): a chart window, named as such.

use super::NilScene;
use crate::scene::walls::{Veil, WallStyle, wall_colours};
use crate::space::nil::NilSpace;
use glam::DVec3;

/// The walls of a Nil box in a style.
#[derive(Clone, Debug, PartialEq)]
pub struct NilWalls {
    /// Per face (`x = ½`, `x = −½`, `y = ½`, `y = −½`, `z = h`, `z = −h`): its pair's colour.
    pub colours: [DVec3; 6],
    /// The margin round a side's window and round the bottom's (infinite: solid walls).
    pub margins: [f64; 2],
    /// Half the box's height.
    pub half_height: f64,
    /// The share of light a panel stops.
    pub opacity: f64,
    /// A ray stops once less than this share of light gets through.
    pub stop_below: f64,
}

/// The face of each pair the panel is defined on: `x = −½`, `y = −½`, `z = −h`.
#[must_use]
pub fn panel_face(face: usize) -> usize {
    face | 1
}

impl NilWalls {
    /// The walls of `space` in `style`; `None` where nothing is drawn (opening 1). Rays stop
    /// behind walls that let less than `stop_below` of the light through.
    #[must_use]
    pub fn new(space: &NilSpace, style: WallStyle, stop_below: f64) -> Option<Self> {
        if style.opening >= 1.0 {
            return None;
        }
        let colours = wall_colours(&[1, 0, 3, 2, 5, 4], &[false; 6]);
        let h = space.half_height();
        let margin = |half_width: f64| {
            if style.opening <= 0.0 {
                f64::INFINITY
            } else {
                (1.0 - style.opening) * half_width
            }
        };
        Some(Self {
            colours: [0, 1, 2, 3, 4, 5].map(|f| colours[f]),
            margins: [margin(h.min(0.5)), margin(0.5)],
            half_height: h,
            opacity: style.opacity,
            stop_below,
        })
    }

    /// Whether the point `p` of the panel's face ([`panel_face`]) of `face`'s pair is on the
    /// panel rather than in its window.
    #[must_use]
    pub fn on_panel(&self, face: usize, p: [f64; 3]) -> bool {
        let [x, y, z] = p;
        match face / 2 {
            0 => (0.5 - y.abs()).min(self.half_height - z.abs()) < self.margins[0],
            1 => (0.5 - x.abs()).min(self.half_height - z.abs()) < self.margins[0],
            _ => (0.5 - x.abs()).min(0.5 - y.abs()) < self.margins[1],
        }
    }

    /// The panel's colour lit by the angle at which the unit body velocity `v` meets the
    /// face at `p` (the face's unit normal in the frame `E₁, E₂, E₃`: `E₁`, `E₂`, or the
    /// gradient of the height `(−y/2, x/2, 1)` normalised).
    #[must_use]
    pub fn lit_colour(&self, face: usize, p: [f64; 3], v: [f64; 3]) -> DVec3 {
        let v = DVec3::from_array(v);
        let normal = match face / 2 {
            0 => DVec3::X,
            1 => DVec3::Y,
            _ => DVec3::new(-0.5 * p[1], 0.5 * p[0], 1.0).normalize(),
        };
        let facing = normal.dot(v).abs().min(1.0);
        (self.colours[face] * (0.55 + 0.45 * facing)).min(DVec3::ONE)
    }

    /// Adds the wall a ray meets crossing `face` (the panel judged at `on_panel_face`, its
    /// point on the pair's [`panel_face`]; lit at the crossing `p` with velocity `v`),
    /// `distance` from the eye, to the veil. Returns whether enough light still gets
    /// through to go on.
    pub fn cross(
        &self,
        veil: &mut Veil,
        scene: &NilScene,
        face: usize,
        (on_panel_face, p, v): ([f64; 3], [f64; 3], [f64; 3]),
        distance: f64,
    ) -> bool {
        if self.on_panel(face, on_panel_face) {
            let fog = (-distance / scene.fog_distance).exp();
            let seen = fog * self.lit_colour(face, p, v) + (1.0 - fog) * scene.fog_colour;
            veil.colour += veil.through * self.opacity * seen;
            veil.through *= 1.0 - self.opacity;
        }
        veil.through >= self.stop_below
    }
}
