//! The secret every request must carry (`?token=...`).
//!
//! Any page in the user's browser can reach 127.0.0.1; the token, printed
//! only in the URL the user opens, keeps other pages from driving the
//! renderer or reading the scene.

use std::collections::hash_map::RandomState;
use std::hash::{BuildHasher, Hasher};
use std::time::{SystemTime, UNIX_EPOCH};

/// A fresh random token of 32 hexadecimal digits. The randomness is the
/// standard library's per-process hash keys (seeded from the operating
/// system), mixed with the time and the process id.
pub fn new_token() -> String {
    let mut out = String::new();
    for round in 0..2u64 {
        let mut h = RandomState::new().build_hasher();
        h.write_u64(round);
        h.write_u128(
            SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos()),
        );
        h.write_u32(std::process::id());
        out.push_str(&format!("{:016x}", h.finish()));
    }
    out
}

/// Whether a request's query string carries `token`. Compares in time
/// independent of where the first difference is.
pub fn query_has_token(query: Option<&str>, token: &str) -> bool {
    let Some(query) = query else {
        return false;
    };
    query.split('&').any(|pair| match pair.split_once('=') {
        Some(("token", given)) => same_secret(given.as_bytes(), token.as_bytes()),
        _ => false,
    })
}

fn same_secret(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_differ_and_are_hex() {
        let (a, b) = (new_token(), new_token());
        assert_ne!(a, b);
        assert_eq!(a.len(), 32);
        assert!(a.chars().all(|c| c.is_ascii_hexdigit()));
    }

    #[test]
    fn the_query_must_carry_the_exact_token() {
        let t = "abc123";
        assert!(query_has_token(Some("token=abc123"), t));
        assert!(query_has_token(Some("x=1&token=abc123"), t));
        assert!(!query_has_token(Some("token=abc12"), t));
        assert!(!query_has_token(Some("token=abc1234"), t));
        assert!(!query_has_token(Some("tok=abc123"), t));
        assert!(!query_has_token(None, t));
    }
}
