//! The colour of fired clay, as vertex colours: an oxidised red-brown, a buff or a
//! reduced grey body colour, blotched by firing clouds (slow variations over the vessel,
//! tens of millimetres across), the inside a little darker. It gives the drawing layer's
//! colour style something realistic to show; orientation does not use it.

use rand::Rng;

use super::truth::SurfaceKind;
use crate::mesh::{Point, Vector};

/// A vessel's colouring.
#[derive(Clone, Debug, PartialEq)]
pub struct ClayColour {
    body_rgb: [f64; 3],
    clouds: Vec<(Vector, f64, f64)>,
}

/// Fired-clay body colours (sRGB): oxidised red-brown, orange, buff, reduced grey.
const BODY_COLOURS: [[f64; 3]; 4] = [[168.0, 92.0, 62.0], [196.0, 128.0, 82.0], [205.0, 176.0, 134.0], [96.0, 90.0, 84.0]];

impl ClayColour {
    /// A random clay colour with three firing clouds.
    pub fn random(rng: &mut impl Rng) -> Self {
        let [a, b] = [rng.random_range(0..BODY_COLOURS.len()), rng.random_range(0..BODY_COLOURS.len())];
        let mix: f64 = rng.random_range(0.0..0.4);
        let body_rgb = std::array::from_fn(|k| (1.0 - mix) * BODY_COLOURS[a][k] + mix * BODY_COLOURS[b][k]);
        let clouds = (0..3)
            .map(|_| {
                let direction = Vector::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                let wavelength_mm: f64 = rng.random_range(40.0..150.0);
                let wave = direction.try_normalize(1e-6).unwrap_or_else(Vector::z) * (std::f64::consts::TAU / wavelength_mm);
                (wave, rng.random_range(0.0..std::f64::consts::TAU), rng.random_range(0.03..0.08))
            })
            .collect();
        ClayColour { body_rgb, clouds }
    }

    /// The colour at `point` (vessel frame) of the skin `kind`.
    pub fn at(&self, point: &Point, kind: SurfaceKind) -> [u8; 4] {
        let cloud: f64 = self.clouds.iter().map(|(wave, phase, amplitude)| amplitude * (wave.dot(&point.coords) + phase).sin()).sum();
        let inside = if kind == SurfaceKind::Inner { 0.9 } else { 1.0 };
        let shade = (1.0 + cloud) * inside;
        let [r, g, b] = self.body_rgb.map(|c| (c * shade).round().clamp(0.0, 255.0) as u8);
        [r, g, b, 255]
    }
}
