//! How a lamp's light reaches a surface point of the manifold: along the geodesics to its
//! images in the universal cover, the nearest few walked for shadows, the far ones by their
//! mean (`docs/light.md`). The shader mirrors it (`shaders/lighting.wgsl`).
//!
//! A surface point `x` with normal `n` gets from a lamp of colour × power `P`
//!
//! ```text
//! E(x) = P · Σ_paths  max(0, ⟨n, l⟩) · e^(−d/λ) / max(S(d), S(r₀))²   +   P · T / 4
//! ```
//!
//! the sum over the geodesics from `x` to the images `g·L` within the reach `R` (`l` the
//! unit tangent at `x` along it, `d` its length, `λ` the fog distance: the medium that fogs
//! the view absorbs the light too), each left out where a shadow ray walked along it
//! through the faces meets an object first (the [`Lighting::shadows`] images nearest the
//! cell's centre; the rest are not walked). `T` is the mean fluence of the images beyond `R`
//! ([`tail_fluence`]): they come from every direction alike, and the mean of `max(0, cos θ)`
//! over the sphere of directions is `1/4`.
//!
//! In a spherical space an image is reached along the short arc (length `d`, direction `l`)
//! and the long one (`2π − d`, direction `−l`), and each again after whole turns round the
//! great circle; a turn passes both arcs, so it is dark where either arc is shadowed, and
//! the turns sum to a factor `t / (1 − t)`, `t = e^(−2π/λ)`.
//!
//! [`LightPaths::Nearest`] is the older model: the nearest of the lamp and its images
//! through the faces only, with no absorption on the way.

use crate::geometry::Geometry;
use crate::space::Space;
use crate::space::invariants::{circumradius, inradius, volume};
use glam::{DVec3, DVec4};
use std::f64::consts::{PI, TAU};

/// How far a shadow ray starts from the surface it leaves (a geodesic distance): it keeps
/// the surface itself from shadowing the point where f32 rounding puts the start a little
/// inside it.
pub const SHADOW_OFFSET: f64 = 1e-3;

/// In a spherical space, images farther than this (within 1e-3 of the point's antipode) are
/// left out: the geodesics to them have no one direction.
pub const ANTIPODE: f64 = PI - 1e-3;

/// The most images of one lamp summed exactly: past them the reach is shortened to what
/// they cover, and the rest joins the tail. The shader holds them in its uniform, 16 bytes
/// each.
pub const MAX_LAMP_IMAGES: usize = 256;

/// The images `found` (each with its distance from the cell's centre, nearest first) that a
/// lamp keeps, and the reach they cover from every point of a cell of circumradius `rho`:
/// all of them and `reach`, or, past [`MAX_LAMP_IMAGES`], every image nearer the centre
/// than the first one left out and the reach those cover.
#[must_use]
pub fn nearest_images<T>(mut found: Vec<(T, f64)>, reach: f64, rho: f64) -> (Vec<T>, f64) {
    let mut covered = reach;
    if found.len() > MAX_LAMP_IMAGES {
        let edge = found[MAX_LAMP_IMAGES].1;
        found.truncate(MAX_LAMP_IMAGES);
        found.retain(|(_, d)| *d < edge);
        covered = covered.min((edge - rho).max(0.0));
    }
    (found.into_iter().map(|(q, _)| q).collect(), covered)
}

/// A lamp's images in a family that finds them by its own search (the product spaces, Nil,
/// SL̃(2,R)), for [`LightPaths::Images`]: the images, nearest the cell's centre first, the
/// reach they cover from every point of the cell, and the space's volume (their density, for
/// the tail).
#[derive(Clone, Debug, PartialEq)]
pub struct LampImages<T> {
    /// The images.
    pub images: Vec<T>,
    /// The reach they cover from every point of the cell.
    pub reach: f64,
    /// The space's volume.
    pub volume: f64,
}

impl<T> Default for LampImages<T> {
    fn default() -> Self {
        Self {
            images: Vec::new(),
            reach: 0.0,
            volume: 0.0,
        }
    }
}

impl<T> LampImages<T> {
    /// The images `search(reach)` finds, with the reach they cover, in a space of `volume`
    /// (none for [`LightPaths::Nearest`]).
    #[must_use]
    pub fn searched(
        lighting: &Lighting,
        reach: f64,
        volume: f64,
        search: impl FnOnce(f64) -> (Vec<T>, f64),
    ) -> Self {
        if lighting.paths == LightPaths::Nearest {
            return Self::default();
        }
        let (images, reach) = search(reach);
        Self {
            images,
            reach,
            volume,
        }
    }
}

