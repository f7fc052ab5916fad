//! The picture: its size, the cell to render, the camera and the light
//! added around the scene.

use super::{check, SettingsError};
use crate::camera::framing::CameraMode;
use crate::camera::{Camera, CameraView, PixelFilter};
use crate::film::PixelRect;
use crate::light::{EnvironmentLookup, EnvironmentMap, EnvironmentOptions, ProceduralSky};
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::sync::Arc;

/// `env_map = "sky"` names the built-in procedural sky (unless a file of
/// that name exists).
pub const BUILT_IN_SKY: &str = "sky";

/// What `cell` means (the CLI's `-p`, Python's `cell=`).
pub const CELL_HELP: &str = "Render only the cell of DX × DY pixels at (X, Y) (y = 0 at the top) \
    into the full-size image; the rest stays black (CS184 -p; in JSON [x, y, w, h]).";

/// The image settings.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[serde(default)]
pub struct ImageSettings {
    /// Image width in pixels (also `-r W H`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "W", default_value_t = ImageSettings::default().width))]
    pub width: u32,

    /// Image height in pixels.
    #[cfg_attr(feature = "cli", arg(long, value_name = "H", default_value_t = ImageSettings::default().height))]
    pub height: u32,

    /// The cell to render, or the whole frame: see [`CELL_HELP`].
    #[cfg_attr(feature = "cli", arg(skip))]
    pub cell: Option<PixelRect>,

    /// Where the camera comes from: `cs184` (the CS184 orbit framing of the
    /// scene's bounds), `file` (the file's own camera, its first if it has
    /// several), or `N` (the file's camera number N, from 0, in file order:
    /// glTF camera nodes, Mitsuba sensors).
    #[cfg_attr(feature = "cli", arg(long, value_name = "cs184|file|N", default_value_t = ImageSettings::default().camera))]
    pub camera: CameraMode,

    /// Thin-lens aperture radius in scene units (depth of field; 0 is a
    /// pinhole).
    #[cfg_attr(feature = "cli", arg(short = 'b', long, value_name = "RADIUS", default_value_t = ImageSettings::default().aperture))]
    pub aperture: f32,

    /// Distance from the lens to the plane in focus (default: the framing's
    /// distance to the scene centre).
    #[cfg_attr(feature = "cli", arg(short = 'd', long, value_name = "DIST"))]
    pub focal_distance: Option<f32>,

    /// Environment map: an equirectangular image (.exr, .hdr, .pfm, or an
    /// 8-bit .png, .jpg, .tga, .bmp, .webp read as sRGB), +Y up, lighting the scene
    /// from infinitely far away; `sky` is a built-in procedural sky with a
    /// sun.
    #[cfg_attr(feature = "cli", arg(short = 'e', long = "env", value_name = "MAP"))]
    pub env_map: Option<PathBuf>,

    /// Multiplies the environment map's radiance.
    #[cfg_attr(feature = "cli", arg(long, value_name = "S", default_value_t = ImageSettings::default().env_scale))]
    pub env_scale: f32,

    /// Turns the environment map about the vertical axis, in degrees.
    #[cfg_attr(feature = "cli", arg(long, value_name = "DEG", default_value_t = ImageSettings::default().env_rotate, allow_negative_numbers = true))]
    pub env_rotate: f32,

    /// Camera position X,Y,Z, replacing the framing's (with `look_at`; the
    /// viewer's "copy command line" writes these four).
    #[cfg_attr(feature = "cli", arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_negative_numbers = true, requires = "look_at"))]
    pub eye: Option<[f32; 3]>,

    /// The point the camera looks at, X,Y,Z (with `eye`).
    #[cfg_attr(feature = "cli", arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_negative_numbers = true, requires = "eye"))]
    pub look_at: Option<[f32; 3]>,

    /// The camera's up direction X,Y,Z with `eye` and `look_at` [default: 0,1,0].
    #[cfg_attr(feature = "cli", arg(long, value_name = "X,Y,Z", value_parser = parse_point, allow_negative_numbers = true))]
    pub up: Option<[f32; 3]>,

    /// Vertical field of view in degrees with `eye` and `look_at` (default:
    /// the framing's).
    #[cfg_attr(feature = "cli", arg(long, value_name = "DEG"))]
    pub fov: Option<f32>,

    /// Pixel reconstruction filter, NAME[:KEY=VALUE,...]: box (the
    /// default, one uniform point per pixel), tent:radius=1,
    /// gaussian:stddev=0.5 (radius 4 stddev unless given; Mitsuba's
    /// default), mitchell:b=0.333,c=0.333, catmull-rom, lanczos:lobes=3,
    /// blackman-harris:width=1.5. Samples are drawn from the filter
    /// (weighted by its sign where it is negative) and splats of light
    /// tracing and BDPT spread over its support; AOVs use the same points.
    #[cfg_attr(feature = "cli", arg(long, value_name = "FILTER", default_value_t = ImageSettings::default().filter))]
    pub filter: PixelFilter,
}

/// `X,Y,Z` of `--eye`, `--look-at` and `--up`.
#[cfg(feature = "cli")]
fn parse_point(text: &str) -> Result<[f32; 3], String> {
    let parts: Vec<&str> = text.split(',').collect();
    let numbers: Result<Vec<f32>, _> = parts.iter().map(|p| p.trim().parse::<f32>()).collect();
    match numbers.as_deref() {
        Ok(&[x, y, z]) => Ok([x, y, z]),
        _ => Err(format!("expected three numbers X,Y,Z, got \"{text}\"")),
    }
}

