//! The geometry families and the one registry that sends a space's id to its family.
//!
//! A *family* is a way of modelling a geometry and walking its cells: the constant-curvature
//! family (E³, S³, H³: a polyhedron in the hyperboloid, sphere or affine chart, its faces
//! paired by 4×4 isometries, [`Space`]) and the product family (H²×R, S²×R: a surface's
//! polygon times an interval, [`ProductSpace`]). [`AnySpace`] holds a space of whichever
//! family, as a closed enum (parry's `TypedShape` is the model), and
//! [`AnySpace::resolve`] is the only place where an id, a file or a word is sent to a family.
//!
//! What a family cannot do is said here too, once: [`AnySpace::supports`] answers a
//! [`Feature`] with `Ok(())` or an [`Unsupported`] that names the family, the feature and
//! why; the command line, the plugin and the benchmark ask it instead of checking by hand.

use super::dirichlet::DirichletOptions;
use super::nil::{NilSpace, nil_space};
use super::product::{ProductOrFlat, ProductSpace, product_space};
use super::sl2r::{UnitTangentSpace, sl2r_space};
use super::{Space, invariants};
use crate::geometry::Geometry;
use glam::{DMat4, DVec3, DVec4};
use std::path::Path;
use std::sync::Arc;

/// A geometry family: how its spaces are modelled and walked.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Family {
    /// E³, S³ and H³: one polyhedral cell in the model of the geometry, faces paired by
    /// isometries ([`Space`], walked by [`super::CellWalker`]).
    Constant,
    /// H²×R and S²×R: a surface's polygon times an interval ([`ProductSpace`], walked by
    /// [`super::product::ProductWalker`]).
    Product,
    /// Nil: the Heisenberg nilmanifolds, a box of the chart whose sides are paired by left
    /// translations ([`NilSpace`], walked by [`super::nil::NilWalker`]).
    Nil,
    /// SL̃(2,R): unit tangent bundles of hyperbolic surfaces, a polygon times the whole
    /// fibre whose sides are paired by the surface group ([`UnitTangentSpace`], walked by
    /// [`super::sl2r::Sl2rWalker`]).
    Sl2r,
}

impl Family {
    /// Every family, in the order `curved-spaces list` shows them.
    pub const ALL: [Family; 4] = [Family::Constant, Family::Product, Family::Nil, Family::Sl2r];

    /// The family's name, as messages use it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Family::Constant => "constant curvature (E³, S³, H³)",
            Family::Product => "product (H²×R, S²×R)",
            Family::Nil => "Nil",
            Family::Sl2r => "SL̃(2,R)",
        }
    }
}

/// Something a command, the plugin or a scene may ask of a space's family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Feature {
    /// `render --time` and moving objects in a scene.
    MovingObjects,
    /// The default scene's part switches (`--no-edges`, `--no-centre`, …).
    SceneParts,
    /// `walk --record`: recording a flight.
    RecordFlight,
    /// `walk --xr`: the OpenXR headset mode.
    Headset,
    /// `export`: writing the space as a space file.
    Export,
    /// `--basepoint`: the Dirichlet domain's centre (spaces from generator files).
    Basepoint,
    /// Lamps of a radius (soft shadows).
    SoftShadows,
    /// Lighting by every image of a lamp, with a bound on the images left out.
    EveryImageBound,
    /// Pictures: `render`, `walk`, `flight`, `light`, `bench` and the plugin.
    Pictures,
    /// `render --cpu`: pictures by the f64 CPU reference tracer.
    ReferencePictures,
    /// The cell's walls with windows (`--walls`).
    Walls,
    /// The teaching views (`--colour-by`).
    TeachingViews,
    /// `light`: a lamp's light at a point, image by image.
    LampFluence,
    /// Flights: `flight` and `walk --replay`.
    Flights,
    /// The holonomy teaching view (`--colour-by holonomy`): the rotation of each copy.
    HolonomyView,
}

