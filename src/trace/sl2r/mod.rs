//! The CPU reference tracer of the SL̃(2,R) spaces: a camera ray per pixel walks the cell of
//! `UT Σ` ([`Sl2rWalker`], exits in closed form), and in each segment the scene's fibre
//! tubes are met exactly.
//!
//! A *fibre tube* is the set of points within `r` of the fibre over a base point `q`: in the
//! Sasaki metric (a Riemannian submersion onto `H²`) that is every `(p, e)` whose base point
//! is within `r` of `q` in `H²`, `⟨p, q⟩ ≥ −cosh r`. Along a ray `⟨p(t), q⟩` has the form
//! `α + βS + γK` of a side's function, so a tube is entered where the same quadratic in `τ`
//! has its root ([`first_crossing`]): in closed form, polished to the last bit. A tube is kept
//! with each image under the surface group that reaches into the cell. The cell's edges are
//! the fibres over the polygon's vertices, drawn as thin tubes.
//!
//! A *metric ball* is the set of points within `r` of a centre `(q, f)` by the Sasaki
//! distance itself ([`crate::space::sl2r::ball`]: the inverse exponential map in closed form
//! but for one scanned unknown, safe steps by the distance, the hit to the last bit). A ball
//! is kept with each image under the surface group that reaches into the cell; because the
//! pairings turn `e` as they move `p`, the copies of a stack of balls along one fibre come
//! back turned: that is the bundle's twist, seen.
//!
//! Shading is by a lamp ([`light`]): a surface's colour times `ambient + (1 − ambient)·P·L`,
//! `L` the light along the shortest geodesic to every image of the lamp within reach
//! (Lambert's cosine against the outward normal — for a tube horizontal, away from `q` —,
//! the fog along the way and the geodesic sphere's area), shadows walked through the faces
//! for the nearest images; then faded into the fog by `e^{−t/λ}` over the distance walked.
//! The cell's sides may be drawn as walls with windows ([`walls`]). No mirrors yet.

#[cfg(feature = "scene-files")]
pub mod file;
#[cfg(feature = "scene-files")]
pub mod flight;
pub mod light;
pub mod walls;

mod camera;
mod images;

pub use camera::{Sl2rCamera, camera_ray, camera_sheet, default_camera, frame_at, looking_along};
use images::{apply, elements_within, group_elements, group_elements_turning};

use crate::space::sl2r::ball::{MAX_SL2R_BALL_RADIUS, ball_hit};
use crate::space::sl2r::flow::{Sl2rRay, flow, lorentz};
use crate::space::sl2r::{Sl2rWalker, UnitTangentSpace, first_crossing};
use crate::space::walk::{CellWalk, NextExit};
use glam::{DMat4, DVec3, DVec4};
use image::RgbImage;

/// The tube about the fibre over a base point: the points whose base point is within
/// `radius` of `base` in `H²`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FibreTube {
    /// The base point `q` on the hyperboloid.
    pub base: [f64; 3],
    /// Its radius.
    pub radius: f64,
    /// Its colour, linear RGB.
    pub colour: DVec3,
}

/// The metric ball of `radius` about a point of `UT H²` (its frame `(e, e⊥, p)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rBall {
    /// The centre's frame: columns `e`, `e⊥`, `p`.
    pub centre: [[f64; 3]; 3],
    /// Its radius, at most [`MAX_SL2R_BALL_RADIUS`].
    pub radius: f64,
    /// Its colour, linear RGB.
    pub colour: DVec3,
    /// The fibre cover's sheet it sits on (0 in `UT Σ`): its lifted fibre angle is its
    /// frame's angle plus `2π·sheet` ([`crate::space::sl2r::cover`]).
    pub sheet: u32,
}

