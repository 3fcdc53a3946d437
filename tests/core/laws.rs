//! The laws every geometry family's walk obeys, written once over the walk contract
//! ([`CellWalk`]) and instantiated per family, as glam instantiates one law suite per type:
//! a family added later gets them all with one line of [`family_laws!`].
//!
//! - a walk's end is the geodesic of the universal cover, carried by the pairings it
//!   crossed;
//! - long walks (10⁵ crossings) stay in the cell;
//! - f32 walks keep the f64 walk's faces over their first crossings;
//! - a walk by distance goes its whole length, and splitting it in two changes nothing;
//! - a player's random walk stays in the cell and on the model, and its frame is the cover's
//!   carried by the holonomy of its wraps.

use bevy_curved_spaces::geometry::{Geometry, Ray, Vector4};
use bevy_curved_spaces::random::SplitMix64;
use bevy_curved_spaces::space::nil::{self, NilSpace};
use bevy_curved_spaces::space::product::motion::camera_frame;
use bevy_curved_spaces::space::product::{ProductSpace, ProductWalker};
use bevy_curved_spaces::space::sl2r::{self, Sl2rWalker, UnitTangentSpace};
use bevy_curved_spaces::space::{CellWalk, FamilySpace, FrameMotion, FrameSpace, Limit, Space};
use glam::{DMat4, DVec3, DVec4, Vec4};

/// What the laws need of a family beyond the geometry contract ([`FamilySpace`]: the walkers,
/// the chart's rays, the cell, the player's step and wrap): its spaces, the cover's
/// geodesics and how a crossing carries a cover point, which the tests know independently.
trait LawFamily: Sized {
    /// The family's space.
    type Space: FamilySpace;
    /// The family's spaces the laws run in, by name.
    fn cases() -> Vec<(String, Self)>;
    /// The space.
    fn space(&self) -> &Self::Space;
    /// The point at distance `t` along the cover geodesic of `start`.
    fn cover_point(&self, start: &Ray<DVec4>, t: f64) -> DVec4;
    /// A cover point carried through the pairing of a crossing's face, as the walk carries
    /// its ray (`entry`: where the crossing entered, for a family whose faces are paired
    /// piecewise, by where a ray crosses them).
    fn carried(&self, face: usize, entry: DVec4, p: DVec4) -> DVec4;
    /// How far two points are apart, in the model's entries (the sign of a point of S³
    /// matters: the walk keeps it).
    fn gap(&self, a: DVec4, b: DVec4) -> f64 {
        (a - b).abs().max_element()
    }
    /// The tolerance of a walk of length `d`: the problem's conditioning (`e^d` in H³).
    fn tolerance(&self, d: f64) -> f64;
    /// The player's start frame.
    fn player_start(&self) -> DMat4;
    /// The shift along the fibre of a wrap through `face` (a product's top and bottom).
    fn fibre_shift(&self, _face: usize) -> f64 {
        0.0
    }
    /// The cover frame carried by the holonomy of the wraps (`held`, the pairings' product,
    /// and `shift` along a fibre): the matrix applied to the whole frame, by default.
    fn carry_frame(&self, held: DMat4, shift: f64, cover: DMat4) -> DMat4 {
        let mut carried = held * cover;
        carried.w_axis.z += shift;
        carried
    }
    /// A unit ray from the cell's centre in the chart direction `d`.
    fn ray(&self, d: DVec3) -> Ray<DVec4> {
        self.space().chart_ray(DVec3::ZERO, d).expect("a chart ray")
    }
}

/// A constant-curvature space (E³, S³, H³).
struct Constant(Space);

