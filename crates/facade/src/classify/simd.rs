//! Runtime choice of AVX2 + FMA for the two per-pixel kernels of §3.1.3–3.1.4 (the patch
//! projections and the Gaussian log densities). Both kernels are written once, generic over
//! `FMA`; the crate is built for baseline x86-64 (SSE2), so fused multiply-adds and 256-bit
//! registers are only used when the running CPU reports them.

/// Whether the running CPU has AVX2 and FMA (always false off x86-64).
pub fn fma_available() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// acc + a·b, fused when `FMA` (then only call it from code compiled with the `fma` feature:
/// elsewhere `mul_add` is a slow library call).
#[inline(always)]
pub fn madd<const FMA: bool>(acc: f32, a: f32, b: f32) -> f32 {
    if FMA { a.mul_add(b, acc) } else { acc + a * b }
}

/// eˣ for x ≤ 0 (larger x are clamped to 0, x below −87 give ≈ 0), within 1e-6 relative:
/// branch-free, so a loop over lanes vectorises, unlike calls to libm's expf. The classic
/// reduction x = n ln 2 + r, |r| ≤ ½ ln 2, and a degree-6 Taylor polynomial for eʳ.
#[inline(always)]
pub fn exp_nonpositive(x: f32) -> f32 {
    let x = x.clamp(-87.0, 0.0);
    // Round to nearest by the 1.5·2²³ trick: `round` is a library call without SSE4.1.
    const SHIFTER: f32 = 12_582_912.0;
    let n = (x * std::f32::consts::LOG2_E + SHIFTER) - SHIFTER;
    // ln 2 in two parts (Cody–Waite), so n·ln 2 is exact enough for n up to 126.
    let r = (x - n * 0.693_359_4) + n * 2.121_944_4e-4;
    let p = 1.0
        + r * (1.0
            + r * (0.5
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    // 2ⁿ for n in −126..=0, built from its exponent bits.
    p * f32::from_bits(((n as i32 + 127) as u32) << 23)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exp_matches_the_library() {
        for i in 0..=8700 {
            let x = -(i as f32) * 0.01;
            let (got, want) = (exp_nonpositive(x), x.exp());
            assert!(
                (got - want).abs() <= 1e-6 * want + 1e-37,
                "{x}: {got} vs {want}"
            );
        }
        assert_eq!(exp_nonpositive(0.0), 1.0);
        assert!(exp_nonpositive(-1000.0) < 1e-37);
        assert!(exp_nonpositive(f32::NEG_INFINITY) < 1e-37);
    }
}
