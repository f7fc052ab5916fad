//! The Candela renderer: turns a [`candela_scene::SceneDesc`] into pixels.
//!
//! Data flows one way: `scene::Scene::build` (geometry, BVH, materials,
//! lights, camera) → `render::render` (threads, tiles) → integrator per
//! (pixel, sample) → `film` sums.
#![warn(missing_docs)]

pub mod accel;
pub mod bsdf;
pub mod camera;
pub mod checkpoint;
pub mod film;
pub mod geometry;
pub mod integrator;
pub mod light;
pub mod material;
pub mod medium;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod settings;
pub mod shading;
pub mod shape;
pub mod stats;
pub mod texture;