/// What a ray meets: a tube or a ball of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sl2rObject<'a> {
    /// A fibre tube.
    Tube(&'a FibreTube),
    /// A metric ball.
    Ball(&'a Sl2rBall),
}

impl Sl2rObject<'_> {
    /// The object's colour.
    #[must_use]
    pub fn colour(&self) -> DVec3 {
        match self {
            Self::Tube(t) => t.colour,
            Self::Ball(b) => b.colour,
        }
    }
}

/// A scene of an SL̃(2,R) space: fibre tubes and metric balls (with their images that reach
/// into the cell), ambient light and fog.
#[derive(Clone, Debug, PartialEq)]
pub struct Sl2rScene {
    /// The tubes.
    pub tubes: Vec<FibreTube>,
    /// The balls.
    pub balls: Vec<Sl2rBall>,
    /// The fog's colour, linear RGB.
    pub fog_colour: DVec3,
    /// The fog scale `λ`: light fades by `e^{−t/λ}` over a distance `t`.
    pub fog_distance: f64,
    /// The share of a surface's colour it shows facing away from the eye.
    pub ambient: f64,
    /// The teaching view: surfaces tinted by the crossings or the last face crossed
    /// ([`crate::scene::ColourBy`]; the holonomy view is not written for this family).
    pub colour_by: crate::scene::ColourBy,
    /// The cell's walls with windows, if drawn ([`walls`]).
    pub walls: Option<crate::scene::walls::WallStyle>,
    /// The lamp's frame (columns `f`, `f⊥`, `q`), in the cell.
    pub light: [[f64; 3]; 3],
    /// The fibre cover's sheet the lamp sits on (0 in `UT Σ`).
    pub light_sheet: u32,
    /// How the light is gathered; set with [`Sl2rScene::set_lighting`].
    pub lighting: crate::scene::lighting::Lighting,
    /// The lamp's images within the reach.
    pub lamp: light::Sl2rLamp,
    /// The lamp's power: the light a surface facing it gets from one image at distance 1
    /// in a flat space (`A = 1`).
    pub power: f64,
    /// The distance within which the falloff stops growing (a lamp of that size).
    pub near_light: f64,
}

impl Sl2rScene {
    /// Lights the scene as `lighting` says, the lamp at the frame `light` on `sheet` (brought
    /// into the cell): finds the lamp's images again. The message names a setting out of
    /// range, a lamp of a radius, or a lamp that is no frame of `UT H²`.
    pub fn set_lighting(
        &mut self,
        space: &UnitTangentSpace,
        (light, sheet): ([[f64; 3]; 3], u32),
        lighting: crate::scene::lighting::Lighting,
    ) -> Result<(), String> {
        lighting.check()?;
        if lighting.lamp_radius_inradii > 0.0 {
            use crate::space::{Family, Feature};
            Family::Sl2r
                .supports(Feature::SoftShadows)
                .map_err(|e| format!("{e}; got a radius of {}", lighting.lamp_radius_inradii))?;
        }
        let [f, g, q] = light;
        let frame_defect = (lorentz(q, q) + 1.0)
            .abs()
            .max((lorentz(f, f) - 1.0).abs())
            .max((lorentz(g, g) - 1.0).abs())
            .max(lorentz(f, q).abs())
            .max(lorentz(g, q).abs())
            .max(lorentz(f, g).abs());
        if !(frame_defect < 1e-6 && q[2] > 0.0) {
            return Err(format!(
                "the lamp's position {:?} is no point of the space",
                crate::space::sl2r::chart_point(&light).to_array()
            ));
        }
        if sheet >= space.sheets() {
            return Err(format!(
                "the lamp's sheet {sheet} is not one of the cover's {} sheets",
                space.sheets()
            ));
        }
        let at = Sl2rRay {
            frame: light,
            velocity: [1.0, 0.0, 0.0],
        };
        self.light = space.into_cell(&at).frame;
        self.light_sheet = crate::space::sl2r::cover::sheet_plus(
            sheet,
            i64::from(space.sheets_into_cell(&light)),
            space.sheets(),
        );
        self.lighting = lighting;
        self.lamp = light::Sl2rLamp::new(
            space,
            light::LampImage {
                frame: self.light,
                sheet: self.light_sheet,
            },
            &lighting,
        );
        Ok(())
    }

