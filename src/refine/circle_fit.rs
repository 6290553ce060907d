//! Circle fitting in the plane after N. Chernov, "Circular and Linear Regression:
//! Fitting Circles and Lines by Least Squares" (CRC, 2010): the algebraic fits of Kåsa,
//! Pratt and Taubin (chapter 5; Pratt and Taubin by Newton's method on the
//! characteristic polynomial of the centred moments, chapter 5.7-5.10), and the
//! geometric fit (chapter 4) by Levenberg-Marquardt started from the Taubin circle.
//!
//! Horizontal sections of a sherd are short arcs (often 10-40 degrees), where Kåsa's fit
//! is biased towards small radii; Taubin's is nearly unbiased and is the start the
//! geometric fit needs to converge on such arcs.

use crate::mesh::planar_length;

/// A circle in the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    /// Centre `[x, y]`, millimetres.
    pub center: [f64; 2],
    /// Radius, millimetres.
    pub radius_mm: f64,
}

impl Circle {
    /// Geometric distance of `p` to the circle (signed: positive outside).
    pub fn signed_distance(&self, p: [f64; 2]) -> f64 {
        planar_length(p[0] - self.center[0], p[1] - self.center[1]) - self.radius_mm
    }

    /// Root mean square geometric distance of the points to the circle.
    pub fn rms_residual_mm(&self, points: &[[f64; 2]]) -> f64 {
        if points.is_empty() {
            return 0.0;
        }
        (points.iter().map(|&p| self.signed_distance(p).powi(2)).sum::<f64>() / points.len() as f64).sqrt()
    }
}

crate::vocabulary! {
    /// Which circle fit to use.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
    pub enum CircleFitMethod: "circle fit", "circle fits" {
        /// Kåsa: linear least squares on `x^2 + y^2 + Dx + Ey + F = 0`; fast, biased on short arcs.
        Kasa = "kasa" => "Algebraic fit, biased towards small circles on short arcs",
        /// Pratt: algebraic fit with the constraint `B^2 + C^2 - 4AD = 1`.
        Pratt = "pratt" => "Algebraic fit",
        /// Taubin: algebraic fit with the gradient-weighted constraint; nearly unbiased.
        Taubin = "taubin" => "Algebraic fit, nearly unbiased on short arcs",
        /// Geometric: minimises the sum of squared orthogonal distances (started from Taubin).
        Geometric = "geometric" => "Least-squares distances, from Taubin's circle",
    }
}

/// Centred second and third moments Chernov's algebraic fits work on.
struct Moments {
    mean: [f64; 2],
    xx: f64,
    yy: f64,
    xy: f64,
    xz: f64,
    yz: f64,
    zz: f64,
}

impl Moments {
    fn of(points: &[[f64; 2]]) -> Moments {
        let n = points.len() as f64;
        let mean = [points.iter().map(|p| p[0]).sum::<f64>() / n, points.iter().map(|p| p[1]).sum::<f64>() / n];
        let mut m = Moments { mean, xx: 0.0, yy: 0.0, xy: 0.0, xz: 0.0, yz: 0.0, zz: 0.0 };
        for p in points {
            let (x, y) = (p[0] - mean[0], p[1] - mean[1]);
            let z = x * x + y * y;
            m.xx += x * x;
            m.yy += y * y;
            m.xy += x * y;
            m.xz += x * z;
            m.yz += y * z;
            m.zz += z * z;
        }
        for v in [&mut m.xx, &mut m.yy, &mut m.xy, &mut m.xz, &mut m.yz, &mut m.zz] {
            *v /= n;
        }
        m
    }

    /// The circle for the root `eta` of the characteristic polynomial.
    fn circle_for_root(&self, eta: f64) -> Option<Circle> {
        let covariance = self.xx * self.yy - self.xy * self.xy;
        let mz = self.xx + self.yy;
        let determinant = eta * eta - eta * mz + covariance;
        if determinant.abs() < 1e-300 {
            return None;
        }
        let cx = (self.xz * (self.yy - eta) - self.yz * self.xy) / determinant / 2.0;
        let cy = (self.yz * (self.xx - eta) - self.xz * self.xy) / determinant / 2.0;
        let radius = (cx * cx + cy * cy + mz).sqrt();
        let circle = Circle { center: [cx + self.mean[0], cy + self.mean[1]], radius_mm: radius };
        (circle.center.iter().all(|c| c.is_finite()) && radius.is_finite()).then_some(circle)
    }

