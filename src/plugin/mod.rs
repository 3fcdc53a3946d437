//! The Bevy layer: everything that needs Bevy at compile time, over the maths core.
//!
//! [`CurvedSpacesPlugin`] (in [`setup`]) registers the rest:
//!
//! - [`components`]: the components on curved-space cameras and the resources that configure
//!   and report on the tracer, shared by the modules below;
//! - [`family`]: the systems written once over the geometry contract, added per family;
//! - [`player`]: input, motion and the wrap of each camera's frame through the faces;
//! - [`objects`]: a game's things as entities, moving along geodesics through the faces;
//! - [`product`]: the product spaces' (H²×R, S²×R) scene upload, while one is shown;
//! - [`flight`]: replaying and recording camera flights;
//! - [`render`]: the scene packed for the WGSL tracer and the render node that draws it;
//! - [`frame_rate`]: the traced resolution (and the crossing budget) following frame times;
//! - [`offscreen`]: one picture through the real plugin without a window;
//! - [`screenshot`]: saving a captured frame;
//! - `ui` (feature `ui`): the egui panel;
//! - `xr` (feature `xr`): OpenXR headsets.
//!
//! Dependencies run one way: `components` is read by all, `setup` and `family` name the systems of
//! the others and order them, and `offscreen` builds the plugin.

pub mod components;
pub mod family;
#[cfg(feature = "scene-files")]
pub mod flight;
pub mod frame_rate;
pub mod nil;
pub mod objects;
pub mod offscreen;
pub mod player;
pub mod product;
pub mod render;
pub mod screenshot;
pub mod setup;
pub mod sl2r;
#[cfg(feature = "ui")]
pub mod ui;
#[cfg(feature = "xr")]
pub mod xr;

pub use setup::CurvedSpacesPlugin;
