//! Deterministic mutations of a valid file, for sweeps that prove bad input
//! never panics, hangs or allocates without bound. Each function returns
//! named mutants, so a failure says exactly which change broke what; the
//! positions come from a [`SplitMix64`] with the caller's seed, so every run
//! makes the same mutants.

use crate::SplitMix64;

/// One changed copy of a file, named after the change (`flip@1234^0x5a`,
/// `number#7=nan`, `count="#0=4294967295`).
#[derive(Clone, Debug)]
pub struct Mutant {
    /// What was changed, and where.
    pub name: String,
    /// The changed file.
    pub bytes: Vec<u8>,
}

/// Numbers a loader must survive in place of any number: huge floats,
/// the largest `u32` and `u64`, non-finite values, -1 and 0.
pub const EXTREME_NUMBERS: [&str; 10] = [
    "1e30",
    "1e300",
    "4294967295",
    "18446744073709551615",
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "-0",
];

/// Counts that ask for more than any machine has: a loader must refuse
/// them before it allocates.
pub const HUGE_COUNTS: [&str; 4] = ["4294967295", "18446744073709551615", "2147483648", "-1"];

/// The file cut at the start, a few fractions of its length, and one byte
/// short of its end.
pub fn truncations(bytes: &[u8]) -> Vec<Mutant> {
    let n = bytes.len();
    let mut cuts: Vec<usize> = [0, n / 9, n / 4, n / 2, 3 * n / 4, n.saturating_sub(1)].into();
    cuts.dedup();
    cuts.into_iter()
        .map(|at| Mutant {
            name: format!("truncate@{at}"),
            bytes: bytes[..at].to_vec(),
        })
        .collect()
}

/// `count` copies, each with one byte at a seeded position xor-ed with a
/// seeded non-zero value.
pub fn flips(bytes: &[u8], seed: u64, count: usize) -> Vec<Mutant> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .filter(|_| !bytes.is_empty())
        .map(|_| {
            let at = (rng.next_u64() % bytes.len() as u64) as usize;
            let x = (rng.next_u64() % 255 + 1) as u8;
            let mut b = bytes.to_vec();
            b[at] ^= x;
            Mutant {
                name: format!("flip@{at}^{x:#04x}"),
                bytes: b,
            }
        })
        .collect()
}

/// `count` copies, each with one byte at a seeded position removed.
pub fn deletions(bytes: &[u8], seed: u64, count: usize) -> Vec<Mutant> {
    let mut rng = SplitMix64::new(seed);
    (0..count)
        .filter(|_| !bytes.is_empty())
        .map(|_| {
            let at = (rng.next_u64() % bytes.len() as u64) as usize;
            let mut b = bytes.to_vec();
            b.remove(at);
            Mutant {
                name: format!("delete@{at}"),
                bytes: b,
            }
        })
        .collect()
}

/// For each of `values`, `per_value` copies with one seeded number of the
/// text replaced by it. A number is a run of digits, signs, dots and
/// exponents that starts with a digit (or a sign or dot before one) and is
/// not part of a word, so names like `x2` keep their digits.
pub fn numbers(bytes: &[u8], values: &[&str], per_value: usize, seed: u64) -> Vec<Mutant> {
    let spans = number_spans(bytes);
    let mut rng = SplitMix64::new(seed);
    let mut out = Vec::new();
    if spans.is_empty() {
        return out;
    }
    for value in values {
        for _ in 0..per_value {
            let i = (rng.next_u64() % spans.len() as u64) as usize;
            out.push(Mutant {
                name: format!("number#{i}={value}"),
                bytes: splice(bytes, spans[i], value),
            });
        }
    }
    out
}

