//! Stipple shading (Wilczek et al. 2018, section 2.4.3, Fig. 6): dots placed more densely
//! where the surface is darker. Dots are spread as variable-radius Poisson-disk samples
//! (dart throwing: a candidate is kept only if no kept dot lies within the spacing its
//! tone asks for), which gives blue-noise spacing: even, never clumped, never a grid.
//!
//! The shading of a sherd spans a narrow band of darkness (light from the upper left on a
//! surface mostly facing the viewer), and dots placed in proportion to it come out nearly
//! uniform: relief and wheel rills, plain in the light style, vanish. So the darkness is
//! tone-mapped first ([`tone_map`]), as an illustrator works: the local relief is
//! emphasised (the darkness minus its blur, added back twice over) and the result
//! stretched so that the view's highlights are white and its deepest shadows black. The
//! dots then follow the mapped tone in proportion ([`place_dots`]).

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

/// Share of the view's shaded pixels left white (the highlights) and made black (the
/// deepest shadows) by the contrast stretch of [`tone_map`]: an illustrator leaves the
/// lit surface almost blank, so that the shadows of relief and rills stand out.
const STRETCH_QUANTILES: [f64; 2] = [0.12, 0.99];

/// The stretched tone is raised to this power: mid tones lighter, shadows kept.
const TONE_GAMMA: f32 = 1.5;

/// Smallest span of darkness the stretch widens to [0, 1]: a view shaded almost evenly is
/// not made to show its noise.
const MIN_STRETCH_SPAN: f32 = 0.12;

/// How much of the local relief (darkness minus its blur) is added back.
const RELIEF_GAIN: f32 = 2.0;

/// Radius of the blur the local relief is taken against, in dot spacings: wider than a
/// wheel rill (1-3 mm) at the default spacing of 0.35 mm, narrower than the sherd.
const RELIEF_RADIUS_SPACINGS: f64 = 6.0;

/// Areas lighter than this (after tone mapping) get no dots.
const WHITE_CUTOFF: f32 = 0.06;

/// Dot centres of the stipple shading of a view, in pixel coordinates of its
/// `width x height` darkness image (`darkness` in [0, 1], row-major, 0 where the view is
/// empty): the darkness tone-mapped by [`tone_map`], then dots placed by [`place_dots`]
/// in proportion to it. `spacing_px` is the distance between dots in fully black areas.
/// Deterministic for a given `seed`.
pub fn stipple_dots(darkness: &[f32], width: usize, height: usize, spacing_px: f64, seed: u64) -> Vec<[f64; 2]> {
    if width == 0 || height == 0 || !(spacing_px > 0.0) || darkness.len() != width * height {
        return Vec::new();
    }
    let spacing = spacing_px.max(1.0);
    let relief_radius = (RELIEF_RADIUS_SPACINGS * spacing).round() as usize;
    let tone = tone_map(darkness, width, height, relief_radius, (2.0 * spacing).round() as usize);
    place_dots(&tone, width, height, spacing_px, seed)
}

