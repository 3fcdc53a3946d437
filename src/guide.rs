#![doc = include_str!("../docs/guide/README.md")]

#[doc = include_str!("../docs/guide/command-line.md")]
pub mod command_line {}

#[doc = include_str!("../docs/guide/spaces.md")]
pub mod spaces {}

#[doc = include_str!("../docs/guide/products.md")]
pub mod products {}

#[doc = include_str!("../docs/guide/light.md")]
pub mod light {}

#[doc = include_str!("../docs/guide/scenes.md")]
pub mod scenes {}

#[doc = include_str!("../docs/guide/plugin.md")]
pub mod plugin {}

#[doc = include_str!("../docs/guide/stereo-and-vr.md")]
pub mod stereo_and_vr {}

#[doc = include_str!("../docs/guide/accuracy-and-speed.md")]
pub mod accuracy_and_speed {}

#[doc = include_str!("../docs/guide/layout.md")]
pub mod layout {}
