//! SplitMix64 (Steele, Lea & Flood 2014): the seeded generator of the fuzzing tests
//! (`fuzz_inputs.rs` here, `fuzz_cli.rs` and the in-process parse fuzzing of the CLI's
//! `main.rs`, which include this file by path). `Rng::new(seed, index)` makes every input
//! reproducible from its index, whatever the thread count.
#![allow(dead_code)]

/// The generator's state (`Rng(seed)` starts the plain sequence of `seed`).
pub struct Rng(pub u64);

impl Rng {
    /// The stream of input `index` of a run seeded with `seed`.
    pub fn new(seed: u64, index: u64) -> Self {
        let mut r = Rng(seed ^ index.wrapping_mul(0xA076_1D64_78BD_642F));
        r.next();
        r
    }
    pub fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in 0..n (n > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// True with probability p.
    pub fn chance(&mut self, p: f64) -> bool {
        self.unit() < p
    }
    /// A uniformly chosen element of a non-empty slice.
    pub fn pick<'a, T>(&mut self, v: &'a [T]) -> &'a T {
        &v[self.below(v.len())]
    }
}