    /// Newton's method from 0 on the cubic (Taubin) or quartic (Pratt) characteristic
    /// polynomial; it converges monotonically to the smallest non-negative root.
    fn newton_root(polynomial: impl Fn(f64) -> (f64, f64), start_value: f64) -> f64 {
        let (mut x, mut y) = (0.0, start_value);
        for _ in 0..99 {
            let (_, derivative) = polynomial(x);
            let next = x - y / derivative;
            if next == x || !next.is_finite() {
                break;
            }
            let (next_value, _) = polynomial(next);
            if next_value.abs() >= y.abs() {
                break;
            }
            x = next;
            y = next_value;
        }
        x
    }
}

/// Kåsa's fit: least squares on the algebraic distance `x^2 + y^2 + Dx + Ey + F`.
pub fn fit_kasa(points: &[[f64; 2]]) -> Option<Circle> {
    if points.len() < 3 {
        return None;
    }
    let m = Moments::of(points);
    // In centred coordinates the normal equations for (D, E) decouple from F.
    let matrix = nalgebra::Matrix2::new(m.xx, m.xy, m.xy, m.yy);
    let solution = matrix.try_inverse()? * nalgebra::Vector2::new(-m.xz, -m.yz);
    let (cx, cy) = (-solution[0] / 2.0, -solution[1] / 2.0);
    let mz = m.xx + m.yy;
    let radius = (cx * cx + cy * cy + mz).sqrt();
    let circle = Circle { center: [cx + m.mean[0], cy + m.mean[1]], radius_mm: radius };
    (circle.center.iter().all(|c| c.is_finite()) && radius.is_finite()).then_some(circle)
}

/// The coefficients shared by the Taubin and Pratt characteristic polynomials:
/// `(Mz, Cov_xy, a1, a0)` in Chernov's notation.
fn shared_coefficients(m: &Moments) -> (f64, f64, f64, f64) {
    let mz = m.xx + m.yy;
    let covariance = m.xx * m.yy - m.xy * m.xy;
    let variance_z = m.zz - mz * mz;
    let a1 = variance_z * mz + 4.0 * covariance * mz - m.xz * m.xz - m.yz * m.yz;
    let a0 = m.xz * (m.xz * m.yy - m.yz * m.xy) + m.yz * (m.yz * m.xx - m.xz * m.xy) - variance_z * covariance;
    (mz, covariance, a1, a0)
}

/// Taubin's fit by Newton's method on its cubic characteristic polynomial (Chernov 2010, 5.10).
pub fn fit_taubin(points: &[[f64; 2]]) -> Option<Circle> {
    if points.len() < 3 {
        return None;
    }
    let m = Moments::of(points);
    let (mz, _, a1, a0) = shared_coefficients(&m);
    let a3 = 4.0 * mz;
    let a2 = -3.0 * mz * mz - m.zz;
    let polynomial = |x: f64| (a0 + x * (a1 + x * (a2 + x * a3)), a1 + x * (2.0 * a2 + 3.0 * a3 * x));
    m.circle_for_root(Moments::newton_root(polynomial, a0))
}

/// Pratt's fit by Newton's method on its quartic characteristic polynomial (Chernov 2010, 5.8).
pub fn fit_pratt(points: &[[f64; 2]]) -> Option<Circle> {
    if points.len() < 3 {
        return None;
    }
    let m = Moments::of(points);
    let (mz, covariance, a1, a0) = shared_coefficients(&m);
    let a2 = 4.0 * covariance - 3.0 * mz * mz - m.zz;
    let polynomial = |x: f64| (a0 + x * (a1 + x * (a2 + 4.0 * x * x)), a1 + x * (2.0 * a2 + 16.0 * x * x));
    let center = m.circle_for_root(Moments::newton_root(polynomial, a0))?.center;
    // Pratt's radius follows from its constraint; the mean distance to the centre is
    // the same for exact data and more robust when the root is poorly conditioned.
    let radius = points.iter().map(|p| planar_length(p[0] - center[0], p[1] - center[1])).sum::<f64>() / points.len() as f64;
    radius.is_finite().then_some(Circle { center, radius_mm: radius })
}

