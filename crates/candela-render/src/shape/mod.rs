//! Ray–shape intersection: triangles and spheres.

pub mod triangle;