/// Which geodesics from a point to a lamp carry its light.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LightPaths {
    /// Only the nearest of the lamp and its images through the cell's faces, unabsorbed:
    /// the older model, cheap, and wrong by the other images.
    Nearest,
    /// Every image within the reach, absorbed by the fog, and the rest by its mean.
    #[default]
    Images,
}

impl LightPaths {
    /// Its name on the command line and in scene files.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            LightPaths::Nearest => "nearest",
            LightPaths::Images => "images",
        }
    }

    /// The paths of a name.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        [LightPaths::Nearest, LightPaths::Images]
            .into_iter()
            .find(|m| m.name() == name)
    }
}

/// How the lamps' light is gathered ([the module's description](self)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Which geodesics carry light.
    pub paths: LightPaths,
    /// How far, in inradii of the cell, the images are summed exactly ([`LightPaths::Images`];
    /// a spherical space sums all of them, up to [`MAX_LAMP_IMAGES`]).
    pub reach_inradii: f64,
    /// Whether the images beyond the reach add their mean.
    pub tail: bool,
    /// How many images of each lamp (those nearest the cell's centre) are walked for
    /// shadows; 0: none.
    pub shadows: u32,
    /// The lamps' radius in inradii of the cell, for their shadows: 0, points (hard
    /// shadows); more, balls whose discs the shadow rays spread over (soft shadows). Their
    /// light still comes from their centres, and the falloff's floor is the shading's own
    /// (`Shading::near_light`).
    pub lamp_radius_inradii: f64,
    /// Shadow rays per shadowed image of a lamp with a radius, spread over the lamp's disc
    /// as seen from the lit point ([`shadow_directions`]). 1: one ray, to the lamp's centre
    /// (a hard shadow). Point lamps always take one.
    pub soft_samples: u32,
}

impl Default for Lighting {
    fn default() -> Self {
        Self {
            paths: LightPaths::Images,
            reach_inradii: Self::DEFAULT_REACH_INRADII,
            tail: true,
            shadows: Self::DEFAULT_SHADOWS,
            lamp_radius_inradii: 0.0,
            soft_samples: Self::DEFAULT_SOFT_SAMPLES,
        }
    }
}

impl Lighting {
    /// The default reach in inradii: `bench --lighting` found 2 as close to its reference as
    /// 4 or 8 once the tail is added, and cheaper (docs/light.md).
    pub const DEFAULT_REACH_INRADII: f64 = 2.0;
    /// The default number of shadowed images per lamp: none. In the default scenes 4
    /// shadows cost 1.25–1.6 times the unshadowed frame on lavapipe and take off at most
    /// 0.4/255 of mean error (docs/light.md); scenes that need them ask
    /// (`[lighting] shadows`).
    pub const DEFAULT_SHADOWS: u32 = 0;
    /// The most shadowed images per lamp.
    pub const MAX_SHADOWS: u32 = 64;
    /// The default shadow rays per shadowed image of a lamp with a radius: 8
    /// (`bench --lighting` and docs/light.md: the penumbra's error against 64 rays).
    pub const DEFAULT_SOFT_SAMPLES: u32 = 8;
    /// The most shadow rays per shadowed image.
    pub const MAX_SOFT_SAMPLES: u32 = 64;

    /// The older model: the nearest copy, no tail, no shadows.
    pub const NEAREST: Self = Self {
        paths: LightPaths::Nearest,
        reach_inradii: Self::DEFAULT_REACH_INRADII,
        tail: false,
        shadows: 0,
        lamp_radius_inradii: 0.0,
        soft_samples: Self::DEFAULT_SOFT_SAMPLES,
    };

    /// The most a lamp's radius may be, in inradii: a lamp stays well inside the cell.
    pub const MAX_LAMP_RADIUS_INRADII: f64 = 1.0;

    /// The lamps' radius as a distance in `space`.
    #[must_use]
    pub fn lamp_radius(&self, space: &Space) -> f64 {
        self.lamp_radius_inradii * inradius(space)
    }