/// The darkness of a view mapped to the tone its stipple follows: pixels of darkness 0 are
/// empty and stay 0; the others get their local relief (the darkness minus its blur over
/// `radius_px`, the blur taken over shaded pixels only, so the outline does not count as
/// relief) added back twice, and are then stretched so that the lightest 12% are white and
/// the darkest 1% black, mid tones lightened by a gamma of 1.5 (a view whose tones span
/// less than 0.12 is kept as it is).
/// The darkness is first smoothed over `dot_px` (two dot spacings): dots cannot show finer
/// detail, and pixel noise (facets, scanner noise) would otherwise let the darkest pixels
/// of every neighbourhood set its dots' spacing, which evens the density out.
pub fn tone_map(darkness: &[f32], width: usize, height: usize, radius_px: usize, dot_px: usize) -> Vec<f32> {
    if width == 0 || height == 0 || darkness.len() != width * height {
        return Vec::new();
    }
    let shaded: Vec<f32> = darkness.iter().map(|&d| f32::from(d > 0.0)).collect();
    let smoothed = masked_blur(darkness, &shaded, width, height, dot_px);
    let darkness: Vec<f32> = smoothed.iter().zip(darkness).map(|(&s, &d)| if d > 0.0 { s.max(f32::MIN_POSITIVE) } else { 0.0 }).collect();
    let darkness = &darkness[..];
    let blurred = masked_blur(darkness, &shaded, width, height, radius_px);
    let enhanced: Vec<f32> = darkness
        .iter()
        .zip(&blurred)
        .map(|(&d, &b)| if d > 0.0 { (d + RELIEF_GAIN * (d - b)).clamp(0.0, 1.0) } else { 0.0 })
        .collect();
    let mut values: Vec<f32> = enhanced.iter().zip(darkness).filter(|&(_, &d)| d > 0.0).map(|(&e, _)| e).collect();
    if values.is_empty() {
        return enhanced;
    }
    let quantile = |values: &mut Vec<f32>, q: f64| {
        let k = ((values.len() - 1) as f64 * q).round() as usize;
        *values.select_nth_unstable_by(k, f32::total_cmp).1
    };
    let low = quantile(&mut values, STRETCH_QUANTILES[0]);
    let high = quantile(&mut values, STRETCH_QUANTILES[1]);
    // A view shaded almost evenly keeps its tone rather than have its noise stretched.
    if high - low < MIN_STRETCH_SPAN {
        return enhanced;
    }
    enhanced
        .iter()
        .zip(darkness)
        .map(|(&e, &d)| if d > 0.0 { ((e - low) / (high - low)).clamp(0.0, 1.0).powf(TONE_GAMMA) } else { 0.0 })
        .collect()
}

/// `values` blurred over about `radius` pixels, weighted by `weights` (a normalised
/// convolution: pixels of weight 0 neither count nor darken their neighbours); three box
/// passes of a third of the radius per direction approach a Gaussian. A radius of 0 leaves
/// the values as they are.
fn masked_blur(values: &[f32], weights: &[f32], width: usize, height: usize, radius: usize) -> Vec<f32> {
    if radius == 0 {
        return values.to_vec();
    }
    let mut sum: Vec<f32> = values.iter().zip(weights).map(|(v, w)| v * w).collect();
    let mut weight = weights.to_vec();
    let radius = (radius / 3).max(1);
    for _ in 0..3 {
        for buffer in [&mut sum, &mut weight] {
            box_pass(buffer, width, height, radius, true);
            box_pass(buffer, width, height, radius, false);
        }
    }
    sum.iter().zip(&weight).zip(values).map(|((s, w), v)| if *w > 1e-6 { s / w } else { *v }).collect()
}

/// One box filter pass of `radius` along rows (`along_rows`) or columns, by running sums
/// (columns a whole row at a time, reading the buffer in order).
fn box_pass(buffer: &mut [f32], width: usize, height: usize, radius: usize, along_rows: bool) {
    if along_rows {
        let mut line = vec![0f32; width];
        for row in buffer.chunks_mut(width) {
            line.copy_from_slice(row);
            let mut running = 0f64;
            let (mut lo, mut hi) = (0usize, 0usize);
            for (i, out) in row.iter_mut().enumerate() {
                while hi < (i + radius + 1).min(width) {
                    running += line[hi] as f64;
                    hi += 1;
                }
                while lo < i.saturating_sub(radius) {
                    running -= line[lo] as f64;
                    lo += 1;
                }
                *out = running as f32;
            }
        }
    } else {
        let input = buffer.to_vec();
        let mut running = vec![0f64; width];
        let (mut lo, mut hi) = (0usize, 0usize);
        for y in 0..height {
            while hi < (y + radius + 1).min(height) {
                running.iter_mut().zip(&input[hi * width..(hi + 1) * width]).for_each(|(r, &v)| *r += v as f64);
                hi += 1;
            }
            while lo < y.saturating_sub(radius) {
                running.iter_mut().zip(&input[lo * width..(lo + 1) * width]).for_each(|(r, &v)| *r -= v as f64);
                lo += 1;
            }
            buffer[y * width..(y + 1) * width].iter_mut().zip(&running).for_each(|(out, &r)| *out = r as f32);
        }
    }
}

