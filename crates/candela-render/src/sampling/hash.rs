//! Integer mixing shared by the samplers.

/// Golden-ratio increment: consecutive inputs land far apart before mixing.
pub(crate) const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// A 64-bit bijective finaliser (the SplitMix64 output function, Stafford's
/// "Mix13" constants): every input bit affects every output bit, so nearby
/// inputs (pixel (3, 4) and (4, 3), dimension 7 and 8) give unrelated outputs.
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hash of a seed and a pixel; the starting point of every per-pixel stream.
pub(crate) fn pixel_hash(seed: u64, px: u32, py: u32) -> u64 {
    mix64(mix64(seed.wrapping_add(GOLDEN)) ^ (u64::from(px) | (u64::from(py) << 32)))
}

/// Hash of a parent hash and one more 32-bit key (a sample index or a dimension).
pub(crate) fn combine(parent: u64, key: u32) -> u64 {
    mix64(parent ^ (u64::from(key).wrapping_add(1)).wrapping_mul(GOLDEN))
}

/// The top 24 bits of `bits` as a float in [0, 1).
///
/// 24 bits is exactly what an `f32` mantissa holds, so the conversion is exact
/// and the largest result is `1 - 2^-24`, never 1 (rounding a full 32-bit
/// value could give 1.0 and break `floor(u * n) < n` in callers).
pub(crate) fn unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_f32_stays_below_one() {
        assert_eq!(unit_f32(u32::MAX), 1.0 - 2f32.powi(-24));
        assert!(unit_f32(u32::MAX) < 1.0);
        assert_eq!(unit_f32(0), 0.0);
    }

    #[test]
    fn pixel_hash_separates_transposed_pixels_and_seeds() {
        assert_ne!(pixel_hash(0, 3, 4), pixel_hash(0, 4, 3));
        assert_ne!(pixel_hash(0, 1, 0), pixel_hash(1, 0, 0));
        assert_ne!(combine(5, 0), combine(5, 1));
    }
}
