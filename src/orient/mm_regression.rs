//! The pieces of the MM-estimator (Yohai 1987, "High breakdown-point and high efficiency
//! robust estimates for regression"), as the paper uses it for the axis point (section
//! 2.2.2, "very robust linear regression"): a high-breakdown S-estimate of the residual
//! scale (Tukey biweight, `c = 1.547`, breakdown 50%), then an M-estimate with that scale
//! held fixed (Tukey biweight, `c = 4.685`, 95% efficiency at the normal), computed by
//! iteratively reweighted least squares.

use crate::statistics::weighted_median_abs;

/// Tuning constant of the S-scale (50% breakdown).
pub const S_SCALE_TUNING: f64 = 1.547;
/// Tuning constant of the M-step (95% Gaussian efficiency).
pub const M_STEP_TUNING: f64 = 4.685;

/// Tukey's biweight loss, normalised to 1 beyond `c`.
pub fn tukey_rho(t: f64, c: f64) -> f64 {
    let u = t / c;
    if u.abs() >= 1.0 {
        1.0
    } else {
        let v = 1.0 - u * u;
        1.0 - v * v * v
    }
}

/// Tukey's biweight IRLS weight `ψ(t)/t` (up to a constant).
pub fn tukey_weight(t: f64, c: f64) -> f64 {
    let u = t / c;
    if u.abs() >= 1.0 {
        0.0
    } else {
        let v = 1.0 - u * u;
        v * v
    }
}

/// The M-scale of the residuals: the `s` solving `Σ w ρ(r/s) = ½ Σ w` with Tukey's
/// biweight at `c = 1.547`, started from the normalised median absolute residual.
/// Minimising it over candidate fits is the S-estimator.
pub fn m_scale(residuals: &[f64], weights: &[f64]) -> f64 {
    let total: f64 = weights.iter().sum();
    let mut scale = 1.4826 * weighted_median_abs(residuals, weights);
    if !(scale > 0.0) || !(total > 0.0) {
        return scale.max(0.0);
    }
    for _ in 0..30 {
        let mean_rho: f64 =
            residuals.iter().zip(weights).map(|(r, w)| w * tukey_rho(r / scale, S_SCALE_TUNING)).sum::<f64>() / total;
        let next = scale * (mean_rho / 0.5).sqrt();
        if !(next > 0.0) {
            break;
        }
        let converged = ((next - scale) / scale).abs() < 1e-6;
        scale = next;
        if converged {
            break;
        }
    }
    scale
}

/// The M-step weights for residuals at a fixed scale.
pub fn m_step_weights(residuals: &[f64], scale: f64) -> Vec<f64> {
    if !(scale > 0.0) {
        return vec![1.0; residuals.len()];
    }
    residuals.iter().map(|r| tukey_weight(r / scale, M_STEP_TUNING)).collect()
}

/// The MM objective: mean biweight loss at the fixed scale (comparable between fits
/// that share the scale).
pub fn m_step_cost(residuals: &[f64], weights: &[f64], scale: f64) -> f64 {
    let total: f64 = weights.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    residuals.iter().zip(weights).map(|(r, w)| w * tukey_rho(r / scale, M_STEP_TUNING)).sum::<f64>() / total
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale_of_gaussian_like_residuals_ignores_a_third_of_outliers() {
        // Deterministic pseudo-normal residuals (sum of uniforms), sigma about 1.
        let mut state = 12345u64;
        let mut uniform = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut residuals: Vec<f64> = (0..3000).map(|_| (0..12).map(|_| uniform()).sum::<f64>() - 6.0).collect();
        for r in residuals.iter_mut().take(1000) {
            *r = 50.0 + *r;
        }
        let weights = vec![1.0; residuals.len()];
        let scale = m_scale(&residuals, &weights);
        // With a third outliers the S-scale is inflated but stays of the order of sigma.
        assert!(scale > 0.8 && scale < 3.0, "scale {scale}");
        let w = m_step_weights(&residuals, scale);
        assert!(w[..1000].iter().all(|&x| x == 0.0));
        assert!(w[1000..].iter().filter(|&&x| x > 0.5).count() > 1500);
    }
}
