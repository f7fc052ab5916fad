//! The binary container (`.glb`): a 12-byte header, a JSON chunk, and an
//! optional BIN chunk. Split here with every length checked against the
//! file (the `gltf` crate's own splitter subtracts before it checks), so a
//! truncated or lying file is an error, never a panic; the chunks are
//! borrowed, not copied.

use super::Ctx;
use crate::error::{ErrorKind, LoadError};

/// `glTF` in ASCII, little-endian.
const MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// The two chunks of a binary glTF file.
pub(super) struct Glb<'a> {
    /// The JSON document.
    pub json: &'a [u8],
    /// The binary buffer, if the file has one.
    pub bin: Option<&'a [u8]>,
}

/// Whether `bytes` starts like a binary glTF file.
pub(super) fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a `.glb` file into its chunks.
pub(super) fn split<'a>(ctx: &Ctx, bytes: &'a [u8]) -> Result<Glb<'a>, LoadError> {
    let at = |what: &str| format!("<glb {what}>");
    if bytes.len() < 12 {
        return Err(ctx.err(
            at("header"),
            ErrorKind::CountMismatch,
            format!(
                "file of {} bytes is shorter than the 12-byte header",
                bytes.len()
            ),
        ));
    }
    if !is_glb(bytes) {
        return Err(ctx.err(
            at("header"),
            ErrorKind::BadValue,
            format!(
                "magic {:?} is not \"glTF\": not a binary glTF file",
                &bytes[..4]
            ),
        ));
    }
    let version = u32_at(bytes, 4).unwrap_or(0);
    if version != 2 {
        return Err(ctx.err(
            at("header"),
            ErrorKind::Unsupported,
            format!("binary glTF version {version} (only version 2 is read)"),
        ));
    }
    let length = u32_at(bytes, 8).unwrap_or(0) as usize;
    if length > bytes.len() || length < 12 {
        return Err(ctx.err(
            at("header"),
            ErrorKind::CountMismatch,
            format!("header claims {length} bytes, the file has {}", bytes.len()),
        ));
    }
    let body = &bytes[..length];
    let (json_type, json) = chunk(ctx, body, 12)?;
    if json_type != CHUNK_JSON {
        return Err(ctx.err(
            at("chunk 0"),
            ErrorKind::BadValue,
            format!("first chunk has type {json_type:#010x}, not JSON"),
        ));
    }
    // Chunks are 4-byte aligned; `chunk` checked the length fits.
    let mut next = 20 + json.len();
    next = next.div_ceil(4) * 4;
    let mut bin = None;
    if next < body.len() {
        let (ty, data) = chunk(ctx, body, next)?;
        if ty == CHUNK_BIN {
            bin = Some(data);
        } else {
            ctx.warn(
                "<glb chunk>",
                &format!("unknown chunk type {ty:#010x} after the JSON chunk; ignored"),
            )?;
        }
    }
    Ok(Glb { json, bin })
}

/// The chunk whose 8-byte header starts at `start`: its type and data.
fn chunk<'a>(ctx: &Ctx, body: &'a [u8], start: usize) -> Result<(u32, &'a [u8]), LoadError> {
    let (Some(len), Some(ty)) = (u32_at(body, start), u32_at(body, start + 4)) else {
        return Err(ctx.err(
            format!("<glb chunk at byte {start}>"),
            ErrorKind::CountMismatch,
            "file ends inside a chunk header".to_string(),
        ));
    };
    let data_start = start + 8;
    let data = data_start
        .checked_add(len as usize)
        .and_then(|end| body.get(data_start..end))
        .ok_or_else(|| {
            ctx.err(
                format!("<glb chunk at byte {start}>"),
                ErrorKind::CountMismatch,
                format!(
                    "chunk length {len} runs past the end of the file ({} bytes)",
                    body.len()
                ),
            )
        })?;
    Ok((ty, data))
}
