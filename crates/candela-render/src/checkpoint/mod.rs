//! Checkpoints: a stopped render's film and everything needed to continue
//! it, in one versioned file.
//!
//! A render's state at a pass boundary is its film's sums (see
//! [`crate::render::Continuation`]), so a checkpoint is the film plus what
//! identifies the render: the full settings, a content hash of the scene
//! ([`scene_hash`]), the render time spent so far (for `--time` budgets) and
//! an opaque front-end record (the CLI's scene and output paths, the Dask
//! planner's grid) so that `candela resume` writes what the original command
//! asked for.
//!
//! Layout, little-endian:
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `CNDLCKPT` |
//! | 4 | format version ([`VERSION`]) |
//! | 4 + n | length and UTF-8 JSON of the [`Checkpoint`] record (settings, scene hash, front end, time) |
//! | 4 + 4 | film width and height |
//! | w·h·144 | the film's sums ([`crate::film::wire`], the film encoding shared with the Python package) |
//! | 16 | content hash of every byte before it (catches truncation and corruption) |
//!
//! Files are written atomically ([`candela_image::atomic_write`]: a
//! temporary beside the file, fsync, rename), so a render killed while
//! saving leaves the previous checkpoint intact.

mod hash;
mod matching;
mod writer;

pub use hash::{scene_hash, ContentHash, ContentHasher};
pub use matching::{Mismatch, FREE_SETTINGS};
pub use writer::{CheckpointWriter, Resumed, StartError};

use crate::film::wire::{decode_film, encode_pixels, ByteReader, PIXEL_BYTES};
use crate::film::Film;
use crate::settings::Settings;
use serde_json::{json, Map, Value};
use std::io::Write;
use std::path::Path;
use std::time::Duration;

/// First bytes of every checkpoint.
pub const MAGIC: &[u8; 8] = b"CNDLCKPT";
/// The format version this build writes and reads.
pub const VERSION: u32 = 1;
/// Largest JSON record accepted (a sanity bound against corrupt lengths).
const MAX_RECORD: usize = 16 << 20;

/// A stopped render, ready to continue.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    /// Every setting of the render.
    pub settings: Settings,
    /// [`scene_hash`] of the scene it renders.
    pub scene_hash: ContentHash,
    /// What the front end that started the render needs to finish it (a
    /// JSON object; `"front"` names the front end).
    pub front: Map<String, Value>,
    /// Render time spent on the film so far, over every run.
    pub elapsed: Duration,
    /// The sums of every finished pass (full frame).
    pub film: Film,
}

/// Why a checkpoint cannot be read or written; one line each.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// The file cannot be read.
    #[error("{path}: cannot read the checkpoint: {source}")]
    Read {
        /// The file.
        path: String,
        /// Why.
        source: std::io::Error,
    },
    /// The file cannot be written.
    #[error("{path}: cannot write the checkpoint: {message}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// The bytes are not a checkpoint this build reads.
    #[error("{path}: {what}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        what: String,
    },
}