impl Feature {
    /// What the feature is, as a user names it.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Feature::MovingObjects => "moving objects (`--time`, a scene's velocities)",
            Feature::SceneParts => "the scene-part switches",
            Feature::RecordFlight => "recording a flight (`walk --record`)",
            Feature::Headset => "the headset mode (`walk --xr`)",
            Feature::Export => "`export`",
            Feature::Basepoint => "`--basepoint`",
            Feature::SoftShadows => "lamps of a radius (soft shadows)",
            Feature::EveryImageBound => "a bound on the light of the lamp images left out",
            Feature::Pictures => {
                "pictures (`render`, `walk`, `flight`, `light`, `bench`, the plugin)"
            }
            Feature::ReferencePictures => "`render --cpu` (the CPU reference tracer)",
            Feature::Walls => "walls with windows (`--walls`)",
            Feature::TeachingViews => "the teaching views (`--colour-by`)",
            Feature::LampFluence => "`light` (a lamp's light at a point)",
            Feature::Flights => "flights (`flight`, `walk --replay`)",
            Feature::HolonomyView => "the holonomy view (`--colour-by holonomy`)",
        }
    }
}

/// A feature a family does not have, with the reason: the one message every caller shows.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("not in the {} spaces: {}: {reason}", family.name(), feature.name())]
pub struct Unsupported {
    /// The family asked.
    pub family: Family,
    /// What was asked of it.
    pub feature: Feature,
    /// Why it cannot, and what to do instead.
    pub reason: &'static str,
}

impl Family {
    /// `Ok(())` where the family has `feature`, else why not. The one table of what each
    /// family lacks.
    pub fn supports(self, feature: Feature) -> Result<(), Unsupported> {
        let reason = match (self, feature) {
            (Family::Constant, _)
            | (
                Family::Product,
                Feature::RecordFlight
                | Feature::Headset
                | Feature::MovingObjects
                | Feature::Pictures
                | Feature::ReferencePictures
                | Feature::Walls
                | Feature::TeachingViews
                | Feature::HolonomyView
                | Feature::LampFluence
                | Feature::Flights,
            ) => return Ok(()),
            (
                Family::Nil,
                Feature::Pictures
                | Feature::ReferencePictures
                | Feature::Flights
                | Feature::RecordFlight
                | Feature::LampFluence
                | Feature::Headset
                | Feature::Walls
                | Feature::TeachingViews
                | Feature::MovingObjects,
            ) => {
                return Ok(());
            }
            (Family::Nil, Feature::Export) => {
                "a Nil space is written by its id (`nil-K`), which holds all of it"
            }
            (Family::Nil, Feature::Basepoint) => {
                "a Nil cell is the box about the origin; `--basepoint` moves the Dirichlet \
                 domains of generator files"
            }
            (Family::Nil, Feature::SoftShadows) => "a Nil lamp is a point",
            (Family::Nil, Feature::HolonomyView) => {
                "Nil's copies of the box are left translations, which turn no direction: every \
                 copy would show white; `--colour-by crossings` or `face` tell the copies apart"
            }
            (Family::Nil, Feature::SceneParts) => {
                "a Nil scene file's `edges` and `centre_ball` choose the parts"
            }
            (Family::Nil, _) => {
                "not written for the Nil family yet (it draws, walks and flies its default \
                 scene and scene files with walls and the teaching views: `render`, `walk`, \
                 `walk --xr`, `flight`, `light`, `bench`)"
            }
            (
                Family::Sl2r,
                Feature::Pictures
                | Feature::ReferencePictures
                | Feature::TeachingViews
                | Feature::Flights
                | Feature::RecordFlight
                | Feature::Headset
                | Feature::Walls
                | Feature::LampFluence,
            ) => return Ok(()),
            (Family::Sl2r, Feature::SoftShadows) => "an SL̃(2,R) lamp is a point",
            (Family::Sl2r, Feature::HolonomyView) => {
                "the holonomy view is not written for SL̃(2,R) yet; `--colour-by crossings` or \
                 `face` tell the copies apart"
            }
            (Family::Sl2r, Feature::Export) => {
                "a unit tangent bundle is written by its id (`unit-tangent-WORD`), which holds \
                 all of it"
            }
            (Family::Sl2r, Feature::Basepoint) => {
                "an SL̃(2,R) cell is centred on its polygon's centre; `--basepoint` moves the \
                 Dirichlet domains of generator files"
            }
            (Family::Sl2r, _) => {
                "not written for the SL̃(2,R) family yet (it draws its fibre tubes and metric \
                 balls lit by a lamp and walks exactly: `trace`, `info`, `list`, `render`, \
                 `walk`, `flight`, `walk --replay`, `walk --record`, `walk --xr`, `light`, \
                 `bench`)"
            }
            (Family::Product, Feature::SceneParts) => {
                "a product scene file's `edges` and `centre_ball` choose the parts"
            }
            (Family::Product, Feature::Export) => {
                "a product space is written by its id (`surface-WORD-circle-L`), which holds all \
                 of it"
            }
            (Family::Product, Feature::Basepoint) => {
                "a product cell is centred on its polygon's centre; `--basepoint` moves the \
                 Dirichlet domains of generator files"
            }
            (Family::Product, Feature::SoftShadows) => {
                "a product lamp is a point (its light's floor is the falloff at distance 1)"
            }
            (Family::Product, Feature::EveryImageBound) => {
                "the images are gathered to a reach, but the light beyond it is not bounded"
            }
        };
        Err(Unsupported {
            family: self,
            feature,
            reason,
        })
    }
}

