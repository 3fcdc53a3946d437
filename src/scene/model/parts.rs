//! The optional parts of the default scene: the centrepiece, the Clifford parallels and the
//! gyroscope.

use super::*;

/// Which parts of the default scene to show.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SceneParts {
    /// The cell's edges (tubes coloured by edge cycle) and a small ball at each vertex.
    pub edges: bool,
    /// What sits at the cell's centre.
    pub centrepiece: Centrepiece,
    /// The player's ship ([`crate::scene::avatar`]), seen where rays come back round the
    /// space; put it at the player with [`CurvedScene::set_avatar_frame`].
    pub avatar: bool,
    /// In spherical spaces, Clifford parallels: great circles of one Hopf fibration (the
    /// one the space's pairings preserve, where one does) as thin tubes, through the
    /// centre and round it ([`clifford_parallels`]).
    pub clifford: bool,
}

/// What sits at the cell's centre in the default scene: something to recognise in every
/// copy of the cell, and to tell how each copy is turned.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Centrepiece {
    /// Nothing.
    None,
    /// A plain gold ball (a quarter of the inradius).
    #[default]
    Ball,
    /// The textured Earth-like globe (`assets/textures/globe.png`, built in), slowly
    /// spinning: its continents show how each copy is turned and mirrored.
    Globe,
    /// A gyroscope: a ring, an axis through it and two coloured markers
    /// ([`gyroscope`]).
    Gyroscope,
    /// A spiral galaxy: a cloud of small glowing stars in two arms round a bulge, one mesh
    /// with its own bounding hierarchy ([`galaxy_model`](crate::scene::centrepiece::galaxy_model)).
    Galaxy,
}

impl Centrepiece {
    /// Every centrepiece, nothing first.
    pub const ALL: [Centrepiece; 5] = [
        Centrepiece::None,
        Centrepiece::Ball,
        Centrepiece::Globe,
        Centrepiece::Gyroscope,
        Centrepiece::Galaxy,
    ];

    /// Its name on the command line, in scene files and in the panel.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Centrepiece::None => "none",
            Centrepiece::Ball => "ball",
            Centrepiece::Globe => "globe",
            Centrepiece::Gyroscope => "gyroscope",
            Centrepiece::Galaxy => "galaxy",
        }
    }

    /// The centrepiece of a name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|c| c.name() == name)
    }
}

impl Default for SceneParts {
    /// Edges and the centre ball; no avatar (still pictures have no player).
    fn default() -> Self {
        Self {
            edges: true,
            centrepiece: Centrepiece::Ball,
            avatar: false,
            clifford: false,
        }
    }
}

/// Fibres of the Hopf fibrations: `J₊(x, y, z, w) = (−y, x, −w, z)` and `J₋` with the
/// second pair turned the other way. A great circle through `p` is `cos t·p + sin t·J p`.
pub(super) fn hopf_structures() -> [DMat4; 2] {
    let j = |sign: f64| {
        DMat4::from_cols(
            DVec4::new(0.0, 1.0, 0.0, 0.0),
            DVec4::new(-1.0, 0.0, 0.0, 0.0),
            DVec4::new(0.0, 0.0, 0.0, sign),
            DVec4::new(0.0, 0.0, -sign, 0.0),
        )
    };
    [j(1.0), j(-1.0)]
}

