//! Surface relief: the slow undulation of a hand-finished pot's surface (finger marks,
//! uneven smoothing, slip runs) that a scanner records and no axis explains. Unlike the
//! noise on every coordinate (the options' `noise_mm`), neighbouring vertices move
//! together, over about a wavelength, so that smoothing a scan does not take it away.
//!
//! The field is a sum of plane waves of random directions, wavelengths and phases (a
//! random-phase approximation of a Gaussian field), fixed in the vessel's frame by the
//! vessel's seed: the fragments of one vessel carry one relief, as sherds of one pot do.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::{Mesh, Vector};

/// Plane waves summed into the field: enough for its values to be near Gaussian.
const WAVES: usize = 32;
/// Mixed into the vessel's seed, so that the waves do not repeat the other draws of it.
const SEED_SALT: u64 = 0x5EED_0F2E_11EF;

/// The relief of a vessel's surface.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Relief {
    /// Standard deviation of the displacement along the normal, mm (0: none).
    pub amplitude_mm: f64,
    /// Typical distance between neighbouring crests, mm.
    pub wavelength_mm: f64,
}

impl Relief {
    /// Whether the relief moves any vertex.
    pub fn is_flat(&self) -> bool {
        !(self.amplitude_mm > 0.0 && self.wavelength_mm > 0.0)
    }
}

/// Moves every vertex of `mesh` (in the vessel's frame) along its normal by the relief
/// field drawn from `seed`.
pub(super) fn add_relief(mesh: &mut Mesh, relief: &Relief, seed: u64) {
    if relief.is_flat() {
        return;
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ SEED_SALT);
    let waves: Vec<(Vector, f64)> = (0..WAVES)
        .map(|_| {
            let direction = loop {
                let v = Vector::new(rng.sample(StandardNormal), rng.sample(StandardNormal), rng.sample(StandardNormal));
                if v.norm() > 1e-6 {
                    break v.normalize();
                }
            };
            let wavelength_mm = relief.wavelength_mm * rng.random_range(0.6..1.6);
            (direction * (std::f64::consts::TAU / wavelength_mm), rng.random_range(0.0..std::f64::consts::TAU))
        })
        .collect();
    // Each cosine has variance 1/2: the sum of WAVES of them, scaled so, has the amplitude
    // as its standard deviation.
    let scale = relief.amplitude_mm * (2.0 / WAVES as f64).sqrt();
    let normals = compute_vertex_normals(mesh, NormalWeighting::Area);
    mesh.positions.par_iter_mut().zip(&normals).for_each(|(p, n)| {
        let height: f64 = waves.iter().map(|(k, phase)| (k.dot(&p.coords) + phase).cos()).sum();
        *p += n * (scale * height);
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{synthetic_sherd, SherdOptions};

    /// The relief moves vertices by about its amplitude, neighbours together, and the same
    /// seed gives the same field.
    #[test]
    fn relief_moves_neighbours_together_by_its_amplitude() {
        let sherd = synthetic_sherd(3, &SherdOptions { random_motion: false, ..SherdOptions::default().ideal() });
        let relief = Relief { amplitude_mm: 0.2, wavelength_mm: 8.0 };
        let mut moved = sherd.mesh.clone();
        add_relief(&mut moved, &relief, 11);
        let shifts: Vec<Vector> = moved.positions.iter().zip(&sherd.mesh.positions).map(|(a, b)| a - b).collect();
        let rms = (shifts.iter().map(|s| s.norm_squared()).sum::<f64>() / shifts.len() as f64).sqrt();
        assert!((0.1..0.3).contains(&rms), "rms shift {rms} mm for an amplitude of 0.2 mm");
        // Across an edge (about a millimetre, an eighth of a wavelength) the shifts differ
        // by much less than they are.
        let mut across = 0.0;
        for t in &sherd.mesh.triangles {
            across += (shifts[t[0] as usize] - shifts[t[1] as usize]).norm_squared();
        }
        let across_rms = (across / sherd.mesh.triangles.len() as f64).sqrt();
        assert!(across_rms < 0.5 * rms, "neighbours differ by {across_rms} mm against {rms} mm");
        let mut again = sherd.mesh.clone();
        add_relief(&mut again, &relief, 11);
        assert_eq!(again.positions, moved.positions);
    }
}