impl LawFamily for Constant {
    type Space = Space;
    fn cases() -> Vec<(String, Self)> {
        [
            "torus",
            "torus-two-cells",
            "half-turn",
            "hantzsche-wendt",
            "poincare",
            "seifert-weber",
            "lens-7-2",
            "prism-3",
            "mirrored-tetrahedron",
            "three-sphere",
            "projective-space",
            "weeks",
        ]
        .into_iter()
        .map(|id| (id.to_string(), Constant(crate::common::library_space(id))))
        .collect()
    }
    fn space(&self) -> &Space {
        &self.0
    }
    fn cover_point(&self, start: &Ray<DVec4>, t: f64) -> DVec4 {
        let g = self.0.geometry();
        let (p, _) = g.geodesic(start.point, start.tangent, t);
        match g {
            Geometry::Spherical => p / p.length(),
            _ => g.project_point(p),
        }
    }
    fn carried(&self, face: usize, _entry: DVec4, p: DVec4) -> DVec4 {
        let q = self.0.faces()[face].pairing * p;
        match self.0.geometry() {
            Geometry::Euclidean => q / q.w,
            _ => q,
        }
    }
    fn tolerance(&self, d: f64) -> f64 {
        match self.0.geometry() {
            Geometry::Hyperbolic => 1e-12 * d.exp().powi(2),
            _ => 1e-10 * (1.0 + d),
        }
    }
    fn player_start(&self) -> DMat4 {
        bevy_curved_spaces::view::TraceCamera::default_for(&self.0).frame
    }
}

/// A product space (H²×R, S²×R).
struct Product(ProductSpace);

impl LawFamily for Product {
    type Space = ProductSpace;
    fn cases() -> Vec<(String, Self)> {
        [
            "bitorus-circle",
            "bitorus-circle-turn",
            "crosscaps-circle",
            "sphere-circle",
            "sphere-circle-turn",
            "projective-plane-circle",
        ]
        .into_iter()
        .map(|id| (id.to_string(), Product(crate::common::product(id))))
        .collect()
    }
    fn space(&self) -> &ProductSpace {
        &self.0
    }
    fn cover_point(&self, start: &Ray<DVec4>, t: f64) -> DVec4 {
        let g = self.0.base();
        let v = start.tangent;
        let lambda = DVec3::new(v.x, v.y, v.w).length();
        let (c, s) = g.cs(lambda * t);
        let vb = DVec4::new(v.x, v.y, 0.0, v.w) / lambda.max(1e-300);
        let pb = DVec4::new(start.point.x, start.point.y, 0.0, start.point.w);
        let b = if lambda > 0.0 { pb * c + vb * s } else { pb };
        DVec4::new(b.x, b.y, start.point.z + v.z * t, b.w)
    }
    fn carried(&self, face: usize, _entry: DVec4, p: DVec4) -> DVec4 {
        let w = ProductWalker::<DVec4>::new(&self.0);
        let base = DVec4::new(p.x, p.y, 0.0, p.w);
        let (m, dz): (DMat4, f64) = if face == w.top() {
            (w.up.0, -self.0.length())
        } else if face == w.bottom() {
            (w.down.0, self.0.length())
        } else {
            (w.pairings[face], 0.0)
        };
        let q = m * base;
        DVec4::new(q.x, q.y, p.z + dz, q.w)
    }
    fn tolerance(&self, d: f64) -> f64 {
        match self.0.base() {
            Geometry::Hyperbolic => 1e-12 * d.exp().powi(2),
            _ => 1e-10 * (1.0 + d),
        }
    }
    fn player_start(&self) -> DMat4 {
        let camera = bevy_curved_spaces::trace::product::default_camera(&self.0);
        camera_frame(camera.point, camera.frame)
    }
    fn fibre_shift(&self, face: usize) -> f64 {
        // The top's and bottom's shifts along the fibre, a circle at a time.
        let sides = self.0.face_count() - 2;
        if face == sides {
            -self.0.length()
        } else if face == sides + 1 {
            self.0.length()
        } else {
            0.0
        }
    }
}

/// A Nil space: the box of `nil-K`, its sides paired piecewise.
struct Nil(NilSpace);