/// Clifford parallels for a spherical space (none for other geometries): six great circles
/// of the Hopf fibration that commutes with most of the space's pairings (so that in lens
/// spaces and the Poincaré space they are the fibres the space is made of), through points
/// half an inradius round the centre, twisting about the fibre through the centre (the
/// default view's axis); each cut into segments no longer than the
/// inradius, every segment brought into the cell through the faces, as thin pink tubes. Place them with [`CurvedScene::place`] (their images through the faces).
#[must_use]
pub fn clifford_parallels(space: &Space) -> Vec<Object> {
    let g = space.geometry;
    if g != Geometry::Spherical {
        return Vec::new();
    }
    let commuting = |j: &DMat4| {
        space
            .faces
            .iter()
            .filter(|f| {
                crate::geometry::max_abs_entry(&(f.pairing * *j - *j * f.pairing).to_cols_array())
                    < 1e-9
            })
            .count()
    };
    let [plus, minus] = hopf_structures();
    let j = if commuting(&minus) > commuting(&plus) {
        minus
    } else {
        plus
    };
    let inradius = crate::space::invariants::inradius_at_most(space, std::f64::consts::FRAC_PI_2);
    let c = space.centre();
    // A unit vector orthogonal to c and J c, and its partner J e1.
    let jc = j * c;
    let e1 = [DVec4::X, DVec4::Y, DVec4::Z, DVec4::W]
        .into_iter()
        .map(|e| e - c * e.dot(c) - jc * e.dot(jc))
        .max_by(|a, b| a.length().total_cmp(&b.length()))
        .map_or(DVec4::X, |v| v.normalize());
    let e2 = j * e1;
    let rho = 0.5 * inradius;
    let through: Vec<DVec4> = (0..6)
        .map(|k| {
            let phi = f64::from(k) * std::f64::consts::FRAC_PI_3;
            c * rho.cos() + (e1 * phi.cos() + e2 * phi.sin()) * rho.sin()
        })
        .collect();
    let segments = ((std::f64::consts::TAU / inradius).ceil() as usize).clamp(4, 64);
    let radius = 0.02 * inradius;
    let mut tubes = Vec::new();
    for p in &through {
        let jp = j * *p;
        let at = |t: f64| *p * t.cos() + jp * t.sin();
        // One colour for all: circles that are one circle of the quotient overlap, and
        // overlapping tubes of one colour look the same whichever a ray meets first.
        let colour = DVec3::new(0.95, 0.55, 0.85);
        for k in 0..segments {
            let t0 = std::f64::consts::TAU * k as f64 / segments as f64;
            let t1 = std::f64::consts::TAU * (k + 1) as f64 / segments as f64;
            let tube = Object::Tube(Tube::new(g, at(t0), at(t1), radius, colour));
            // The segment moved by the pairings that bring its midpoint into the cell.
            let mid = g.translation_to(at(0.5 * (t0 + t1)));
            let (wrapped, _) = crate::space::wrap_into_cell(space, mid, 0.0);
            let h = wrapped * g.inverse(mid);
            tubes.push(tube.transformed(g, h));
        }
    }
    tubes
}

/// A gyroscope at the cell's centre, in the centre's axes: a ring of radius 0.45 inradii
/// about the `y` axis (24 tube segments), the axis itself (a tube 1.1 inradii long), a red
/// ball at the axis's `+y` end and a green one on the ring at `+x`. Its chirality makes
/// every turn and mirror of a copy visible.
#[must_use]
pub fn gyroscope(space: &Space) -> Vec<Object> {
    let g = space.geometry;
    let r = crate::space::invariants::inradius_at_most(space, std::f64::consts::FRAC_PI_4);
    let centre = g.translation_to(space.centre());
    let point = |local: DMat4| g.project_point((centre * local).w_axis);
    let ring_radius = 0.45 * r;
    let tube = 0.03 * r;
    let ring_at = |a: f64| point(g.translation(DVec3::new(a.cos(), 0.0, a.sin()), ring_radius));
    let gold = DVec3::new(0.95, 0.75, 0.3);
    let mut objects: Vec<Object> = (0..24)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 24.0;
            let b = std::f64::consts::TAU * f64::from(k + 1) / 24.0;
            Object::Tube(Tube::new(g, ring_at(a), ring_at(b), tube, gold))
        })
        .collect();
    let axis = |t: f64| point(g.translation(DVec3::Y, t));
    objects.push(Object::Tube(Tube::new(
        g,
        axis(-0.55 * r),
        axis(0.55 * r),
        0.7 * tube,
        DVec3::splat(0.85),
    )));
    objects.push(Object::Ball(Ball::new(
        g,
        axis(0.55 * r),
        2.5 * tube,
        DVec3::new(0.9, 0.15, 0.1),
    )));
    objects.push(Object::Ball(Ball::new(
        g,
        ring_at(0.0),
        2.5 * tube,
        DVec3::new(0.15, 0.85, 0.2),
    )));
    objects
}
