//! Barycentric weights of a kept vertex's new place in a face of the collapsed edge: its
//! attributes and texture coordinates are interpolated with them.

use crate::mesh::Vector;

/// Barycentric coordinates of `point` projected on the plane of the triangle `a b c`
/// (uniform weights for a degenerate triangle).
pub(super) fn barycentric(point: &Vector, a: &Vector, b: &Vector, c: &Vector) -> [f64; 3] {
    let (ab, ac, ap) = (b - a, c - a, point - a);
    let (d00, d01, d11) = (ab.dot(&ab), ab.dot(&ac), ac.dot(&ac));
    let (d20, d21) = (ap.dot(&ab), ap.dot(&ac));
    let denominator = d00 * d11 - d01 * d01;
    if !(denominator.abs() > 1e-30 * d00 * d11) {
        return [1.0 / 3.0; 3];
    }
    let beta = (d11 * d20 - d01 * d21) / denominator;
    let gamma = (d00 * d21 - d01 * d20) / denominator;
    [1.0 - beta - gamma, beta, gamma]
}

/// The least of barycentric weights: positive inside the triangle, the further inside
/// the larger.
pub(super) fn least(weights: &[f64; 3]) -> f64 {
    weights.iter().copied().fold(f64::INFINITY, f64::min)
}

/// Barycentric weights moved onto the triangle (negative ones to zero, renormalised).
pub(super) fn clamped_to_triangle(weights: [f64; 3]) -> [f64; 3] {
    let clamped = weights.map(|w| w.max(0.0));
    let sum: f64 = clamped.iter().sum();
    if sum > 0.0 { clamped.map(|w| w / sum) } else { [1.0 / 3.0; 3] }
}
