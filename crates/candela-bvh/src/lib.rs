//! A geometry-agnostic bounding volume hierarchy.
#![warn(missing_docs)]