    /// Where the fog has left less than half a grey level (`λ ln 510`): rays stop there.
    #[must_use]
    pub fn cutoff_distance(&self) -> f64 {
        self.fog_distance * 510f64.ln()
    }

    /// Adds `tube` and each image `γ·tube` (`γ` in the surface group) that reaches into the
    /// cell: those within the polygon's circumradius plus the radius of its centre.
    pub fn add_with_images(&mut self, space: &UnitTangentSpace, tube: FibreTube) {
        let reach = (space.circumradius() + tube.radius).cosh();
        for m in group_elements(space, tube.base) {
            let q = apply(&m, tube.base);
            if q[2] <= reach * (1.0 + 1e-12) {
                self.tubes.push(FibreTube { base: q, ..tube });
            }
        }
    }

    /// Adds `ball` and each image `γ·ball` that reaches into the cell (its base point
    /// within the polygon's circumradius plus the radius of the centre: the base point of
    /// every point of a ball is within its radius of the centre's).
    pub fn add_ball_with_images(&mut self, space: &UnitTangentSpace, ball: Sl2rBall) {
        use crate::space::sl2r::cover::{fibre_angle, sheet_plus};
        let reach = (space.circumradius() + ball.radius).cosh();
        let angle = fibre_angle(&ball.centre);
        for (m, turn) in group_elements_turning(space, ball.centre[2]) {
            let centre = ball.centre.map(|c| apply(&m, c));
            if centre[2][2] <= reach * (1.0 + 1e-12) {
                // The image's lifted angle is the centre's plus the element's turn: the
                // whole turns between that and the image's own angle are sheets climbed.
                let climbed =
                    ((angle + turn - fibre_angle(&centre)) / std::f64::consts::TAU).round();
                let sheet = sheet_plus(ball.sheet, climbed as i64, space.sheets());
                self.balls.push(Sl2rBall {
                    centre,
                    sheet,
                    ..ball
                });
            }
        }
    }
}

/// The base point at distance `r` from the polygon's centre in the direction `angle`.
fn base_at(r: f64, angle: f64) -> [f64; 3] {
    [r.sinh() * angle.cos(), r.sinh() * angle.sin(), r.cosh()]
}

/// Which parts of the default scene a scene is built on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Sl2rParts {
    /// The cell's edges: thin white tubes over the polygon's vertices.
    pub edges: bool,
    /// A pale pillar (a fibre tube) over the polygon's centre.
    pub centre_pillar: bool,
    /// Four coloured pillars half-way to every other side.
    pub pillars: bool,
    /// A stack of three balls along one fibre (0.8 radians apart), whose copies
    /// across the sides come back turned: the bundle's twist.
    pub ball_stack: bool,
}

/// The default scene: the cell's edges (thin white tubes over the polygon's vertices), a
/// pale pillar (a fibre tube) over the centre and four coloured ones half-way to every
/// other side, and a stack of three balls along one fibre, each with its images; fog at one
/// inradius.
#[must_use]
pub fn default_scene(space: &UnitTangentSpace) -> Sl2rScene {
    scene_with_parts(
        space,
        Sl2rParts {
            edges: true,
            centre_pillar: true,
            pillars: true,
            ball_stack: true,
        },
    )
}

/// The default lamp's size: the falloff is held at its value there.
pub const NEAR_LIGHT: f64 = 0.05;

/// The default lamp's power: full (1) at 0.6 inradii from it, but no more than makes the
/// mean light of all its images (`πλ/vol`, what a small space fills with) ½.
#[must_use]
pub fn default_power(space: &UnitTangentSpace, fog_distance: f64) -> f64 {
    let mean = std::f64::consts::PI * fog_distance / space.volume();
    (0.6 * space.inradius()).powi(2).min(0.5 / mean)
}