    /// The reach as a distance in `space`.
    #[must_use]
    pub fn reach(&self, space: &Space) -> f64 {
        self.reach_inradii * inradius(space)
    }

    /// Whether the settings are usable: a reach that is a positive number, shadows within
    /// [`Lighting::MAX_SHADOWS`]. The message names what is wrong.
    pub fn check(&self) -> Result<(), String> {
        if !(self.reach_inradii > 0.0 && self.reach_inradii <= 64.0) {
            return Err(format!(
                "the light reach must be more than 0 and at most 64 inradii, got {}",
                self.reach_inradii
            ));
        }
        if self.shadows > Self::MAX_SHADOWS {
            return Err(format!(
                "at most {} shadowed images per light, got {}",
                Self::MAX_SHADOWS,
                self.shadows
            ));
        }
        if !(0.0..=Self::MAX_LAMP_RADIUS_INRADII).contains(&self.lamp_radius_inradii) {
            return Err(format!(
                "a lamp's radius must be 0 to {} inradii, got {}",
                Self::MAX_LAMP_RADIUS_INRADII,
                self.lamp_radius_inradii
            ));
        }
        if !(1..=Self::MAX_SOFT_SAMPLES).contains(&self.soft_samples) {
            return Err(format!(
                "soft shadows take 1 to {} shadow rays per image, got {}",
                Self::MAX_SOFT_SAMPLES,
                self.soft_samples
            ));
        }
        Ok(())
    }
}

/// A lamp's images in the cover for [`LightPaths::Images`]: those within `reach + ρ` of the
/// origin (`ρ` the circumradius, so that every image within `reach` of a point of the cell
/// is there), nearest the origin first, and the reach they cover. Past
/// [`MAX_LAMP_IMAGES`] the reach is shortened to what the nearest ones cover.
#[must_use]
pub fn cover_images(space: &Space, lamp: DVec4, reach: f64) -> (Vec<DVec4>, f64) {
    let g = space.geometry;
    let rho = if g == Geometry::Spherical {
        PI
    } else {
        circumradius(space)
    };
    // The images within `radius` of the origin and the reach they cover from every point
    // of the cell, or `None` where the walk to them visits too many cells.
    let fit = |radius: f64| -> Option<(Vec<DVec4>, f64)> {
        let images = super::light_images::lamp_images(space, lamp, radius, 64 * MAX_LAMP_IMAGES)?;
        if images.len() <= MAX_LAMP_IMAGES {
            let covered = if g == Geometry::Spherical {
                PI
            } else {
                radius - rho
            };
            return Some((images.into_iter().map(|(q, _)| q).collect(), covered));
        }
        // Every image nearer the origin than the first one left out is kept.
        let edge = images[MAX_LAMP_IMAGES].1;
        let kept = images[..MAX_LAMP_IMAGES]
            .iter()
            .take_while(|(_, d)| *d < edge)
            .map(|(q, _)| *q)
            .collect();
        Some((kept, (edge - rho).max(0.0)))
    };
    if let Some(found) = fit(reach + rho) {
        return found;
    }
    // Too many cells to walk that far: the farthest radius that can be walked, by
    // bisection (the cell alone, reach 0, always can).
    let (mut lo, mut hi) = (rho, reach + rho);
    let mut best = None;
    for _ in 0..12 {
        let mid = 0.5 * (lo + hi);
        match fit(mid) {
            Some(found) => {
                best = Some(found);
                lo = mid;
            }
            None => hi = mid,
        }
    }
    best.or_else(|| fit(rho)).unwrap_or((vec![lamp], 0.0))
}

/// The mean fluence of a unit lamp's images beyond `reach` from a point, in fog of distance
/// `fog` (`docs/light.md`): images spread with density `1/vol(M)`, and a sphere's area
/// `4π S(r)²` cancels the falloff, so the shells add `4π e^(−r/λ) dr / vol(M)`:
/// `4πλ e^(−R/λ) / vol(M)` in E³ and H³; in S³ from `R` to `π`, both arcs and the turns,
/// `4πλ (e^(−R/λ) − e^(−(2π−R)/λ)) / (vol(M) (1 − e^(−2π/λ)))`.
#[must_use]
pub fn tail_fluence(geometry: Geometry, reach: f64, fog: f64, volume: f64) -> f64 {
    if !(volume > 0.0 && fog > 0.0) {
        return 0.0;
    }
    let near = (-reach / fog).exp();
    match geometry {
        Geometry::Spherical => {
            let reach = reach.min(PI);
            4.0 * PI * fog * (near - (-(TAU - reach) / fog).exp())
                / (volume * (1.0 - (-TAU / fog).exp()))
        }
        _ => 4.0 * PI * fog * near / volume,
    }
}

