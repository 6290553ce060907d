//! A noisy piece of a revolved vessel wall for the decimation tests: a sector of a
//! surface of revolution (open, so it has one boundary loop), with radial noise, vertex
//! normals and a colour that encodes height. Deliberately tiny; `sherd::synth` is the
//! real generator.
#![allow(dead_code)] // each test uses part of it

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use sherd::mesh::{Mesh, Point, Vector};

/// Height of the piece, mm.
pub const HEIGHT_MM: f64 = 80.0;
/// Angle of the sector, radians.
pub const SECTOR_RAD: f64 = 2.4;

/// The noise-free radius at height `z_mm`: a bowl-like bulging profile.
pub fn vessel_radius_mm(z_mm: f64) -> f64 {
    60.0 + 25.0 * (0.9 * std::f64::consts::PI * z_mm / HEIGHT_MM).sin() - 0.1 * z_mm
}

/// About `faces` triangles, radial noise uniform in `[-noise_mm, noise_mm]`; red
/// channel = `255 z / HEIGHT_MM`, green = `255 θ / SECTOR_RAD`.
pub fn noisy_vessel(faces: usize, noise_mm: f64, seed: u64) -> Mesh {
    let mut random = ChaCha8Rng::seed_from_u64(seed);
    let rows = ((faces as f64 / 4.2).sqrt().round() as usize).max(2);
    let columns = ((2.1 * rows as f64).round() as usize).max(2);
    let (mut positions, mut normals, mut colors) = (Vec::new(), Vec::new(), Vec::new());
    for row in 0..rows {
        let z = HEIGHT_MM * row as f64 / (rows - 1) as f64;
        let slope = (vessel_radius_mm(z + 1e-4) - vessel_radius_mm(z - 1e-4)) / 2e-4;
        for column in 0..columns {
            let theta = SECTOR_RAD * column as f64 / (columns - 1) as f64;
            let radius = vessel_radius_mm(z) + noise_mm * random.random_range(-1.0..=1.0);
            let (sin, cos) = theta.sin_cos();
            positions.push(Point::new(radius * cos, radius * sin, z));
            normals.push(Vector::new(cos, sin, -slope).normalize());
            colors.push([(255.0 * z / HEIGHT_MM).round() as u8, (255.0 * theta / SECTOR_RAD).round() as u8, 90, 255]);
        }
    }
    let index = |row: usize, column: usize| (row * columns + column) as u32;
    let mut triangles = Vec::new();
    for row in 0..rows - 1 {
        for column in 0..columns - 1 {
            let [a, b, c, d] = [index(row, column), index(row, column + 1), index(row + 1, column + 1), index(row + 1, column)];
            triangles.extend([[a, b, c], [a, c, d]]);
        }
    }
    Mesh { positions, triangles, normals: Some(normals), colors: Some(colors), ..Default::default() }
}