impl Default for ImageSettings {
    fn default() -> Self {
        Self {
            width: 800,
            height: 600,
            cell: None,
            camera: CameraMode::Cs184,
            aperture: 0.0,
            focal_distance: None,
            env_map: None,
            env_scale: 1.0,
            env_rotate: 0.0,
            eye: None,
            look_at: None,
            up: None,
            fov: None,
            filter: PixelFilter::default(),
        }
    }
}

impl ImageSettings {
    /// The pixels to render: the cell, or the whole frame.
    pub fn region(&self) -> PixelRect {
        self.cell
            .unwrap_or(PixelRect::full(self.width, self.height))
    }

    /// The explicit camera placement, if `eye` and `look_at` are given.
    pub fn view(&self) -> Option<CameraView> {
        Some(CameraView {
            eye: Vec3::from(self.eye?),
            target: Vec3::from(self.look_at?),
            up: self.up.map_or(Vec3::Y, Vec3::from),
            vfov_deg: self.fov,
        })
    }

    /// Loads the environment map asked for, if any.
    pub fn environment(&self) -> Result<Option<Arc<EnvironmentMap>>, SettingsError> {
        let Some(path) = &self.env_map else {
            return Ok(None);
        };
        let options = EnvironmentOptions {
            scale: self.env_scale,
            rotate_y_deg: self.env_rotate,
            // `-e` is CS184's flag, and CS184's environment light reads
            // its map bilinearly between pixel centres.
            lookup: EnvironmentLookup::Bilinear,
            ..EnvironmentOptions::default()
        };
        let bad = |err: &dyn std::fmt::Display| {
            SettingsError::new(format!(
                "env_map (-e) {}: cannot read the environment map: {err}",
                path.display()
            ))
        };
        let map = if path.as_os_str() == BUILT_IN_SKY && !path.exists() {
            let image = ProceduralSky::default()
                .image(512, 256)
                .map_err(|e| bad(&e))?;
            EnvironmentMap::from_image(&image, &options).map_err(|e| bad(&e))?
        } else {
            EnvironmentMap::load(path, &options).map_err(|e| bad(&e))?
        };
        Ok(Some(Arc::new(map)))
    }

    /// Checks the settings that depend on the scene: a camera number must
    /// name one of the file's `camera_count` cameras.
    pub fn validate_for_scene(&self, camera_count: usize) -> Result<(), SettingsError> {
        match self.camera {
            CameraMode::Numbered(n) => check(
                n < camera_count,
                "camera",
                "--camera",
                n,
                format_args!("the file has {camera_count} camera(s), numbered from 0"),
            ),
            _ => Ok(()),
        }
    }

    pub(super) fn validate(&self) -> Result<(), SettingsError> {
        let (w, h) = (self.width, self.height);
        check(
            w >= 1 && h >= 1,
            "width, height",
            "-r",
            format_args!("{w} {h}"),
            "the image must not be empty",
        )?;
        if let Some(c) = self.cell {
            check(
                c.fits_in(w, h),
                "cell",
                "-p",
                format_args!("{} {} {} {}", c.x, c.y, c.width, c.height),
                format_args!("the cell must be non-empty and inside the {w}x{h} image"),
            )?;
        }
        let a = self.aperture;
        check(
            a.is_finite() && a >= 0.0,
            "aperture",
            "-b",
            a,
            "a radius >= 0",
        )?;
        if let Some(d) = self.focal_distance {
            check(
                d.is_finite() && d > 0.0,
                "focal_distance",
                "-d",
                d,
                "a distance > 0",
            )?;
        }
        self.validate_view()?;
        let s = self.env_scale;
        check(
            s.is_finite() && s >= 0.0,
            "env_scale",
            "--env-scale",
            s,
            "a factor >= 0",
        )?;
        check(
            self.env_rotate.is_finite(),
            "env_rotate",
            "--env-rotate",
            self.env_rotate,
            "a finite angle in degrees",
        )
    }
}

impl ImageSettings {
    /// `eye`, `look_at`, `up` and `fov` make a camera: both points or
    /// neither, a view [`Camera::with_view`] accepts.
    fn validate_view(&self) -> Result<(), SettingsError> {
        let show =
            |p: Option<[f32; 3]>| p.map_or("none".into(), |[x, y, z]| format!("{x},{y},{z}"));
        check(
            self.eye.is_some() == self.look_at.is_some(),
            "eye, look_at",
            "--eye, --look-at",
            format_args!("{} {}", show(self.eye), show(self.look_at)),
            "the eye and the look-at point go together",
        )?;
        let Some(view) = self.view() else {
            return Ok(());
        };
        let probe = Camera::look_at(Vec3::ZERO, Vec3::NEG_Z, Vec3::Y, 60.0, 45.0, 4, 3);
        match probe.with_view(&view) {
            Ok(_) => Ok(()),
            Err(e) => check(
                false,
                "eye, look_at, up, fov",
                "--eye, --look-at, --up, --fov",
                format_args!(
                    "{} {} {} {}",
                    show(self.eye),
                    show(self.look_at),
                    show(self.up),
                    self.fov.map_or("none".into(), |f| f.to_string())
                ),
                e,
            ),
        }
    }
}
