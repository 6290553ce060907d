//! The statistics the layers share: quantiles, medians and weighted medians, equal-count
//! bins, and the principal axes of a point set. They live at the crate's root because the
//! orientation and the refinement both need them and neither may depend on the other's
//! code.

// The same types as `mesh::Point` and `mesh::Vector`, named here so that the statistics
// sit below the mesh layer that uses them.
type Point = nalgebra::Point3<f64>;
type Vector = nalgebra::Vector3<f64>;

/// The `fraction` quantile of `values`, interpolated linearly between the two nearest
/// ranks (reorders `values` in place).
///
/// By selection, not by sorting: the criteria take a median per section at every
/// evaluation, and only the one or two ranks around the quantile are needed. The
/// value is the same, bit for bit, as from a full sort: `total_cmp` is a total order
/// whose equal elements are identical.
pub fn quantile(values: &mut [f64], fraction: f64) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let position = fraction.clamp(0.0, 1.0) * (values.len() - 1) as f64;
    let (low, high) = (position.floor() as usize, position.ceil() as usize);
    let (_, &mut low_value, above) = values.select_nth_unstable_by(low, f64::total_cmp);
    let high_value = if high == low {
        low_value
    } else {
        // The next rank is the least of the elements selected above `low`.
        above.iter().copied().min_by(f64::total_cmp).expect("high < len, so some element lies above low")
    };
    low_value + (high_value - low_value) * (position - low as f64)
}

/// The value of rank `round((n - 1) * fraction)` of `values` (sorts `values` in place):
/// a quantile that is always one of the values, as the accuracy tables report them; NaN
/// for no values.
pub fn nearest_rank_quantile(values: &mut [f64], fraction: f64) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_unstable_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * fraction.clamp(0.0, 1.0)).round() as usize]
}

/// The values of ranks `n * 2 / 100` and `n * 98 / 100` of the `n` finite `values` (the
/// 2nd and 98th percentiles by rank), `None` for none: the range a tone or colour scale
/// stretches over, a few outliers left out. By selection, the same values as from a sort.
pub fn central_range(values: impl Iterator<Item = f32>) -> Option<(f32, f32)> {
    let mut finite: Vec<f32> = values.filter(|v| v.is_finite()).collect();
    let n = finite.len();
    if n == 0 {
        return None;
    }
    let (low, high) = (n * 2 / 100, (n * 98 / 100).min(n - 1));
    let (below, &mut high_value, _) = finite.select_nth_unstable_by(high, f32::total_cmp);
    // The `high` least values are `below` (or none when `low == high`).
    let low_value = if low == high { high_value } else { *below.select_nth_unstable_by(low, f32::total_cmp).1 };
    Some((low_value, high_value))
}

/// The upper median of `values` (rank `n / 2` of the sorted values: one of the values
/// even for an even count). Panics on no values: callers test for them first.
pub fn upper_median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    sorted[sorted.len() / 2]
}

/// The least-squares line through the `(x, y)` pairs, as `(mean_x, mean_y, slope)`: it
/// runs through the means with slope dy/dx, 0 where the x spread (their summed squared
/// deviations) is at most `min_spread`. `None` for no pairs.
pub fn least_squares_line(pairs: &[(f64, f64)], min_spread: f64) -> Option<(f64, f64, f64)> {
    if pairs.is_empty() {
        return None;
    }
    let n = pairs.len() as f64;
    let mean_x = pairs.iter().map(|p| p.0).sum::<f64>() / n;
    let mean_y = pairs.iter().map(|p| p.1).sum::<f64>() / n;
    let (covariance, spread) =
        pairs.iter().fold((0.0, 0.0), |(c, s), p| (c + (p.0 - mean_x) * (p.1 - mean_y), s + (p.0 - mean_x).powi(2)));
    Some((mean_x, mean_y, if spread > min_spread { covariance / spread } else { 0.0 }))
}

/// For each index of `members`, its bin `0..bins` by rank of `values` (equal counts);
/// other indices get 0.
pub fn equal_count_bins(values: &[f64], members: &[usize], bins: usize) -> Vec<usize> {
    let mut order = members.to_vec();
    order.sort_by(|a, b| values[*a].total_cmp(&values[*b]));
    let mut bin = vec![0; values.len()];
    let m = order.len().max(1);
    for (rank, &i) in order.iter().enumerate() {
        bin[i] = (rank * bins / m).min(bins - 1);
    }
    bin
}

