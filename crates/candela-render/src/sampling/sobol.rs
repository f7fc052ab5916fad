//! Owen-scrambled, index-shuffled two-dimensional Sobol points.
//!
//! Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): take the
//! first two Sobol dimensions, shuffle the sample index by a nested uniform
//! (Owen) scramble, and Owen-scramble each coordinate, all keyed by hashes.
//! Higher dimensions are "padded": each dimension (or pair) gets its own
//! independent shuffle and scramble, so dimensions are uncorrelated while
//! each one keeps the stratification of a (0, m, 2)-net for every prefix of
//! `2^m` samples.

/// Sobol dimension 0: the van der Corput radical inverse in base 2.
pub(crate) fn sobol_dim0(index: u32) -> u32 {
    index.reverse_bits()
}

/// Sobol dimension 1, whose generator matrix is Pascal's triangle modulo 2:
/// each direction number is the previous one xor-ed with itself shifted by
/// one bit (primitive polynomial x + 1).
pub(crate) fn sobol_dim1(index: u32) -> u32 {
    let mut direction = 1u32 << 31;
    let mut result = 0;
    let mut rest = index;
    while rest != 0 {
        if rest & 1 != 0 {
            result ^= direction;
        }
        rest >>= 1;
        direction ^= direction >> 1;
    }
    result
}

/// Owen scrambling of a 32-bit binary fraction, keyed by `seed`.
///
/// In bit-reversed order, adding the seed and xor-ing in even multiples of
/// the value only lets each bit depend on less significant ones; reversed
/// back, each bit is flipped by a function of the bits *above* it, which is
/// the definition of a nested uniform scramble. The multipliers are the ones
/// Burley (2020) tuned for a good avalanche.
pub(crate) fn owen_scramble(value: u32, seed: u32) -> u32 {
    let mut x = value.reverse_bits();
    x = x.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x.reverse_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sobol_dim1_matches_known_direction_numbers() {
        // m_k = 1, 3, 5, 15, 17 for the second Sobol dimension.
        let expected = [1u32, 3, 5, 15, 17];
        for (k, m) in expected.iter().enumerate() {
            assert_eq!(sobol_dim1(1 << k), m << (31 - k), "direction {k}");
        }
    }

    #[test]
    fn owen_scramble_is_a_nested_permutation() {
        // Values sharing their top `b` bits must still share them after the
        // scramble, and the scramble must be a bijection on each prefix block.
        let seed = 0x1234_5678;
        for bits in 1..=8u32 {
            let mut seen = vec![false; 1 << bits];
            for prefix in 0..(1u32 << bits) {
                let base = prefix << (32 - bits);
                let a = owen_scramble(base, seed) >> (32 - bits);
                let b = owen_scramble(base | 0x1357, seed) >> (32 - bits);
                assert_eq!(a, b, "prefix {prefix} of {bits} bits");
                assert!(!seen[a as usize], "not a bijection at {bits} bits");
                seen[a as usize] = true;
            }
        }
    }
}
