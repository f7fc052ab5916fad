//! The WebSocket messages between the page and the server.
//!
//! The page sends JSON text ([`Request`]); the server answers with JSON
//! text ([`Reply`]) and, for images, binary messages made by
//! [`frame_message`]: a little-endian `u32` header length, the header
//! ([`FrameHeader`] as JSON), then a PNG.
//!
//! Job ids belong to the page: every request that produces frames
//! ([`Request::Render`], [`Request::Layer`]) carries the page's `job`, and
//! every frame echoes the id of the request it answers. The page shows only
//! frames of its newest job, so a request the server never saw, or frames
//! of a render cancelled on the way, cannot leave the page waiting for an
//! id the server does not use (which two separate counters could).

use candela_render::film::CostMeasure;
use candela_render::integrator::inspect::PathRecord;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};

/// What the page asks for.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum Request {
    /// Render the current camera with these settings changes (flat JSON of
    /// the settings description, camera and cell included): a coarse frame,
    /// then refinement to the target sample count. Cancels any render in
    /// progress.
    Render {
        /// The page's id of this request, echoed in its frames.
        #[serde(default)]
        job: u64,
        /// Changes to the scene's default settings.
        #[serde(default)]
        settings: Map<String, Value>,
        /// The layer to show.
        #[serde(default)]
        layer: Layer,
    },
    /// Stop the render in progress (the camera is moving).
    Cancel,
    /// Show another layer: of the last film if its render is finished (no
    /// new samples), else the running render is cancelled and started
    /// again showing this layer.
    Layer {
        /// The page's id of this request, echoed in its frames.
        #[serde(default)]
        job: u64,
        /// The layer to show.
        layer: Layer,
    },
    /// Trace the first `samples` samples of pixel (`x`, `y`) of the last
    /// render with full records (the path inspector).
    Inspect {
        /// Column, from the left.
        x: u32,
        /// Row, from the top.
        y: u32,
        /// How many samples, from index 0.
        #[serde(default = "default_inspected")]
        samples: u32,
    },
    /// Write the last film into the output folder.
    Save {
        /// `png` (tone-mapped beauty) or `exr` (linear, with layers).
        format: SaveFormat,
    },
}

fn default_inspected() -> u32 {
    4
}

/// The film's layers the page can show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Layer {
    /// The tone-mapped radiance.
    #[default]
    Beauty,
    /// First-hit albedo.
    Albedo,
    /// First-hit shading normal, `n * 0.5 + 0.5`.
    Normal,
    /// Samples per pixel as the CS184 rate colours (blue few, red the most).
    Samples,
    /// Standard error of each pixel's mean, tone-mapped like the beauty.
    StdError,
    /// Mean distance to the first hit, grey (near is bright; black where
    /// nothing was hit).
    Depth,
    /// Traversal work per sample (BVH nodes visited plus primitive tests)
    /// as a heat map up to its 99th percentile.
    Cost,
    /// BVH nodes visited per sample alone, as [`Layer::Cost`].
    CostNodes,
    /// Primitive intersection tests per sample alone, as [`Layer::Cost`].
    CostTests,
}

impl Layer {
    /// The traversal work a cost layer shows.
    pub fn cost_measure(self) -> Option<CostMeasure> {
        match self {
            Layer::Cost => Some(CostMeasure::Total),
            Layer::CostNodes => Some(CostMeasure::Nodes),
            Layer::CostTests => Some(CostMeasure::PrimTests),
            _ => None,
        }
    }
}

/// File formats of [`Request::Save`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SaveFormat {
    /// 8-bit sRGB through the tone map.
    Png,
    /// Linear float with albedo, normal and sample-count layers.
    Exr,
}

impl SaveFormat {
    /// The file extension.
    pub fn extension(self) -> &'static str {
        match self {
            SaveFormat::Png => "png",
            SaveFormat::Exr => "exr",
        }
    }
}

