//! Render settings a scene suggests: Mitsuba files carry a sample count,
//! a depth and a film size; the built-in demo its camera and sample count.
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
}
