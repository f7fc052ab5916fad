//! The few functions of Open Image Denoise's C API that Candela calls,
//! declared here and looked up in the library at run time.
//!
//! The signatures are those of `OpenImageDenoise/oidn.h`, identical in
//! versions 1.x and 2.x for these functions: a CPU device, the `"RT"`
//! filter, images shared with the caller's memory (no OIDN buffers), bool
//! parameters, and the device's error query. Nothing else of the API is
//! needed, so nothing else is declared.

use libloading::Library;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::{Path, PathBuf};

/// `OIDNDevice`: an opaque handle.
pub(super) type Device = *mut c_void;
/// `OIDNFilter`: an opaque handle.
pub(super) type Filter = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`: the CPU device (always present; no GPU module
/// is probed).
pub(super) const DEVICE_TYPE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3`: three `f32` channels per pixel.
pub(super) const FORMAT_FLOAT3: c_int = 3;
/// `OIDN_ERROR_NONE`.
const ERROR_NONE: c_int = 0;

/// The loaded library and its entry points. The library is never unloaded
/// (see [`super::Oidn`]), so the function pointers stay valid.
pub(super) struct Api {
    pub new_device: unsafe extern "C" fn(c_int) -> Device,
    pub commit_device: unsafe extern "C" fn(Device),
    pub release_device: unsafe extern "C" fn(Device),
    pub get_device_error: unsafe extern "C" fn(Device, *mut *const c_char) -> c_int,
    pub new_filter: unsafe extern "C" fn(Device, *const c_char) -> Filter,
    #[allow(clippy::type_complexity)]
    pub set_shared_filter_image: unsafe extern "C" fn(
        Filter,
        *const c_char,
        *mut c_void,
        c_int,
        usize,
        usize,
        usize,
        usize,
        usize,
    ),
    pub set_filter_bool: unsafe extern "C" fn(Filter, *const c_char, bool),
    pub commit_filter: unsafe extern "C" fn(Filter),
    pub execute_filter: unsafe extern "C" fn(Filter),
    pub release_filter: unsafe extern "C" fn(Filter),
    /// The file the library was loaded from.
    pub path: PathBuf,
    _library: Library,
}

impl Api {
    /// Loads the library at `path` and looks up every entry point; the
    /// error names the library or the missing symbol.
    pub fn load(path: &Path) -> Result<Self, String> {
        // SAFETY: loading runs the library's initialisers; OIDN's are plain
        // C++ static constructors that need nothing from us.
        let library = unsafe { Library::new(path) }.map_err(|e| e.to_string())?;
        macro_rules! symbol {
            ($name:literal) => {
                // SAFETY: the declared type is the C signature of `oidn.h`.
                *unsafe { library.get(concat!($name, "\0").as_bytes()) }
                    .map_err(|e| format!("{}: {e}", path.display()))?
            };
        }
        Ok(Self {
            new_device: symbol!("oidnNewDevice"),
            commit_device: symbol!("oidnCommitDevice"),
            release_device: symbol!("oidnReleaseDevice"),
            get_device_error: symbol!("oidnGetDeviceError"),
            new_filter: symbol!("oidnNewFilter"),
            set_shared_filter_image: symbol!("oidnSetSharedFilterImage"),
            set_filter_bool: symbol!("oidnSetFilterBool"),
            commit_filter: symbol!("oidnCommitFilter"),
            execute_filter: symbol!("oidnExecuteFilter"),
            release_filter: symbol!("oidnReleaseFilter"),
            path: path.to_path_buf(),
            _library: library,
        })
    }

    /// The device's first pending error, if any (reading it clears it).
    ///
    /// # Safety
    /// `device` is a live device of this library.
    pub unsafe fn device_error(&self, device: Device) -> Option<String> {
        let mut message: *const c_char = std::ptr::null();
        let code = (self.get_device_error)(device, &mut message);
        if code == ERROR_NONE {
            return None;
        }
        let text = if message.is_null() {
            String::new()
        } else {
            CStr::from_ptr(message).to_string_lossy().into_owned()
        };
        Some(format!("error {code}: {text}"))
    }
}
