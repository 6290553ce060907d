//! From the vessel frame to a scan: measurement noise on every vertex, a random rigid
//! motion (a scanner puts the sherd anywhere, in any attitude).

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;

use crate::mesh::{Point, Vector};

/// Vertices per independently seeded noise stream: the noise is the same whatever the
/// number of threads.
const NOISE_CHUNK: usize = 4096;

/// Adds Gaussian noise of standard deviation `sigma_mm` to every coordinate.
pub fn add_noise(positions: &mut [Point], sigma_mm: f64, seed: u64) {
    if sigma_mm <= 0.0 {
        return;
    }
    positions.par_chunks_mut(NOISE_CHUNK).enumerate().for_each(|(chunk, points)| {
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ (chunk as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        for p in points {
            for c in p.coords.iter_mut() {
                let n: f64 = rng.sample(StandardNormal);
                *c += sigma_mm * n;
            }
        }
    });
}

/// A uniformly random rotation, and the translation that puts `centroid` at a random
/// point within `spread_mm` of the origin (where a scanner leaves a sherd).
pub fn random_motion(rng: &mut impl Rng, centroid: &Point, spread_mm: f64) -> Isometry3<f64> {
    // A normalised 4D Gaussian vector is a uniformly distributed unit quaternion.
    let rotation = loop {
        let q = Quaternion::new(rng.sample(StandardNormal), rng.sample(StandardNormal), rng.sample(StandardNormal), rng.sample(StandardNormal));
        if q.norm() > 1e-6 {
            break UnitQuaternion::from_quaternion(q);
        }
    };
    let target = Vector::new(
        rng.random_range(-spread_mm..=spread_mm),
        rng.random_range(-spread_mm..=spread_mm),
        rng.random_range(-spread_mm..=spread_mm),
    );
    let translation = target - rotation * centroid.coords;
    Isometry3::from_parts(Translation3::from(translation), rotation)
}
