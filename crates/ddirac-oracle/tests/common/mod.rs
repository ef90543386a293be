//! Helpers shared by the oracle's integration tests.

/// Deterministic pseudo-random numbers in [−1, 1).
pub fn sampler(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}
