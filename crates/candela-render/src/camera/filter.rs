//! Pixel reconstruction filters: which film points a pixel's samples come
//! from, and with what weight.
//!
//! A pixel's value is `I_p = ∫ f_n(x − c_p) L(x) dx`, the radiance on the
//! film weighted by the filter `f_n` (normalised to integral 1) centred on
//! the pixel's centre `c_p`. Every filter here is separable,
//! `f(dx, dy) = f₁(dx) f₁(dy)`, and is one of the usual ones
//! ([`PixelFilter`]): box (the default; radius 0.5 is CS184's "one
//! uniform point per pixel"), tent, Gaussian (Mitsuba 3's default, σ 0.5,
//! radius 4σ; pbrt-v4's is σ 0.5, radius 1.5), Mitchell-Netravali,
//! Catmull-Rom, Lanczos and Blackman-Harris (Blender's, width 1.5).
//!
//! # Filter importance sampling
//! Camera samples are not spread uniformly over the pixel and weighted by
//! the filter (which would need a weighted mean per pixel); they are
//! *drawn from* the filter (pbrt-v4's `FilterSampler`): per axis, an
//! offset from the pixel centre from the tabulated `|f₁|` by inverting its
//! CDF ([`FilmFilter`], `filter_table.rs`), and the sample carries the
//! weight `f/p`, the same for every sample of a non-negative filter (1)
//! and `±∫|f₁|/∫f₁` per axis for the filters with negative lobes. The film
//! keeps summing per-sample values and dividing by the sample count, so
//! `E[w L] = ∫ f_n(x − c_p) L(x) dx`: unbiased, and merging, adaptive
//! sampling, checkpoints and determinism are untouched. The tabulated
//! function (32 cells per pixel, the value at each cell's centre) *is* the
//! filter: sampling and the splats' weights read the same table, so the
//! camera's and the lights' estimators agree exactly.
//!
//! The box of radius 0.5 keeps the old code path: the film point is the
//! pixel corner plus the sampler's 2-D number, bit for bit as before.
//!
//! # The image border
//! A pixel at the edge of the frame takes its samples from the whole
//! filter, so camera rays may leave through film points up to
//! `radius − 0.5` pixels outside the frame, and the camera's importance
//! (light tracing, BDPT) extends over the same margin
//! ([`FilmFilter::margin`]): every pixel, the edge ones included, is the
//! full filter's weighted mean of the radiance around it. Mitsuba instead
//! (`sample_border` false by default) samples only inside the frame and
//! divides by the weights that landed, i.e. a truncated, renormalised
//! filter at the edge; the two differ only in the outermost `radius − 0.5`
//! pixels.
//!
//! # AOVs
//! The albedo, normal and depth layers come from the same camera rays, so
//! they are averaged over the same filtered film points; they are not
//! multiplied by the weight (a sign would make no sense for a normal or a
//! distance), i.e. they are filtered by `|f|` normalised, which is the
//! filter itself for the non-negative ones.

use serde::{Deserialize, Serialize};
use std::f32::consts::PI;
use std::fmt;
use std::str::FromStr;

/// Largest filter radius accepted, in pixels: a splat goes to every pixel
/// within the radius, `(2r)²` of them.
pub const MAX_FILTER_RADIUS: f32 = 8.0;

/// What `--filter` / `filter` means (the settings' help).
pub const FILTER_HELP: &str = "box (radius 0.5: one uniform point per pixel), \
    tent:radius=1, gaussian:stddev=0.5,radius=2 (radius 4 stddev unless given), \
    mitchell:b=0.333,c=0.333 (radius 2), catmull-rom (radius 2), lanczos:lobes=3, \
    blackman-harris:width=1.5; parameters may be left out";

/// A pixel reconstruction filter and its parameters, as the settings name
/// it: `name[:key=value,...]` (see [`FILTER_HELP`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum PixelFilter {
    /// Constant over `|x| < radius`.
    Box {
        /// Half width in pixels (0.5: the pixel itself).
        radius: f32,
    },
    /// `max(0, 1 − |x|/radius)`.
    Tent {
        /// Half width in pixels.
        radius: f32,
    },
    /// Mitsuba 3's truncated Gaussian, `max(0, exp(−x²/2σ²) − exp(−r²/2σ²))`.
    Gaussian {
        /// Standard deviation σ in pixels.
        stddev: f32,
        /// Half width r in pixels.
        radius: f32,
    },
    /// Mitchell-Netravali's cubic with parameters B, C, radius 2.
    Mitchell {
        /// Blur parameter B.
        b: f32,
        /// Ringing parameter C.
        c: f32,
    },
    /// The Catmull-Rom spline: Mitchell-Netravali with B = 0, C = 0.5.
    CatmullRom,
    /// `sinc(x) sinc(x/lobes)` over `|x| < lobes`.
    Lanczos {
        /// Lobes of the sinc kept, = the radius in pixels.
        lobes: u32,
    },
    /// The four-term Blackman-Harris window over a full width (Blender's
    /// pixel filter).
    BlackmanHarris {
        /// Full width in pixels (the radius is half of it).
        width: f32,
    },
}

