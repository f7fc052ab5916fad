//! The PLY header: `ply`, `format <encoding> 1.0`, then `element <name>
//! <count>` lines, each followed by its `property <type> <name>` or
//! `property list <count type> <item type> <name>` lines, then
//! `end_header`. `comment` and `obj_info` lines are skipped.

use super::located;
use crate::desc::SourceLoc;
use crate::error::{clip, ErrorKind, LoadError};
use std::path::Path;

/// Longest header accepted: real headers are a few hundred bytes.
const MAX_HEADER_BYTES: usize = 64 << 10;

/// How the body stores numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    /// Whitespace-separated text.
    Ascii,
    /// Binary, least significant byte first.
    LittleEndian,
    /// Binary, most significant byte first.
    BigEndian,
}

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn named(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// Size in bytes in a binary body.
    pub fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The largest value of an integer type (a colour stored in it is
    /// this over 1); `None` for floats.
    pub fn integer_max(self) -> Option<f64> {
        Some(match self {
            Scalar::I8 => f64::from(i8::MAX),
            Scalar::U8 => f64::from(u8::MAX),
            Scalar::I16 => f64::from(i16::MAX),
            Scalar::U16 => f64::from(u16::MAX),
            Scalar::I32 => f64::from(i32::MAX),
            Scalar::U32 => f64::from(u32::MAX),
            Scalar::F32 | Scalar::F64 => return None,
        })
    }

    /// Whether values are integers.
    pub fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }
}

/// One property of an element.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Property {
    /// One number.
    Scalar { name: String, ty: Scalar },
    /// A count, then that many numbers.
    List {
        name: String,
        count: Scalar,
        item: Scalar,
    },
}

impl Property {
    pub fn name(&self) -> &str {
        match self {
            Property::Scalar { name, .. } | Property::List { name, .. } => name,
        }
    }
}

/// An `element` line and its properties.
#[derive(Clone, Debug)]
pub(crate) struct Element {
    pub name: String,
    pub count: u64,
    pub properties: Vec<Property>,
    /// Where the `element` line is.
    pub loc: SourceLoc,
}

impl Element {
    /// The fewest body bytes one instance can take: binary sizes with empty
    /// lists, or in text one character and one separator per number.
    pub fn min_bytes(&self, encoding: Encoding) -> u64 {
        let per = self.properties.iter().map(|p| match (p, encoding) {
            (_, Encoding::Ascii) => 2,
            (Property::Scalar { ty, .. }, _) => ty.size() as u64,
            (Property::List { count, .. }, _) => count.size() as u64,
        });
        per.sum::<u64>().max(1)
    }
}

/// A parsed header.
pub(crate) struct Header {
    pub encoding: Encoding,
    pub elements: Vec<Element>,
    /// Byte offset of the body.
    pub body_start: usize,
    /// Line number of the body's first line (for text bodies).
    pub body_line: u32,
}

