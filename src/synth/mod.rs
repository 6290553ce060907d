//! Synthetic sherds with known axes: a random vessel profile revolved with wall
//! thickness, deformed, made noisy, broken along a Voronoi diagram and moved by random
//! rigid motions. The test bed of every later layer: its tests know the true axis.
//!
//! * [`synthetic_sherd`] makes one fragment of a requested part ([`SherdPart`]) at a
//!   requested resolution, with its [`GroundTruth`]; [`SherdOptions::hard_case`] gives the
//!   fragments orientation must refuse (flat base piece, near-spherical piece, tiny piece).
//! * [`generate_vessel`] breaks a whole vessel into fragments.
//!
//! Every fragment is a closed, watertight, outward-oriented triangle mesh with
//! area-weighted vertex normals, and the same seed always gives the same bytes.

pub(crate) mod colour;
pub(crate) mod deform;
pub(crate) mod fracture;
pub(crate) mod motion;
pub mod shape;
pub(crate) mod shell;
pub mod truth;
pub mod write;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

pub use deform::Deformation;
pub use shape::{RimForm, VesselProfile, VesselShape};
pub use truth::{GroundTruth, HardCase, RigidMotion, SherdPart, SurfaceKind, VesselTruth};
pub use write::{read_truth, write_sherd};

use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::{Mesh, Point, Vector};
use crate::axis::Axis;
use colour::ClayColour;
use fracture::{clean_mask, mid_surface_point, RoughVoronoi};
use shell::{build_shell, ParamGrid, Shell};

/// How to make one synthetic sherd.
#[derive(Clone, Debug, PartialEq)]
pub struct SherdOptions {
    /// Approximate number of triangles (the result is within about 15 %).
    pub target_faces: usize,
    /// Standard deviation of the Gaussian noise added to every coordinate, mm.
    pub noise_mm: f64,
    /// The part wanted; `None` draws rim, body, base or complete profile at random.
    pub part: Option<SherdPart>,
    /// Range of the circumference angle the fragment should span, degrees (clamped to
    /// 3-150; the break lines' roughness makes the result differ by a few degrees).
    pub sector_deg: [f64; 2],
    /// The vessel family; `None` draws an ordinary one at random.
    pub shape: Option<VesselShape>,
    /// Size of the hand-made irregularities (ovality, rim tilt, wobble): 0 gives an
    /// ideal surface of revolution, 1 a carefully thrown vessel.
    pub deformation_scale: f64,
    /// How far the break lines wander from straight, mm.
    pub roughness_mm: f64,
    /// Move the fragment by a random rigid motion (otherwise it stays in the vessel
    /// frame: axis on z, standing plane z = 0).
    pub random_motion: bool,
    /// Make one of the fragments orientation must refuse (overrides `part` and, for
    /// near-spherical pieces, `shape`).
    pub hard_case: Option<HardCase>,
    /// Give the vertices fired-clay colours.
    pub colours: bool,
}

impl Default for SherdOptions {
    fn default() -> Self {
        SherdOptions {
            target_faces: 20_000,
            noise_mm: 0.02,
            part: None,
            sector_deg: [15.0, 60.0],
            shape: None,
            deformation_scale: 1.0,
            roughness_mm: 1.5,
            random_motion: true,
            hard_case: None,
            colours: true,
        }
    }
}

impl SherdOptions {
    /// Default options for a fragment of `part`.
    pub fn for_part(part: SherdPart) -> Self {
        SherdOptions { part: Some(part), ..Default::default() }
    }

    /// Default options for one of the hard cases.
    pub fn hard_case(case: HardCase) -> Self {
        SherdOptions { hard_case: Some(case), ..Default::default() }
    }

    /// An ideal fragment: no deformation, no noise (for tests of exact recovery).
    pub fn ideal(self) -> Self {
        SherdOptions { noise_mm: 0.0, deformation_scale: 0.0, ..self }
    }
}