/// Dot centres in pixel coordinates of a `width x height` tone image (`tone` in [0, 1],
/// row-major), their density in proportion to the tone: `spacing_px` is the distance
/// between dots in fully black areas, lighter areas get `spacing_px / sqrt(tone)`, and
/// areas lighter than 0.06 none. At most [`MAX_STIPPLE_DOTS`] dots: a view that
/// would need more gets a wider spacing. Deterministic for a given `seed`.
pub fn place_dots(darkness: &[f32], width: usize, height: usize, spacing_px: f64, seed: u64) -> Vec<[f64; 2]> {
    if width == 0 || height == 0 || !(spacing_px > 0.0) || darkness.len() != width * height {
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
    // Each tile gets candidates in proportion to its summed tone, thrown uniformly and
    // kept with probability tone / (the tile's darkest tone): candidates fall in proportion
    // to the tone, so that every tone is packed as closely relative to its spacing and the
    // dots' density follows the tone in proportion (uniform candidates saturate light
    // areas sooner and flatten the contrast).
    let tiles: Vec<(usize, usize, f64, f64, f64, f32)> = (0..height.div_ceil(TILE_PX))
        .flat_map(|ty| (0..width.div_ceil(TILE_PX)).map(move |tx| (tx * TILE_PX, ty * TILE_PX)))
        .filter_map(|(x0, y0)| {
            let (x1, y1) = ((x0 + TILE_PX).min(width), (y0 + TILE_PX).min(height));
            let (mut sum, mut max) = (0f64, 0f32);
            for row in (y0..y1).map(|y| &darkness[y * width + x0..y * width + x1]) {
                for &d in row.iter().filter(|&&d| d >= WHITE_CUTOFF) {
                    sum += d as f64;
                    max = max.max(d);
                }
            }
            (max > 0.0).then(|| (x0, y0, (x1 - x0) as f64, (y1 - y0) as f64, sum, max))
        })
        .collect();
    let shaded_tone: f64 = tiles.iter().map(|t| t.4).sum();
    for (x0, y0, tile_width, tile_height, tone_sum, tone_max) in tiles {
        // Candidates thrown so that `candidates * tone_sum / shaded_tone` are kept.
        let share = candidates as f64 * tone_sum / shaded_tone * (tile_width * tile_height * tone_max as f64 / tone_sum);
        // Stochastic rounding keeps every tile's expected count exact.
        let count = share.floor() as usize + usize::from(rng.random::<f64>() < share.fract());
        for _ in 0..count {
            let (x, y) = (x0 as f64 + rng.random::<f64>() * tile_width, y0 as f64 + rng.random::<f64>() * tile_height);
            let tone = tone_at(x, y);
            if tone < WHITE_CUTOFF || rng.random::<f32>() * tone_max > tone {
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

    /// Dots per square pixel inside `[x0, x1) x [y0, y1)`.
    fn density(dots: &[[f64; 2]], x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
        let inside = dots.iter().filter(|d| d[0] >= x0 && d[0] < x1 && d[1] >= y0 && d[1] < y1).count();
        inside as f64 / ((x1 - x0) * (y1 - y0))
    }

    #[test]
    fn dot_density_is_in_proportion_to_the_tone() {
        // Two halves of tone 0.2 and 0.6: three times the dots on the darker half.
        let (width, height) = (400, 200);
        let tone: Vec<f32> = (0..width * height).map(|i| if i % width < 200 { 0.2 } else { 0.6 }).collect();
        let dots = place_dots(&tone, width, height, 3.0, 5);
        // Away from the border between them, where the spacings of both tones meet.
        let (light, dark) = (density(&dots, 10.0, 190.0, 0.0, 200.0), density(&dots, 210.0, 390.0, 0.0, 200.0));
        let ratio = dark / light;
        println!("dark/light density {ratio:.3}, dark {dark:.5} dots/px^2");
        assert!((ratio - 3.0).abs() < 0.2, "dark/light density {ratio:.2} for tones 0.6/0.2 ({} dots)", dots.len());
        // And in absolute terms: tone / spacing^2 times the saturated packing.
        let expected = SATURATED_DOTS_PER_SPACING_SQUARED * 0.6 / 9.0;
        assert!((dark / expected - 1.0).abs() < 0.2, "{dark} dots/px^2 against {expected}");
    }

    #[test]
    fn faint_wheel_rills_come_out_plainly_darker() {
        // A surface shaded almost evenly (darkness 0.30), crossed by rills only 0.06
        // darker, as the light style shades A011: dots in proportion to the raw darkness
        // would make the rills 1.2 times as dense, uniform dots 1.0; the tone-mapped
        // stipple must make them at least twice as dense.
        let (width, height) = (600, 600);
        let rill = |y: usize| y % 60 >= 24 && y % 60 < 36;
        let mut darkness = vec![0f32; width * height];
        for y in 20..580 {
            for x in 20..580 {
                // A gentle gradient across the sherd, as the light gives it.
                darkness[y * width + x] = 0.27 + 0.06 * x as f32 / 600.0 + if rill(y) { 0.06 } else { 0.0 };
            }
        }
        let rill_contrast = |dots: &[[f64; 2]]| {
            let (mut in_rills, mut between) = ((0usize, 0usize), (0usize, 0usize));
            for y in 60..540 {
                let row = if rill(y) { &mut in_rills } else { &mut between };
                row.1 += 1;
                row.0 += dots.iter().filter(|d| d[1] as usize == y && d[0] >= 60.0 && d[0] < 540.0).count();
            }
            (in_rills.0 as f64 / in_rills.1 as f64) / (between.0 as f64 / between.1 as f64)
        };
        let dots = stipple_dots(&darkness, width, height, 4.0, 9);
        let ratio = rill_contrast(&dots);
        assert!(ratio > 2.0, "rills only {ratio:.2} times as dense as the surface between them");
        // Dots in proportion to the raw darkness (the stipple before tone mapping) leave
        // the rills all but invisible.
        let raw = rill_contrast(&place_dots(&darkness, width, height, 4.0, 9));
        assert!(raw < 1.4, "raw darkness gives {raw:.2}");
        println!("rills {ratio:.2} times as dense as the surface between them (raw darkness: {raw:.2})");
        // Nothing outside the view.
        assert!(dots.iter().all(|d| (20.0..580.0).contains(&d[0]) && (20.0..580.0).contains(&d[1])));
    }

    #[test]
    fn tone_mapping_whitens_highlights_blackens_shadows_and_keeps_empty_pixels() {
        let (width, height) = (100, 100);
        let darkness: Vec<f32> = (0..width * height)
            .map(|i| if i % width < 10 { 0.0 } else { 0.2 + 0.3 * (i % width) as f32 / 100.0 })
            .collect();
        let tone = tone_map(&darkness, width, height, 6, 1);
        assert!((0..height).all(|y| (0..10).all(|x| tone[y * width + x] == 0.0)), "empty pixels stay empty");
        let row = &tone[50 * width..51 * width];
        assert!(row[11] < 0.05 && row[98] > 0.95, "stretched to white and black: {} .. {}", row[11], row[98]);
        assert!(row[20..90].windows(2).all(|w| w[1] >= w[0]), "the ramp stays a ramp");
        // An evenly shaded view keeps its tone instead of having its noise stretched.
        let even = tone_map(&vec![0.4; 400], 20, 20, 3, 1);
        assert!(even.iter().all(|&t| (t - 0.4).abs() < 1e-5), "{:?}", &even[..3]);
    }

    #[test]
    fn darker_half_gets_more_dots_and_none_are_too_close() {
        let (width, height) = (200, 100);
        let darkness: Vec<f32> = (0..width * height)
            .map(|i| if i % width < 100 { 0.9 } else { 0.25 })
            .collect();
        let dots = place_dots(&darkness, width, height, 3.0, 7);
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