impl Checkpoint {
    /// The checkpoint as bytes (see the module docs for the layout).
    pub fn to_bytes(&self) -> Vec<u8> {
        let record = json!({
            "settings": Value::Object(self.settings.to_json()),
            "scene_hash": self.scene_hash.to_string(),
            "front": Value::Object(self.front.clone()),
            "elapsed_s": self.elapsed.as_secs_f64(),
        })
        .to_string();
        let mut out = Vec::with_capacity(64 + record.len() + self.film.pixels.len() * PIXEL_BYTES);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&(record.len() as u32).to_le_bytes());
        out.extend_from_slice(record.as_bytes());
        out.extend_from_slice(&self.film.width.to_le_bytes());
        out.extend_from_slice(&self.film.height.to_le_bytes());
        encode_pixels(&self.film.pixels, &mut out);
        let mut h = ContentHasher::new();
        h.write(&out);
        for lane in h.finish().0 {
            out.extend_from_slice(&lane.to_le_bytes());
        }
        out
    }

    /// Reads a checkpoint from bytes; `Err` is what is wrong with them.
    pub fn from_bytes(bytes: &[u8]) -> Result<Self, String> {
        if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
            return Err("not a candela checkpoint".into());
        }
        let truncated = || "the checkpoint is truncated".to_string();
        let mut r = ByteReader::new(&bytes[MAGIC.len()..]);
        let version = r.u32().ok_or_else(truncated)?;
        if version != VERSION {
            return Err(format!(
                "checkpoint format version {version}; this candela reads version {VERSION}"
            ));
        }
        if bytes.len() < 16 {
            return Err(truncated());
        }
        let (body, tail) = bytes.split_at(bytes.len() - 16);
        let mut h = ContentHasher::new();
        h.write(body);
        let [a, b] = h.finish().0;
        if tail[..8] != a.to_le_bytes() || tail[8..] != b.to_le_bytes() {
            return Err(
                "the checkpoint is truncated or corrupt (its checksum does not match)".into(),
            );
        }
        let mut r = ByteReader::new(&body[MAGIC.len() + 4..]);
        let n = r.u32().ok_or_else(truncated)? as usize;
        if n > MAX_RECORD {
            return Err(truncated());
        }
        let record = r.take(n).ok_or_else(truncated)?;
        let record: Value = serde_json::from_slice(record)
            .map_err(|e| format!("the checkpoint's record is not valid JSON: {e}"))?;
        let field = |key: &str| {
            record
                .get(key)
                .ok_or_else(|| format!("the checkpoint's record has no `{key}`"))
        };
        let Value::Object(settings) = field("settings")? else {
            return Err("the checkpoint's settings are not an object".into());
        };
        let settings = Settings::from_json(settings)
            .map_err(|e| format!("the checkpoint's settings are invalid: {e}"))?;
        let scene_hash = field("scene_hash")?
            .as_str()
            .and_then(ContentHash::parse)
            .ok_or("the checkpoint's scene hash is malformed")?;
        let Value::Object(front) = field("front")?.clone() else {
            return Err("the checkpoint's front-end record is not an object".into());
        };
        let elapsed = field("elapsed_s")?
            .as_f64()
            .and_then(|s| Duration::try_from_secs_f64(s).ok())
            .ok_or("the checkpoint's render time is malformed")?;
        let (w, h) = (
            r.u32().ok_or_else(truncated)?,
            r.u32().ok_or_else(truncated)?,
        );
        if (w, h) != (settings.image.width, settings.image.height) {
            return Err(format!(
                "the checkpoint's film is {w}x{h} but its settings say {}x{}",
                settings.image.width, settings.image.height
            ));
        }
        let film = decode_film(&mut r, w, h).ok_or_else(truncated)?;
        if r.remaining() != 0 {
            return Err(format!("{} unexpected bytes after the film", r.remaining()));
        }
        Ok(Self {
            settings,
            scene_hash,
            front,
            elapsed,
            film,
        })
    }

    /// Writes the checkpoint to `path` atomically.
    pub fn save(&self, path: &Path) -> Result<(), CheckpointError> {
        let bytes = self.to_bytes();
        candela_image::atomic_write(path, |w| w.write_all(&bytes)).map_err(|e| {
            CheckpointError::Write {
                path: path.display().to_string(),
                message: e.to_string(),
            }
        })
    }

    /// Reads the checkpoint at `path`.
    pub fn load(path: &Path) -> Result<Self, CheckpointError> {
        let bytes = std::fs::read(path).map_err(|source| CheckpointError::Read {
            path: path.display().to_string(),
            source,
        })?;
        Self::from_bytes(&bytes).map_err(|what| CheckpointError::Invalid {
            path: path.display().to_string(),
            what,
        })
    }

    /// Samples in the film, over all pixels.
    pub fn samples(&self) -> u64 {
        self.film.pixels.iter().map(|p| p.count as u64).sum()
    }
}

#[cfg(test)]
mod tests;
