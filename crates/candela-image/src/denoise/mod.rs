//! Denoising with Intel Open Image Denoise (OIDN), loaded at run time.
//!
//! OIDN's `RT` filter (a U-Net trained on path-traced images) turns a noisy
//! render plus its first-hit albedo and normal into a clean estimate. It is
//! not part of the build: the shared library is found when first asked for
//! ([`Oidn::load`]; where it looks: [`LIB_ENV`] and the `locate` module) and
//! kept loaded for the rest of the process. A machine without it renders
//! as before; only denoising reports, in one line, what is missing and how
//! to get it (`pip install pyoidn`, whose wheel ships the library).
//!
//! The guides are prefiltered as OIDN's documentation recommends for noisy
//! auxiliary images (Candela's albedo and normal come from the same samples
//! as the beauty, so depth of field or glossy first hits make them noisy):
//! the albedo and the normal are each denoised on their own first, then the
//! beauty is filtered with `cleanAux` set, so the network trusts the guides
//! and does not carry their noise over. The beauty is HDR (`hdr`): linear
//! radiance, any non-negative value.

mod ffi;
mod locate;

pub use locate::{pyoidn_lib_folder, LIB_ENV};

use crate::RgbImage;
use ffi::{Api, Device, Filter};
use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Why an image could not be denoised.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DenoiseError {
    /// The library could not be found or loaded; the message says what is
    /// missing and how to get it.
    #[error("{0}")]
    Unavailable(String),
    /// OIDN reported an error (unsupported CPU, out of memory, ...).
    #[error("Open Image Denoise ({library}): {message}")]
    Oidn {
        /// The library file in use.
        library: PathBuf,
        /// OIDN's error code and message.
        message: String,
    },
    /// A guide image's size differs from the beauty's.
    #[error("cannot denoise: the {what} image is {got:?}, the beauty {want:?}")]
    SizeMismatch {
        /// Which guide.
        what: &'static str,
        /// Its width and height.
        got: (usize, usize),
        /// The beauty's width and height.
        want: (usize, usize),
    },
}

/// The feature images that guide the filter: the first-hit albedo (in
/// [0, 1]) and shading normal (in [-1, 1], any fixed space), per pixel.
#[derive(Clone, Copy, Debug)]
pub struct Guides<'a> {
    /// Mean first-hit albedo.
    pub albedo: &'a RgbImage,
    /// Mean first-hit shading normal (not renormalised).
    pub normal: &'a RgbImage,
}

/// Open Image Denoise, loaded. Obtained from [`Oidn::load`]; lives for the
/// rest of the process (unloading a library that started TBB's threads is
/// not safe).
pub struct Oidn {
    api: Api,
}

/// The library once loaded, shared by every caller of the process.
static LOADED: Mutex<Option<&'static Oidn>> = Mutex::new(None);

impl Oidn {
    /// The library, loaded on first use from where [`LIB_ENV`] names, else
    /// the Python `pyoidn` package, else the system.
    pub fn load() -> Result<&'static Oidn, DenoiseError> {
        Self::load_with(&[])
    }

    /// As [`Oidn::load`], trying the library folders `hint_dirs` before the
    /// Python on the path and the system (unless [`LIB_ENV`] is set).
    pub fn load_with(hint_dirs: &[PathBuf]) -> Result<&'static Oidn, DenoiseError> {
        let mut loaded = LOADED.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(oidn) = *loaded {
            return Ok(oidn);
        }
        let oidn: &'static Oidn = Box::leak(Box::new(load_from(locate::search(hint_dirs))?));
        *loaded = Some(oidn);
        Ok(oidn)
    }

    /// The file the library was loaded from.
    pub fn library_path(&self) -> &Path {
        &self.api.path
    }

    /// The denoised `color`, guided by `guides` when given (prefiltered:
    /// see the module documentation). Non-finite values are read as 0,
    /// negative radiance as 0 and albedo is clamped to [0, 1], the ranges
    /// OIDN is defined on.
    pub fn denoise(
        &self,
        color: &RgbImage,
        guides: Option<Guides<'_>>,
    ) -> Result<RgbImage, DenoiseError> {
        let size = (color.width(), color.height());
        if size.0 == 0 || size.1 == 0 {
            return Ok(color.clone());
        }
        let mut beauty = sanitized(color, |v| v.max(0.0));
        let mut output = vec![[0.0f32; 3]; beauty.len()];
        let device = DeviceHandle::new(&self.api)?;
        let mut guide_images = match guides {
            Some(g) => {
                check_size("albedo", g.albedo, size)?;
                check_size("normal", g.normal, size)?;
                let mut albedo = sanitized(g.albedo, |v| v.clamp(0.0, 1.0));
                let mut normal = sanitized(g.normal, |v| v.clamp(-1.0, 1.0));
                device.prefilter(size, "albedo", &mut albedo)?;
                device.prefilter(size, "normal", &mut normal)?;
                Some((albedo, normal))
            }
            None => None,
        };
        let mut inputs: Vec<(&str, &mut Vec<[f32; 3]>)> = vec![("color", &mut beauty)];
        let clean_aux = guide_images.is_some();
        if let Some((albedo, normal)) = guide_images.as_mut() {
            inputs.push(("albedo", albedo));
            inputs.push(("normal", normal));
        }
        device.run_into(
            size,
            &mut inputs,
            &mut output,
            &[("hdr", true), ("cleanAux", clean_aux)],
        )?;
        Ok(RgbImage::from_pixels(size.0, size.1, output).expect("the output has the input's size"))
    }
}