impl LawFamily for Nil {
    type Space = NilSpace;
    fn cases() -> Vec<(String, Self)> {
        // (nil-50's box is so thin that the player's random walk of 2 000 small steps
        // crosses it only a few times; its walks are tested in nil.rs.)
        [1, 3, 8]
            .into_iter()
            .map(|k| (format!("nil-{k}"), Nil(NilSpace::new(k))))
            .collect()
    }
    fn space(&self) -> &NilSpace {
        &self.0
    }
    fn cover_point(&self, start: &Ray<DVec4>, t: f64) -> DVec4 {
        let end = nil::flow(
            &nil::NilRay {
                point: start.point.truncate().to_array(),
                velocity: start.tangent.truncate().to_array(),
            },
            t,
        );
        DVec3::from_array(end.point).extend(1.0)
    }
    /// The element a crossing applied, found from where it entered (not from the walker's
    /// own choice): the side's generator `G` and the power of the centre `C^m` with the exit
    /// point `C^{−m} G⁻¹ · entry` in the box; the top and bottom by `C^{∓1}`.
    fn carried(&self, face: usize, entry: DVec4, p: DVec4) -> DVec4 {
        let k = f64::from(self.0.k());
        let generator = match face {
            0 => [-1.0, 0.0, 0.0],
            1 => [1.0, 0.0, 0.0],
            2 => [0.0, -1.0, 0.0],
            3 => [0.0, 1.0, 0.0],
            4 => [0.0, 0.0, -1.0 / k],
            _ => [0.0, 0.0, 1.0 / k],
        };
        let g = if face < 4 {
            let back = generator.map(|x: f64| -x);
            let exit = nil::group_product(back, entry.truncate().to_array());
            let m = (exit[2] * k).round();
            nil::group_product([0.0, 0.0, m / k], generator)
        } else {
            generator
        };
        DVec3::from_array(nil::group_product(g, p.truncate().to_array())).extend(1.0)
    }
    fn tolerance(&self, d: f64) -> f64 {
        // Nil's geodesics spread polynomially.
        1e-12 * (1.0 + d * d)
    }
    fn player_start(&self) -> DMat4 {
        DMat4::IDENTITY
    }
    /// A left translation moves the point and keeps the body axes.
    fn carry_frame(&self, held: DMat4, _shift: f64, cover: DMat4) -> DMat4 {
        let mut carried = cover;
        carried.w_axis = held * cover.w_axis;
        carried
    }
}

/// An SL̃(2,R) space: `UT Σ`, the polygon times the fibre. A walk's point holds the base
/// point `p` (and `e`'s first entry); the laws compare base points, which the pairings
/// carry as isometries of `H²` (the whole frame is compared in `sl2r/walks.rs`).
struct Sl2r(UnitTangentSpace);

impl Sl2r {
    /// The pairing's action on `(x, y, w)` (the model's entries 0, 1 and 3 of the 4×4 the
    /// holonomy composes).
    fn surface_part(m: DMat4) -> [[f64; 3]; 3] {
        let idx = [0, 1, 3];
        idx.map(|r| idx.map(|c| m.col(c)[r]))
    }

