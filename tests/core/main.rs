//! The library's tests that need no optional feature: geometry, spaces, the walk and its hard
//! cases, the CPU reference renderer, placing objects, stereo and headset maths, and the
//! player's ECS systems. One test binary, so Bevy is linked once.

#[allow(dead_code)]
#[path = "../common/mod.rs"]
mod common;

mod accuracy;
mod cells;
mod culling;
mod edge_answers;
mod elliptic;
mod files;
#[cfg(feature = "scene-files")]
mod flight;
mod frame_rate;
mod geometry;
mod groups;
mod hard_cases;
mod headset;
mod laws;
mod layers;
mod light_images;
mod lighting;
mod mirrors;
mod nil;
mod objects;
mod player;
#[cfg(feature = "scene-files")]
mod product_flight;
mod product_lighting;
mod product_motion;
mod product_player;
#[cfg(feature = "scene-files")]
mod product_scenes;
mod products;
mod render;
mod several_cells;
mod sl2r;
mod soft_shadows;
mod sol;
mod spaces;
mod stereo;
mod straddling;
mod trace;
mod walls;
