//! Breaking a vessel: a Voronoi diagram on the vessel's mid-wall surface whose seeds are
//! the fragments, with a rough (noisy) distance so that the break lines wander like real
//! fractures instead of running straight, and clean-ups that make every fragment's cell
//! set one simply-connected, manifold region (so its shell is a closed 2-manifold).

use rand::Rng;
use rayon::prelude::*;

use super::shape::VesselProfile;
use super::shell::ParamGrid;
use crate::mesh::{Point, Vector};

/// Number of sine waves in each seed's roughness field.
const WAVES_PER_SEED: usize = 6;

#[derive(Clone, Copy, Debug)]
struct Wave {
    wave_vector: Vector,
    phase: f64,
    amplitude_mm: f64,
}

/// A Voronoi diagram of seeds in space, restricted to the vessel surface, whose distance
/// to seed `k` is perturbed by a smooth field of its own (a sum of sine waves of 4-25 mm
/// wavelength): the boundary between two fragments then wanders by up to
/// `roughness_mm` on either side of the bisector.
#[derive(Clone, Debug)]
pub struct RoughVoronoi {
    seeds: Vec<Point>,
    waves: Vec<[Wave; WAVES_PER_SEED]>,
    roughness_mm: f64,
}

impl RoughVoronoi {
    /// A diagram of `seeds` with break lines wandering by up to `roughness_mm`.
    pub fn new(seeds: Vec<Point>, roughness_mm: f64, rng: &mut impl Rng) -> Self {
        let waves = seeds
            .iter()
            .map(|_| {
                std::array::from_fn(|_| {
                    let direction = loop {
                        let v = Vector::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                        let norm = v.norm();
                        if norm > 0.1 && norm <= 1.0 {
                            break v / norm;
                        }
                    };
                    let wavelength_mm: f64 = rng.random_range(4.0..25.0);
                    Wave {
                        wave_vector: direction * (std::f64::consts::TAU / wavelength_mm),
                        phase: rng.random_range(0.0..std::f64::consts::TAU),
                        amplitude_mm: roughness_mm / WAVES_PER_SEED as f64 * rng.random_range(0.5..1.5),
                    }
                })
            })
            .collect();
        RoughVoronoi { seeds, waves, roughness_mm }
    }

    /// The fragment (seed index) owning surface point `p`.
    pub fn label(&self, p: &Point) -> u32 {
        let nearest_squared = self.seeds.iter().map(|s| (p - s).norm_squared()).fold(f64::INFINITY, f64::min);
        // The roughness field is bounded by 1.5 * roughness: seeds farther than that beyond
        // the nearest cannot win, and skipping them keeps large diagrams fast.
        let reach = nearest_squared.sqrt() + 3.0 * self.roughness_mm;
        let reach_squared = reach * reach;
        let mut best = (f64::INFINITY, 0u32);
        for (k, seed) in self.seeds.iter().enumerate() {
            let squared = (p - seed).norm_squared();
            if squared > reach_squared {
                continue;
            }
            let rough: f64 = self.waves[k]
                .iter()
                .map(|w| w.amplitude_mm * (w.wave_vector.dot(&p.coords) + w.phase).sin())
                .sum();
            let distance = squared.sqrt() + rough;
            if distance < best.0 {
                best = (distance, k as u32);
            }
        }
        best.1
    }

    /// The label of every cell of `grid` (cell centres on the undeformed mid-wall surface).
    pub fn label_grid(&self, grid: &ParamGrid, profile: &VesselProfile) -> Vec<u32> {
        let mut labels = vec![0u32; grid.cell_count()];
        labels.par_chunks_mut(grid.columns).enumerate().for_each(|(row, chunk)| {
            for (column, label) in chunk.iter_mut().enumerate() {
                let (theta, s) = grid.cell_centre(column, row);
                *label = self.label(&mid_surface_point(profile, theta, s));
            }
        });
        labels
    }
}

/// The undeformed mid-wall surface point at angle `theta` and arc length `s_mm`. Arc
/// lengths below zero continue through the base centre onto the opposite side, and
/// beyond the rim straight along the rim's direction, so seeds may be placed anywhere.
pub fn mid_surface_point(profile: &VesselProfile, theta: f64, s_mm: f64) -> Point {
    let (theta, s_mm) = if s_mm < 0.0 { (theta + std::f64::consts::PI, -s_mm) } else { (theta, s_mm) };
    let length = profile.length_mm();
    let sample = profile.sample(s_mm.min(length));
    let (mut r, mut z) = (sample.r_mm, sample.z_mm);
    if s_mm > length {
        // Continue along the tangent (the normal turned anticlockwise).
        let extra = s_mm - length;
        r += -sample.normal_z * extra;
        z += sample.normal_r * extra;
    }
    let (sin, cos) = theta.sin_cos();
    Point::new(r * cos, r * sin, z)
}