/// Parses the header at the start of `bytes` (the file `file`).
pub(crate) fn parse(bytes: &[u8], file: &Path) -> Result<Header, LoadError> {
    let err = |line: usize, col: usize, element: &str, kind, msg: String| {
        located(file, loc(line, col), element, kind, msg)
    };
    if !bytes.starts_with(b"ply\n") && !bytes.starts_with(b"ply\r\n") {
        return Err(err(
            1,
            1,
            "ply",
            ErrorKind::BadValue,
            "not a PLY file: it does not start with the line \"ply\"".into(),
        ));
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut pos = 0;
    let mut line_no = 0;
    loop {
        line_no += 1;
        let Some(len) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            let kind = if pos > MAX_HEADER_BYTES {
                ErrorKind::TooLarge
            } else {
                ErrorKind::Truncated
            };
            return Err(err(
                line_no,
                1,
                "end_header",
                kind,
                "the header has no end_header line".into(),
            ));
        };
        if pos + len > MAX_HEADER_BYTES {
            return Err(err(
                line_no,
                1,
                "end_header",
                ErrorKind::TooLarge,
                format!("the header exceeds {MAX_HEADER_BYTES} bytes"),
            ));
        }
        let raw = &bytes[pos..pos + len];
        pos += len + 1;
        let Ok(line) = std::str::from_utf8(raw) else {
            return Err(err(
                line_no,
                1,
                "",
                ErrorKind::NotText,
                "header line is not text".into(),
            ));
        };
        let line = line.strip_suffix('\r').unwrap_or(line);
        let words: Vec<&str> = line.split_whitespace().collect();
        let Some(&keyword) = words.first() else {
            continue;
        };
        let col_of = |i: usize| {
            let w = words[i.min(words.len() - 1)];
            line[..w.as_ptr() as usize - line.as_ptr() as usize]
                .chars()
                .count()
                + 1
        };
        match keyword {
            "ply" if line_no == 1 => {}
            "comment" | "obj_info" => {}
            "format" => {
                encoding = Some(match words.get(1).copied() {
                    Some("ascii") => Encoding::Ascii,
                    Some("binary_little_endian") => Encoding::LittleEndian,
                    Some("binary_big_endian") => Encoding::BigEndian,
                    other => {
                        return Err(err(
                            line_no,
                            col_of(1),
                            "format",
                            ErrorKind::BadValue,
                            format!("unknown encoding \"{}\"", clip(other.unwrap_or(""))),
                        ))
                    }
                });
                if !matches!(words.get(2).copied(), Some("1.0" | "1")) {
                    return Err(err(
                        line_no,
                        col_of(2),
                        "format",
                        ErrorKind::BadValue,
                        "only PLY version 1.0 is supported".into(),
                    ));
                }
            }
            "element" => {
                let (Some(name), Some(count)) = (words.get(1), words.get(2)) else {
                    return Err(err(
                        line_no,
                        col_of(0),
                        "element",
                        ErrorKind::MissingElement,
                        "expected \"element <name> <count>\"".into(),
                    ));
                };
                let count: u64 = count.parse().map_err(|_| {
                    err(
                        line_no,
                        col_of(2),
                        "element",
                        ErrorKind::BadNumber,
                        format!("\"{}\" is not a count", clip(count)),
                    )
                })?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                    loc: loc(line_no, col_of(0)),
                });
            }
            "property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(err(
                        line_no,
                        1,
                        "property",
                        ErrorKind::MissingElement,
                        "property before any element".into(),
                    ));
                };
                let ty = |i: usize| {
                    let name = words.get(i).copied().unwrap_or("");
                    Scalar::named(name).ok_or_else(|| {
                        err(
                            line_no,
                            col_of(i),
                            "property",
                            ErrorKind::BadValue,
                            format!("unknown type \"{}\"", clip(name)),
                        )
                    })
                };
                let name = |i: usize| {
                    words.get(i).map(|s| s.to_string()).ok_or_else(|| {
                        err(
                            line_no,
                            col_of(i),
                            "property",
                            ErrorKind::MissingElement,
                            "expected a property name".into(),
                        )
                    })
                };
                let property = if words.get(1) == Some(&"list") {
                    let count = ty(2)?;
                    if !count.is_integer() {
                        return Err(err(
                            line_no,
                            col_of(2),
                            "property",
                            ErrorKind::BadValue,
                            "a list's count type must be an integer type".into(),
                        ));
                    }
                    Property::List {
                        count,
                        item: ty(3)?,
                        name: name(4)?,
                    }
                } else {
                    Property::Scalar {
                        ty: ty(1)?,
                        name: name(2)?,
                    }
                };
                element.properties.push(property);
            }
            "end_header" => {
                let Some(encoding) = encoding else {
                    return Err(err(
                        line_no,
                        1,
                        "format",
                        ErrorKind::MissingElement,
                        "the header has no format line".into(),
                    ));
                };
                return Ok(Header {
                    encoding,
                    elements,
                    body_start: pos,
                    body_line: u32::try_from(line_no + 1).unwrap_or(u32::MAX),
                });
            }
            other => {
                return Err(err(
                    line_no,
                    1,
                    &clip(other),
                    ErrorKind::BadValue,
                    format!("unknown header line \"{}\"", clip(other)),
                ))
            }
        }
    }
}

fn loc(line: usize, col: usize) -> SourceLoc {
    SourceLoc {
        line: u32::try_from(line).unwrap_or(u32::MAX),
        col: u32::try_from(col).unwrap_or(u32::MAX),
    }
}
