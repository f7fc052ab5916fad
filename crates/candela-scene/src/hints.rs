//! Render settings a scene suggests: Mitsuba files carry a sample count,
//! a depth, a film size and a reconstruction filter; the built-in demo its
//! camera and sample count.
//! They sit below every setting the user gives explicitly (a flag, a
//! keyword) and above the renderer's defaults.

/// Settings a scene suggests; `None` (or `false`) leaves the renderer's
/// default.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RenderHints {
    /// Samples per pixel.
    pub spp: Option<u32>,
    /// Maximum bounces.
    pub max_depth: Option<u32>,
    /// Image width and height in pixels.
    pub resolution: Option<(u32, u32)>,
    /// Render from the file's camera rather than the CS184 framing.
    pub file_camera: bool,
    /// Largest radiance a camera sample may carry (a firefly clamp).
    pub clamp: Option<f32>,
    /// The pixel reconstruction filter (Mitsuba's `<rfilter>`, Gaussian by
    /// default there).
    pub filter: Option<FilterHint>,
    /// Leave out emitters seen directly by the camera (Mitsuba's
    /// `hide_emitters`).
    pub hide_emitters: bool,
}

/// A pixel reconstruction filter as a scene describes it (Mitsuba 3's
/// plugins and parameters; radii in pixels).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterHint {
    /// The one-pixel box (radius 0.5).
    Box,
    /// A tent of this radius.
    Tent {
        /// Half width.
        radius: f32,
    },
    /// Mitsuba's truncated Gaussian, radius 4σ.
    Gaussian {
        /// Standard deviation σ.
        stddev: f32,
    },
    /// Mitchell-Netravali (radius 2).
    Mitchell {
        /// B.
        b: f32,
        /// C.
        c: f32,
    },
    /// Catmull-Rom (radius 2).
    CatmullRom,
    /// Lanczos' windowed sinc.
    Lanczos {
        /// Lobes (= radius).
        lobes: u32,
    },
}

impl FilterHint {
    /// Mitsuba 3's film default: a Gaussian of σ = 0.5.
    pub const MITSUBA_DEFAULT: FilterHint = FilterHint::Gaussian { stddev: 0.5 };
}