/// The 4-neighbours of cell `(column, row)` inside the grid (wrapping around when periodic).
fn neighbours(grid: &ParamGrid, column: usize, row: usize) -> impl Iterator<Item = (usize, usize)> {
    let mut result = [None; 4];
    if column > 0 {
        result[0] = Some((column - 1, row));
    } else if grid.periodic {
        result[0] = Some((grid.columns - 1, row));
    }
    if column + 1 < grid.columns {
        result[1] = Some((column + 1, row));
    } else if grid.periodic {
        result[1] = Some((0, row));
    }
    if row > 0 {
        result[2] = Some((column, row - 1));
    }
    if row + 1 < grid.rows {
        result[3] = Some((column, row + 1));
    }
    result.into_iter().flatten()
}

/// Connected components (4-neighbourhood) of the cells where `member` is true: a component
/// id per cell (`u32::MAX` outside) and each component's size.
fn components(grid: &ParamGrid, member: &[bool]) -> (Vec<u32>, Vec<usize>) {
    let mut id = vec![u32::MAX; member.len()];
    let mut sizes = Vec::new();
    let mut stack = Vec::new();
    for start in 0..member.len() {
        if !member[start] || id[start] != u32::MAX {
            continue;
        }
        let component = sizes.len() as u32;
        let mut size = 0;
        id[start] = component;
        stack.push(start);
        while let Some(cell) = stack.pop() {
            size += 1;
            let (column, row) = (cell % grid.columns, cell / grid.columns);
            for (c, r) in neighbours(grid, column, row) {
                let next = r * grid.columns + c;
                if member[next] && id[next] == u32::MAX {
                    id[next] = component;
                    stack.push(next);
                }
            }
        }
        sizes.push(size);
    }
    (id, sizes)
}

/// Makes `mask` one region whose shell is a closed 2-manifold: keeps the component
/// containing `anchor` (or the largest one), fills holes (pockets of outside cells that
/// touch no border of the grid), fills the cells that would make two parts of the region
/// touch at a single corner only (a pinched, non-manifold vertex), and makes the cells
/// around the base centre one contiguous fan. Returns false if the mask is empty.
pub fn clean_mask(grid: &ParamGrid, mask: &mut [bool], anchor: Option<usize>) -> bool {
    let (id, sizes) = components(grid, mask);
    let keep = match anchor.filter(|&a| mask[a]) {
        Some(cell) => id[cell],
        None => match (0..sizes.len()).max_by_key(|&k| sizes[k]) {
            Some(k) => k as u32,
            None => return false,
        },
    };
    for (cell, inside) in mask.iter_mut().enumerate() {
        *inside = id[cell] == keep;
    }
    loop {
        let mut changed = fill_holes(grid, mask);
        changed |= fill_pinches(grid, mask);
        changed |= fill_pole_fan(grid, mask);
        if !changed {
            return true;
        }
    }
}

fn fill_holes(grid: &ParamGrid, mask: &mut [bool]) -> bool {
    let outside: Vec<bool> = mask.iter().map(|&m| !m).collect();
    let (id, sizes) = components(grid, &outside);
    let mut touches_border = vec![false; sizes.len()];
    for row in 0..grid.rows {
        for column in 0..grid.columns {
            let cell = row * grid.columns + column;
            if id[cell] == u32::MAX {
                continue;
            }
            let on_border = row == 0 || row + 1 == grid.rows || (!grid.periodic && (column == 0 || column + 1 == grid.columns));
            if on_border {
                touches_border[id[cell] as usize] = true;
            }
        }
    }
    let mut changed = false;
    for (cell, inside) in mask.iter_mut().enumerate() {
        if id[cell] != u32::MAX && !touches_border[id[cell] as usize] {
            *inside = true;
            changed = true;
        }
    }
    changed
}

fn fill_pinches(grid: &ParamGrid, mask: &mut [bool]) -> bool {
    let mut changed = false;
    let column_pairs = if grid.periodic { grid.columns } else { grid.columns.saturating_sub(1) };
    for row in 0..grid.rows.saturating_sub(1) {
        for left in 0..column_pairs {
            let right = (left + 1) % grid.columns;
            let cell = |c: usize, r: usize| r * grid.columns + c;
            let (lower_left, lower_right) = (cell(left, row), cell(right, row));
            let (upper_left, upper_right) = (cell(left, row + 1), cell(right, row + 1));
            let (a, b, c, d) = (mask[lower_left], mask[lower_right], mask[upper_left], mask[upper_right]);
            if a && d && !b && !c {
                mask[lower_right] = true;
                changed = true;
            } else if b && c && !a && !d {
                mask[lower_left] = true;
                changed = true;
            }
        }
    }
    changed
}

/// Around the base centre all cells of the first row share one vertex: they must form a
/// single arc, or that vertex would be pinched.
fn fill_pole_fan(grid: &ParamGrid, mask: &mut [bool]) -> bool {
    if !grid.pole {
        return false;
    }
    let first_row = &mut mask[..grid.columns];
    let count = first_row.iter().filter(|&&m| m).count();
    if count == 0 || count == first_row.len() {
        return false;
    }
    let runs = (0..grid.columns).filter(|&c| first_row[c] && !first_row[(c + grid.columns - 1) % grid.columns]).count();
    if runs <= 1 {
        return false;
    }
    first_row.iter_mut().for_each(|m| *m = true);
    true
}
