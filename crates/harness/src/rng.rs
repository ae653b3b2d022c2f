//! A small seeded generator for the report's scenes, the mesh test and the
//! mesh benchmark: the same numbers on every machine, no dependency.

/// SplitMix64 (Steele, Lea, Flood 2014): the state is the seed, advanced by a
/// fixed odd constant; each output is the state mixed by two multiply–xorshift
/// rounds.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`: the top 53 bits.
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }

    /// An index in `0..n` (`n > 0`; the modulo bias is below 2⁻⁴⁰ for the
    /// sizes used here).
    pub fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A uniform random rotation matrix, from a uniform unit quaternion
    /// (rejection sampling in the 4-ball, then normalized).
    pub fn rotation(&mut self) -> [[f64; 3]; 3] {
        let q = loop {
            let q = [0; 4].map(|_| self.range(-1.0, 1.0));
            let n2: f64 = q.iter().map(|x| x * x).sum();
            if n2 > 1e-4 && n2 <= 1.0 {
                let n = n2.sqrt();
                break q.map(|x| x / n);
            }
        };
        let [w, x, y, z] = q;
        [
            [1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y - w * z), 2.0 * (x * z + w * y)],
            [2.0 * (x * y + w * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z - w * x)],
            [2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)],
        ]
    }

    /// Standard normal (Box–Muller).
    pub fn normal(&mut self) -> f64 {
        let u = 1.0 - self.unit();
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * self.unit()).cos()
    }
}
