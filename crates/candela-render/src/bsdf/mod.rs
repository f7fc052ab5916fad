//! BSDFs in a local shading frame.
