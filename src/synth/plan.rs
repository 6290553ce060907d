//! Where a single synthetic sherd lies on its vessel: a Voronoi plan whose seed's cell
//! is a fragment of the wanted part and size, found on a coarse grid of the parameter
//! plane and meshed on a fine one sized for the faces asked for.

use rand::Rng;

use super::deform::Deformation;
use super::fracture::{clean_mask, mid_surface_point, RoughVoronoi};
use super::shell::{build_shell, ParamGrid, Shell};
use super::{HardCase, SherdOptions, SherdPart, VesselProfile, MAX_TARGET_FACES};
use crate::mesh::Point;

/// Cells of margin around a fragment's coarse extent when meshing it finely.
const WINDOW_MARGIN_CELLS: f64 = 3.0;

pub(super) fn random_part(rng: &mut impl Rng) -> SherdPart {
    match rng.random_range(0..20) {
        0..7 => SherdPart::Rim,
        7..14 => SherdPart::Body,
        14..18 => SherdPart::Base,
        _ => SherdPart::RimToBase,
    }
}

/// Where a fragment should be: the Voronoi seeds (the fragment's own first) and where its
/// own seed lies in the parameter plane.
pub(super) struct FragmentPlan {
    pub(super) seeds: Vec<Point>,
    pub(super) theta: f64,
    pub(super) s_mm: f64,
    /// The neighbours' angular and arc-length extent: the fragment lies inside.
    pub(super) theta_extent: [f64; 2],
    pub(super) s_extent: [f64; 2],
}

/// Seeds whose Voronoi cell is a fragment of `part`: the fragment's seed in the middle of
/// the wanted arc-length band, and a ring of 6-9 neighbours at twice the wanted half
/// extents, so that the bisectors fall on the wanted outline. Neighbours that would lie
/// beyond the rim are left out when the fragment should reach the rim, and seeds along
/// the rest of the rim take their place.
pub(super) fn plan_fragment(profile: &VesselProfile, part: SherdPart, options: &SherdOptions, rng: &mut impl Rng) -> Option<FragmentPlan> {
    let length = profile.length_mm();
    let edge = profile.base_edge_s_mm();
    let wall = length - edge;
    let uniform = |rng: &mut dyn rand::RngCore, low: f64, high: f64| low + (high - low) * rng.random::<f64>();
    let [sector_low, sector_high] = [options.sector_deg[0].clamp(3.0, 150.0), options.sector_deg[1].clamp(3.0, 150.0)];
    let mut sector_rad = uniform(rng, sector_low.min(sector_high), sector_low.max(sector_high) + 1e-9).to_radians();
    let (s_low, s_high) = match (options.hard_case, part) {
        (Some(HardCase::Tiny), _) => {
            let centre = edge + wall * uniform(rng, 0.3, 0.7);
            let half = uniform(rng, 6.0, 9.0);
            sector_rad = 2.0 * uniform(rng, 6.0, 9.0) / profile.mid_radius_mm(centre);
            (centre - half, centre + half)
        }
        (Some(HardCase::NearSpherical), _) => {
            let [low, high] = profile.spherical_band_s_mm()?;
            let band = high - low;
            let size = band * uniform(rng, 0.25, 0.4);
            let start = low + 0.15 * band + (0.7 * band - size) * rng.random::<f64>();
            (start, start + size)
        }
        (_, SherdPart::Rim) => (length - wall * uniform(rng, 0.25, 0.6), length),
        (_, SherdPart::Body) => {
            let size = wall * uniform(rng, 0.2, 0.4);
            let start = edge + 0.1 * wall + (0.8 * wall - size) * rng.random::<f64>();
            (start, start + size)
        }
        (_, SherdPart::Base) => (edge * uniform(rng, 0.3, 0.7), edge + wall * uniform(rng, 0.15, 0.4)),
        (_, SherdPart::RimToBase) => (edge * uniform(rng, 0.4, 0.8), length),
        (_, SherdPart::Flat) => {
            let start = edge * uniform(rng, 0.15, 0.35);
            (start, (start + edge * uniform(rng, 0.3, 0.45)).min(0.85 * edge))
        }
    };
    if s_high <= s_low {
        return None;
    }
    let open_top = s_high >= length;
    let centre_s = 0.5 * (s_low + s_high);
    let centre_radius = profile.mid_radius_mm(centre_s).max(1.0);
    let half_width = 0.5 * sector_rad * centre_radius;
    let half_height = 0.5 * (s_high - s_low);
    let mut seeds = vec![mid_surface_point(profile, 0.0, centre_s)];
    let (mut theta_extent, mut s_extent) = ([0.0f64, 0.0f64], [centre_s, if open_top { length } else { centre_s }]);
    let neighbour_count = rng.random_range(6..=9);
    for k in 0..neighbour_count {
        let jitter = uniform(rng, -0.3, 0.3) * std::f64::consts::PI / neighbour_count as f64;
        let direction = std::f64::consts::TAU * k as f64 / neighbour_count as f64 + jitter;
        let stretch = uniform(rng, 0.85, 1.15);
        let s = centre_s + 2.0 * half_height * direction.sin() * stretch;
        let theta = 2.0 * half_width * direction.cos() * stretch / centre_radius;
        if open_top && s >= length {
            continue;
        }
        theta_extent = [theta_extent[0].min(theta), theta_extent[1].max(theta)];
        s_extent = [s_extent[0].min(s), s_extent[1].max(s)];
        seeds.push(mid_surface_point(profile, theta, s));
    }
    if open_top {
        // With no neighbours above, nothing would stop the cell creeping round the rim
        // (on a jar's narrow neck the far side of the rim is nearer to the fragment's
        // seed than to its lateral neighbours): the rest of the rim is broken too, into
        // pieces about as wide as this one.
        let step = sector_rad.max(10f64.to_radians());
        let mut theta = 1.5 * sector_rad.max(step);
        while theta < std::f64::consts::PI {
            seeds.push(mid_surface_point(profile, theta, length));
            seeds.push(mid_surface_point(profile, -theta, length));
            theta += step;
        }
    }
    Some(FragmentPlan { seeds, theta: 0.0, s_mm: centre_s, theta_extent, s_extent })
}

