//! A tiny deterministic noise source: SplitMix64 for uniform bits, Box–Muller for Gaussians.
//!
//! The crate has no random-number dependency and reads no entropy: every stream is a pure
//! function of its seed, so simulated gloves and synthetic calibration users are reproducible
//! bit for bit on every machine.
//!
//! **SplitMix64** (Steele, Lea & Flood 2014; the public-domain reference constants used to
//! seed xoshiro generators): the state advances by the odd constant `φ = 0x9E37_79B9_7F4A_7C15`
//! (2⁶⁴ / golden ratio) and each output is the state passed through a bijective mixer
//!
//! ```text
//! z ← state += φ
//! z ← (z ⊕ (z ≫ 30)) · 0xBF58_476D_1CE4_E5B9
//! z ← (z ⊕ (z ≫ 27)) · 0x94D0_49BB_1331_11EB
//! out = z ⊕ (z ≫ 31)                          (all arithmetic mod 2⁶⁴)
//! ```
//!
//! Its period is 2⁶⁴ and it passes BigCrush; that is plenty for sensor jitter (not for
//! cryptography).
//!
//! **Uniforms**: the top 53 bits scaled by 2⁻⁵³, in `[0, 1)`. **Gaussians** (Box–Muller):
//! from two uniforms `u₁ ∈ (0, 1]`, `u₂ ∈ [0, 1)`, `√(−2 ln u₁) · cos(2π u₂)` is standard
//! normal (the sine partner is discarded, so each Gaussian costs two outputs and the stream
//! has no hidden state beyond the counter).
//!
//! **Keyed streams**: [`SplitMix64::keyed`] derives an independent stream from a seed and a
//! key (for a simulated glove: the frame time's bits), so the noise of a frame depends on
//! `(seed, time)` only, not on which frames were drawn before.

use std::f64::consts::TAU;

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// The SplitMix64 output mixer (a bijection of `u64`).
const fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A SplitMix64 generator (see the module documentation).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator seeded with `seed`.
    pub const fn new(seed: u64) -> SplitMix64 {
        SplitMix64 { state: seed }
    }

    /// An independent stream for `(seed, key)`: the seed combined with the mixed key.
    pub const fn keyed(seed: u64, key: u64) -> SplitMix64 {
        SplitMix64::new(mix64(seed ^ mix64(key.wrapping_add(GOLDEN_GAMMA))))
    }

    /// The next 64 uniform bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        mix64(self.state)
    }

    /// A uniform number in `[0, 1)` with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A standard normal number (mean 0, standard deviation 1), by Box–Muller.
    pub fn next_gaussian(&mut self) -> f64 {
        let u1 = 1.0 - self.next_f64(); // (0, 1]: the logarithm stays finite
        let u2 = self.next_f64();
        (-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_reference_sequence_for_seed_zero() {
        // SplitMix64 from seed 0: the published first outputs of the reference algorithm.
        let mut g = SplitMix64::new(0);
        assert_eq!(g.next_u64(), 0xE220_A839_7B1D_CDAF);
        assert_eq!(g.next_u64(), 0x6E78_9E6A_A1B9_65F4);
        assert_eq!(g.next_u64(), 0x06C4_5D18_8009_454F);
    }

    #[test]
    fn gaussians_have_unit_moments_and_streams_are_reproducible() {
        let mut g = SplitMix64::keyed(42, 7);
        let n = 200_000;
        let xs: Vec<f64> = (0..n).map(|_| g.next_gaussian()).collect();
        let mean = xs.iter().sum::<f64>() / n as f64;
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((var - 1.0).abs() < 0.02, "variance {var}");
        let within_one = xs.iter().filter(|x| x.abs() < 1.0).count() as f64 / n as f64;
        assert!(
            (within_one - 0.6827).abs() < 0.01,
            "P(|x|<1) = {within_one}"
        );
        assert!(xs.iter().all(|x| x.is_finite()));

        let mut again = SplitMix64::keyed(42, 7);
        assert_eq!(again.next_gaussian(), xs[0]);
        assert_ne!(
            SplitMix64::keyed(42, 8).next_u64(),
            SplitMix64::keyed(42, 7).next_u64()
        );
        assert_ne!(
            SplitMix64::keyed(43, 7).next_u64(),
            SplitMix64::keyed(42, 7).next_u64()
        );
    }
}