/// [`tail_fluence`] where geodesic spheres never close up (E³, H³, the products, Nil):
/// `4πλ e^(−R/λ)/vol(M)`, and 0 for a fog that is not a positive finite distance or a
/// volume that is not positive.
#[must_use]
pub fn open_tail_fluence(reach: f64, fog: f64, volume: f64) -> f64 {
    if !(volume > 0.0 && fog > 0.0 && fog.is_finite()) {
        return 0.0;
    }
    4.0 * PI * fog * (-reach / fog).exp() / volume
}

/// The volume of the space, for the tail (0 where it cannot be computed: no tail then).
#[must_use]
pub fn cell_volume(space: &Space) -> f64 {
    let v = volume(space);
    if v.is_finite() && v > 0.0 { v } else { 0.0 }
}

/// Asks whether anything lies on the geodesic from a point along a unit tangent within a
/// length: `occluded(point, tangent, length)`.
pub type Occluded<'a> = dyn FnMut(DVec4, DVec4, f64) -> bool + 'a;

/// A point light, with its copies in the cells around the fundamental cell.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Where the light is, inside the cell.
    pub position: DVec4,
    /// Colour, linear RGB.
    pub colour: DVec3,
    /// Brightness at distance `d` is `power / S(d)²` (`sin²`, `d²`, `sinh²`).
    pub power: f64,
    /// The light and its images under the face pairings, in the cell's coordinates: a
    /// surface point is lit by the nearest of them ([`LightPaths::Nearest`]).
    pub images: Vec<DVec4>,
    /// Its images in the universal cover within `reach + ρ` of the origin, nearest the
    /// origin first ([`LightPaths::Images`], [`crate::scene::lighting::cover_images`]).
    pub cover: Vec<DVec4>,
    /// The distance from a lit point within which the images are summed exactly.
    pub reach: f64,
    /// The space's volume, the images' density in the cover (the tail beyond the reach).
    pub volume: f64,
    /// The lamp's radius for its shadows ([`Lighting::lamp_radius`], set with the reach by
    /// `CurvedScene::set_lighting`): 0, a point (hard shadows); more, a ball whose disc the
    /// shadow rays spread over ([`Lighting::soft_samples`], [`shadow_directions`]). Its
    /// light still comes from its centre.
    pub radius: f64,
}

impl Light {
    /// A light at `position` (inside the cell) with its images under the pairings and in
    /// the cover within the default reach ([`Lighting::DEFAULT_REACH_INRADII`]).
    #[must_use]
    pub fn new(space: &Space, position: DVec4, colour: DVec3, power: f64) -> Self {
        Self::reaching(
            space,
            position,
            colour,
            power,
            Lighting::default().reach(space),
        )
    }

    /// [`Light::new`] with the images in the cover within `reach` of each lit point.
    #[must_use]
    pub fn reaching(space: &Space, position: DVec4, colour: DVec3, power: f64, reach: f64) -> Self {
        let g = space.geometry;
        let mut images = vec![position];
        for face in &space.faces {
            let image = g.project_point(face.pairing * position);
            if images.iter().all(|q| g.distance(*q, image) > 1e-9) {
                images.push(image);
            }
        }
        let (cover, reach) = cover_images(space, position, reach);
        Self {
            position,
            colour,
            power,
            images,
            cover,
            reach,
            volume: cell_volume(space),
            radius: 0.0,
        }
    }

    /// The same lamp with a radius for its shadows ([`Light::radius`]).
    #[must_use]
    pub fn with_radius(self, radius: f64) -> Self {
        Self { radius, ..self }
    }

    /// The same light with its images in the cover within `reach`.
    #[must_use]
    pub fn with_reach(&self, space: &Space, reach: f64) -> Self {
        Self::reaching(space, self.position, self.colour, self.power, reach)
            .with_radius(self.radius)
    }