impl Default for PixelFilter {
    fn default() -> Self {
        PixelFilter::Box { radius: 0.5 }
    }
}

impl PixelFilter {
    /// Mitsuba 3's default: a Gaussian of σ = 0.5, radius 4σ.
    pub const MITSUBA_DEFAULT: PixelFilter = PixelFilter::Gaussian {
        stddev: 0.5,
        radius: 2.0,
    };

    /// The filter's name in the settings.
    pub fn name(&self) -> &'static str {
        match self {
            PixelFilter::Box { .. } => "box",
            PixelFilter::Tent { .. } => "tent",
            PixelFilter::Gaussian { .. } => "gaussian",
            PixelFilter::Mitchell { .. } => "mitchell",
            PixelFilter::CatmullRom => "catmull-rom",
            PixelFilter::Lanczos { .. } => "lanczos",
            PixelFilter::BlackmanHarris { .. } => "blackman-harris",
        }
    }

    /// The half width of the support, in pixels.
    pub fn radius(&self) -> f32 {
        match *self {
            PixelFilter::Box { radius }
            | PixelFilter::Tent { radius }
            | PixelFilter::Gaussian { radius, .. } => radius,
            PixelFilter::Mitchell { .. } | PixelFilter::CatmullRom => 2.0,
            PixelFilter::Lanczos { lobes } => lobes as f32,
            PixelFilter::BlackmanHarris { width } => 0.5 * width,
        }
    }

    /// Whether this is the one-pixel box: a uniform point in the pixel,
    /// the renderer's exact old path.
    pub fn is_pixel_box(&self) -> bool {
        *self == PixelFilter::Box { radius: 0.5 }
    }

    /// The 1-D filter `f₁(x)` (unnormalised; 0 outside the radius).
    pub fn eval_1d(&self, x: f32) -> f32 {
        let r = self.radius();
        let ax = x.abs();
        if ax >= r {
            return 0.0;
        }
        match *self {
            PixelFilter::Box { .. } => 1.0,
            PixelFilter::Tent { radius } => 1.0 - ax / radius,
            PixelFilter::Gaussian { stddev, radius } => {
                let g = |t: f32| (-t * t / (2.0 * stddev * stddev)).exp();
                (g(ax) - g(radius)).max(0.0)
            }
            PixelFilter::Mitchell { b, c } => mitchell(ax, b, c),
            PixelFilter::CatmullRom => mitchell(ax, 0.0, 0.5),
            PixelFilter::Lanczos { lobes } => sinc(ax) * sinc(ax / lobes as f32),
            PixelFilter::BlackmanHarris { width } => {
                let t = 2.0 * PI * (x / width + 0.5);
                0.35875 - 0.48829 * t.cos() + 0.14128 * (2.0 * t).cos() - 0.01168 * (3.0 * t).cos()
            }
        }
    }

    /// The parameters as `(key, value)`, in the order they are written.
    fn params(&self) -> Vec<(&'static str, f32)> {
        match *self {
            PixelFilter::Box { radius } | PixelFilter::Tent { radius } => vec![("radius", radius)],
            PixelFilter::Gaussian { stddev, radius } => {
                vec![("stddev", stddev), ("radius", radius)]
            }
            PixelFilter::Mitchell { b, c } => vec![("b", b), ("c", c)],
            PixelFilter::CatmullRom => vec![],
            PixelFilter::Lanczos { lobes } => vec![("lobes", lobes as f32)],
            PixelFilter::BlackmanHarris { width } => vec![("width", width)],
        }
    }

    /// Checks the parameters: a finite radius in (0, [`MAX_FILTER_RADIUS`]]
    /// and each filter's own conditions.
    pub fn validate(&self) -> Result<(), String> {
        let bad = |what: &str| Err(format!("filter {self}: {what}"));
        let r = self.radius();
        if !(r.is_finite() && r > 0.0 && r <= MAX_FILTER_RADIUS) {
            return bad(&format!(
                "the radius must be in (0, {MAX_FILTER_RADIUS}] pixels"
            ));
        }
        match *self {
            PixelFilter::Gaussian { stddev, .. } if !(stddev.is_finite() && stddev > 0.0) => {
                bad("stddev must be > 0")
            }
            PixelFilter::Mitchell { b, c } if !(b.is_finite() && c.is_finite()) => {
                bad("b and c must be finite")
            }
            _ => Ok(()),
        }
    }
}

