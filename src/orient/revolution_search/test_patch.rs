//! The tests' fragment: both skins of a wall patch of a surface of revolution, as the
//! normal lines the search starts from.

use crate::mesh::{Point, Vector};
use crate::orient::normal_lines::NormalLines;

/// Both skins of a wall patch of a surface of revolution about the z axis through
/// `(ax, ay)`: radius `radius(z)` with slope `slope(z)`, over `arc` radians and `heights`.
pub(super) fn patch(ax: f64, ay: f64, radius: impl Fn(f64) -> f64, slope: impl Fn(f64) -> f64, arc: (f64, f64), heights: (f64, f64)) -> NormalLines {
    let mut lines = NormalLines::default();
    for i in 0..60 {
        for j in 0..40 {
            let t = arc.0 + (arc.1 - arc.0) * i as f64 / 59.0;
            let z = heights.0 + (heights.1 - heights.0) * j as f64 / 39.0;
            for (offset, sign) in [(0.0, 1.0), (-5.0, -1.0)] {
                let r = radius(z) + offset;
                let (c, s) = (t.cos(), t.sin());
                // The outward normal of r(z) is (cos, sin, -r'(z)), normalised.
                let n = Vector::new(c, s, -slope(z)).normalize() * sign;
                lines.push(Point::new(ax + r * c, ay + r * s, z), n, 1.0, lines.len());
            }
        }
    }
    lines
}
