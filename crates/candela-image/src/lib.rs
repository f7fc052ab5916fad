//! Image buffers, PNG and OpenEXR output, tone mapping and error metrics.
#![warn(missing_docs)]
