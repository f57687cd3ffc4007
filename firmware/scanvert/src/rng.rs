//! The unit tests' pseudo-random numbers (Marsaglia's xorshift), one
//! generator of each width for every module's tests. Test builds only.

/// xorshift32 (13, 17, 5) from `seed`, which must not be 0: each call the
/// next state.
pub(crate) fn xorshift32(mut seed: u32) -> impl FnMut() -> u32 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 17;
        seed ^= seed << 5;
        seed
    }
}

/// xorshift64 (13, 7, 17) from `seed`, which must not be 0: each call the
/// next state.
pub(crate) fn xorshift64(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}