/// The default scene's fog distance: the polygon's inradius.
#[must_use]
pub fn default_fog_distance(space: &UnitTangentSpace) -> f64 {
    space.inradius()
}

/// The default scene's `parts` (no tube where none is asked for), its fog and ambient.
#[must_use]
pub fn scene_with_parts(space: &UnitTangentSpace, parts: Sl2rParts) -> Sl2rScene {
    let rho = space.inradius();
    let mut scene = Sl2rScene {
        tubes: Vec::new(),
        balls: Vec::new(),
        fog_colour: DVec3::new(0.55, 0.6, 0.7),
        fog_distance: default_fog_distance(space),
        ambient: 0.3,
        colour_by: crate::scene::ColourBy::Shading,
        walls: None,
        light: crate::space::sl2r::chart_frame(0.0, 0.0, 0.0),
        light_sheet: 0,
        lighting: crate::scene::lighting::Lighting::default(),
        lamp: light::Sl2rLamp::default(),
        power: 1.0,
        near_light: NEAR_LIGHT,
    };
    // The lamp: over the point half-way between the default camera and the centre, half a
    // radian up the fibre from the camera's e.
    let lamp = base_at(0.35 * rho, std::f64::consts::PI);
    scene
        .set_lighting(
            space,
            (crate::space::sl2r::chart_frame(lamp[0], lamp[1], 0.5), 0),
            crate::scene::lighting::Lighting::default(),
        )
        .expect("the default lighting is in range");
    scene.power = default_power(space, scene.fog_distance);
    if parts.edges {
        for v in space.vertices() {
            scene.tubes.push(FibreTube {
                base: v,
                radius: 0.03 * rho,
                colour: DVec3::splat(0.95),
            });
        }
    }
    if parts.centre_pillar {
        scene.add_with_images(
            space,
            FibreTube {
                base: [0.0, 0.0, 1.0],
                radius: 0.1 * rho,
                colour: DVec3::new(0.85, 0.85, 0.8),
            },
        );
    }
    if parts.ball_stack {
        // Over the base point half-way to side 2 (left of the centre as the default camera
        // sees it), e at −0.8, 0 and 0.8 radians: violet, orange and white, climbing.
        let n = space.sides().len() as f64;
        let angle = 2.0 * std::f64::consts::PI * 2.0 / n;
        let (r, b) = (0.5 * rho, 0.0);
        let (x, y) = (r.sinh() * angle.cos(), r.sinh() * angle.sin());
        let colours = [
            DVec3::new(0.6, 0.3, 0.9),
            DVec3::new(0.95, 0.55, 0.15),
            DVec3::new(0.95, 0.95, 0.95),
        ];
        for (k, colour) in colours.into_iter().enumerate() {
            let theta = b + 0.8 * (k as f64 - 1.0);
            scene.add_ball_with_images(
                space,
                Sl2rBall {
                    centre: crate::space::sl2r::chart_frame(x, y, theta),
                    radius: (0.22 * rho).min(MAX_SL2R_BALL_RADIUS),
                    colour,
                    // In a fibre cover the stack is on the first sheet only.
                    sheet: 0,
                },
            );
        }
    }
    if !parts.pillars {
        return scene;
    }
    let colours = [
        DVec3::new(0.9, 0.25, 0.2),
        DVec3::new(0.25, 0.75, 0.3),
        DVec3::new(0.25, 0.4, 0.95),
        DVec3::new(0.95, 0.8, 0.2),
    ];
    let n = space.sides().len();
    for (i, colour) in colours.into_iter().enumerate() {
        let angle = 2.0 * std::f64::consts::PI * (2 * i + 1) as f64 / n as f64;
        scene.add_with_images(
            space,
            FibreTube {
                base: base_at(0.55 * rho, angle),
                radius: 0.08 * rho,
                colour,
            },
        );
    }
    scene
}

