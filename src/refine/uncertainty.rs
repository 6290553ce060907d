//! Uncertainty of a refined axis by bootstrap over sections: the criterion is run again
//! on resampled sections (horizontal sections for the circles criterion, vertical
//! sections as well for the tangent plane), each resample drawing as many sections as
//! there are, with replacement. The spread of the resampled axes about the estimate gives
//! a 95% interval for the axis angle and, through the measurements recomputed on each
//! resampled axis, for the rim and base diameters.
//!
//! For the tangent plane a resample turns the estimate by the change of the
//! least-squares plane through the level rim (base) extremes of its sections, instead
//! of searching Eq. 7 again (see [`super::tangent::TangentObjective::plane_tilts`]).
//!
//! Neighbouring sections share the vessel's deformation, so resampling them as if they
//! were independent underestimates the spread; [`BootstrapOptions::spread_factor`]
//! widens the intervals, and floors ([`BootstrapOptions::angle_floor_deg`],
//! [`BootstrapOptions::rim_diameter_floor_fraction`],
//! [`BootstrapOptions::base_diameter_floor_fraction`]) add what no resample shows (a
//! rim's own tilt, the vessel's deformation, the axis's radial position on a short arc). `examples/refine_accuracy.rs`
//! measures the coverage.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::circles::CirclesObjective;
use super::objective::{minimize, FreeParameters, SearchSettings};
use super::sections::{quantile, PreparedSurface};
use super::tangent::TangentObjective;
use super::{choose_criterion, place_by_circles, Criterion, RefineOptions};
use crate::mesh::Mesh;
use crate::Error;
use crate::orient::Axis;
use crate::Result;

/// Settings of the bootstrap.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct BootstrapOptions {
    /// Number of resamples; 0 disables the intervals.
    pub samples: usize,
    /// Seed of the resampling (the same seed gives the same intervals).
    pub seed: u64,
    /// Confidence level of the intervals.
    pub confidence: f64,
    /// Factor widening the bootstrap spread (see [`SPREAD_FACTOR`]).
    pub spread_factor: f64,
    /// Half-width of the axis interval that resampling cannot show, degrees: a rim is
    /// never quite perpendicular to the axis (a thrown vessel's rim tilts by up to a
    /// few tenths of a degree) and every resample shares that tilt.
    pub angle_floor_deg: f64,
    /// Half-width of the rim diameter interval that resampling cannot show, as a fraction
    /// of the diameter (see [`RIM_DIAMETER_FLOOR_FRACTION`]).
    pub rim_diameter_floor_fraction: f64,
    /// The same for the base diameter (see [`BASE_DIAMETER_FLOOR_FRACTION`]).
    pub base_diameter_floor_fraction: f64,
}

impl Default for BootstrapOptions {
    fn default() -> Self {
        BootstrapOptions {
            samples: 24,
            seed: 0x5e4d,
            confidence: 0.95,
            spread_factor: SPREAD_FACTOR,
            angle_floor_deg: ANGLE_FLOOR_DEG,
            rim_diameter_floor_fraction: RIM_DIAMETER_FLOOR_FRACTION,
            base_diameter_floor_fraction: BASE_DIAMETER_FLOOR_FRACTION,
        }
    }
}

/// Default [`BootstrapOptions::angle_floor_deg`], calibrated on the synthetic corpus.
const ANGLE_FLOOR_DEG: f64 = 0.5;
/// Default [`BootstrapOptions::spread_factor`]. The bootstrap draws sections as if they
/// were independent, but neighbouring sections share the vessel's deformation and the
/// scan's noise pattern, so the resampled axes scatter less than the estimate's error:
/// at 2.0 the synthetic corpus's axis intervals covered the truth too rarely, at 2.5
/// (`examples/refine_accuracy.rs`) about 93% of them do.
pub const SPREAD_FACTOR: f64 = 2.5;
/// Default [`BootstrapOptions::rim_diameter_floor_fraction`]: the synthetic corpus
/// deforms its vessels (ovality, lean, wobble) and adds noise; a rim's radius on a
/// short arc of an oval rim differs from the vessel's nominal one by up to a few
/// percent whatever the axis, an error no resample of the sections shows.
pub const RIM_DIAMETER_FLOOR_FRACTION: f64 = 0.03;
/// Default [`BootstrapOptions::base_diameter_floor_fraction`]: as for the rim, and the
/// base edge (where the outer skin leaves the standing plane) is a rounded foot whose
/// measured radius moves with the band it is taken in by up to 4% (see
/// `tests/measure.rs`), so the base's floor is wider.
pub const BASE_DIAMETER_FLOOR_FRACTION: f64 = 0.05;

