//! The pieces every sweep is built from: the parameter grid (ten preferred
//! numbers per decade), a small seeded generator, portable sine and cosine, and
//! the rigid poses a canonical scene is moved by.
//!
//! Portability: as in the case generators, nothing here calls a libm function
//! whose last bit differs between platforms. Grid values are parsed from decimal
//! text (correctly rounded everywhere), sine and cosine are Taylor sums of basic
//! operations, square roots are IEEE's (correctly rounded). The same seed gives
//! the same cases on every machine.

use crate::generate::build::{Scene, Similarity, normalize_or, perpendicular};
use crate::rng::SplitMix64;
use crashtest_core::vec3::{cross, dot, scale, sub};
use oracle::geom::P3;

/// The ten preferred numbers of a decade (Renard's R10 series, ISO 3): each
/// about `10^(1/10)` times the last, so ten points per decade, log-spaced to
/// within 1.5 %, and every grid value prints as a short decimal (`2.5e-9`).
pub const R10: [&str; 10] = ["1", "1.25", "1.6", "2", "2.5", "3.2", "4", "5", "6.3", "8"];

/// One value of a sweep's grid: the number and the text it was parsed from.
#[derive(Clone, Debug, PartialEq)]
pub struct GridValue {
    /// The value (the correctly rounded `f64` of `label`).
    pub value: f64,
    /// Its decimal text, as printed in tables.
    pub label: String,
}

/// The grid from `10^lo` to `10^hi` inclusive, ascending: the R10 numbers of
/// each decade, then `10^hi` itself.
pub fn r10_grid(lo: i32, hi: i32) -> Vec<GridValue> {
    let mut out = Vec::new();
    for k in lo..hi {
        for m in R10 {
            out.push(parse(&format!("{m}e{k}")));
        }
    }
    out.push(parse(&format!("1e{hi}")));
    out
}

fn parse(label: &str) -> GridValue {
    // The labels are built above from literals: they always parse.
    let value = label.parse::<f64>().unwrap_or(f64::NAN);
    let label = label.strip_suffix("e0").unwrap_or(label).to_string();
    GridValue { value, label }
}

/// The sweeps' generator: [`SplitMix64`] (the same on every platform), with
/// the draws the sweeps need; the draws of one pose come from one generator
/// keyed by the seed, the sweep, the query and the pose.
#[derive(Clone, Debug)]
pub struct Rng(SplitMix64);

impl Rng {
    /// A generator keyed by `seed` and a list of words (mixed in one by one).
    pub fn keyed(seed: u64, words: &[u64]) -> Self {
        let mut r = SplitMix64(seed ^ 0x6A09_E667_F3BC_C909);
        for &w in words {
            r.0 ^= w;
            let _ = r.next_u64();
        }
        Rng(r)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Uniform in `[lo, hi)` (53 random bits).
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0.range(lo, hi)
    }

    /// An integer uniform in `[lo, hi]`.
    pub fn int(&mut self, lo: i64, hi: i64) -> i64 {
        let span = (hi - lo + 1) as u64;
        lo + (self.next_u64() % span) as i64
    }

    /// A fair coin.
    pub fn coin(&mut self) -> bool {
        self.next_u64() >> 63 == 1
    }

    /// A unit vector (a normalized point of the cube; `+z` for the rare short
    /// draw).
    pub fn unit(&mut self) -> P3 {
        let v = [self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0)];
        normalize_or(v, [0.0, 0.0, 1.0])
    }

    /// A unit vector in the plane `z = 0`.
    pub fn unit_xy(&mut self) -> P3 {
        let v = [self.uniform(-1.0, 1.0), self.uniform(-1.0, 1.0), 0.0];
        normalize_or(v, [1.0, 0.0, 0.0])
    }

    /// A point of the cube `[-lim, lim)³`.
    pub fn point(&mut self, lim: f64) -> P3 {
        [self.uniform(-lim, lim), self.uniform(-lim, lim), self.uniform(-lim, lim)]
    }
}

/// Sine and cosine of `x`, `|x| ≤ 2`, by their Taylor series summed until the
/// terms vanish (at most 30 terms; accurate to a few ulps). Basic operations
/// only, so every platform gives the same bits.
pub fn sin_cos(x: f64) -> (f64, f64) {
    let (mut s, mut c) = (0.0, 0.0);
    let (mut ts, mut tc) = (x, 1.0);
    let x2 = x * x;
    for k in 0..30 {
        s += ts;
        c += tc;
        let k = k as f64;
        ts *= -x2 / ((2.0 * k + 2.0) * (2.0 * k + 3.0));
        tc *= -x2 / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
        if ts == 0.0 && tc == 0.0 {
            break;
        }
    }
    (s, c)
}

/// The six permutations of three axes.
const PERMUTATIONS: [[usize; 3]; 6] = [[0, 1, 2], [0, 2, 1], [1, 0, 2], [1, 2, 0], [2, 0, 1], [2, 1, 0]];

/// How a pose moves a canonical scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PoseKind {
    /// One of the 48 signed permutations of the axes, nothing else: every
    /// coordinate is moved exactly, so the scene stays exactly at the nominal
    /// parameter (1e-17 from an edge is 1e-17 from it; exactly on stays on).
    Exact,
    /// A random rotation and a translation in `[-4, 4)³`: a generic
    /// orientation, every coordinate rounded once, so the scene is at the
    /// nominal parameter to within about an ulp of its coordinates.
    Rotated,
}

