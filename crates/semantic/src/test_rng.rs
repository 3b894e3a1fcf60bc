//! A small xorshift generator for the unit tests' random inputs: fixed seeds, so the inputs
//! never change from run to run or machine to machine.

/// Uniform numbers in `[0, 1)` from a xorshift64 state.
pub(crate) struct TestRng(u64);

impl TestRng {
    /// A generator from `seed` (any value: a zero state is avoided).
    pub fn new(seed: u64) -> TestRng {
        TestRng(seed | 1)
    }

    /// The next number in `[0, 1)` (53 bits).
    pub fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in `[0, 1)` as an `f32`.
    pub fn next_f32(&mut self) -> f32 {
        (self.next_f64() as f32).min(1.0 - f32::EPSILON)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_uniform_in_the_unit_interval() {
        let mut r = TestRng::new(7);
        let v: Vec<f64> = (0..10_000).map(|_| r.next_f64()).collect();
        assert!(v.iter().all(|x| (0.0..1.0).contains(x)));
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        assert!((mean - 0.5).abs() < 0.02, "{mean}");
        assert!(v.iter().filter(|&&x| x < 0.1).count() > 900);
    }
}