/// The first object `ray` meets within `t_max`, and where: the tubes in closed form, then
/// the balls within what is left (each a bracketed root of its distance).
fn first_object<'a>(
    scene: &'a Sl2rScene,
    ray: &Sl2rRay<f64>,
    sheet: u32,
    sheets: u32,
    t_max: f64,
) -> Option<(f64, Sl2rObject<'a>)> {
    let mut best: Option<(f64, Sl2rObject<'a>)> = None;
    for tube in &scene.tubes {
        let q = tube.base;
        let n = [q[0], q[1], -q[2]];
        if let Some(t) = first_crossing(ray, n, tube.radius.cosh())
            && t <= t_max
            && best.is_none_or(|(b, _)| t < b)
        {
            best = Some((t, Sl2rObject::Tube(tube)));
        }
    }
    for ball in &scene.balls {
        let reach = best.map_or(t_max, |(b, _)| b);
        if let Some(t) = ball_hit_on_sheet(ray, sheet, sheets, ball, reach)
            && t <= reach
        {
            best = Some((t, Sl2rObject::Ball(ball)));
        }
    }
    best
}

/// Where `ray` (on `sheet` of a cover of `sheets` sheets) first meets `ball` within `t_max`.
/// In `UT H²` (one sheet) the ball's hit; in a cover the ball there is one of the `N` lifts of
/// that ball, `2π` apart along the fibre: a hit counts where the ray's lifted angle is within
/// `π` of the ball's (the shortest geodesic from the centre, at most `r ≤ ½` long, turns it
/// by less than `√2·r`); else the ray passes through that lift (a chord at most `2r`) and
/// the search goes on past it.
fn ball_hit_on_sheet(
    ray: &Sl2rRay<f64>,
    sheet: u32,
    sheets: u32,
    ball: &Sl2rBall,
    t_max: f64,
) -> Option<f64> {
    use crate::space::sl2r::cover::{fibre_angle, sheets_climbed};
    use std::f64::consts::TAU;
    if sheets <= 1 {
        return ball_hit(ray, &ball.centre, ball.radius, t_max);
    }
    let mut from = 0.0;
    while from <= t_max {
        let start = flow(ray, from);
        let t = from + ball_hit(&start, &ball.centre, ball.radius, t_max - from)?;
        let at = flow(ray, t);
        let climbed = sheets_climbed(ray, t, &at.frame)?;
        let turns =
            (i64::from(sheet) + climbed - i64::from(ball.sheet)).rem_euclid(i64::from(sheets));
        let apart = fibre_angle(&at.frame) - fibre_angle(&ball.centre) + TAU * turns as f64;
        // The lifted angles' difference modulo 2πN, nearest 0.
        let apart = apart - TAU * f64::from(sheets) * (apart / (TAU * f64::from(sheets))).round();
        if apart.abs() < std::f64::consts::PI {
            return Some(t);
        }
        from = t + 2.0 * ball.radius + 1e-9;
    }
    None
}

/// The outward unit normal of `object` at the frame `at`, in `at`'s body frame (`X, Y, V`):
/// for a tube horizontal, away from its fibre; for a ball the distance's gradient.
fn normal_at(object: Sl2rObject, at: &[[f64; 3]; 3]) -> Option<DVec3> {
    let [e, f, p] = *at;
    match object {
        Sl2rObject::Tube(tube) => {
            let q = tube.base;
            // The outward normal: the tangent at p pointing away from q (−q's tangent part).
            let along = lorentz(q, p);
            let u = [0, 1, 2].map(|i| -(q[i] + along * p[i]));
            let len = lorentz(u, u).max(0.0).sqrt();
            (len > 0.0).then(|| DVec3::new(lorentz(u, e) / len, lorentz(u, f) / len, 0.0))
        }
        Sl2rObject::Ball(ball) => {
            crate::space::sl2r::ball::normal(&ball.centre, at).map(DVec3::from_array)
        }
    }
}

/// The colour of the object `hit` met, lit by the scene's lamp ([`light::gather`]; shadow
/// rays walked through the faces within `max_crossings`).
fn shade(
    walker: &Sl2rWalker<DVec4>,
    scene: &Sl2rScene,
    hit: &Sl2rHit,
    max_crossings: usize,
) -> DVec3 {
    let at = flow(&hit.segment, hit.t);
    let Some(normal) = normal_at(hit.object, &at.frame) else {
        return hit.object.colour() * scene.ambient;
    };
    let mut occluded = |ray: Sl2rRay<f64>, sheet: u32, length: f64| {
        walk_to_object(walker, scene, (ray, sheet), length, max_crossings, None).is_some()
    };
    let light = light::gather(
        scene,
        (&at.frame, hit.sheet, walker.sheets()),
        normal,
        &mut occluded,
    );
    let lit = scene.ambient + (1.0 - scene.ambient) * scene.power * light;
    (hit.object.colour() * lit).min(DVec3::ONE)
}

/// Where a camera ray first meets an object: the distance walked to it, the object, and
/// the ray at the start of the segment it is met in with the time along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sl2rHit<'a> {
    /// The geodesic distance from the camera.
    pub distance: f64,
    /// The object met.
    pub object: Sl2rObject<'a>,
    /// The ray at the start of the segment (in the cell).
    pub segment: Sl2rRay<f64>,
    /// The time along `segment` to the hit.
    pub t: f64,
    /// The faces crossed before it.
    pub crossings: usize,
    /// The last face crossed, if any.
    pub last_face: Option<usize>,
    /// The fibre cover's sheet of the point met (0 in `UT Σ`).
    pub sheet: u32,
}

