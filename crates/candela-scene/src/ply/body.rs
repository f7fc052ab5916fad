//! Reading the numbers of a PLY body, text or binary, one at a time: every
//! read is checked against the bytes that remain, so a count in the header
//! can never make the reader allocate or loop beyond the file's size.

use super::header::{Encoding, Scalar};
use crate::desc::SourceLoc;
use crate::error::{clip, ErrorKind};

/// A cursor over the body.
pub(crate) struct Body<'a> {
    bytes: &'a [u8],
    pos: usize,
    encoding: Encoding,
    /// Text bodies: the current line and the byte where it starts.
    line: u32,
    line_start: usize,
}

/// Why a read failed, and where (text) or at which byte (binary).
pub(crate) struct ReadError {
    pub kind: ErrorKind,
    pub message: String,
    /// The place in a text body; `None` in a binary one.
    pub loc: Option<SourceLoc>,
}

impl<'a> Body<'a> {
    /// The body starting at `start` of `bytes`, on line `line` for text.
    pub fn new(bytes: &'a [u8], start: usize, encoding: Encoding, line: u32) -> Self {
        Self {
            bytes,
            pos: start.min(bytes.len()),
            encoding,
            line,
            line_start: start,
        }
    }

    /// Bytes not yet read.
    pub fn remaining(&self) -> u64 {
        (self.bytes.len() - self.pos) as u64
    }

    /// Reads one value of type `ty`.
    pub fn read(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        match self.encoding {
            Encoding::Ascii => self.read_text(ty),
            Encoding::LittleEndian | Encoding::BigEndian => self.read_binary(ty),
        }
    }

    /// Checks that `n` values of `ty` can still follow (binary), so a list
    /// count is never trusted beyond the file.
    pub fn ensure(&self, n: u64, ty: Scalar) -> Result<(), ReadError> {
        let need = match self.encoding {
            Encoding::Ascii => n.saturating_mul(2).saturating_sub(1),
            _ => n.saturating_mul(ty.size() as u64),
        };
        if need > self.remaining() {
            return Err(self.error(
                ErrorKind::Truncated,
                format!(
                    "a list of {n} values does not fit in the {} bytes left",
                    self.remaining()
                ),
            ));
        }
        Ok(())
    }

    fn read_binary(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        let size = ty.size();
        let Some(raw) = self.bytes.get(self.pos..self.pos + size) else {
            return Err(self.error(ErrorKind::Truncated, "the file ends early".into()));
        };
        self.pos += size;
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(raw);
        if self.encoding == Encoding::BigEndian {
            b[..size].reverse();
        }
        Ok(match ty {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(i16::from_le_bytes([b[0], b[1]])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            Scalar::F64 => f64::from_le_bytes(b),
        })
    }

    fn read_text(&mut self, ty: Scalar) -> Result<f64, ReadError> {
        while let Some(&c) = self.bytes.get(self.pos) {
            if !c.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
            if c == b'\n' {
                self.line = self.line.saturating_add(1);
                self.line_start = self.pos;
            }
        }
        let start = self.pos;
        while self
            .bytes
            .get(self.pos)
            .is_some_and(|c| !c.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.error(ErrorKind::Truncated, "the file ends early".into()));
        }
        let token = &self.bytes[start..self.pos];
        let token = String::from_utf8_lossy(token);
        let loc = self.loc_of(start);
        let bad = |what: &str| ReadError {
            kind: ErrorKind::BadNumber,
            message: format!("\"{}\" is not {what}", clip(&token)),
            loc: Some(loc),
        };
        if ty.is_integer() {
            let v: i64 = token.parse().map_err(|_| bad("an integer"))?;
            Ok(v as f64)
        } else {
            token.parse::<f64>().map_err(|_| bad("a number"))
        }
    }

    fn loc_of(&self, byte: usize) -> SourceLoc {
        let col = self.bytes[self.line_start..byte]
            .iter()
            .filter(|&&b| b & 0xC0 != 0x80)
            .count()
            + 1;
        SourceLoc {
            line: self.line,
            col: u32::try_from(col).unwrap_or(u32::MAX),
        }
    }

    /// An error at the cursor.
    pub fn error(&self, kind: ErrorKind, message: String) -> ReadError {
        match self.encoding {
            Encoding::Ascii => ReadError {
                kind,
                message,
                loc: Some(self.loc_of(self.pos)),
            },
            _ => ReadError {
                kind,
                message: format!("{message} (at byte {})", self.pos),
                loc: None,
            },
        }
    }
}