/// The geometric (orthogonal distance) fit by Levenberg-Marquardt from `start`.
pub fn refine_geometric(points: &[[f64; 2]], start: Circle) -> Circle {
    let cost = |c: &Circle| points.iter().map(|&p| c.signed_distance(p).powi(2)).sum::<f64>();
    let mut circle = start;
    let mut current = cost(&circle);
    let mut lambda = 1e-3;
    for _ in 0..50 {
        // Normal equations of the residual d_i = |p_i - c| - R in (cx, cy, R).
        let mut jtj = nalgebra::Matrix3::<f64>::zeros();
        let mut jtr = nalgebra::Vector3::<f64>::zeros();
        for p in points {
            let (dx, dy) = (p[0] - circle.center[0], p[1] - circle.center[1]);
            let distance = planar_length(dx, dy);
            if distance < 1e-12 {
                continue;
            }
            let jacobian = nalgebra::Vector3::new(-dx / distance, -dy / distance, -1.0);
            let residual = distance - circle.radius_mm;
            jtj += jacobian * jacobian.transpose();
            jtr += jacobian * residual;
        }
        let mut improved = false;
        for _ in 0..10 {
            let mut damped = jtj;
            for i in 0..3 {
                damped[(i, i)] *= 1.0 + lambda;
            }
            let Some(step) = damped.cholesky().map(|c| c.solve(&(-jtr))) else {
                lambda *= 10.0;
                continue;
            };
            let candidate = Circle {
                center: [circle.center[0] + step[0], circle.center[1] + step[1]],
                radius_mm: circle.radius_mm + step[2],
            };
            let candidate_cost = cost(&candidate);
            if candidate_cost.is_finite() && candidate_cost <= current {
                let relative_change = (current - candidate_cost) / current.max(1e-300);
                circle = candidate;
                current = candidate_cost;
                lambda = (lambda / 10.0).max(1e-12);
                improved = relative_change > 1e-12;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    circle
}

/// Fits a circle by `method`; `None` for fewer than three points or collinear points.
pub fn fit_circle(points: &[[f64; 2]], method: CircleFitMethod) -> Option<Circle> {
    match method {
        CircleFitMethod::Kasa => fit_kasa(points),
        CircleFitMethod::Pratt => fit_pratt(points),
        CircleFitMethod::Taubin => fit_taubin(points),
        CircleFitMethod::Geometric => fit_taubin(points).map(|start| refine_geometric(points, start)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    fn arc(center: [f64; 2], radius: f64, from_deg: f64, span_deg: f64, n: usize, noise: f64, seed: u64) -> Vec<[f64; 2]> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, noise.max(1e-300)).unwrap();
        (0..n)
            .map(|i| {
                let a = (from_deg + span_deg * i as f64 / (n - 1) as f64).to_radians();
                let r = radius + if noise > 0.0 { normal.sample(&mut rng) } else { 0.0 };
                [center[0] + r * a.cos(), center[1] + r * a.sin()]
            })
            .collect()
    }

    #[test]
    fn every_method_recovers_an_exact_short_arc() {
        let points = arc([12.0, -40.0], 95.0, 30.0, 15.0, 40, 0.0, 1);
        for method in [CircleFitMethod::Kasa, CircleFitMethod::Pratt, CircleFitMethod::Taubin, CircleFitMethod::Geometric] {
            let c = fit_circle(&points, method).unwrap();
            assert!((c.center[0] - 12.0).abs() < 1e-5 && (c.center[1] + 40.0).abs() < 1e-5, "{method:?}: {c:?}");
            assert!((c.radius_mm - 95.0).abs() < 1e-5, "{method:?}: {c:?}");
        }
    }

    #[test]
    fn geometric_fit_is_less_biased_than_kasa_on_noisy_short_arcs() {
        let (mut kasa_error, mut geometric_error) = (0.0, 0.0);
        for seed in 0..40 {
            let points = arc([0.0, 0.0], 80.0, 0.0, 25.0, 60, 0.3, seed);
            kasa_error += fit_kasa(&points).unwrap().radius_mm - 80.0;
            geometric_error += fit_circle(&points, CircleFitMethod::Geometric).unwrap().radius_mm - 80.0;
        }
        assert!(kasa_error / 40.0 < -1.0, "Kåsa should shrink short noisy arcs, mean error {}", kasa_error / 40.0);
        assert!(geometric_error.abs() < kasa_error.abs() / 3.0, "geometric {geometric_error} vs Kåsa {kasa_error}");
    }

    #[test]
    fn degenerate_input_gives_none() {
        assert!(fit_circle(&[[0.0, 0.0], [1.0, 1.0]], CircleFitMethod::Taubin).is_none());
        let line: Vec<[f64; 2]> = (0..10).map(|i| [i as f64, 2.0 * i as f64]).collect();
        let c = fit_kasa(&line);
        assert!(c.is_none() || c.unwrap().radius_mm > 1e6);
    }
}