/// The first object the ray meets within `max_crossings` crossings and the fog's cut-off.
#[must_use]
pub fn first_hit<'a>(
    walker: &Sl2rWalker<DVec4>,
    scene: &'a Sl2rScene,
    ray: Sl2rRay<f64>,
    max_crossings: usize,
) -> Option<Sl2rHit<'a>> {
    first_hit_on_sheet(walker, scene, ray, 0, max_crossings)
}

/// [`first_hit`] from a point on the fibre cover's sheet `sheet`.
#[must_use]
pub fn first_hit_on_sheet<'a>(
    walker: &Sl2rWalker<DVec4>,
    scene: &'a Sl2rScene,
    ray: Sl2rRay<f64>,
    sheet: u32,
    max_crossings: usize,
) -> Option<Sl2rHit<'a>> {
    first_hit_past_walls(walker, scene, (ray, sheet), max_crossings, None)
}

/// [`first_hit_on_sheet`] seen through `walls`: each panel crossed is added to the veil,
/// and the walk ends (no hit) once too little light gets through.
#[must_use]
pub fn first_hit_past_walls<'a>(
    walker: &Sl2rWalker<DVec4>,
    scene: &'a Sl2rScene,
    (ray, sheet): (Sl2rRay<f64>, u32),
    max_crossings: usize,
    walls: Option<(&walls::Sl2rWalls, &mut crate::scene::walls::Veil)>,
) -> Option<Sl2rHit<'a>> {
    let cutoff = scene.cutoff_distance();
    walk_to_object(walker, scene, (ray, sheet), cutoff, max_crossings, walls)
}