/// The fragment of seed 0 of `voronoi`: found on a coarse grid of the whole vessel, then
/// meshed on a fine grid over its extent, with cells sized for `target_faces`.
pub(super) fn mesh_planned_fragment(profile: &VesselProfile, deformation: &Deformation, voronoi: &RoughVoronoi, plan: &FragmentPlan, target_faces: usize) -> Option<Shell> {
    let length = profile.length_mm();
    let (area, parameter_area) = surface_areas(profile);
    let coarse_cell = (area / 100_000.0).sqrt().max(1.0);
    // The fragment lies within its neighbours' ring; the whole vessel is the fallback
    // when the rough break lines carry it out of the ring's window.
    let windowed = ParamGrid::covering(Some(plan.theta_extent), plan.s_extent, length, coarse_cell, area / parameter_area);
    let whole = ParamGrid::covering(None, [0.0, length], length, coarse_cell, area / parameter_area);
    let mut found = None;
    for coarse in [windowed, whole] {
        let mut mask: Vec<bool> = voronoi.label_grid(&coarse, profile).iter().map(|&l| l == 0).collect();
        if !clean_mask(&coarse, &mut mask, cell_at(&coarse, plan.theta, plan.s_mm)) {
            return None;
        }
        if !touches_window_border(&coarse, &mask) {
            found = Some((coarse, mask));
            break;
        }
    }
    let (coarse, mask) = found?;
    let extent = CellSetExtent::measure(&coarse, &mask, profile);

    // Faces ~ 4 per cell + 2 per boundary edge: 4 A / h^2 + 2 P / h = target, solved for 1/h.
    let target = target_faces.clamp(64, MAX_TARGET_FACES) as f64;
    let (a, p) = (extent.area_mm2, extent.perimeter_mm);
    let inverse_cell = (-2.0 * p + (4.0 * p * p + 16.0 * a * target).sqrt()) / (8.0 * a);
    let cell = 1.0 / inverse_cell;
    let margin_s = WINDOW_MARGIN_CELLS * coarse.ds;
    let margin_theta = WINDOW_MARGIN_CELLS * coarse.dtheta;
    let theta_range = extent.theta_range.map(|[low, high]| [low - margin_theta, high + margin_theta]);
    let s_range = [extent.s_range[0] - margin_s, extent.s_range[1] + margin_s];
    let fine = ParamGrid::covering(theta_range, s_range, length, cell, extent.mean_radius_mm);
    let mut mask: Vec<bool> = voronoi.label_grid(&fine, profile).iter().map(|&l| l == 0).collect();
    if !clean_mask(&fine, &mut mask, cell_at(&fine, plan.theta, plan.s_mm)) {
        return None;
    }
    if touches_window_border(&fine, &mask) {
        return None;
    }
    Some(build_shell(&fine, &mask, profile, deformation))
}

