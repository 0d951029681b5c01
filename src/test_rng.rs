//! The unit tests' random numbers: xorshift64* (Vigna, "An experimental exploration of
//! Marsaglia's xorshift generators, scrambled", 2016), seeded, with no external crate. One
//! generator for every unit test, so that a case found by one can be replayed by its seed.
//! (The integration tests, benches and lab are separate crates and keep their own copy.)

use glam::DVec3;

/// A seeded xorshift64* stream. The seed must not be 0 (the stream would stay 0).
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    /// Uniform in [0, 1), 53 bits.
    pub(crate) fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub(crate) fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.unit()
    }

    /// 10^x, x uniform in [a, b).
    pub(crate) fn log(&mut self, a: f64, b: f64) -> f64 {
        10f64.powf(self.range(a, b))
    }

    /// Uniform in 0..n (n > 0).
    pub(crate) fn below(&mut self, n: u32) -> u32 {
        ((self.unit() * n as f64) as u32).min(n - 1)
    }

    /// Uniform in the cube [-half, half)^3.
    pub(crate) fn point(&mut self, half: f64) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit()) * 2.0 * half - half
    }

    /// A unit vector, uniform over the sphere (rejection from the cube).
    pub(crate) fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.unit(), self.unit(), self.unit()) * 2.0 - 1.0;
            if (1e-3..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }
}