/// Mitchell and Netravali's cubic at `x = |offset|` in [0, 2).
fn mitchell(x: f32, b: f32, c: f32) -> f32 {
    let (x2, x3) = (x * x, x * x * x);
    let v = if x < 1.0 {
        (12.0 - 9.0 * b - 6.0 * c) * x3 + (-18.0 + 12.0 * b + 6.0 * c) * x2 + (6.0 - 2.0 * b)
    } else {
        (-b - 6.0 * c) * x3
            + (6.0 * b + 30.0 * c) * x2
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c)
    };
    v / 6.0
}

/// `sin(πx)/(πx)`, 1 at 0.
fn sinc(x: f32) -> f32 {
    let px = PI * x;
    if px.abs() < 1e-5 {
        1.0
    } else {
        px.sin() / px
    }
}

impl fmt::Display for PixelFilter {
    /// The canonical spelling, every parameter written: `gaussian:stddev=0.5,radius=2`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.name())?;
        for (i, (key, value)) in self.params().into_iter().enumerate() {
            write!(f, "{}{key}={value}", if i == 0 { ':' } else { ',' })?;
        }
        Ok(())
    }
}

impl FromStr for PixelFilter {
    type Err = String;

    /// Parses `name[:key=value,...]`; left-out parameters take their
    /// defaults (a Gaussian's radius is 4σ unless given).
    fn from_str(text: &str) -> Result<Self, String> {
        let (name, rest) = text.trim().split_once(':').unwrap_or((text.trim(), ""));
        let name = name.trim().to_ascii_lowercase();
        let mut filter = match name.as_str() {
            "box" => PixelFilter::Box { radius: 0.5 },
            "tent" | "triangle" => PixelFilter::Tent { radius: 1.0 },
            "gaussian" => PixelFilter::MITSUBA_DEFAULT,
            "mitchell" => PixelFilter::Mitchell {
                b: 1.0 / 3.0,
                c: 1.0 / 3.0,
            },
            "catmull-rom" | "catmullrom" => PixelFilter::CatmullRom,
            "lanczos" => PixelFilter::Lanczos { lobes: 3 },
            "blackman-harris" => PixelFilter::BlackmanHarris { width: 1.5 },
            _ => {
                return Err(format!(
                    "unknown filter \"{text}\" (expected box, tent, gaussian, mitchell, \
                     catmull-rom, lanczos or blackman-harris)"
                ))
            }
        };
        let mut radius_given = false;
        for part in rest.split(',').filter(|p| !p.trim().is_empty()) {
            let (key, value) = part
                .split_once('=')
                .ok_or_else(|| format!("filter \"{text}\": \"{part}\" is not key=value"))?;
            let key = key.trim().to_ascii_lowercase();
            let v: f32 = value.trim().parse().map_err(|_| {
                format!(
                    "filter \"{text}\": {key} \"{}\" is not a number",
                    value.trim()
                )
            })?;
            let slot = match (&mut filter, key.as_str()) {
                (PixelFilter::Box { radius }, "radius")
                | (PixelFilter::Tent { radius }, "radius")
                | (PixelFilter::Gaussian { radius, .. }, "radius") => {
                    radius_given = true;
                    radius
                }
                (PixelFilter::Gaussian { stddev, .. }, "stddev") => stddev,
                (PixelFilter::Mitchell { b, .. }, "b") => b,
                (PixelFilter::Mitchell { c, .. }, "c") => c,
                (PixelFilter::BlackmanHarris { width }, "width") => width,
                (PixelFilter::Lanczos { lobes }, "lobes") => {
                    if !(v >= 1.0 && v.fract() == 0.0 && v <= MAX_FILTER_RADIUS) {
                        return Err(format!(
                            "filter \"{text}\": lobes {v} must be a whole number in 1..={MAX_FILTER_RADIUS}"
                        ));
                    }
                    *lobes = v as u32;
                    continue;
                }
                (f, _) => {
                    let keys: Vec<&str> = f.params().iter().map(|(k, _)| *k).collect();
                    return Err(format!(
                        "filter \"{text}\": unknown parameter \"{key}\" (expected {})",
                        if keys.is_empty() {
                            "none".to_string()
                        } else {
                            keys.join(", ")
                        }
                    ));
                }
            };
            *slot = v;
        }
        if let PixelFilter::Gaussian { stddev, radius } = &mut filter {
            if !radius_given {
                *radius = 4.0 * *stddev;
            }
        }
        filter.validate()?;
        Ok(filter)
    }
}

impl TryFrom<String> for PixelFilter {
    type Error = String;
    fn try_from(text: String) -> Result<Self, String> {
        text.parse()
    }
}

impl From<PixelFilter> for String {
    fn from(f: PixelFilter) -> String {
        f.to_string()
    }
}
