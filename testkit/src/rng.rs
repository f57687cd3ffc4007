//! The generators' random numbers: a 64-bit xorshift (shifts 13, 7, 17),
//! so that every scene and workload is the same on every run and every
//! machine.

/// A 64-bit xorshift. The state must not be zero (it would stay zero).
#[derive(Clone, Debug)]
pub struct Rng(pub u64);

impl Rng {
    /// The next state, which is also the number drawn.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A number in `0..n` (`0 < n ≤ 2³¹`), by remainder.
    pub fn below(&mut self, n: u32) -> i32 {
        (self.next_u64() % n as u64) as i32
    }

    /// A number in `lo..hi` (`lo < hi`), by remainder.
    pub fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next_u64() % (hi - lo) as u64) as i32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sequence_is_fixed() {
        let mut r = Rng(1);
        assert_eq!(r.next_u64(), 0x4082_2041);
        let mut r = Rng(0x2545_f491_4f6c_dd1d);
        for _ in 0..1000 {
            let v = r.range(-5, 7);
            assert!((-5..7).contains(&v));
            assert!((0..3).contains(&r.below(3)));
        }
    }
}
