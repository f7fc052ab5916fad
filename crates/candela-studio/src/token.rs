//! The secret every request must carry (`?token=...`).
//!
//! Any page in the user's browser can reach 127.0.0.1; the token, printed
//! only in the URL the user opens, keeps other pages from driving the
//! renderer or reading the scene.

/// A fresh random token of 32 hexadecimal digits: 128 bits from the
/// operating system's random source (`getrandom`), so nobody can guess it
/// from the time or the process id.
///
/// # Errors
/// When the operating system gives no randomness (the studio then does not
/// start: a guessable token would let any page in).
pub fn new_token() -> Result<String, String> {
    let mut bytes = [0u8; 16];
    getrandom::fill(&mut bytes)
        .map_err(|e| format!("no random token for the studio from the operating system: {e}"))?;
    Ok(bytes.iter().map(|b| format!("{b:02x}")).collect())
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
        let (a, b) = (new_token().unwrap(), new_token().unwrap());
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