/// A rigid pose: the map, and a random unit direction builders may use.
#[derive(Clone, Copy, Debug)]
pub struct Pose {
    /// Exact or rotated.
    pub kind: PoseKind,
    /// Rows of the rotation (a signed permutation matrix for exact poses).
    pub rot: [P3; 3],
    /// The translation (zero for exact poses).
    pub shift: P3,
}

/// Half the side of the box rotated poses translate into.
pub const POSE_BOX: f64 = 4.0;

impl Pose {
    /// A random pose of `kind` from `rng` (the same number of draws for both
    /// kinds, so a pose index gives the same shapes whichever kind it takes).
    pub fn draw(rng: &mut Rng, kind: PoseKind) -> Self {
        let perm = PERMUTATIONS[rng.int(0, 5) as usize];
        let signs = [rng.coin(), rng.coin(), rng.coin()].map(|neg| if neg { -1.0 } else { 1.0 });
        let (u, w) = (rng.unit(), rng.unit());
        let shift = rng.point(POSE_BOX);
        match kind {
            PoseKind::Exact => {
                let mut rot = [[0.0; 3]; 3];
                for i in 0..3 {
                    rot[i][perm[i]] = signs[i];
                }
                Pose { kind, rot, shift: [0.0; 3] }
            }
            PoseKind::Rotated => {
                let v = normalize_or(sub(w, scale(u, dot(u, w))), perpendicular(u));
                Pose { kind, rot: [u, v, cross(u, v)], shift }
            }
        }
    }

    /// The same pose with another translation.
    pub fn shifted(self, shift: P3) -> Self {
        Pose { shift, ..self }
    }

    /// The image of a point.
    pub fn point(&self, p: P3) -> P3 {
        self.similarity().point(p)
    }

    /// The image of a vector (no translation).
    pub fn vector(&self, v: P3) -> P3 {
        Pose { shift: [0.0; 3], ..*self }.point(v)
    }

    /// The image of a scene (a plane's offset follows its translated point).
    pub fn scene(&self, scene: &Scene) -> Scene {
        self.similarity().scene(scene)
    }

    fn similarity(&self) -> Similarity {
        Similarity { rot: self.rot, scale: 1.0, shift: self.shift }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_has_ten_log_spaced_points_per_decade_and_ends_on_its_decades() {
        let g = r10_grid(-3, 0);
        assert_eq!(g.len(), 31, "3 decades × 10 + the closing 1");
        assert_eq!(g[0].label, "1e-3");
        assert_eq!(g[30].label, "1");
        for w in g.windows(2) {
            let ratio = w[1].value / w[0].value;
            // R10 steps are 10^(1/10) = 1.2589 to within the rounding of the
            // preferred numbers (1.25/1 is the smallest, 1.28 the largest step).
            assert!((1.2..1.3).contains(&ratio), "{} → {}: ratio {ratio}", w[0].label, w[1].label);
        }
    }

    #[test]
    fn sin_cos_matches_the_identity_and_small_angle_limits() {
        /// Taylor sums of a few dozen rounded terms: a few ulps of 1.
        const TRIG_TOL: f64 = 1e-15;
        for x in [1.0, 0.5, 1e-3, 1e-8, 1e-16] {
            let (s, c) = sin_cos(x);
            assert!((s * s + c * c - 1.0).abs() <= TRIG_TOL, "sin² + cos² at {x}");
            assert!(s <= x && s >= x - x * x * x / 6.0 - TRIG_TOL * x, "sin {x} = {s}");
        }
        let (s, c) = sin_cos(1e-16);
        assert_eq!((s.to_bits(), c.to_bits()), (1e-16f64.to_bits(), 1.0f64.to_bits()), "tiny angles are exact");
    }

    #[test]
    fn exact_poses_move_points_without_rounding() {
        let mut rng = Rng::keyed(1, &[2, 3]);
        for _ in 0..48 {
            let pose = Pose::draw(&mut rng, PoseKind::Exact);
            let p = [1e-17, 0.1 + 1e-3, -3.0];
            let q = pose.point(p);
            let mut a: Vec<u64> = p.iter().map(|x| x.abs().to_bits()).collect();
            let mut b: Vec<u64> = q.iter().map(|x| x.abs().to_bits()).collect();
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "a signed permutation only reorders and negates coordinates");
        }
    }

    #[test]
    fn rotated_poses_are_rotations() {
        /// Gram–Schmidt of unit vectors in f64: orthonormal to a few ulps.
        const ORTHO_TOL: f64 = 1e-14;
        let mut rng = Rng::keyed(7, &[]);
        for _ in 0..32 {
            let r = Pose::draw(&mut rng, PoseKind::Rotated).rot;
            for i in 0..3 {
                for j in 0..3 {
                    let want = if i == j { 1.0 } else { 0.0 };
                    assert!((dot(r[i], r[j]) - want).abs() <= ORTHO_TOL, "rows {i}, {j}");
                }
            }
            let det = dot(r[0], cross(r[1], r[2]));
            assert!((det - 1.0).abs() <= ORTHO_TOL, "proper rotation, det {det}");
        }
    }

    #[test]
    fn the_generator_is_keyed_by_every_word() {
        let a = Rng::keyed(5, &[1, 2]).next_u64();
        assert_ne!(a, Rng::keyed(5, &[1, 3]).next_u64());
        assert_ne!(a, Rng::keyed(6, &[1, 2]).next_u64());
        assert_eq!(a, Rng::keyed(5, &[1, 2]).next_u64(), "deterministic");
    }
}