/// Copies with the value after `key` (up to a quote, comma, bracket, `<` or
/// white space) replaced by each of `values`, at the first occurrence and
/// at up to `extra` more seeded ones. E.g. key `count="` with value
/// `4294967295`, key `"bufferView": ` with `99`, key `mtllib ` with
/// `missing.mtl`.
pub fn after_key(bytes: &[u8], key: &str, values: &[&str], extra: usize, seed: u64) -> Vec<Mutant> {
    let spans = key_value_spans(bytes, key.as_bytes());
    let mut rng = SplitMix64::new(seed);
    let mut picks = Vec::new();
    if !spans.is_empty() {
        picks.push(0);
        for _ in 0..extra {
            picks.push((rng.next_u64() % spans.len() as u64) as usize);
        }
        picks.sort_unstable();
        picks.dedup();
    }
    let mut out = Vec::new();
    for &i in &picks {
        for value in values {
            out.push(Mutant {
                name: format!("{key}#{i}={value}"),
                bytes: splice(bytes, spans[i], value),
            });
        }
    }
    out
}

/// Copies with the little-endian `u32` at each of `offsets` set to each
/// of `values`: for binary headers (a `.glb`'s lengths).
pub fn u32_words(bytes: &[u8], offsets: &[usize], values: &[u32]) -> Vec<Mutant> {
    let mut out = Vec::new();
    for &at in offsets.iter().filter(|&&at| at + 4 <= bytes.len()) {
        for &v in values {
            let mut b = bytes.to_vec();
            b[at..at + 4].copy_from_slice(&v.to_le_bytes());
            out.push(Mutant {
                name: format!("u32@{at}={v}"),
                bytes: b,
            });
        }
    }
    out
}

fn splice(bytes: &[u8], (start, end): (usize, usize), value: &str) -> Vec<u8> {
    let mut b = Vec::with_capacity(bytes.len() + value.len());
    b.extend_from_slice(&bytes[..start]);
    b.extend_from_slice(value.as_bytes());
    b.extend_from_slice(&bytes[end..]);
    b
}

fn is_number_byte(c: u8) -> bool {
    c.is_ascii_digit() || matches!(c, b'.' | b'-' | b'+' | b'e' | b'E')
}

fn number_spans(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            || (matches!(bytes[i], b'-' | b'.')
                && bytes.get(i + 1).is_some_and(|c| c.is_ascii_digit()));
        let in_word = i > 0 && (bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if starts && !in_word {
            let mut end = i + 1;
            while end < bytes.len() && is_number_byte(bytes[end]) {
                end += 1;
            }
            if end == bytes.len() || !(bytes[end].is_ascii_alphabetic() || bytes[end] == b'_') {
                spans.push((i, end));
            }
            i = end;
        } else {
            i += 1;
        }
    }
    spans
}

fn key_value_spans(bytes: &[u8], key: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut from = 0;
    while let Some(pos) = find(&bytes[from..], key) {
        let start = from + pos + key.len();
        let mut end = start;
        while end < bytes.len() && !b"\"',<>[]{} \t\r\n".contains(&bytes[end]) {
            end += 1;
        }
        spans.push((start, end));
        from = start;
    }
    spans
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_found_outside_words() {
        let text = b"v 1 -2.5e3 .5\nname x2 \"count\": 12,";
        let got: Vec<&[u8]> = number_spans(text)
            .into_iter()
            .map(|(a, b)| &text[a..b])
            .collect();
        assert_eq!(got, [&b"1"[..], b"-2.5e3", b".5", b"12"]);
    }

    #[test]
    fn a_keyed_value_is_replaced_up_to_its_delimiter() {
        let m = after_key(b"<a count=\"4\" x/>", "count=\"", &["9"], 0, 1);
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].bytes, b"<a count=\"9\" x/>");
    }

    #[test]
    fn the_same_seed_makes_the_same_mutants() {
        let text = b"1 2 3 4 5 6 7 8 9";
        let a: Vec<_> = numbers(text, &["0"], 3, 7)
            .into_iter()
            .map(|m| m.bytes)
            .collect();
        let b: Vec<_> = numbers(text, &["0"], 3, 7)
            .into_iter()
            .map(|m| m.bytes)
            .collect();
        assert_eq!(a, b);
    }
}