    /// The first of [`Light::cover`] up to the last that may lie within [`Light::reach`] of
    /// `point`. The images come nearest the origin first, and none further from it than
    /// the point plus the reach is within the reach of the point (the triangle inequality),
    /// so every image within the reach is in this prefix; it is found by bisection on a
    /// number that grows with the distance from the origin (`w = cosh d` in H³, `|x|²` in
    /// E³), with a margin for rounding. In S³ every image may reach: all of them.
    #[must_use]
    pub fn cover_reaching(&self, g: Geometry, point: DVec4) -> &[DVec4] {
        let beyond = g.distance(crate::geometry::ORIGIN, point) + self.reach;
        let end = match g {
            Geometry::Hyperbolic => {
                let last = beyond.cosh() * (1.0 + 1e-9);
                self.cover.partition_point(|q| q.w <= last)
            }
            Geometry::Euclidean => {
                let last = beyond * beyond * (1.0 + 1e-9);
                self.cover
                    .partition_point(|q| (q.truncate() / q.w).length_squared() <= last)
            }
            Geometry::Spherical => self.cover.len(),
        };
        &self.cover[..end]
    }

    /// The image nearest to `x` and its distance.
    #[must_use]
    pub fn nearest(&self, geometry: Geometry, x: DVec4) -> (DVec4, f64) {
        self.images
            .iter()
            .map(|q| (*q, geometry.distance(x, *q)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((self.position, geometry.distance(x, self.position)))
    }
}

/// The light a surface point (`point`, unit normal `normal`) gets from `light`, per unit of
/// its colour × power ([the module's description](self)), in fog of distance `fog`, the
/// falloff held at `S(near_light)` within `near_light`; `occluded` walks the shadow rays
/// (answer `false` for none).
#[must_use]
pub fn gather(
    lighting: &Lighting,
    (fog, near_light): (f64, f64),
    g: Geometry,
    light: &Light,
    point: DVec4,
    normal: DVec4,
    occluded: &mut Occluded<'_>,
) -> f64 {
    let s2 = |d: f64| {
        let s = g.s(d).abs().max(g.s(near_light));
        s * s
    };
    let lambert = |l: DVec4| g.form(normal, l).max(0.0);
    let shadows = lighting.shadows as usize;
    let samples = if light.radius > 0.0 {
        lighting.soft_samples.max(1)
    } else {
        1
    };
    // The share of the lamp's disc seen from the point along `l`, `length` away.
    let seen = |l: DVec4, length: f64, occluded: &mut Occluded<'_>| -> f64 {
        let dirs = shadow_directions(g, point, l, length, light.radius, samples);
        let open = dirs
            .iter()
            .filter(|&&v| !shadowed(g, occluded, point, v, length))
            .count();
        open as f64 / dirs.len() as f64
    };
    if lighting.paths == LightPaths::Nearest {
        let (at, dl) = light.nearest(g, point);
        if !(dl > 0.0) {
            return 0.0;
        }
        let l = g.tangent_towards(point, at);
        let cos = lambert(l);
        if cos > 0.0 && shadows > 0 {
            return cos * seen(l, dl, occluded) / s2(dl);
        }
        return cos / s2(dl);
    }
    let absorbed = |d: f64| (-d / fog).exp();
    let mut sum = 0.0;
    for (k, q) in light.cover_reaching(g, point).iter().enumerate() {
        let d = g.distance(point, *q);
        if !(d > 0.0) || d > light.reach {
            continue;
        }
        let walk = k < shadows;
        if g == Geometry::Spherical && d > ANTIPODE {
            continue;
        }
        let l = g.tangent_towards(point, *q);
        if g == Geometry::Spherical {
            let (short, long) = (lambert(l), lambert(-l));
            if short == 0.0 && long == 0.0 {
                continue;
            }
            let t = (-TAU / fog).exp();
            // The shares of the lamp seen along the short arcs, the long ones, and both
            // (a whole turn passes both arcs of the same great circle).
            let (a, b, both) = if walk {
                let dirs = shadow_directions(g, point, l, d, light.radius, samples);
                let (mut a, mut b, mut both) = (0.0, 0.0, 0.0);
                for v in &dirs {
                    let short_open = !shadowed(g, occluded, point, *v, d);
                    let long_open = !shadowed(g, occluded, point, -*v, TAU - d);
                    a += f64::from(u8::from(short_open));
                    b += f64::from(u8::from(long_open));
                    both += f64::from(u8::from(short_open && long_open));
                }
                let n = dirs.len() as f64;
                (a / n, b / n, both / n)
            } else {
                (1.0, 1.0, 1.0)
            };
            let fs = short * absorbed(d);
            let fl = long * absorbed(TAU - d);
            let paths = fs * a + fl * b + (fs + fl) * both * t / (1.0 - t);
            sum += paths / s2(d);
        } else {
            let cos = lambert(l);
            if cos > 0.0 {
                let open = if walk { seen(l, d, occluded) } else { 1.0 };
                sum += cos * open * absorbed(d) / s2(d);
            }
        }
    }
    if lighting.tail {
        sum += 0.25 * tail_fluence(g, light.reach, fog, light.volume);
    }
    sum
}

/// The directions of the shadow rays from `point` towards a lamp of `radius` whose centre
/// lies `distance` away along the unit tangent `l`: `samples` of them, spread evenly by
/// solid angle over the cone of half-angle `α`, `sin α = S(radius)/|S(distance)|` (the
/// lamp's disc as seen from the point: the law of sines of a right geodesic triangle, in
/// each geometry), on a Fibonacci spiral: sample `j` is `θ` from `l` with
/// `1 − cos θ = u (1 − cos α)`, `u = (j + ½)/n`, turned `j` golden angles about it. One
/// sample, or a lamp without a radius, gives `l` itself. The shader builds the same
/// directions (`soft_direction` in `shaders/lighting.wgsl`).
#[must_use]
pub fn shadow_directions(
    g: Geometry,
    point: DVec4,
    l: DVec4,
    distance: f64,
    radius: f64,
    samples: u32,
) -> Vec<DVec4> {
    if samples <= 1 || !(radius > 0.0) {
        return vec![l];
    }
    let sin_alpha = (g.s(radius) / g.s(distance).abs()).min(1.0);
    // 1 − cos α without cancellation.
    let versine = sin_alpha * sin_alpha / (1.0 + (1.0 - sin_alpha * sin_alpha).sqrt());
    let (e1, e2) = tangent_frame(g, point, l);
    (0..samples)
        .map(|j| {
            let u = (f64::from(j) + 0.5) / f64::from(samples);
            // 1 − cos θ = 2 sin²(θ/2).
            let theta = 2.0 * (0.5 * u * versine).sqrt().asin();
            let phi = f64::from(j) * GOLDEN_ANGLE;
            let v = l * theta.cos() + (e1 * phi.cos() + e2 * phi.sin()) * theta.sin();
            g.unit_tangent(point, v)
        })
        .collect()
}

/// The golden angle, `π (3 − √5)`: successive samples of a Fibonacci spiral turn by it.
pub const GOLDEN_ANGLE: f64 = 2.399_963_229_728_653;

/// Two unit tangents at `point` orthogonal to the unit tangent `l` and to each other (in the
/// geometry's form): of the coordinate axes' tangent parts, with `l` taken off, the longest,
/// then of the rest, with the first taken off too, the longest.
fn tangent_frame(g: Geometry, point: DVec4, l: DVec4) -> (DVec4, DVec4) {
    let longest = |taken: &[DVec4]| -> DVec4 {
        let (mut best, mut best_n) = (DVec4::ZERO, -1.0);
        for axis in [DVec4::X, DVec4::Y, DVec4::Z, DVec4::W] {
            let mut v = g.project_tangent(point, axis);
            for t in taken {
                v -= *t * g.form(v, *t);
            }
            let n = g.form(v, v);
            // The first of equals, as the shader takes it.
            if n > best_n {
                (best, best_n) = (v, n);
            }
        }
        best / best_n.sqrt()
    };
    let e1 = longest(&[l]);
    let e2 = longest(&[l, e1]);
    (e1, e2)
}

/// Whether the shadow ray from `point` along `l` for `length` meets something: it starts
/// [`SHADOW_OFFSET`] along the geodesic.
fn shadowed(g: Geometry, occluded: &mut Occluded<'_>, point: DVec4, l: DVec4, length: f64) -> bool {
    if length <= SHADOW_OFFSET {
        return false;
    }
    let (from, along) = g.geodesic(point, l, SHADOW_OFFSET);
    let from = g.project_point(from);
    occluded(from, g.unit_tangent(from, along), length - SHADOW_OFFSET)
}
