//! Small deformations of the ideal surface of revolution: real vessels are hand made or
//! thrown and dried unevenly, so their rims are slightly oval and tilted and their walls
//! wobble. Each deformation grows from nothing at the base to its full size at the rim,
//! since the base stands on the wheel and keeps its shape best. The truth axis stays the
//! axis of the undeformed vessel; [`Deformation::bound_mm`] says how far any point moved.

use rand::Rng;
use serde::{Deserialize, Serialize};

use crate::mesh::Point;

/// One wobble component: `amplitude * sin(lobes * theta + phase) * cos(2 pi z / wavelength + vertical_phase)`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WobbleWave {
    /// Radial amplitude, mm.
    pub amplitude_mm: f64,
    /// Number of lobes around the vessel.
    pub lobes: u32,
    /// Angular phase, radians.
    pub phase_rad: f64,
    /// Wavelength along the axis, mm.
    pub vertical_wavelength_mm: f64,
    /// Phase along the axis, radians.
    pub vertical_phase_rad: f64,
}

/// The deformation applied to a vessel (all zero for an ideal surface of revolution).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Deformation {
    /// Relative ovality at the rim: radii scale by `1 + ovality * cos(2 (theta - ovality_angle))`.
    pub ovality: f64,
    /// Direction of the long diameter, radians.
    pub ovality_angle_rad: f64,
    /// Tilt of the rim plane, radians.
    pub rim_tilt_rad: f64,
    /// Direction in which the rim rises, radians.
    pub rim_tilt_azimuth_rad: f64,
    /// Wobble of the wall.
    pub wobble: Vec<WobbleWave>,
    /// Height of the vessel, mm: the deformations reach full size there.
    pub height_mm: f64,
}

impl Deformation {
    /// No deformation at all.
    pub fn none(height_mm: f64) -> Self {
        Deformation {
            ovality: 0.0,
            ovality_angle_rad: 0.0,
            rim_tilt_rad: 0.0,
            rim_tilt_azimuth_rad: 0.0,
            wobble: Vec::new(),
            height_mm,
        }
    }

    /// A random deformation; `scale` 1 gives a carefully thrown vessel (rim ovality up to
    /// 0.6 %, rim tilt up to 0.3 degrees, wobble up to 0.3 mm), 0 none.
    pub fn random(rng: &mut impl Rng, scale: f64, height_mm: f64) -> Self {
        let full_turn = std::f64::consts::TAU;
        let mut deformation = Deformation {
            ovality: scale * rng.random_range(0.0..0.006),
            ovality_angle_rad: rng.random_range(0.0..full_turn),
            rim_tilt_rad: scale * rng.random_range(0.0..0.3f64).to_radians(),
            rim_tilt_azimuth_rad: rng.random_range(0.0..full_turn),
            wobble: Vec::new(),
            height_mm,
        };
        for _ in 0..3 {
            deformation.wobble.push(WobbleWave {
                amplitude_mm: scale * rng.random_range(0.0..0.1),
                lobes: rng.random_range(3..8),
                phase_rad: rng.random_range(0.0..full_turn),
                vertical_wavelength_mm: rng.random_range(30.0..120.0),
                vertical_phase_rad: rng.random_range(0.0..full_turn),
            });
        }
        deformation
    }

    /// The deformed position of the ideal point at angle `theta`, radius `r_mm` and
    /// height `z_mm` (vessel frame: axis on z, standing plane z = 0).
    pub fn apply(&self, theta: f64, r_mm: f64, z_mm: f64) -> Point {
        let growth = (z_mm / self.height_mm).clamp(0.0, 1.0);
        let wobble: f64 = self
            .wobble
            .iter()
            .map(|w| {
                w.amplitude_mm
                    * (w.lobes as f64 * theta + w.phase_rad).sin()
                    * (std::f64::consts::TAU * z_mm / w.vertical_wavelength_mm + w.vertical_phase_rad).cos()
            })
            .sum();
        let radius = r_mm * (1.0 + growth * self.ovality * (2.0 * (theta - self.ovality_angle_rad)).cos())
            + growth * wobble * (r_mm / 10.0).min(1.0);
        let (sin, cos) = theta.sin_cos();
        let (x, y) = (radius * cos, radius * sin);
        let lift = growth * self.rim_tilt_rad.tan() * radius * (theta - self.rim_tilt_azimuth_rad).cos();
        Point::new(x, y, z_mm + lift)
    }

    /// An upper bound of the distance any point within `max_radius_mm` of the axis moves, mm.
    pub fn bound_mm(&self, max_radius_mm: f64) -> f64 {
        let wobble: f64 = self.wobble.iter().map(|w| w.amplitude_mm.abs()).sum();
        let radial = max_radius_mm * self.ovality.abs() + wobble;
        radial + self.rim_tilt_rad.tan().abs() * (max_radius_mm + radial)
    }
}