/// True when a cell of `mask` lies on a side of the window that is not the vessel's own
/// edge (base centre or rim): the fragment may continue beyond the window.
fn touches_window_border(grid: &ParamGrid, mask: &[bool]) -> bool {
    let sides = !grid.periodic && (0..grid.rows).any(|row| mask[row * grid.columns] || mask[row * grid.columns + grid.columns - 1]);
    let bottom = !grid.pole && grid.s0 > 0.0 && mask[..grid.columns].iter().any(|&m| m);
    let top = !grid.rim && mask[(grid.rows - 1) * grid.columns..].iter().any(|&m| m);
    sides || bottom || top
}

/// Area, outline and angular and arc-length extent of a set of cells.
struct CellSetExtent {
    area_mm2: f64,
    perimeter_mm: f64,
    /// Angular interval (radians, low < high, not wrapped), `None` when all round.
    theta_range: Option<[f64; 2]>,
    s_range: [f64; 2],
    /// Mean radius over the parameter area (area / parameter area).
    mean_radius_mm: f64,
}

impl CellSetExtent {
    fn measure(grid: &ParamGrid, mask: &[bool], profile: &VesselProfile) -> Self {
        let (mut area, mut parameter_area, mut perimeter) = (0.0, 0.0, 0.0);
        let (mut low_row, mut high_row) = (usize::MAX, 0);
        let mut occupied_columns = vec![false; grid.columns];
        for row in 0..grid.rows {
            let s = grid.cell_centre(0, row).1;
            let radius = profile.mid_radius_mm(s);
            for column in 0..grid.columns {
                if !mask[row * grid.columns + column] {
                    continue;
                }
                area += radius * grid.dtheta * grid.ds;
                parameter_area += grid.dtheta * grid.ds;
                low_row = low_row.min(row);
                high_row = high_row.max(row);
                occupied_columns[column] = true;
                let left = mask[row * grid.columns + (column + grid.columns - 1) % grid.columns];
                let right = mask[row * grid.columns + (column + 1) % grid.columns];
                let below = row > 0 && mask[(row - 1) * grid.columns + column];
                let above = row + 1 < grid.rows && mask[(row + 1) * grid.columns + column];
                perimeter += (!left as u8 + !right as u8) as f64 * grid.ds + (!below as u8 + !above as u8) as f64 * radius * grid.dtheta;
            }
        }
        // The largest run of empty columns (circularly) is where the fragment is not.
        let (mut best_gap, mut best_end) = (0, 0);
        let mut run = 0;
        for k in 0..2 * grid.columns {
            if occupied_columns[k % grid.columns] {
                run = 0;
            } else {
                run += 1;
                if run > best_gap && run <= grid.columns {
                    best_gap = run;
                    best_end = k;
                }
            }
        }
        let theta_range = if best_gap == 0 {
            None
        } else {
            // Occupied columns run from just after the gap to just before it.
            let first = (best_end + 1) % grid.columns;
            let count = grid.columns - best_gap;
            let low = grid.theta0 + first as f64 * grid.dtheta;
            Some([low, low + count as f64 * grid.dtheta])
        };
        CellSetExtent {
            area_mm2: area.max(1e-6),
            perimeter_mm: perimeter,
            theta_range,
            s_range: [grid.s0 + low_row as f64 * grid.ds, grid.s0 + (high_row + 1) as f64 * grid.ds],
            mean_radius_mm: area / parameter_area.max(1e-12),
        }
    }
}

/// The surface area of the mid-wall surface and its area in the `(theta, s)` plane.
pub(super) fn surface_areas(profile: &VesselProfile) -> (f64, f64) {
    let length = profile.length_mm();
    let steps = (length / 0.5).ceil() as usize;
    let ds = length / steps as f64;
    let area: f64 = (0..steps).map(|k| profile.mid_radius_mm((k as f64 + 0.5) * ds)).sum::<f64>() * ds * std::f64::consts::TAU;
    (area, std::f64::consts::TAU * length)
}

/// The index of the cell containing `(theta, s_mm)`, if inside the grid.
pub(super) fn cell_at(grid: &ParamGrid, theta: f64, s_mm: f64) -> Option<usize> {
    let row = ((s_mm - grid.s0) / grid.ds).floor();
    let mut column = ((theta - grid.theta0) / grid.dtheta).floor();
    if grid.periodic {
        column = column.rem_euclid(grid.columns as f64);
    }
    if row < 0.0 || row >= grid.rows as f64 || column < 0.0 || column >= grid.columns as f64 {
        return None;
    }
    Some(row as usize * grid.columns + column as usize)
}