/// Loads the first candidate that loads.
fn load_from(search: locate::Search) -> Result<Oidn, DenoiseError> {
    match search {
        locate::Search::Explicit(value, files) => {
            let shown = Path::new(&value).display().to_string();
            let Some(first) = files.first() else {
                return Err(DenoiseError::Unavailable(format!(
                    "{LIB_ENV}={shown}: no Open Image Denoise library there ({})",
                    locate::FILE_NAMES.join(", ")
                )));
            };
            Api::load(first).map(|api| Oidn { api }).map_err(|e| {
                DenoiseError::Unavailable(format!(
                    "{LIB_ENV}={shown}: cannot load Open Image Denoise: {e}"
                ))
            })
        }
        locate::Search::Candidates(files) => {
            if let Some(api) = files.iter().find_map(|file| Api::load(file).ok()) {
                return Ok(Oidn { api });
            }
            Err(DenoiseError::Unavailable(format!(
                "Intel Open Image Denoise ({}) was not found: `pip install pyoidn` \
                 (its wheel ships the library), or set {LIB_ENV} to the library's path",
                locate::FILE_NAMES[0]
            )))
        }
    }
}

fn check_size(
    what: &'static str,
    image: &RgbImage,
    want: (usize, usize),
) -> Result<(), DenoiseError> {
    let got = (image.width(), image.height());
    if got == want {
        Ok(())
    } else {
        Err(DenoiseError::SizeMismatch { what, got, want })
    }
}

/// The pixels with every channel through `f`, non-finite values as 0.
fn sanitized(image: &RgbImage, f: impl Fn(f32) -> f32) -> Vec<[f32; 3]> {
    let clean = |v: f32| if v.is_finite() { f(v) } else { 0.0 };
    image.pixels().iter().map(|p| p.map(clean)).collect()
}

/// A CPU device, released when dropped.
struct DeviceHandle<'a> {
    api: &'a Api,
    device: Device,
}

impl<'a> DeviceHandle<'a> {
    fn new(api: &'a Api) -> Result<Self, DenoiseError> {
        // SAFETY: plain C calls on a handle we own; a null device is
        // checked before use and errors are read from the thread's slot.
        unsafe {
            let device = (api.new_device)(ffi::DEVICE_TYPE_CPU);
            if device.is_null() {
                let message = api
                    .device_error(std::ptr::null_mut())
                    .unwrap_or_else(|| "cannot create a CPU device".into());
                return Err(oidn_error(api, message));
            }
            let handle = Self { api, device };
            (api.commit_device)(device);
            handle.check()?;
            Ok(handle)
        }
    }

    fn check(&self) -> Result<(), DenoiseError> {
        // SAFETY: the device is live until `self` drops.
        match unsafe { self.api.device_error(self.device) } {
            None => Ok(()),
            Some(message) => Err(oidn_error(self.api, message)),
        }
    }

    /// Prefilters one guide in place: the `RT` filter with only that image
    /// (by its OIDN name) as input, written back over it.
    fn prefilter(
        &self,
        size: (usize, usize),
        name: &str,
        image: &mut [[f32; 3]],
    ) -> Result<(), DenoiseError> {
        let mut input = image.to_vec();
        self.run_into(size, &mut [(name, &mut input)], image, &[])
    }

    /// One `RT` filter: `inputs` by OIDN's image names, `flags` as bool
    /// parameters, the result into `output`.
    fn run_into(
        &self,
        (width, height): (usize, usize),
        inputs: &mut [(&str, &mut Vec<[f32; 3]>)],
        output: &mut [[f32; 3]],
        flags: &[(&str, bool)],
    ) -> Result<(), DenoiseError> {
        let api = self.api;
        let set_image = |filter: Filter, name: &str, data: *mut [f32; 3]| {
            let name = CString::new(name).expect("image names have no NUL");
            // SAFETY: `data` holds width × height packed FLOAT3 pixels and
            // outlives the filter's execution below.
            unsafe {
                (api.set_shared_filter_image)(
                    filter,
                    name.as_ptr(),
                    data.cast(),
                    ffi::FORMAT_FLOAT3,
                    width,
                    height,
                    0,
                    0,
                    0,
                )
            }
        };
        // SAFETY: the filter belongs to this live device; it is released
        // before returning, and every image it reads outlives it.
        unsafe {
            let filter = (api.new_filter)(self.device, c"RT".as_ptr());
            if filter.is_null() {
                self.check()?;
                return Err(oidn_error(api, "cannot create the RT filter".into()));
            }
            let filter = FilterHandle { api, filter };
            for (name, image) in inputs.iter_mut() {
                set_image(filter.filter, name, image.as_mut_ptr());
            }
            set_image(filter.filter, "output", output.as_mut_ptr());
            for (name, value) in flags {
                let name = CString::new(*name).expect("flag names have no NUL");
                (api.set_filter_bool)(filter.filter, name.as_ptr(), *value);
            }
            (api.commit_filter)(filter.filter);
            self.check()?;
            (api.execute_filter)(filter.filter);
            self.check()
        }
    }
}

impl Drop for DeviceHandle<'_> {
    fn drop(&mut self) {
        // SAFETY: released once, after every filter of it.
        unsafe { (self.api.release_device)(self.device) }
    }
}

/// A filter, released when dropped.
struct FilterHandle<'a> {
    api: &'a Api,
    filter: Filter,
}

impl Drop for FilterHandle<'_> {
    fn drop(&mut self) {
        // SAFETY: released once.
        unsafe { (self.api.release_filter)(self.filter) }
    }
}

fn oidn_error(api: &Api, message: String) -> DenoiseError {
    DenoiseError::Oidn {
        library: api.path.clone(),
        message,
    }
}

#[cfg(test)]
mod tests;
