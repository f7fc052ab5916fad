//! Scene descriptions for the Candela path tracer, and the loaders that make them.
//!
//! Loading happens in stages (parse, describe, validate); every error carries
//! the file, `line:col` and the element, and everything a loader ignores is
//! named once in a [`Report`].
#![warn(missing_docs)]

pub mod desc;

pub use desc::*;
