//! Stipple shading (Wilczek et al. 2018, section 2.4.3, Fig. 6): dots placed more densely
//! where the surface is darker. Dots are spread as variable-radius Poisson-disk samples
//! (dart throwing: a candidate is kept only if no kept dot lies within the spacing its
//! tone asks for), which gives blue-noise spacing: even, never clumped, never a grid.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Most dots one view gets. A publication drawing never needs more (a full A4 page at
/// 600 dpi stippled at the default spacing is a few tens of thousands), while fuzzed huge or
/// degenerate meshes asked for millions and made one drawing take 33 s: beyond this the
/// spacing is widened so that the whole view is still shaded evenly, then the count is
/// capped outright.
pub const MAX_STIPPLE_DOTS: usize = 100_000;

/// Dots per square pixel of spacing when dart throwing saturates a tone: random
/// sequential packing of disks fills 0.547 of the plane, so about 0.547 / (pi / 4) = 0.7
/// dots per `spacing^2`.
const SATURATED_DOTS_PER_SPACING_SQUARED: f64 = 0.7;

/// Dot centres in pixel coordinates of a `width x height` tone image (`darkness` in
/// [0, 1], row-major). `spacing_px` is the distance between dots in fully black areas;
/// lighter areas get `spacing_px / sqrt(darkness)`, and areas lighter than
/// `1 - white_cutoff` none. At most [`MAX_STIPPLE_DOTS`] dots: a view that would need more
/// gets a wider spacing. Deterministic for a given `seed`.
pub fn stipple_dots(darkness: &[f32], width: usize, height: usize, spacing_px: f64, seed: u64) -> Vec<[f64; 2]> {
    const WHITE_CUTOFF: f32 = 0.06;
    if width == 0 || height == 0 || spacing_px <= 0.0 || darkness.len() != width * height {
        return Vec::new();
    }
    // Dots closer than one pixel of the view would sample the same tone and only cost
    // time: at very low resolutions (a few dpi) the candidates and the grid grow as the
    // inverse square of the spacing, which made a 10 dpi drawing take 16 s (fuzzing).
    let spacing_px = spacing_px.max(1.0);
    let dark_area: f64 = darkness.iter().map(|&d| d as f64).sum();
    let expected_dots = SATURATED_DOTS_PER_SPACING_SQUARED * dark_area / (spacing_px * spacing_px);
    let spacing_px = spacing_px * (expected_dots / MAX_STIPPLE_DOTS as f64).sqrt().max(1.0);
    let tone_at = |x: f64, y: f64| {
        let (column, row) = ((x as usize).min(width - 1), (y as usize).min(height - 1));
        darkness[row * width + column]
    };
    let max_spacing = spacing_px / (WHITE_CUTOFF as f64).sqrt();
    // Grid of cells of the smallest spacing: a cell holds at most a few dots.
    let cell = spacing_px / std::f64::consts::SQRT_2;
    let (columns, rows) = ((width as f64 / cell).ceil() as usize + 1, (height as f64 / cell).ceil() as usize + 1);
    let mut grid: Vec<Vec<[f64; 2]>> = vec![Vec::new(); columns * rows];
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // Enough candidates to saturate the darkest areas several times over.
    let candidates = ((dark_area / (spacing_px * spacing_px)) * 12.0).ceil() as usize + 16;
    let reach = (max_spacing / cell).ceil() as i64;
    let mut dots = Vec::new();
    for _ in 0..candidates {
        let (x, y) = (rng.random::<f64>() * width as f64, rng.random::<f64>() * height as f64);
        let tone = tone_at(x, y);
        if tone < WHITE_CUTOFF {
            continue;
        }
        let spacing = spacing_px / (tone as f64).sqrt();
        let spacing2 = spacing * spacing;
        let (cx, cy) = ((x / cell) as i64, (y / cell) as i64);
        let reach_here = ((spacing / cell).ceil() as i64).min(reach);
        let mut free = true;
        'search: for gy in (cy - reach_here).max(0)..=(cy + reach_here).min(rows as i64 - 1) {
            for gx in (cx - reach_here).max(0)..=(cx + reach_here).min(columns as i64 - 1) {
                for q in &grid[gy as usize * columns + gx as usize] {
                    if (q[0] - x).powi(2) + (q[1] - y).powi(2) < spacing2 {
                        free = false;
                        break 'search;
                    }
                }
            }
        }
        if free {
            grid[cy as usize * columns + cx as usize].push([x, y]);
            dots.push([x, y]);
            if dots.len() == MAX_STIPPLE_DOTS {
                break;
            }
        }
    }
    dots
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn darker_half_gets_more_dots_and_none_are_too_close() {
        let (width, height) = (200, 100);
        let darkness: Vec<f32> = (0..width * height)
            .map(|i| if i % width < 100 { 0.9 } else { 0.25 })
            .collect();
        let dots = stipple_dots(&darkness, width, height, 3.0, 7);
        let left = dots.iter().filter(|d| d[0] < 100.0).count();
        let right = dots.len() - left;
        // Density goes with darkness (spacing^-2): about 0.9 / 0.25 = 3.6 times more.
        let ratio = left as f64 / right as f64;
        assert!(ratio > 2.5 && ratio < 5.0, "{left} vs {right}");
        // Blue noise: no two dots closer than the darkest spacing.
        let min_spacing = 3.0 / 0.9f64.sqrt();
        for (i, a) in dots.iter().enumerate() {
            for b in &dots[i + 1..] {
                if a[0] < 100.0 && b[0] < 100.0 {
                    assert!((a[0] - b[0]).hypot(a[1] - b[1]) >= min_spacing - 1e-9);
                }
            }
        }
        // Not a grid: the x coordinates do not repeat.
        let mut xs: Vec<i64> = dots.iter().map(|d| (d[0] * 1000.0) as i64).collect();
        xs.sort();
        xs.dedup();
        assert_eq!(xs.len(), dots.len());
        assert!(stipple_dots(&vec![0.0; 100], 10, 10, 2.0, 1).is_empty());
    }

    #[test]
    fn a_huge_dark_view_is_capped_but_shaded_all_over() {
        // 4000 x 4000 pixels all black at one-pixel spacing would be about 11 million dots.
        let (width, height) = (4000, 4000);
        let dots = stipple_dots(&vec![1.0; width * height], width, height, 1.0, 3);
        assert!(dots.len() <= MAX_STIPPLE_DOTS);
        assert!(dots.len() > MAX_STIPPLE_DOTS / 2, "{} dots", dots.len());
        // The widened spacing still covers the whole view: every quarter has its share.
        for (x0, y0) in [(0.0, 0.0), (2000.0, 0.0), (0.0, 2000.0), (2000.0, 2000.0)] {
            let quarter = dots
                .iter()
                .filter(|d| d[0] >= x0 && d[0] < x0 + 2000.0 && d[1] >= y0 && d[1] < y0 + 2000.0)
                .count();
            assert!(
                quarter > dots.len() / 5,
                "{quarter} of {} dots in the quarter at {x0}, {y0}",
                dots.len()
            );
        }
    }
}