    fn apply(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
        [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
    }
}

impl LawFamily for Sl2r {
    type Space = UnitTangentSpace;
    fn cases() -> Vec<(String, Self)> {
        // Each surface's bundle, and a fibre cover (whose walk also counts sheets).
        [
            ("abABcdCD", 1),
            ("abcdABCD", 1),
            ("abABcdCDefEF", 1),
            ("abABcdCDefEF", 2),
        ]
        .into_iter()
        .map(|(w, n)| {
            let space = UnitTangentSpace::cover(w, n).expect("a hyperbolic word");
            (space.name().to_string(), Sl2r(space))
        })
        .collect()
    }
    fn space(&self) -> &UnitTangentSpace {
        &self.0
    }
    fn cover_point(&self, start: &Ray<DVec4>, t: f64) -> DVec4 {
        let ray = Sl2rWalker::<DVec4>::sl2r_ray(start);
        DVec3::from_array(sl2r::flow::base_point(&ray, t)).extend(0.0)
    }
    fn carried(&self, face: usize, _entry: DVec4, p: DVec4) -> DVec4 {
        let m = self.0.sides()[face].pairing.map(|r| r.map(|x| x.hi));
        DVec3::from_array(Self::apply(&m, p.truncate().to_array())).extend(0.0)
    }
    /// The base points' gap in `x, y` (`w` follows from them; a walk's point holds the
    /// sheet and `e`'s first entry in its last two entries).
    fn gap(&self, a: DVec4, b: DVec4) -> f64 {
        (a.truncate().truncate() - b.truncate().truncate())
            .abs()
            .max_element()
    }
    fn tolerance(&self, d: f64) -> f64 {
        // Hyperbolic spreading, as in H³.
        1e-12 * d.exp()
    }
    fn player_start(&self) -> DMat4 {
        self.0.frame_from_centre(DVec3::ZERO)
    }
    /// The pairings move the point `(p, e)` (the last column, and `e` in the axes' fourth
    /// entries) and keep the axes' body components.
    fn carry_frame(&self, held: DMat4, _shift: f64, cover: DMat4) -> DMat4 {
        let m = Self::surface_part(held);
        let p = Self::apply(&m, cover.w_axis.truncate().to_array());
        let e = Self::apply(&m, [cover.x_axis.w, cover.y_axis.w, cover.z_axis.w]);
        let mut carried = cover;
        carried.x_axis.w = e[0];
        carried.y_axis.w = e[1];
        carried.z_axis.w = e[2];
        carried.w_axis = DVec3::from_array(p).extend(1.0);
        carried
    }
}

/// The player's wrap margin (the plugin's default).
const MARGIN: f64 = 1e-4;

fn directions(seed: u64, n: usize) -> Vec<DVec3> {
    let mut rng = SplitMix64(seed);
    (0..n).map(|_| rng.direction()).collect()
}

/// A walk's end is the cover geodesic's point carried by the pairings it crossed.
fn walk_ends_on_the_cover_geodesic<F: LawFamily>() {
    for (name, family) in F::cases() {
        let walker = family.space().walker::<DVec4>();
        for d in directions(0x1a3, 12) {
            let start = family.ray(d);
            let length = 3.0;
            let mut faces = Vec::new();
            let (end, walked) = walker.walk(start, Limit::Distance(length), |c| {
                faces.push((c.face, c.ray.point));
                true
            });
            assert_eq!(walked, length, "{name}");
            let mut q = family.cover_point(&start, length);
            for &(f, entry) in &faces {
                q = family.carried(f, entry, q);
            }
            let gap = family.gap(q, end.point);
            assert!(
                gap <= family.tolerance(length),
                "{name} {d:?}: the end is {gap:e} off the cover geodesic after {} crossings",
                faces.len()
            );
        }
    }
}

/// 10⁵ crossings, every entry point in the cell.
fn long_walks_stay_in_the_cell<F: LawFamily>() {
    for (name, family) in F::cases() {
        let walker = family.space().walker::<DVec4>();
        for d in directions(0x5e1, 2) {
            let mut worst = f64::NEG_INFINITY;
            let (end, _) = walker.walk(family.ray(d), Limit::Crossings(100_000), |c| {
                worst = worst.max(family.space().outside_by(c.ray.point));
                true
            });
            assert!(
                worst < 1e-9,
                "{name}: a crossing {worst:e} outside the cell"
            );
            assert!(end.point.is_finite(), "{name}");
        }
    }
}

/// f32 keeps the f64 walk's faces over its first crossings (a few units of distance).
fn f32_walks_keep_the_f64_faces<F: LawFamily>() {
    for (name, family) in F::cases() {
        let (w64, w32) = (
            family.space().walker::<DVec4>(),
            family.space().walker::<Vec4>(),
        );
        for d in directions(0x32f, 8) {
            let start = family.ray(d);
            let start32 = Ray {
                point: Vec4::from_f64(start.point),
                tangent: Vec4::from_f64(start.tangent),
            };
            let faces64: Vec<usize> = w64
                .trace(start, Limit::Crossings(4))
                .crossings
                .iter()
                .map(|c| c.face)
                .collect();
            let faces32: Vec<usize> = w32
                .trace(start32, Limit::Crossings(4))
                .crossings
                .iter()
                .map(|c| c.face)
                .collect();
            assert_eq!(faces64, faces32, "{name} {d:?}");
        }
    }
}

/// A walk by distance goes its whole length, and one walk of `a + b` ends where a walk of
/// `a` continued by `b` ends.
fn walks_by_distance_compose<F: LawFamily>() {
    for (name, family) in F::cases() {
        let walker = family.space().walker::<DVec4>();
        for d in directions(0xc0, 6) {
            let start = family.ray(d);
            let (whole, l) = walker.walk(start, Limit::Distance(2.5), |_| true);
            assert_eq!(l, 2.5);
            let (half, _) = walker.walk(start, Limit::Distance(1.0), |_| true);
            let (rest, _) = walker.walk(half, Limit::Distance(1.5), |_| true);
            let gap = family.gap(whole.point, rest.point);
            assert!(gap <= family.tolerance(2.5), "{name} {d:?}: {gap:e}");
        }
    }
}

/// A player's random walk stays in the cell and on the model, and the wrapped frame is the
/// frame walked in the cover, carried by the isometries its wraps crossed (the holonomy).
fn a_player_wraps_with_its_holonomy<F: LawFamily>() {
    for (name, family) in F::cases() {
        let mut rng = SplitMix64(0x91a);
        let mut next = || 2.0 * rng.unit() - 1.0;
        let space = family.space();
        let step = 0.05 * space.scale();
        let walk = |frame, translation, rotation| {
            space.step_frame(
                frame,
                &FrameMotion {
                    translation,
                    rotation,
                    level: true,
                },
            )
        };
        let (mut wrapped, mut cover) = (family.player_start(), family.player_start());
        let (mut held, mut shift) = (DMat4::IDENTITY, 0.0);
        let mut crossings = 0;
        for _ in 0..2_000 {
            let t = DVec3::new(next(), next(), next()) * step;
            let r = DVec3::new(next(), next(), next()) * 0.1;
            cover = walk(cover, t, r);
            let (f, crossed) = space.wrap_frame(walk(wrapped, t, r), MARGIN);
            for c in crossed {
                held = c.pairing * held;
                shift += family.fibre_shift(c.face);
                crossings += 1;
            }
            wrapped = f;
            assert!(space.outside_by(wrapped.w_axis) <= 2.0 * MARGIN, "{name}");
            assert!(space.frame_defect(wrapped) < 1e-9, "{name}");
        }
        let carried = family.carry_frame(held, shift, cover);
        let gap = (0..4)
            .map(|c| family.gap(carried.col(c), wrapped.col(c)))
            .fold(0.0, f64::max);
        assert!(
            crossings > 5 || space.face_count() == 0,
            "{name}: only {crossings} crossings"
        );
        assert!(
            gap < 1e-6,
            "{name}: the wrapped frame is {gap:e} off the carried one"
        );
    }
}

/// Every law, as tests of a family: `family_laws!(module, Family);`.
macro_rules! family_laws {
    ($module:ident, $family:ty) => {
        mod $module {
            use super::*;

            #[test]
            fn a_walk_ends_on_the_cover_geodesic_carried_by_its_pairings() {
                walk_ends_on_the_cover_geodesic::<$family>();
            }

            #[test]
            fn long_walks_stay_in_the_cell() {
                super::long_walks_stay_in_the_cell::<$family>();
            }

            #[test]
            fn f32_walks_keep_the_f64_faces() {
                super::f32_walks_keep_the_f64_faces::<$family>();
            }

            #[test]
            fn walks_by_distance_compose() {
                super::walks_by_distance_compose::<$family>();
            }

            #[test]
            fn a_player_wraps_with_its_holonomy() {
                super::a_player_wraps_with_its_holonomy::<$family>();
            }
        }
    };
}

family_laws!(constant_curvature, Constant);
family_laws!(products, Product);
family_laws!(nil_spaces, Nil);
family_laws!(sl2r_spaces, Sl2r);
