//! Vertical sections: angular sectors about a candidate axis spanning the preserved arc,
//! which the largest angular gap between the points delimits.

use crate::mesh::Point;

/// Angles per bucket of [`largest_angular_gap`]: a scan's vertices stand in columns a
/// mesh edge apart, far wider than a bucket even at this count, and the buckets of a
/// 100k-vertex scan stay within a core's cache (one per angle, they did not).
const ANGLES_PER_BUCKET: usize = 16;

/// The largest gap between consecutive `angles` (radians, in `[-pi, pi]`) around the
/// circle, and the angle that ends it: the wrap-around gap from the largest angle to the
/// smallest unless a gap between neighbours is strictly larger, the first such in
/// increasing order. The same two numbers, bit for bit, as a scan of the sorted angles.
///
/// Without sorting (the measurements cut a 100k-vertex scan into vertical sections once
/// per bootstrap replicate): the angles go to buckets of equal widths between the least
/// and the greatest, one per [`ANGLES_PER_BUCKET`] angles. A gap inside a bucket is at
/// most its width, so a gap between neighbours wider than a bucket lies between the
/// greatest angle of one non-empty bucket and the least of the next, and bucket order is
/// angle order. Where no gap between buckets is wider than a bucket (few angles, evenly
/// spread), or an angle is not a number, the angles are sorted.
pub(crate) fn largest_angular_gap(angles: &[f64]) -> (f64, f64) {
    let by_sorting = || largest_angular_gap_sorted(angles);
    let count = angles.len();
    if count < 64 || angles.iter().any(|a| a.is_nan()) {
        return by_sorting();
    }
    let low = angles.iter().copied().fold(f64::INFINITY, f64::min);
    let high = angles.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let bucket_count = count.div_ceil(ANGLES_PER_BUCKET);
    let width = (high - low) / bucket_count as f64;
    if !(width > 0.0) {
        return by_sorting();
    }
    // Least and greatest angle per bucket (empty: +inf, -inf).
    let mut buckets = vec![(f64::INFINITY, f64::NEG_INFINITY); bucket_count];
    for &a in angles {
        let bucket = (((a - low) / width) as usize).min(bucket_count - 1);
        let entry = &mut buckets[bucket];
        entry.0 = entry.0.min(a);
        entry.1 = entry.1.max(a);
    }
    let mut start = low;
    let mut largest_gap = low + std::f64::consts::TAU - high;
    let mut widest_between = 0.0f64;
    let mut previous_high: Option<f64> = None;
    for &(least, greatest) in buckets.iter().filter(|b| b.0 <= b.1) {
        if let Some(previous) = previous_high {
            let gap = least - previous;
            widest_between = widest_between.max(gap);
            if gap > largest_gap {
                largest_gap = gap;
                start = least;
            }
        }
        previous_high = Some(greatest);
    }
    // Gaps inside buckets were not looked at: they are at most `width`.
    if widest_between <= width { by_sorting() } else { (start, largest_gap) }
}

/// [`largest_angular_gap`] by a scan of the sorted angles (at least one).
fn largest_angular_gap_sorted(angles: &[f64]) -> (f64, f64) {
    let mut sorted = angles.to_vec();
    sorted.sort_unstable_by(f64::total_cmp);
    let mut start = sorted[0];
    let mut largest_gap = sorted[0] + std::f64::consts::TAU - sorted[sorted.len() - 1];
    for w in sorted.windows(2) {
        if w[1] - w[0] > largest_gap {
            largest_gap = w[1] - w[0];
            start = w[1];
        }
    }
    (start, largest_gap)
}

/// The full turn minus the largest gap between the given angles (radians, within one turn).
pub fn sector_angle_rad(angles: Vec<f64>) -> f64 {
    if angles.len() < 2 {
        return 0.0;
    }
    std::f64::consts::TAU - largest_angular_gap(&angles).1
}

