//! Four f32 lanes (shared with the renderer's 4-triangle packets): SSE on x86_64 (part of its baseline, so no run-time
//! detection is needed), plain arrays elsewhere. Only what the 4-wide slab
//! test uses. `min`/`max` return the *second* operand when either is NaN,
//! like SSE's `minps`/`maxps`; the slab test relies on that to ignore NaNs.

#[cfg(target_arch = "x86_64")]
#[allow(missing_docs)] // each method is the lane-wise operation its name says
mod imp {
    use std::arch::x86_64::*;

    /// Four lanes in one SSE register.
    #[derive(Clone, Copy, Debug)]
    pub struct F32x4(__m128);

    // SAFETY (every `unsafe` below): SSE and SSE2 are always enabled on
    // x86_64, and the only loads read a whole `&[f32; 4]`.
    impl F32x4 {
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            Self(unsafe { _mm_loadu_ps(a.as_ptr()) })
        }
        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            Self(unsafe { _mm_set1_ps(x) })
        }
        #[inline(always)]
        pub fn lane_sub(self, o: Self) -> Self {
            Self(unsafe { _mm_sub_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub fn lane_mul(self, o: Self) -> Self {
            Self(unsafe { _mm_mul_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub fn min(self, o: Self) -> Self {
            Self(unsafe { _mm_min_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub fn max(self, o: Self) -> Self {
            Self(unsafe { _mm_max_ps(self.0, o.0) })
        }
        #[inline(always)]
        pub fn lane_add(self, o: Self) -> Self {
            Self(unsafe { _mm_add_ps(self.0, o.0) })
        }
        /// Clears the sign bits.
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), self.0) })
        }
        #[inline(always)]
        pub fn lane_div(self, o: Self) -> Self {
            Self(unsafe { _mm_div_ps(self.0, o.0) })
        }
        /// Bit `i` set where lane `i` of `self <= o`.
        #[inline(always)]
        pub fn le_mask(self, o: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmple_ps(self.0, o.0)) as u32 }
        }
        /// Bit `i` set where lane `i` of `self < o`.
        #[inline(always)]
        pub fn lt_mask(self, o: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmplt_ps(self.0, o.0)) as u32 }
        }
        /// Bit `i` set where lane `i` of `self != o` (true for NaN).
        #[inline(always)]
        pub fn ne_mask(self, o: Self) -> u32 {
            unsafe { _mm_movemask_ps(_mm_cmpneq_ps(self.0, o.0)) as u32 }
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            let mut out = [0.0f32; 4];
            unsafe { _mm_storeu_ps(out.as_mut_ptr(), self.0) };
            out
        }
    }
}

#[cfg(not(target_arch = "x86_64"))]
#[allow(missing_docs)]
mod imp {
    /// Four lanes as an array; the compiler vectorises what it can.
    #[derive(Clone, Copy, Debug)]
    pub struct F32x4([f32; 4]);

    impl F32x4 {
        #[inline(always)]
        pub fn load(a: &[f32; 4]) -> Self {
            Self(*a)
        }
        #[inline(always)]
        pub fn splat(x: f32) -> Self {
            Self([x; 4])
        }
        #[inline(always)]
        pub fn lane_sub(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] - o.0[i]))
        }
        #[inline(always)]
        pub fn lane_mul(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] * o.0[i]))
        }
        #[inline(always)]
        pub fn min(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| {
                if self.0[i] < o.0[i] {
                    self.0[i]
                } else {
                    o.0[i]
                }
            }))
        }
        #[inline(always)]
        pub fn max(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| {
                if self.0[i] > o.0[i] {
                    self.0[i]
                } else {
                    o.0[i]
                }
            }))
        }
        #[inline(always)]
        pub fn lane_add(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] + o.0[i]))
        }
        #[inline(always)]
        pub fn abs(self) -> Self {
            Self(self.0.map(f32::abs))
        }
        #[inline(always)]
        pub fn lane_div(self, o: Self) -> Self {
            Self(std::array::from_fn(|i| self.0[i] / o.0[i]))
        }
        #[inline(always)]
        pub fn le_mask(self, o: Self) -> u32 {
            (0..4).fold(0, |m, i| m | (((self.0[i] <= o.0[i]) as u32) << i))
        }
        #[inline(always)]
        pub fn lt_mask(self, o: Self) -> u32 {
            (0..4).fold(0, |m, i| m | (((self.0[i] < o.0[i]) as u32) << i))
        }
        #[inline(always)]
        pub fn ne_mask(self, o: Self) -> u32 {
            (0..4).fold(0, |m, i| m | (((self.0[i] != o.0[i]) as u32) << i))
        }
        #[inline(always)]
        pub fn to_array(self) -> [f32; 4] {
            self.0
        }
    }
}

pub use imp::F32x4;

macro_rules! lane_op {
    ($trait:ident, $method:ident, $lane:ident) => {
        impl std::ops::$trait for F32x4 {
            type Output = F32x4;
            #[inline(always)]
            fn $method(self, o: F32x4) -> F32x4 {
                self.$lane(o)
            }
        }
    };
}
lane_op!(Add, add, lane_add);
lane_op!(Sub, sub, lane_sub);
lane_op!(Mul, mul, lane_mul);
lane_op!(Div, div, lane_div);

/// Hints the CPU to start loading `x` into cache (a node pushed for later).
#[inline(always)]
pub fn prefetch<T>(x: &T) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch never faults and has no visible effect; SSE is baseline.
    unsafe {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        _mm_prefetch::<_MM_HINT_T0>((x as *const T).cast());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = x;
}

#[cfg(test)]
mod tests {
    use super::F32x4;

    #[test]
    fn lanes_and_nan_rules() {
        let a = F32x4::load(&[1.0, f32::NAN, 3.0, -1.0]);
        let b = F32x4::splat(2.0);
        assert_eq!(a.min(b).to_array()[..1], [1.0]);
        assert_eq!(a.min(b).to_array()[1], 2.0, "NaN yields the second operand");
        assert_eq!(a.max(b).to_array()[1], 2.0);
        assert_eq!(a.le_mask(b), 0b1001);
        assert_eq!(((a - b) * b).to_array()[2], 2.0);
        assert_eq!(((a + b) / b).to_array()[0], 1.5);
        assert_eq!(a.lt_mask(b), 0b1001);
        assert_eq!(a.ne_mask(F32x4::splat(3.0)), 0b1011);
        let signs = F32x4::load(&[-1.5, 0.0, -0.0, 2.0]).abs().to_array();
        assert_eq!(
            signs.map(f32::to_bits),
            [1.5f32, 0.0, 0.0, 2.0].map(f32::to_bits)
        );
    }
}