/// What the server says in text.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Reply {
    /// A request could not be honoured; the message is one line.
    Error {
        /// What was wrong.
        message: String,
    },
    /// Files written by [`Request::Save`].
    Saved {
        /// The paths written.
        files: Vec<String>,
    },
    /// The traced paths of [`Request::Inspect`].
    Paths {
        /// The pixel.
        pixel: [u32; 2],
        /// One record per sample, from index 0.
        paths: Vec<PathRecord>,
        /// The pixel's mean radiance in the film shown (over all its samples).
        film_mean: [f64; 3],
        /// The pixel's sample count in that film.
        film_samples: u32,
    },
}

impl Reply {
    /// An error reply.
    pub fn error(message: impl Into<String>) -> Self {
        Reply::Error {
            message: message.into(),
        }
    }

    /// The reply as JSON text.
    pub fn to_text(&self) -> String {
        serde_json::to_string(self).unwrap_or_else(|_| r#"{"type":"error"}"#.into())
    }
}

/// What a binary image message carries besides the PNG.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FrameHeader {
    /// The page's id of the request this frame answers.
    pub job: u64,
    /// The coarse preview (lower resolution, one sample per pixel).
    pub coarse: bool,
    /// Samples per pixel in the film so far.
    pub spp: u32,
    /// The sample count the render refines to.
    pub target_spp: u32,
    /// The last frame of this render.
    pub done: bool,
    /// The image's size in pixels (the coarse frame is smaller than the
    /// render).
    pub width: u32,
    /// See `width`.
    pub height: u32,
    /// The render's full size, which the image is shown at.
    pub render_width: u32,
    /// See `render_width`.
    pub render_height: u32,
    /// The layer shown.
    pub layer: Layer,
    /// Milliseconds since the request arrived.
    pub elapsed_ms: f64,
    /// Of those, the milliseconds spent rendering (the rest is the
    /// server's own work: camera set-up, copying out and encoding frames).
    pub render_ms: f64,
    /// The `candela` command line that renders the same image.
    pub command: String,
}

/// A binary message: header length, header JSON, PNG bytes.
pub fn frame_message(header: &FrameHeader, png: &[u8]) -> Vec<u8> {
    let json = serde_json::to_vec(header).unwrap_or_default();
    let mut out = Vec::with_capacity(4 + json.len() + png.len());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(&json);
    out.extend_from_slice(png);
    out
}

/// Parses a request, or says in one line why it is not one.
pub fn parse_request(text: &str) -> Result<Request, String> {
    serde_json::from_str(text).map_err(|e| format!("bad request: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_parse_and_bad_ones_are_errors() {
        let r = parse_request(r#"{"type":"render","settings":{"spp":4},"layer":"albedo"}"#);
        match r {
            Ok(Request::Render {
                job,
                settings,
                layer,
            }) => {
                assert_eq!(job, 0, "no job id: 0");
                assert_eq!(settings["spp"], 4);
                assert_eq!(layer, Layer::Albedo);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(parse_request(r#"{"type":"cancel"}"#), Ok(Request::Cancel));
        assert_eq!(
            parse_request(r#"{"type":"layer","layer":"depth","job":7}"#),
            Ok(Request::Layer {
                job: 7,
                layer: Layer::Depth
            })
        );
        for bad in [
            "{",
            "[]",
            r#"{"type":"fly"}"#,
            r#"{"type":"render","job":-1}"#,
            r#"{"type":"save","format":"gif"}"#,
        ] {
            let err = parse_request(bad).unwrap_err();
            assert!(err.starts_with("bad request:"), "{err}");
        }
    }

    #[test]
    fn a_frame_message_starts_with_its_header_length() {
        let header = FrameHeader {
            job: 1,
            coarse: true,
            spp: 1,
            target_spp: 16,
            done: false,
            width: 2,
            height: 1,
            render_width: 8,
            render_height: 4,
            layer: Layer::Beauty,
            elapsed_ms: 3.0,
            render_ms: 2.0,
            command: "candela".into(),
        };
        let msg = frame_message(&header, b"PNG");
        let n = u32::from_le_bytes(msg[..4].try_into().unwrap()) as usize;
        let json: Value = serde_json::from_slice(&msg[4..4 + n]).unwrap();
        assert_eq!(json["target_spp"], 16);
        assert_eq!(&msg[4 + n..], b"PNG");
    }
}