/// A validated space of any family (cheap to clone: the space is shared).
#[derive(Clone, Debug)]
pub enum AnySpace {
    /// E³, S³ or H³.
    Constant(Arc<Space>),
    /// H²×R or S²×R.
    Product(Arc<ProductSpace>),
    /// Nil.
    Nil(Arc<NilSpace>),
    /// SL̃(2,R).
    Sl2r(Arc<UnitTangentSpace>),
}

impl From<UnitTangentSpace> for AnySpace {
    fn from(space: UnitTangentSpace) -> Self {
        AnySpace::Sl2r(Arc::new(space))
    }
}

impl From<NilSpace> for AnySpace {
    fn from(space: NilSpace) -> Self {
        AnySpace::Nil(Arc::new(space))
    }
}

impl From<Space> for AnySpace {
    fn from(space: Space) -> Self {
        AnySpace::Constant(Arc::new(space))
    }
}

impl From<ProductSpace> for AnySpace {
    fn from(space: ProductSpace) -> Self {
        AnySpace::Product(Arc::new(space))
    }
}

impl From<Arc<Space>> for AnySpace {
    fn from(space: Arc<Space>) -> Self {
        AnySpace::Constant(space)
    }
}

impl From<Arc<ProductSpace>> for AnySpace {
    fn from(space: Arc<ProductSpace>) -> Self {
        AnySpace::Product(space)
    }
}

impl AnySpace {
    /// The space an id names, whatever its family: a seed space, a library family's member
    /// (`lens-7-2`), a product space (`bitorus-circle`, `surface-WORD-circle-L`; a flat
    /// word's product is the flat space it is), or a space file by path relative to `base`
    /// (`.gen` generator file, JSON). The one registry of ids.
    pub fn resolve(id: &str, base: &Path, options: &DirichletOptions) -> Result<Self, String> {
        if let Some(space) = super::library::seed_or_library(id) {
            return space.map(Self::from);
        }
        if let Some(space) = nil_space(id) {
            return space.map(Self::from).map_err(|e| e.to_string());
        }
        if let Some(space) = sl2r_space(id) {
            return space.map(Self::from).map_err(|e| e.to_string());
        }
        match product_space(id) {
            Some(Ok(ProductOrFlat::Product(p))) => Ok(Self::from(*p)),
            Some(Ok(ProductOrFlat::Flat(s))) => Ok(Self::from(*s)),
            Some(Err(e)) => Err(e),
            None => super::library::space_file(id, base, options).map(Self::from),
        }
    }

    /// [`AnySpace::resolve`] with paths relative to the working directory and the default
    /// Dirichlet options.
    pub fn named(id: &str) -> Result<Self, String> {
        Self::resolve(id, Path::new(""), &DirichletOptions::default())
    }