/// The weighted `fraction` quantile of `(value, weight)` pairs: the least value whose
/// cumulative weight (values ascending) reaches `fraction` of the total; NaN for none.
pub fn weighted_quantile(values: impl Iterator<Item = (f64, f64)>, fraction: f64) -> f64 {
    let mut pairs: Vec<(f64, f64)> = values.collect();
    if pairs.is_empty() {
        return f64::NAN;
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let target = pairs.iter().map(|p| p.1).sum::<f64>() * fraction;
    let mut running = 0.0;
    for (v, w) in &pairs {
        running += w;
        if running >= target {
            return *v;
        }
    }
    pairs[pairs.len() - 1].0
}

/// The weighted median of `(value, weight)` pairs ([`weighted_quantile`] at one half).
pub fn weighted_median(values: impl Iterator<Item = (f64, f64)>) -> f64 {
    weighted_quantile(values, 0.5)
}

/// The weighted median of `|values|` over the positive weights (weights need not be
/// normalised); 0 when no weight is positive.
pub fn weighted_median_abs(values: &[f64], weights: &[f64]) -> f64 {
    let pairs = values.iter().zip(weights).filter(|(_, w)| **w > 0.0).map(|(v, w)| (v.abs(), *w));
    let median = weighted_median(pairs);
    if median.is_nan() { 0.0 } else { median }
}

/// The two-sided 95% point of Student's t distribution with `degrees_of_freedom`: what a
/// standard error estimated from that few replicates is multiplied by for a 95% interval
/// (the normal's 1.96 holds only for many). Tabulated to 30 degrees of freedom, the
/// normal's point beyond; `None` for 0.
pub fn student_t_95(degrees_of_freedom: usize) -> Option<f64> {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101,
        2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042,
    ];
    match degrees_of_freedom {
        0 => None,
        d if d <= TABLE.len() => Some(TABLE[d - 1]),
        _ => Some(1.960),
    }
}

/// The principal axes of weighted points: their weighted mean, the eigenvalues of their
/// weighted covariance in ascending order, and the unit eigenvectors in the same order
/// (the first is the normal of their total-least-squares plane). `None` when the weights
/// sum to nothing.
pub fn principal_axes<'a>(points: impl IntoIterator<Item = (&'a Point, f64)> + Clone) -> Option<(Point, [f64; 3], [Vector; 3])> {
    let (sum, weight) = points.clone().into_iter().fold((Vector::zeros(), 0.0), |(sum, total), (p, w)| (sum + w * p.coords, total + w));
    if !(weight > 0.0) {
        return None;
    }
    let mean = sum / weight;
    let covariance = points.into_iter().fold(nalgebra::Matrix3::<f64>::zeros(), |sum, (p, w)| {
        let d = p.coords - mean;
        sum + w * d * d.transpose()
    }) / weight;
    let eigen = covariance.symmetric_eigen();
    let mut order = [0, 1, 2];
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    Some((Point::from(mean), order.map(|i| eigen.eigenvalues[i]), order.map(|i| eigen.eigenvectors.column(i).into_owned())))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantile_by_selection_equals_the_sorted_quantile_bit_for_bit() {
        // Ties, negative zeros, both parities of length, every interpolation position.
        let mut state = 12345u64;
        for length in 1..40 {
            let values: Vec<f64> = (0..length)
                .map(|_| {
                    state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    let v = (((state >> 33) % 17) as f64 - 8.0) * 0.37;
                    if v == 0.0 && state & 1 == 1 { -0.0 } else { v }
                })
                .collect();
            for fraction in [0.0, 0.05, 0.25, 0.5, 0.77, 0.95, 1.0] {
                let mut sorted = values.clone();
                sorted.sort_unstable_by(f64::total_cmp);
                let position = fraction * (length - 1) as f64;
                let (low, high) = (position.floor() as usize, position.ceil() as usize);
                let expected = sorted[low] + (sorted[high] - sorted[low]) * (position - low as f64);
                let found = quantile(&mut values.clone(), fraction);
                assert_eq!(found.to_bits(), expected.to_bits(), "{values:?} at {fraction}");
            }
        }
        assert!(quantile(&mut [], 0.5).is_nan());
    }

    #[test]
    fn central_range_is_the_sorted_ranks() {
        let mut state = 777u64;
        for length in [1usize, 2, 3, 49, 50, 51, 99, 100, 101, 1000, 4321] {
            let values: Vec<f32> = (0..length)
                .map(|i| {
                    state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    match i % 13 {
                        0 => f32::NAN,
                        1 => -0.0,
                        _ => ((state >> 40) % 50) as f32 * 0.25 - 3.0,
                    }
                })
                .collect();
            let mut sorted: Vec<f32> = values.iter().copied().filter(|v| v.is_finite()).collect();
            sorted.sort_by(f32::total_cmp);
            let n = sorted.len();
            let expected = (n > 0).then(|| (sorted[n * 2 / 100].to_bits(), sorted[(n * 98 / 100).min(n - 1)].to_bits()));
            assert_eq!(central_range(values.into_iter()).map(|(l, h)| (l.to_bits(), h.to_bits())), expected, "{length}");
        }
        assert_eq!(central_range([f32::INFINITY, f32::NAN].into_iter()), None);
    }

    #[test]
    fn the_medians_pick_the_documented_ranks() {
        assert_eq!(upper_median(&[3.0, 1.0, 2.0, 4.0]), 3.0);
        assert_eq!(nearest_rank_quantile(&mut [5.0, 1.0, 3.0], 0.5), 3.0);
        assert!(nearest_rank_quantile(&mut [], 0.5).is_nan());
        assert_eq!(weighted_median([(1.0, 1.0), (2.0, 1.0), (10.0, 5.0)].into_iter()), 10.0);
        assert_eq!(weighted_quantile([(1.0, 1.0), (2.0, 1.0), (10.0, 5.0)].into_iter(), 0.25), 2.0);
        assert_eq!(weighted_median_abs(&[-4.0, 1.0, 2.0], &[1.0, 1.0, 0.0]), 1.0);
        assert_eq!(weighted_median_abs(&[1.0], &[0.0]), 0.0);
    }
}