/// A synthetic sherd: a closed mesh with vertex normals, in the scan frame, and the truth.
#[derive(Clone, Debug)]
pub struct SynthSherd {
    /// The fragment's surface (positions, outward triangles, vertex normals), mm.
    pub mesh: Mesh,
    /// What the fragment really is.
    pub truth: GroundTruth,
    /// Outer or inner skin, per vertex.
    pub vertex_kinds: Vec<SurfaceKind>,
    /// Outer skin, inner skin, fracture or rim (top or rounding), per face.
    pub face_kinds: Vec<SurfaceKind>,
}

/// How to break a whole vessel.
#[derive(Clone, Debug, PartialEq)]
pub struct VesselOptions {
    /// The vessel family; `None` draws an ordinary one at random.
    pub shape: Option<VesselShape>,
    /// Number of Voronoi seeds (fragments), at least 2.
    pub fragment_count: usize,
    /// Size of the mesh cells, mm (each cell gives four triangles).
    pub cell_size_mm: f64,
    /// Standard deviation of the Gaussian noise added to every coordinate, mm.
    pub noise_mm: f64,
    /// As [`SherdOptions::deformation_scale`].
    pub deformation_scale: f64,
    /// How far the break lines wander from straight, mm.
    pub roughness_mm: f64,
    /// Move each fragment by its own random rigid motion; otherwise they stay in the
    /// vessel frame and fit together.
    pub random_motion: bool,
    /// Give the vertices fired-clay colours.
    pub colours: bool,
}

impl Default for VesselOptions {
    fn default() -> Self {
        VesselOptions {
            shape: None,
            fragment_count: 24,
            cell_size_mm: 2.0,
            noise_mm: 0.02,
            deformation_scale: 1.0,
            roughness_mm: 1.5,
            random_motion: false,
            colours: true,
        }
    }
}

/// A whole broken vessel.
#[derive(Clone, Debug)]
pub struct SynthVessel {
    /// The fragments, one per Voronoi cell, in seed order.
    pub fragments: Vec<SynthSherd>,
    /// The vessel's outer profile `[r, z]` from the base centre to the rim, mm.
    pub profile: Vec<[f64; 2]>,
    /// The vessel's measurements and deformation.
    pub vessel: VesselTruth,
}

/// Attempts at drawing a vessel and a fragment plan before settling for what came out.
const MAX_ATTEMPTS: usize = 24;
/// Spacing of the points of the truth profiles, mm.
const PROFILE_STEP_MM: f64 = 0.5;
/// Cells of margin around a fragment's coarse extent when meshing it finely.
const WINDOW_MARGIN_CELLS: f64 = 3.0;

/// Most triangles a synthetic sherd may be asked for: ten times a large real scan. The
/// command line and the C ABI refuse more, and the mesher never plans more.
pub const MAX_TARGET_FACES: usize = 10_000_000;

/// The finest mesh tried when the resolution asked for cannot hold a fragment: past the
/// default (20,000 faces), at which every fragment plan is meshed.
const MAX_FALLBACK_TARGET_FACES: usize = 80_000;