    /// Its family.
    #[must_use]
    pub fn family(&self) -> Family {
        match self {
            AnySpace::Constant(_) => Family::Constant,
            AnySpace::Product(_) => Family::Product,
            AnySpace::Nil(_) => Family::Nil,
            AnySpace::Sl2r(_) => Family::Sl2r,
        }
    }

    /// `Ok(())` where the space's family has `feature` ([`Family::supports`]).
    pub fn supports(&self, feature: Feature) -> Result<(), Unsupported> {
        self.family().supports(feature)
    }

    /// The constant-curvature space, if it is one.
    #[must_use]
    pub fn constant(&self) -> Option<&Arc<Space>> {
        match self {
            AnySpace::Constant(s) => Some(s),
            AnySpace::Product(_) | AnySpace::Nil(_) | AnySpace::Sl2r(_) => None,
        }
    }

    /// The space as the object-safe part of the geometry contract ([`super::FrameSpace`]: the
    /// chart, the cell, the motion of frames), whatever its family.
    #[must_use]
    pub fn frames(&self) -> &dyn super::FrameSpace {
        match self {
            AnySpace::Constant(s) => &**s,
            AnySpace::Product(p) => &**p,
            AnySpace::Nil(n) => &**n,
            AnySpace::Sl2r(s) => &**s,
        }
    }

    /// The space of family `F`, if it is one (the plugin's systems of a family ask so).
    #[must_use]
    pub fn get<F: super::FamilySpace>(&self) -> Option<&Arc<F>> {
        let shared: &dyn std::any::Any = match self {
            AnySpace::Constant(s) => s,
            AnySpace::Product(p) => p,
            AnySpace::Nil(n) => n,
            AnySpace::Sl2r(s) => s,
        };
        shared.downcast_ref::<Arc<F>>()
    }

    /// The product space, if it is one.
    #[must_use]
    pub fn product(&self) -> Option<&Arc<ProductSpace>> {
        match self {
            AnySpace::Product(p) => Some(p),
            AnySpace::Constant(_) | AnySpace::Nil(_) | AnySpace::Sl2r(_) => None,
        }
    }

    /// The space's name (its id or file, or a seed space's name).
    #[must_use]
    pub fn name(&self) -> &str {
        match self {
            AnySpace::Constant(s) => s.name(),
            AnySpace::Product(p) => p.name(),
            AnySpace::Nil(n) => n.name(),
            AnySpace::Sl2r(s) => s.name(),
        }
    }

    /// One line about it.
    #[must_use]
    pub fn description(&self) -> &str {
        match self {
            AnySpace::Constant(s) => s.description(),
            AnySpace::Product(p) => p.description(),
            AnySpace::Nil(n) => n.description(),
            AnySpace::Sl2r(s) => s.description(),
        }
    }

    /// Its geometry's name: `E3`, `S3`, `H3`, `H2xR`, `S2xR`, `Nil`, `SL2R`.
    #[must_use]
    pub fn geometry_name(&self) -> &'static str {
        match self {
            AnySpace::Constant(s) => s.geometry().name(),
            AnySpace::Product(p) => p.geometry_name(),
            AnySpace::Nil(_) => "Nil",
            AnySpace::Sl2r(_) => "SL2R",
        }
    }

    /// The geometry of the model its points live in: the space's own for constant
    /// curvature, the surface's for a product, the affine chart (`w = 1`) for Nil, the
    /// hyperboloid of the base point for SL̃(2,R).
    #[must_use]
    pub fn model_geometry(&self) -> Geometry {
        match self {
            AnySpace::Constant(s) => s.geometry(),
            AnySpace::Product(p) => p.base(),
            AnySpace::Nil(_) => Geometry::Euclidean,
            AnySpace::Sl2r(_) => Geometry::Hyperbolic,
        }
    }

    /// Its volume.
    #[must_use]
    pub fn volume(&self) -> f64 {
        match self {
            AnySpace::Constant(s) => invariants::volume(s),
            AnySpace::Product(p) => p.volume(),
            AnySpace::Nil(n) => n.volume(),
            AnySpace::Sl2r(s) => s.volume(),
        }
    }

    /// A length of the cell's size, in which walking speeds, the default fog and the eye
    /// distance are measured: the cell's inradius, or a product's smaller of its polygon's
    /// inradius and half its circle.
    #[must_use]
    pub fn scale(&self) -> f64 {
        match self {
            AnySpace::Constant(s) => invariants::inradius(s),
            AnySpace::Product(p) => p.scale(),
            AnySpace::Nil(n) => super::FrameSpace::scale(&**n),
            AnySpace::Sl2r(s) => super::FrameSpace::scale(&**s),
        }
    }

    /// The injectivity radius; `None` where the group is too large to enumerate.
    #[must_use]
    pub fn injectivity_radius(&self) -> Option<f64> {
        match self {
            AnySpace::Constant(s) => invariants::injectivity_radius(s),
            AnySpace::Product(p) => p.injectivity_radius(PRODUCT_GROUP_LIMIT),
            AnySpace::Nil(n) => Some(n.injectivity_radius()),
            AnySpace::Sl2r(s) => s.injectivity_radius(PRODUCT_GROUP_LIMIT),
        }
    }
}