/// The first object met by `ray` (on `sheet`) within `length` and `max_crossings`, through
/// `walls` where given: the camera rays' walk, and the shadow rays'.
fn walk_to_object<'a>(
    walker: &Sl2rWalker<DVec4>,
    scene: &'a Sl2rScene,
    (ray, sheet): (Sl2rRay<f64>, u32),
    cutoff: f64,
    max_crossings: usize,
    mut walls: Option<(&walls::Sl2rWalls, &mut crate::scene::walls::Veil)>,
) -> Option<Sl2rHit<'a>> {
    let sheets = walker.sheets();
    let mut ray = Sl2rWalker::<DVec4>::ray_on_sheet(&ray, sheet);
    let mut walked = 0.0;
    let mut entered = None;
    let mut last_face = None;
    for crossings in 0..=max_crossings {
        let r = Sl2rWalker::<DVec4>::sl2r_ray(&ray);
        let (segment, exit) = match walker.next_exit(&ray, entered, 0) {
            NextExit::Exit(exit) => (exit.t, Some(exit)),
            NextExit::NoFaceAhead => (cutoff - walked, None),
            NextExit::Degenerate => return None,
        };
        let within = segment.min(cutoff - walked);
        let on = Sl2rWalker::<DVec4>::sheet_of(&ray);
        if let Some((t, object)) = first_object(scene, &r, on, sheets, within) {
            let sheet = if sheets > 1 {
                let climbed = crate::space::sl2r::cover::sheets_climbed(&r, t, &flow(&r, t).frame);
                crate::space::sl2r::cover::sheet_plus(on, climbed.unwrap_or(0), sheets)
            } else {
                0
            };
            return Some(Sl2rHit {
                distance: walked + t,
                object,
                segment: r,
                t,
                crossings,
                last_face,
                sheet,
            });
        }
        walked += segment;
        let exit = exit?;
        if walked >= cutoff {
            return None;
        }
        if let Some((walls, veil)) = walls.as_mut()
            && !walls.cross(veil, scene, exit.face, &flow(&r, exit.t), walked)
        {
            return None;
        }
        ray = walker.through(&ray, &exit);
        entered = walker.skip_after(&exit);
        last_face = Some(exit.face);
    }
    None
}

/// The colour seen along the camera ray `ray`, walking at most `max_crossings` crossings.
#[must_use]
pub fn trace_sl2r_pixel(
    (walker, walls): (&Sl2rWalker<DVec4>, Option<&walls::Sl2rWalls>),
    scene: &Sl2rScene,
    ray: Sl2rRay<f64>,
    sheet: u32,
    max_crossings: usize,
) -> DVec3 {
    let mut veil = crate::scene::walls::Veil::CLEAR;
    let hit = first_hit_past_walls(
        walker,
        scene,
        (ray, sheet),
        max_crossings,
        walls.map(|w| (w, &mut veil)),
    );
    veil.over(match hit {
        Some(hit) => {
            let fade = (-hit.distance / scene.fog_distance).exp();
            let mut surface = shade(walker, scene, &hit, max_crossings);
            if scene.colour_by != crate::scene::ColourBy::Shading {
                // The holonomy view is refused for this family: crossings and face tint.
                let tint = scene.colour_by.tint(
                    crate::geometry::Geometry::Hyperbolic,
                    hit.crossings,
                    hit.last_face,
                    DMat4::IDENTITY,
                );
                surface = crate::scene::ColourBy::recolour(tint, surface);
            }
            scene.fog_colour.lerp(surface, fade)
        }
        None => scene.fog_colour,
    })
}

/// Renders a view (mono or stereo) of `space` with the f64 reference.
#[must_use]
pub fn render_sl2r_view(
    space: &UnitTangentSpace,
    scene: &Sl2rScene,
    layout: &crate::view::ViewLayout,
    max_crossings: usize,
) -> RgbImage {
    let walker = Sl2rWalker::<DVec4>::new(space);
    let walls = scene
        .walls
        .and_then(|style| walls::Sl2rWalls::new(space, style, crate::scene::DEFAULT_CUTOFF_WEIGHT));
    super::render_layout_by_eye(layout, |eye, u, v| {
        let (x, y) = layout.lens.at(u, v);
        trace_sl2r_pixel(
            (&walker, walls.as_ref()),
            scene,
            camera_ray(&layout.frames[eye], x, y),
            camera_sheet(&layout.frames[eye]),
            max_crossings,
        )
    })
}