/// One synthetic sherd for `seed` (deterministic: the same seed and options give the
/// same mesh, whatever the number of threads).
pub fn synthetic_sherd(seed: u64, options: &SherdOptions) -> SynthSherd {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let wanted_part = match options.hard_case {
        Some(HardCase::FlatBase) => SherdPart::Flat,
        Some(HardCase::NearSpherical) | Some(HardCase::Tiny) => SherdPart::Body,
        None => options.part.unwrap_or_else(|| random_part(&mut rng)),
    };
    let shape_of = |rng: &mut ChaCha8Rng| match options.hard_case {
        Some(HardCase::NearSpherical) => VesselShape::Globular,
        _ => options.shape.unwrap_or_else(|| VesselShape::random(rng)),
    };
    // A mesh asked for a few dozen faces may be too coarse to hold any fragment's outline;
    // then finer ones are tried, up to past the default resolution, where every plan
    // holds its own seed.
    let mut target_faces = options.target_faces;
    let fallback = loop {
        let mut fallback = None;
        for attempt in 0..MAX_ATTEMPTS {
            let profile = VesselProfile::random(shape_of(&mut rng), &mut rng);
            let deformation = Deformation::random(&mut rng, options.deformation_scale, profile.height_mm());
            let Some(plan) = plan_fragment(&profile, wanted_part, options, &mut rng) else {
                continue;
            };
            let voronoi = RoughVoronoi::new(plan.seeds.clone(), options.roughness_mm, &mut rng);
            let Some(shell) = mesh_planned_fragment(&profile, &deformation, &voronoi, &plan, target_faces) else {
                continue;
            };
            let part = classify(&profile, &shell);
            let surface = Surface {
                noise_mm: options.noise_mm,
                noise_seed: rng.random(),
                motion_seed: options.random_motion.then(|| rng.random()),
                colour: options.colours.then(|| ClayColour::random(&mut rng)),
                hard_case: options.hard_case,
                fragment_index: None,
            };
            if part == wanted_part || attempt + 1 == MAX_ATTEMPTS {
                return finish(seed, shell, &profile, &deformation, part, &surface);
            }
            fallback.get_or_insert((shell, profile, deformation, part, surface));
        }
        if fallback.is_some() || target_faces >= MAX_FALLBACK_TARGET_FACES {
            break fallback;
        }
        target_faces = (target_faces.max(64) * 4).min(MAX_FALLBACK_TARGET_FACES);
    };
    // Only reached when no attempt gave the wanted part: the truth says what it is.
    let (shell, profile, deformation, part, surface) =
        fallback.expect("some attempt yields a fragment at the default resolution: every plan contains its own seed");
    finish(seed, shell, &profile, &deformation, part, &surface)
}

/// A whole vessel broken into `options.fragment_count` fragments by a rough Voronoi
/// diagram of seeds spread uniformly over its surface.
pub fn generate_vessel(seed: u64, options: &VesselOptions) -> SynthVessel {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let shape = options.shape.unwrap_or_else(|| VesselShape::random(&mut rng));
    let profile = VesselProfile::random(shape, &mut rng);
    let deformation = Deformation::random(&mut rng, options.deformation_scale, profile.height_mm());
    let length = profile.length_mm();
    let max_radius = profile.max_radius_mm();
    let mut seed_params = Vec::new();
    while seed_params.len() < options.fragment_count.max(2) {
        // Uniform over the surface: accept an arc length with probability r / r_max.
        let s = rng.random_range(0.0..length);
        if rng.random_range(0.0..max_radius) < profile.mid_radius_mm(s) {
            seed_params.push((rng.random_range(0.0..std::f64::consts::TAU), s));
        }
    }
    let seeds = seed_params.iter().map(|&(theta, s)| mid_surface_point(&profile, theta, s)).collect();
    let voronoi = RoughVoronoi::new(seeds, options.roughness_mm, &mut rng);
    let (area, parameter_area) = surface_areas(&profile);
    let grid = ParamGrid::covering(None, [0.0, length], length, options.cell_size_mm.max(0.05), area / parameter_area);
    let labels = voronoi.label_grid(&grid, &profile);
    let colour = options.colours.then(|| ClayColour::random(&mut rng));
    let fragment_seeds: Vec<(u64, u64)> = seed_params.iter().map(|_| (rng.random(), rng.random())).collect();
    let fragments = seed_params
        .par_iter()
        .enumerate()
        .filter_map(|(k, &(theta, s))| {
            let mut mask: Vec<bool> = labels.iter().map(|&l| l == k as u32).collect();
            if !clean_mask(&grid, &mut mask, cell_at(&grid, theta, s)) {
                return None;
            }
            let shell = build_shell(&grid, &mask, &profile, &deformation);
            let part = classify(&profile, &shell);
            let (noise_seed, motion_seed) = fragment_seeds[k];
            let surface = Surface {
                noise_mm: options.noise_mm,
                noise_seed,
                motion_seed: options.random_motion.then_some(motion_seed),
                colour: colour.clone(),
                hard_case: None,
                fragment_index: Some(k),
            };
            Some(finish(seed, shell, &profile, &deformation, part, &surface))
        })
        .collect();
    SynthVessel {
        fragments,
        profile: profile.skin_polyline(1.0, PROFILE_STEP_MM),
        vessel: vessel_truth(&profile, &deformation),
    }
}

