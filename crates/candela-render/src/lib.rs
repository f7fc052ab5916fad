//! The Candela renderer: turns a [`candela_scene::SceneDesc`] into pixels.
#![warn(missing_docs)]

pub mod accel;
pub mod bsdf;
pub mod geometry;
pub mod sampling;
pub mod shape;
