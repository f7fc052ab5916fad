//! Geometric building blocks shared by every stage: rays and local frames.

mod frame;
mod ray;

pub use frame::Frame;
pub use ray::Ray;