fn random_part(rng: &mut impl Rng) -> SherdPart {
    match rng.random_range(0..20) {
        0..7 => SherdPart::Rim,
        7..14 => SherdPart::Body,
        14..18 => SherdPart::Base,
        _ => SherdPart::RimToBase,
    }
}

/// Where a fragment should be: the Voronoi seeds (the fragment's own first) and where its
/// own seed lies in the parameter plane.
struct FragmentPlan {
    seeds: Vec<Point>,
    theta: f64,
    s_mm: f64,
    /// The neighbours' angular and arc-length extent: the fragment lies inside.
    theta_extent: [f64; 2],
    s_extent: [f64; 2],
}

/// Seeds whose Voronoi cell is a fragment of `part`: the fragment's seed in the middle of
/// the wanted arc-length band, and a ring of 6-9 neighbours at twice the wanted half
/// extents, so that the bisectors fall on the wanted outline. Neighbours that would lie
/// beyond the rim are left out when the fragment should reach the rim, and seeds along
/// the rest of the rim take their place.
fn plan_fragment(profile: &VesselProfile, part: SherdPart, options: &SherdOptions, rng: &mut impl Rng) -> Option<FragmentPlan> {
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
fn mesh_planned_fragment(profile: &VesselProfile, deformation: &Deformation, voronoi: &RoughVoronoi, plan: &FragmentPlan, target_faces: usize) -> Option<Shell> {
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
fn surface_areas(profile: &VesselProfile) -> (f64, f64) {
    let length = profile.length_mm();
    let steps = (length / 0.5).ceil() as usize;
    let ds = length / steps as f64;
    let area: f64 = (0..steps).map(|k| profile.mid_radius_mm((k as f64 + 0.5) * ds)).sum::<f64>() * ds * std::f64::consts::TAU;
    (area, std::f64::consts::TAU * length)
}

/// The index of the cell containing `(theta, s_mm)`, if inside the grid.
fn cell_at(grid: &ParamGrid, theta: f64, s_mm: f64) -> Option<usize> {
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

/// The part a shell is, from the arc-length band its cells cover and whether it has rim.
fn classify(profile: &VesselProfile, shell: &Shell) -> SherdPart {
    let edge = profile.base_edge_s_mm();
    let has_base = shell.s_range_mm[0] < edge;
    match (shell.has_rim, has_base) {
        (true, true) => SherdPart::RimToBase,
        (true, false) => SherdPart::Rim,
        (false, true) if shell.s_range_mm[1] <= edge => SherdPart::Flat,
        (false, true) => SherdPart::Base,
        (false, false) => SherdPart::Body,
    }
}

fn vessel_truth(profile: &VesselProfile, deformation: &Deformation) -> VesselTruth {
    VesselTruth {
        shape: profile.shape,
        rim_radius_mm: profile.rim_radius_mm(),
        base_radius_mm: profile.base_radius_mm(),
        height_mm: profile.height_mm(),
        wall_thickness_mm: profile.wall_thickness_mm,
        rim_form: profile.rim_form,
        deformation: deformation.clone(),
    }
}

/// Outer-skin extent (mm) below which a fragment counts as too small to orient.
const TINY_EXTENT_MM: f64 = 25.0;

/// The hard case a fragment is, when it was not asked for but came out so (a vessel's
/// base pieces, slivers, pieces of a globular body): a flat base piece, a piece whose
/// outer skin is under 25 mm across, or a piece lying wholly on a spherical zone.
fn inferred_hard_case(profile: &VesselProfile, shell: &Shell, part: SherdPart) -> Option<HardCase> {
    if part == SherdPart::Flat {
        return Some(HardCase::FlatBase);
    }
    let outer = shell.positions.iter().zip(&shell.vertex_kinds).filter(|(_, kind)| **kind == SurfaceKind::Outer);
    let (low, high) = outer.fold((Point::from([f64::INFINITY; 3]), Point::from([f64::NEG_INFINITY; 3])), |(low, high), (p, _)| (low.inf(p), high.sup(p)));
    if (high - low).norm() < TINY_EXTENT_MM {
        return Some(HardCase::Tiny);
    }
    let [band_low, band_high] = profile.spherical_band_s_mm()?;
    (shell.s_range_mm[0] >= band_low && shell.s_range_mm[1] <= band_high).then_some(HardCase::NearSpherical)
}

/// What happens to a shell after it is built: colour, noise, motion.
struct Surface {
    noise_mm: f64,
    noise_seed: u64,
    /// `None`: stay in the vessel frame.
    motion_seed: Option<u64>,
    colour: Option<ClayColour>,
    hard_case: Option<HardCase>,
    fragment_index: Option<usize>,
}

/// Colours, noise, motion, normals and truth for a shell.
fn finish(seed: u64, shell: Shell, profile: &VesselProfile, deformation: &Deformation, part: SherdPart, surface: &Surface) -> SynthSherd {
    let hard_case = surface.hard_case.or_else(|| inferred_hard_case(profile, &shell, part));
    let Shell { positions, triangles, vertex_kinds, face_kinds, .. } = shell;
    let mut mesh = Mesh::new(positions, triangles);
    if let Some(colour) = &surface.colour {
        mesh.colors = Some(mesh.positions.par_iter().zip(&vertex_kinds).map(|(p, kind)| colour.at(p, *kind)).collect());
    }
    motion::add_noise(&mut mesh.positions, surface.noise_mm, surface.noise_seed);
    let isometry = match surface.motion_seed {
        Some(motion_seed) => {
            let centroid = mesh.centroid().unwrap_or_else(Point::origin);
            motion::random_motion(&mut ChaCha8Rng::seed_from_u64(motion_seed), &centroid, 30.0)
        }
        None => nalgebra::Isometry3::identity(),
    };
    mesh.transform(&isometry);
    mesh.normals = Some(compute_vertex_normals(&mesh, NormalWeighting::Area));
    let axis = Axis::new(isometry * Point::origin(), isometry * Vector::z());
    let rim_points: Vec<Point> = mesh
        .triangles
        .iter()
        .zip(&face_kinds)
        .filter(|(_, kind)| **kind == SurfaceKind::Rim)
        .flat_map(|(triangle, _)| triangle.map(|v| mesh.positions[v as usize]))
        .collect();
    let heights = mesh.positions.iter().map(|p| axis.height_of(p));
    let (low, high) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| (lo.min(h), hi.max(h)));
    let truth = GroundTruth {
        axis,
        rim_radius_mm: matches!(part, SherdPart::Rim | SherdPart::RimToBase).then(|| profile.rim_radius_mm()),
        base_radius_mm: matches!(part, SherdPart::Base | SherdPart::RimToBase).then(|| profile.base_radius_mm()),
        sector_angle_deg: truth::sector_angle_deg(&mesh.positions, &axis),
        rim_sector_angle_deg: (!rim_points.is_empty()).then(|| truth::sector_angle_deg(&rim_points, &axis)),
        height_mm: (high - low).max(0.0),
        profile: profile.skin_polyline(1.0, PROFILE_STEP_MM),
        inner_profile: profile.skin_polyline(-1.0, PROFILE_STEP_MM),
        part,
        hard_case,
        noise_mm: surface.noise_mm,
        fragment_index: surface.fragment_index,
        deformation_bound_mm: deformation.bound_mm(profile.max_radius_mm()),
        vessel: vessel_truth(profile, deformation),
        motion: RigidMotion::from_isometry(&isometry),
        seed,
    };
    SynthSherd { mesh, truth, vertex_kinds, face_kinds }
}

/// The value of `all` whose `name` is `text` (case and `-`/`_` ignored), or an error
/// listing the names.
pub(crate) fn parse_name<T: Copy>(text: &str, all: &[T], name: fn(T) -> &'static str, what: &str) -> crate::Result<T> {
    let wanted = text.trim().to_ascii_lowercase().replace('-', "_");
    all.iter().copied().find(|&value| name(value) == wanted).ok_or_else(|| {
        let names: Vec<&str> = all.iter().map(|&value| name(value)).collect();
        crate::Error::InvalidArgument(format!("unknown {what} {text:?}: expected one of {}", names.join(", ")))
    })
}