/// Vertical sections (angular sectors about the candidate axis) of the given points:
/// `count` sectors spanning the preserved arc, each the list of indices into `points`.
pub fn vertical_sections(points: &[Point], count: usize) -> Vec<Vec<usize>> {
    if points.is_empty() || count == 0 {
        return Vec::new();
    }
    let angles: Vec<f64> = points.iter().map(|p| p.y.atan2(p.x)).collect();
    // Measure angles from the start of the preserved arc so that the arc does not wrap.
    let (start, largest_gap) = largest_angular_gap(&angles);
    let span = (std::f64::consts::TAU - largest_gap).max(1e-12);
    let mut sections = vec![Vec::new(); count];
    for (i, a) in angles.iter().enumerate() {
        let offset = within_one_turn(a - start);
        let index = ((offset / span * count as f64) as usize).min(count - 1);
        sections[index].push(i);
    }
    sections
}

/// `difference.rem_euclid(TAU)`, bit for bit, without the call to `fmod` it makes: the
/// difference of two angles in `[-pi, pi]` lies within a turn, where the remainder is
/// the difference itself (the measurements cut a 100k-vertex scan into vertical sections
/// once per bootstrap replicate, and `fmod` was a ninth of that).
#[inline]
fn within_one_turn(difference: f64) -> f64 {
    const TURN: f64 = std::f64::consts::TAU;
    let remainder = if difference.abs() < TURN { difference } else { difference % TURN };
    if remainder < 0.0 { remainder + TURN } else { remainder }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn largest_gap_from_buckets_equals_the_sorted_scan_bit_for_bit() {
        use rand::{Rng, SeedableRng};
        let sorted_scan = |angles: &[f64]| {
            let (start, largest) = largest_angular_gap_sorted(angles);
            (start.to_bits(), largest.to_bits())
        };
        let pi = std::f64::consts::PI;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for case in 0..400 {
            let count = [64, 65, 100, 1000, 20_000][case % 5];
            let angles: Vec<f64> = match case % 4 {
                // An arc somewhere on the circle, across the +-pi seam for some.
                0 => {
                    let (from, length) = (rng.random_range(-pi..pi), rng.random_range(0.05..6.0));
                    (0..count).map(|_| (from + rng.random_range(0.0..length) + pi).rem_euclid(2.0 * pi) - pi).collect()
                }
                // The whole circle, evenly: gaps no wider than a bucket (the sorting path).
                1 => (0..count).map(|k| -pi + 2.0 * pi * k as f64 / count as f64).collect(),
                // Few distinct values, many repeated, two clusters.
                2 => (0..count).map(|k| if k % 3 == 0 { 0.25 } else { [1.0, 1.5, -2.0][k % 3] + (k % 7) as f64 * 1e-3 }).collect(),
                // Two arcs with gaps of the same width (ties go to the first).
                _ => (0..count).map(|k| if k % 2 == 0 { -2.0 + (k % 50) as f64 * 0.01 } else { 1.0 + (k % 50) as f64 * 0.01 }).collect(),
            };
            let (start, gap) = largest_angular_gap(&angles);
            assert_eq!((start.to_bits(), gap.to_bits()), sorted_scan(&angles), "case {case}");
        }
    }

    #[test]
    fn within_one_turn_is_rem_euclid_bit_for_bit() {
        let pi = std::f64::consts::PI;
        let tau = std::f64::consts::TAU;
        let special = [0.0, -0.0, pi, -pi, tau, -tau, 2.0 * tau, -7.5, 1e-300, -1e-300, f64::MIN_POSITIVE, f64::INFINITY, f64::NEG_INFINITY, f64::NAN];
        let near_turn = [tau, -tau, pi, -pi].into_iter().flat_map(|v| [f64::from_bits(v.to_bits() - 1), f64::from_bits(v.to_bits() + 1)]);
        let spread = (-4000..4000).map(|k| k as f64 * 0.00314159 * 1.0001);
        for d in special.into_iter().chain(near_turn).chain(spread) {
            assert_eq!(within_one_turn(d).to_bits(), d.rem_euclid(tau).to_bits(), "{d}");
        }
    }

    #[test]
    fn sector_angle_handles_wrap_around() {
        let angles = vec![3.0, -3.0, 3.1, -3.1];
        let sector = sector_angle_rad(angles);
        assert!((sector - (std::f64::consts::TAU - 6.0)).abs() < 1e-12, "{sector}");
    }
}
