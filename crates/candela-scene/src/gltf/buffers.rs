//! Buffer data: the `.glb` BIN chunk (borrowed, not copied), base64 `data:`
//! URIs, and external files beside the scene. Each buffer is checked to hold
//! at least its declared `byteLength`, so later bounds checks against that
//! length are checks against real bytes.

use super::Ctx;
use crate::error::{ErrorKind, LoadError};
use crate::text_file::MAX_FILE_BYTES;
use base64::Engine;
use std::borrow::Cow;
use std::path::PathBuf;

/// Reads every buffer of `doc`, in order; each is cut to its `byteLength`.
pub(super) fn read_all<'a>(
    ctx: &Ctx,
    doc: &gltf::Document,
    bin: Option<&'a [u8]>,
) -> Result<Vec<Cow<'a, [u8]>>, LoadError> {
    doc.buffers()
        .map(|buffer| {
            let at = format!("/buffers/{}", buffer.index());
            let data: Cow<[u8]> = match buffer.source() {
                gltf::buffer::Source::Bin => Cow::Borrowed(bin.ok_or_else(|| {
                    ctx.err(
                        at.clone(),
                        ErrorKind::MissingReference,
                        "buffer has no uri and the file has no BIN chunk".into(),
                    )
                })?),
                gltf::buffer::Source::Uri(uri) => Cow::Owned(read_uri(ctx, &at, uri)?),
            };
            let declared = buffer.length();
            if data.len() < declared {
                return Err(ctx.err(
                    at,
                    ErrorKind::CountMismatch,
                    format!(
                        "byteLength is {declared} but the data has {} bytes",
                        data.len()
                    ),
                ));
            }
            Ok(match data {
                Cow::Borrowed(b) => Cow::Borrowed(&b[..declared]),
                Cow::Owned(mut v) => {
                    v.truncate(declared);
                    Cow::Owned(v)
                }
            })
        })
        .collect()
}

/// The bytes a buffer or image `uri` names: a base64 `data:` URI or a file
/// relative to the scene (percent-escapes decoded).
pub(super) fn read_uri(ctx: &Ctx, at: &str, uri: &str) -> Result<Vec<u8>, LoadError> {
    if let Some(rest) = uri.strip_prefix("data:") {
        let Some((_, payload)) = rest.split_once(";base64,") else {
            return Err(ctx.err(
                format!("{at}/uri"),
                ErrorKind::Unsupported,
                "data URI is not base64-encoded".into(),
            ));
        };
        return base64::engine::general_purpose::STANDARD
            .decode(payload.trim_end())
            .map_err(|e| {
                ctx.err(
                    format!("{at}/uri"),
                    ErrorKind::BadValue,
                    format!("bad base64 in data URI: {e}"),
                )
            });
    }
    if uri.contains("://") {
        return Err(ctx.err(
            format!("{at}/uri"),
            ErrorKind::Unsupported,
            format!("URI \"{uri}\" is not a relative file path or a data URI"),
        ));
    }
    let path = file_path(ctx, uri);
    let io = |e: std::io::Error| {
        ctx.err(
            format!("{at}/uri"),
            ErrorKind::Io,
            format!("cannot read \"{}\": {e}", path.display()),
        )
    };
    let len = std::fs::metadata(&path).map_err(io)?.len();
    if len > MAX_FILE_BYTES {
        return Err(ctx.err(
            format!("{at}/uri"),
            ErrorKind::TooLarge,
            format!(
                "\"{}\" has {len} bytes, over the limit of {MAX_FILE_BYTES}",
                path.display()
            ),
        ));
    }
    crate::referenced::note_read(&path);
    std::fs::read(&path).map_err(io)
}

/// A relative `uri` as a path beside the scene file.
pub(super) fn file_path(ctx: &Ctx, uri: &str) -> PathBuf {
    let base = ctx.file.parent().unwrap_or(std::path::Path::new(""));
    base.join(percent_decode(uri))
}

/// `%XX` escapes decoded (URIs in glTF are RFC 3986); a malformed escape is
/// kept as written.
fn percent_decode(uri: &str) -> String {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        let hex = bytes
            .get(i + 1..i + 3)
            .and_then(|h| std::str::from_utf8(h).ok())
            .and_then(|h| u8::from_str_radix(h, 16).ok());
        match (bytes[i], hex) {
            (b'%', Some(b)) => {
                out.push(b);
                i += 3;
            }
            (b, _) => {
                out.push(b);
                i += 1;
            }
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

#[cfg(test)]
mod tests {
    use super::percent_decode;

    #[test]
    fn percent_escapes_are_decoded_and_bad_ones_kept() {
        assert_eq!(percent_decode("a%20b.bin"), "a b.bin");
        assert_eq!(percent_decode("a%2"), "a%2");
        assert_eq!(percent_decode("%zz"), "%zz");
    }
}
