//! Image buffers, PNG and OpenEXR output, tone mapping and error metrics.
//!
//! The renderer resolves its film into an [`RgbImage`] of linear radiance;
//! this crate turns it into files ([`write_png`] through a [`ToneMap`],
//! [`write_exr`] with denoiser layers), reads textures back ([`read_png`],
//! [`read_exr`], and JPEG, TGA, BMP, WebP and Radiance HDR through [`read_stored`]
//! and [`read_radiance_hdr`]), measures error ([`metrics`]) and denoises with Intel Open
//! Image Denoise when it is installed ([`denoise`]). Every file is written
//! through [`atomic_write`], so an output path never holds a partial file.
#![warn(missing_docs)]

mod atomic;
mod buffer;
mod colormap;
pub mod denoise;
mod error;
mod exr_io;
mod heat;
mod merge;
pub mod metrics;
mod png_io;
mod raster_io;
pub mod render_info;
mod tonemap;
pub mod variance;

pub use atomic::{atomic_write, check_writable};
pub use buffer::{GrayImage, RgbImage};
pub use colormap::{rate_colormap, rate_image};
pub use error::{BoxError, ImageError};
pub use exr_io::{
    read_exr, read_exr_layers, write_exr, write_exr_compressed, ExrCompression, ExrLayers,
    LayerData, VARIANCE_LAYER,
};
pub use heat::{finite_percentile, heat_colormap, heat_image};
pub use merge::merge_renders;
pub use png_io::{read_png, read_png_stored, write_png, write_png_display, StoredImage};
pub use raster_io::{read_pfm, read_radiance_hdr, read_stored, STORED_EXTENSIONS};
pub use render_info::{RenderInfo, SppSpread};
pub use tonemap::{quantize_u8, srgb_decode, srgb_encode, ToneCurve, ToneMap};