/// Multinomial resampling weights: `count` draws with replacement among `count` items.
fn resample_weights(count: usize, rng: &mut impl Rng) -> Vec<f64> {
    let mut weights = vec![0.0; count];
    for _ in 0..count {
        weights[rng.random_range(0..count)] += 1.0;
    }
    weights
}

/// Most bootstrap resamples accepted: each is a refinement, and intervals stop changing
/// long before (the default is 24).
pub const MAX_BOOTSTRAP_SAMPLES: usize = 10_000;

/// Axes refined again on resampled sections around `axis` (the refined axis) by the
/// criterion `options` chose.
pub fn bootstrap_axes(mesh: &Mesh, axis: &Axis, options: &RefineOptions, bootstrap: &BootstrapOptions) -> Result<Vec<Axis>> {
    if bootstrap.samples == 0 {
        return Ok(Vec::new());
    }
    if bootstrap.samples > MAX_BOOTSTRAP_SAMPLES {
        return Err(Error::InvalidArgument(format!(
            "bootstrap samples must be at most {MAX_BOOTSTRAP_SAMPLES}, got {}",
            bootstrap.samples
        )));
    }
    super::validate(mesh, axis, options)?;
    let surface = PreparedSurface::new(mesh, axis, options.surface, options.section_count)?;
    let (method, _, edge) = choose_criterion(&surface, options);
    let section_count = surface.horizontal_sections(&super::sections::CandidateFrame::new(&[0.0; 4])).len();
    let settings = SearchSettings {
        free: options.free,
        tilt_bound_rad: options.search_bound_deg.to_radians(),
        max_iterations: 80,
        max_restarts: 0,
        ..Default::default()
    };
    let axes = (0..bootstrap.samples)
        .into_par_iter()
        .filter_map(|sample| {
            let mut rng = ChaCha8Rng::seed_from_u64(bootstrap.seed.wrapping_add(sample as u64 * 0x9e37_79b9));
            let weights = resample_weights(section_count, &mut rng);
            let circles = CirclesObjective { surface: &surface, section_weights: Some(&weights) };
            let mut start = [0.0; 4];
            let free = match (method, edge) {
                (Criterion::Tangent, Some(edge)) if options.free != FreeParameters::ShiftsOnly => {
                    // The estimate is level already: each resample moves it by the turn of
                    // the least-squares plane through the level extremes of its sections.
                    // Repeating the Nelder-Mead search of Eq. 7 instead let a resample of a
                    // short rim (its sections nearly on one chord) drift about that chord
                    // to the search bound: intervals of 20 degrees beside others of 0.
                    let tangent =
                        TangentObjective::new(&surface, edge, options.tangent_tolerance_mm, options.vertical_section_count);
                    let weights = resample_weights(tangent.section_count(), &mut rng);
                    let [base_x, base_y] = tangent.plane_tilts(&start, None)?;
                    let [tilt_x, tilt_y] = tangent.plane_tilts(&start, Some(&weights))?;
                    start = [tilt_x - base_x, tilt_y - base_y, 0.0, 0.0];
                    if options.tangent_places_by_circles {
                        start = place_by_circles(&circles, start, &settings).map_or(start, |(placed, _)| placed);
                    }
                    return Some(surface.axis_of(&start));
                }
                _ => options.free,
            };
            let placed = minimize(&circles, start, &SearchSettings { free, ..settings }).ok()?;
            Some(surface.axis_of(&placed.parameters))
        })
        .collect();
    Ok(axes)
}

/// The interval `[0, upper]` of the angle between the true and the estimated axis:
/// the `confidence` quantile of the resampled axes' angles to the estimate, widened,
/// combined with the floor.
pub fn angle_interval_deg(estimate: &Axis, replicates: &[Axis], bootstrap: &BootstrapOptions) -> Option<[f64; 2]> {
    if replicates.len() < 5 {
        return None;
    }
    let mut angles: Vec<f64> = replicates.iter().map(|a| a.line_angle_to_deg(estimate)).collect();
    Some([0.0, (bootstrap.spread_factor * quantile(&mut angles, bootstrap.confidence)).hypot(bootstrap.angle_floor_deg)])
}

/// A symmetric interval about `estimate`: the `confidence` quantile of the resampled
/// values' deviations from it, widened, and never narrower than `floor_half_width`.
pub fn value_interval(estimate: f64, replicates: &[f64], floor_half_width: f64, bootstrap: &BootstrapOptions) -> Option<[f64; 2]> {
    let mut deviations: Vec<f64> = replicates.iter().filter(|v| v.is_finite()).map(|v| (v - estimate).abs()).collect();
    if deviations.len() < 5 {
        return None;
    }
    let half_width = (bootstrap.spread_factor * quantile(&mut deviations, bootstrap.confidence)).hypot(floor_half_width);
    Some([estimate - half_width, estimate + half_width])
}
