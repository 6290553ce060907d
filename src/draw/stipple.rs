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
    let mut grid = DotGrid::new(width, height, spacing_px);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // Enough candidates to saturate the darkest areas several times over.
    let candidates = ((dark_area / (spacing_px * spacing_px)) * 12.0).ceil() as usize + 16;
    let reach = (max_spacing / grid.cell).ceil() as i64;
    // Candidates are thrown tile by tile, each tile its share of them in random order: the
    // tone image and the grid are read where the last candidates read them, instead of at
    // random over a view of millions of pixels (cache misses were most of the time). Every
    // pair of dots is still checked, so the spacing holds across tile borders. White tiles
    // get none: a small dark patch in a large white view gets all the candidates.
    let tiles: Vec<(usize, usize, f64, f64)> = (0..height.div_ceil(TILE_PX))
        .flat_map(|ty| (0..width.div_ceil(TILE_PX)).map(move |tx| (tx * TILE_PX, ty * TILE_PX)))
        .filter(|&(x0, y0)| {
            (y0..(y0 + TILE_PX).min(height)).any(|y| darkness[y * width + x0..y * width + (x0 + TILE_PX).min(width)].iter().any(|&d| d >= WHITE_CUTOFF))
        })
        .map(|(x0, y0)| (x0, y0, (width - x0).min(TILE_PX) as f64, (height - y0).min(TILE_PX) as f64))
        .collect();
    let shaded_area: f64 = tiles.iter().map(|t| t.2 * t.3).sum();
    for (x0, y0, tile_width, tile_height) in tiles {
        let share = candidates as f64 * tile_width * tile_height / shaded_area;
        // Stochastic rounding keeps every tile's expected count exact.
        let count = share.floor() as usize + usize::from(rng.random::<f64>() < share.fract());
        for _ in 0..count {
            let (x, y) = (x0 as f64 + rng.random::<f64>() * tile_width, y0 as f64 + rng.random::<f64>() * tile_height);
            let tone = tone_at(x, y);
            if tone < WHITE_CUTOFF {
                continue;
            }
            let spacing = spacing_px / (tone as f64).sqrt();
            if grid.is_free(x, y, spacing, reach) {
                grid.insert(x, y);
                if grid.dots.len() == MAX_STIPPLE_DOTS {
                    return grid.dots;
                }
            }
        }
    }
    grid.dots
}

/// Side of the tiles candidates are thrown in, pixels.
const TILE_PX: usize = 64;

/// Marks an empty cell or the end of a cell's list.
const NO_DOT: u32 = u32::MAX;

/// Most cells of the search grid (16 MB of list heads): views are up to 50 million
/// pixels, and a cell per half-pixel of such a view would take gigabytes.
const MAX_GRID_CELLS: usize = 4_000_000;

/// The dots placed so far, found by cell: cells of the smallest spacing, so that a cell
/// holds at most one dot (unless the view is so large and so sparsely shaded that they
/// would outnumber [`MAX_GRID_CELLS`]). Each cell is the head of a list of its dots, in
/// flat arrays rather than a vector per cell: an empty cell costs 4 bytes and the search
/// reads neighbouring cells in order.
struct DotGrid {
    cell: f64,
    columns: usize,
    rows: usize,
    first_in_cell: Vec<u32>,
    next_in_cell: Vec<u32>,
    dots: Vec<[f64; 2]>,
}

impl DotGrid {
    fn new(width: usize, height: usize, spacing_px: f64) -> Self {
        let area = width as f64 * height as f64;
        let cell = (spacing_px / std::f64::consts::SQRT_2).max((area / MAX_GRID_CELLS as f64).sqrt());
        let (columns, rows) = ((width as f64 / cell).ceil() as usize + 1, (height as f64 / cell).ceil() as usize + 1);
        DotGrid { cell, columns, rows, first_in_cell: vec![NO_DOT; columns * rows], next_in_cell: Vec::new(), dots: Vec::new() }
    }

    /// True when no dot lies within `spacing` of `(x, y)`, searching at most `reach`
    /// cells away.
    fn is_free(&self, x: f64, y: f64, spacing: f64, reach: i64) -> bool {
        let spacing2 = spacing * spacing;
        let (cx, cy) = ((x / self.cell) as i64, (y / self.cell) as i64);
        let reach = ((spacing / self.cell).ceil() as i64).min(reach);
        for gy in (cy - reach).max(0)..=(cy + reach).min(self.rows as i64 - 1) {
            let row = gy as usize * self.columns;
            for gx in (cx - reach).max(0)..=(cx + reach).min(self.columns as i64 - 1) {
                let mut dot = self.first_in_cell[row + gx as usize];
                while dot != NO_DOT {
                    let q = self.dots[dot as usize];
                    if (q[0] - x).powi(2) + (q[1] - y).powi(2) < spacing2 {
                        return false;
                    }
                    dot = self.next_in_cell[dot as usize];
                }
            }
        }
        true
    }

    fn insert(&mut self, x: f64, y: f64) {
        let cell = (y / self.cell) as usize * self.columns + (x / self.cell) as usize;
        self.next_in_cell.push(self.first_in_cell[cell]);
        self.first_in_cell[cell] = self.dots.len() as u32;
        self.dots.push([x, y]);
    }
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
        let mut xs: Vec<i64> = dots.iter().map(|d| (d[0] * 1e9) as i64).collect();
        xs.sort();
        xs.dedup();
        assert_eq!(xs.len(), dots.len());
        assert!(stipple_dots(&vec![0.0; 100], 10, 10, 2.0, 1).is_empty());
    }

    #[test]
    fn a_large_sparse_view_keeps_the_spacing_with_a_capped_grid() {
        // 6 million pixels at one-pixel spacing would be 12 million cells: the grid is
        // capped and its cells hold several dots; the spacing must hold all the same.
        let (width, height) = (3000, 2000);
        let mut darkness = vec![0f32; width * height];
        for y in 1000..1100 {
            darkness[y * width + 1500..y * width + 1600].fill(1.0);
        }
        let dots = stipple_dots(&darkness, width, height, 1.0, 11);
        assert!(dots.len() > 4000, "{} dots in a 100 x 100 black square", dots.len());
        assert!(dots.iter().all(|d| (1500.0..1600.0).contains(&d[0]) && (1000.0..1100.0).contains(&d[1])));
        for (i, a) in dots.iter().enumerate() {
            for b in &dots[i + 1..] {
                assert!((a[0] - b[0]).hypot(a[1] - b[1]) >= 1.0 - 1e-9, "{a:?} and {b:?} too close");
            }
        }
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