/// A constant-curvature space by id or path, as [`AnySpace::resolve`] finds
/// it; a product space's id is refused with the reason (this returns a [`Space`]).
pub fn resolve_space(id: &str, base: &Path, options: &DirichletOptions) -> Result<Space, String> {
    match AnySpace::resolve(id, base, options)? {
        AnySpace::Constant(space) => {
            Ok(std::sync::Arc::try_unwrap(space).unwrap_or_else(|shared| (*shared).clone()))
        }
        AnySpace::Product(space) => Err(format!(
            "{id} is a space of the geometry {} ({}): this takes the constant-curvature \
             geometries only (E³, S³, H³)",
            space.geometry_name(),
            space.description()
        )),
        AnySpace::Nil(space) => Err(format!(
            "{id} is a space of the geometry Nil ({}): this takes the constant-curvature \
             geometries only (E³, S³, H³)",
            space.description()
        )),
        AnySpace::Sl2r(space) => Err(format!(
            "{id} is a space of the geometry SL̃(2,R) ({}): this takes the constant-curvature \
             geometries only (E³, S³, H³)",
            space.description()
        )),
    }
}

/// Surface group elements enumerated at most for a product's or a unit tangent bundle's
/// injectivity radius.
pub const PRODUCT_GROUP_LIMIT: usize = 200_000;

/// A frame at the end of a geodesic from the cell's centre: where an entity or a camera is
/// placed by an offset in the centre's axes, in any family.
pub trait CentreFrame {
    /// The frame reached from the centre's standard frame by the geodesic of `offset` (its
    /// length the distance, in the centre frame's axes: x right, y up, z back; the fibre is
    /// z in the product spaces), every axis carried along it.
    fn frame_from_centre(&self, offset: DVec3) -> DMat4;
}

impl CentreFrame for Space {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        let g = self.geometry();
        crate::geometry::translate_local(g, g.translation_to(self.centre()), offset)
    }
}

impl CentreFrame for ProductSpace {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        let length = offset.length();
        if !(length > 0.0) || !length.is_finite() {
            return DMat4::IDENTITY;
        }
        let u = offset / length;
        super::product::motion::transport(
            self.base(),
            DMat4::IDENTITY,
            DVec4::new(u.x, u.y, u.z, 0.0),
            length,
        )
    }
}

impl CentreFrame for NilSpace {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        NilSpace::frame_from_centre(self, offset)
    }
}

impl CentreFrame for UnitTangentSpace {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        UnitTangentSpace::frame_from_centre(self, offset)
    }
}

impl CentreFrame for AnySpace {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        match self {
            AnySpace::Constant(s) => s.frame_from_centre(offset),
            AnySpace::Product(p) => p.frame_from_centre(offset),
            AnySpace::Nil(n) => n.frame_from_centre(offset),
            AnySpace::Sl2r(s) => s.frame_from_centre(offset),
        }
    }
}

impl<T: CentreFrame> CentreFrame for Arc<T> {
    fn frame_from_centre(&self, offset: DVec3) -> DMat4 {
        (**self).frame_from_centre(offset)
    }
}
