//! Owen-scrambled, index-shuffled two-dimensional Sobol points.
//!
//! Burley 2020, "Practical Hash-based Owen Scrambling" (JCGT 9(4)): take the
//! first two Sobol dimensions, shuffle the sample index by a nested uniform
//! (Owen) scramble, and Owen-scramble each coordinate, all keyed by hashes.
//! Higher dimensions are "padded": each dimension (or pair) gets its own
//! independent shuffle and scramble, so dimensions are uncorrelated while
//! each one keeps the stratification of a (0, m, 2)-net for every prefix of
//! `2^m` samples.

/// Sobol dimension 0: the van der Corput radical inverse in base 2. The
/// sampler works in reversed bit order, where this is the identity; kept as
/// the reference the tests compare against.
#[cfg(test)]
pub(crate) fn sobol_dim0(index: u32) -> u32 {
    index.reverse_bits()
}

/// Sobol dimension 1, whose generator matrix is Pascal's triangle modulo 2:
/// each direction number is the previous one xor-ed with itself shifted by
/// one bit (primitive polynomial x + 1). The reference for
/// [`sobol_dim1_reversed`], bit by bit.
#[cfg(test)]
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

/// Sobol dimension 1 in bit-reversed coordinates:
/// `sobol_dim1_reversed(i.reverse_bits()) == sobol_dim1(i).reverse_bits()`.
/// The sampler composes scrambles in reversed order, where the Owen scramble
/// is a plain hash, so it needs no bit reversal between the steps.
#[cfg(test)]
pub(crate) fn sobol_dim1_reversed(reversed_index: u32) -> u32 {
    sobol_dim1_reversed_and_reverse(reversed_index).0
}

/// [`sobol_dim1_reversed`] of `r` and `r.reverse_bits()`, from one set of
/// table lookups: each table entry holds a byte's contribution to both (the
/// dimension-1 value in the low half, the reversed byte in the high half).
/// The sampler's 2-D draw needs both of the same value, and a bit reversal
/// costs 17 instructions on x86-64 without a native one.
#[inline(always)]
pub(crate) fn sobol_dim1_reversed_and_reverse(r: u32) -> (u32, u32) {
    let t = &DIM1_REVERSED_TABLES;
    let both = t[0][(r & 255) as usize]
        ^ t[1][((r >> 8) & 255) as usize]
        ^ t[2][((r >> 16) & 255) as usize]
        ^ t[3][(r >> 24) as usize];
    (both as u32, (both >> 32) as u32)
}

/// The generator matrix applied a byte at a time (a bit-by-bit loop has a
/// data-dependent branch per index bit and was the largest cost of sampling
/// in a render profile), with inputs and outputs bit-reversed: bit `b` of
/// the reversed index is bit `31 - b` of the index, and contributes the
/// reversed direction number of that bit. The high half of each entry is
/// the byte's share of the plain bit reversal.
const DIM1_REVERSED_TABLES: [[u64; 256]; 4] = dim1_reversed_tables();

const fn dim1_reversed_tables() -> [[u64; 256]; 4] {
    let mut dirs = [0u32; 32];
    let mut d = 1u32 << 31;
    let mut i = 0;
    while i < 32 {
        dirs[i] = d;
        d ^= d >> 1;
        i += 1;
    }
    let mut t = [[0u64; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut b = 0;
        while b < 256 {
            let mut x = 0u32;
            let mut j = 0;
            while j < 8 {
                if b & (1 << j) != 0 {
                    x ^= dirs[31 - (8 * k + j)].reverse_bits();
                }
                j += 1;
            }
            let reversed = ((b as u32) << (8 * k)).reverse_bits();
            t[k][b] = ((reversed as u64) << 32) | x as u64;
            b += 1;
        }
        k += 1;
    }
    t
}

/// The Laine–Karras hash at the heart of [`owen_scramble`], acting on a
/// bit-reversed value: each output bit depends only on less significant
/// input bits.
#[inline(always)]
pub(crate) fn laine_karras(reversed: u32, seed: u32) -> u32 {
    let mut x = reversed.wrapping_add(seed);
    x ^= x.wrapping_mul(0x6c50_b47c);
    x ^= x.wrapping_mul(0xb82f_1e52);
    x ^= x.wrapping_mul(0xc7af_e638);
    x ^= x.wrapping_mul(0x8d22_f6e6);
    x
}

/// Owen scrambling of a 32-bit binary fraction, keyed by `seed` (the
/// sampler composes [`laine_karras`] directly; this is the reference form).
///
/// In bit-reversed order, adding the seed and xor-ing in even multiples of
/// the value only lets each bit depend on less significant ones; reversed
/// back, each bit is flipped by a function of the bits *above* it, which is
/// the definition of a nested uniform scramble. The multipliers are the ones
/// Burley (2020) tuned for a good avalanche.
#[cfg(test)]
pub(crate) fn owen_scramble(value: u32, seed: u32) -> u32 {
    laine_karras(value.reverse_bits(), seed).reverse_bits()
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
    fn sobol_dim1_is_linear_over_index_bits() {
        // The generator matrix is linear over GF(2): every index is the xor
        // of its set bits' direction numbers, computed here bit by bit.
        let reference = |index: u32| {
            (0..32)
                .filter(|k| index & (1 << k) != 0)
                .fold(0, |acc, k| acc ^ sobol_dim1(1 << k))
        };
        let mut x = 0x9e37_79b9u32;
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            assert_eq!(sobol_dim1(x), reference(x), "index {x:#x}");
        }
        // And the direction numbers follow v_k = v_(k-1) ^ (v_(k-1) >> 1).
        for k in 1..32 {
            let prev = sobol_dim1(1 << (k - 1));
            assert_eq!(sobol_dim1(1 << k), prev ^ (prev >> 1), "direction {k}");
        }
    }

    #[test]
    fn reversed_dimension_1_is_dimension_1_reversed() {
        let mut x = 0x2545_f491u32;
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            assert_eq!(
                sobol_dim1_reversed(x.reverse_bits()),
                sobol_dim1(x).reverse_bits(),
                "index {x:#x}"
            );
        }
    }

    #[test]
    fn one_lookup_gives_dimension_1_and_the_reversal() {
        let mut x = 0x6a09_e667u32;
        for _ in 0..10_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let (d1, rev) = sobol_dim1_reversed_and_reverse(x);
            assert_eq!(d1, sobol_dim1(x.reverse_bits()).reverse_bits(), "{x:#x}");
            assert_eq!(rev, x.reverse_bits(), "{x:#x}");
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
