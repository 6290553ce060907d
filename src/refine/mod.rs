//! Refinement of a pre-oriented axis (Wilczek et al. 2018, section 2.3): one file per
//! criterion behind a common [`objective::Objective`]:
//!
//! * [`circles`]: horizontal circles, radius variance (Eq. 2);
//! * [`pareto`]: circle centres and residuals on a Pareto front (Eq. 3-4);
//! * [`superposition`]: vertical profile superposition (Eq. 5-6);
//! * [`tangent`]: tangent plane to rim or base (Eq. 7);
//!
//! with Chernov's circle fits ([`circle_fit`]), the sections they share ([`sections`]),
//! bootstrap intervals ([`uncertainty`]) and a jackknife over sectors of the arc
//! ([`sector_jackknife`]). [`refine`] runs one criterion, or picks one
//! ([`Criterion::Auto`], which on a fragment with no level rim or base averages the
//! circles' and the profile's directions), and never returns an axis its own criterion
//! rates worse than the start.

mod averaging;
mod choice;
pub mod circle_fit;
pub mod circles;
pub(crate) mod edges;
pub(crate) mod flat_face;
mod levelling;
mod linearized_bootstrap;
pub mod normal_line_placement;
pub mod objective;
pub mod pareto;
mod placement;
pub mod sections;
pub mod sector_jackknife;
pub mod superposition;
pub mod tangent;
pub mod uncertainty;

use std::time::Instant;

use serde::{Deserialize, Serialize};

pub use edges::{detect_edges, detect_edges_over, EDGE_LEVEL_FRACTION};
pub use objective::FreeParameters;
pub use pareto::{ParetoChoice, ParetoChoiceKind, ParetoOptions, ParetoPoint};
pub use superposition::{ProfileMethod, ProfileMethodKind};
pub use sections::Surface;
pub use tangent::{Edge, EdgeChoice};

use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::{Error, Result};
use objective::{run_guarded, CriterionRun, Objective, SearchSettings};
use averaging::{averaged_with_profile, profile_from_start};
pub use choice::chosen_criterion;
use choice::{choose_criterion, Choice};
use placement::{radial_curvature, usable_section_count, MIN_PLACING_CURVATURE, PLACING_PROBE_MM};
use sections::PreparedSurface;

crate::vocabulary! {
    /// The refinement criterion.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
    pub enum Criterion: "criterion", "criteria" {
        /// The tangent plane where the fragment keeps a level rim or base; otherwise the
        /// circles criterion, its direction averaged with the profile superposition's where
        /// the two agree within 5 degrees (the report's method is then `Circles`, its reason
        /// says so). Listed first: it is the default.
        #[default]
        Auto = "auto" => "Let the library choose the criterion",
        /// Horizontal circles, radius variance (Eq. 2).
        Circles = "circles" => "Concentric circles fitted to horizontal sections",
        /// Circle centres and residuals on a Pareto front (Eq. 3-4).
        Pareto = "pareto" => "Pareto front of centre dispersion and circle residual",
        /// Vertical profile superposition (Eq. 5 or 6, see [`ProfileMethod`]).
        Profile = "profile" => "Agreement of profile sections",
        /// Tangent plane to the rim or base (Eq. 7), then the circles criterion for the position.
        Tangent = "tangent" => "Tangent planes",
    }
}

/// Settings of [`refine`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RefineOptions {
    /// The criterion.
    pub criterion: Criterion,
    /// Inner, outer or both skins.
    pub surface: Surface,
    /// Horizontal sections; `None`: as many as the mesh resolution allows (at least 12).
    pub section_count: Option<usize>,
    /// Largest tilt from the start axis searched, degrees (the paper's +-10).
    pub search_bound_deg: f64,
    /// All four parameters, or only the shifts after a manual three-point pre-orientation.
    pub free: FreeParameters,
    /// Form of the profile criterion.
    pub profile_method: ProfileMethod,
    /// Settings of the Pareto search.
    pub pareto: ParetoOptions,
    /// Epsilon of Eq. 7: rim/base points lower than this below the extreme are dropped, mm.
    pub tangent_tolerance_mm: f64,
    /// Vertical sections for the tangent criterion.
    pub vertical_section_count: usize,
    /// Rim or base for the tangent criterion; `None`: the one whose extremes are level.
    pub edge: Option<Edge>,
    /// After the tangent plane has fixed the direction, place the axis by the circles
    /// criterion (two shifts) where the skins fix its position (see `place_by_circles`);
    /// otherwise, or when off, the plane's direction turns about the start axis's point at
    /// the fragment's centroid height and keeps the start's position error there (6 mm on
    /// tall vessels in `examples/refine_accuracy.rs`, whose starts are turned 3 degrees
    /// about the base). Placing unconditionally moved short arcs 5-10 mm off. Where the
    /// circles cannot place a base, the normals that meet one vertical line place it
    /// ([`normal_line_placement`]: a floor with the turn of its foot).
    pub tangent_places_by_circles: bool,
}

impl Default for RefineOptions {
    fn default() -> Self {
        RefineOptions {
            criterion: Criterion::Auto,
            surface: Surface::Both,
            section_count: None,
            search_bound_deg: 10.0,
            free: FreeParameters::All,
            profile_method: ProfileMethod::default(),
            pareto: ParetoOptions::default(),
            tangent_tolerance_mm: 3.0,
            vertical_section_count: 12,
            edge: None,
            tangent_places_by_circles: true,
        }
    }
}

/// Wall-clock times of one run, milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct RefineTimings {
    /// Splitting the skins and placing the sections.
    pub prepare_ms: f64,
    /// The search.
    pub search_ms: f64,
    /// Everything.
    pub total_ms: f64,
}

/// The report of one refinement: what ran, with which settings, and how it went.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RefineReport {
    /// The criterion that ran (for `Auto`, the one it chose).
    pub method: Criterion,
    /// Why `Auto` chose it, or the criterion asked for; for the tangent plane on a base,
    /// whether the plane of its flat underside gave the tilts.
    pub reason: String,
    /// The surface used.
    pub surface: Surface,
    /// The options as given.
    pub parameters: RefineOptions,
    /// The rim or base used by the tangent criterion.
    pub edge: Option<Edge>,
    /// Optimiser iterations (Nelder-Mead) or cost evaluations (Pareto).
    pub iterations: u64,
    /// Square root of the criterion's cost at the start axis (mm for all criteria but
    /// Pareto, whose value is the circle residual); infinite where the criterion is
    /// undefined (an automatic refinement that kept its start, flagged, because nothing
    /// was left to refine by).
    pub start_residual_mm: f64,
    /// The same at the returned axis.
    pub residual_mm: f64,
    /// Angle between the start and the returned axis, degrees.
    pub tilt_deg: f64,
    /// Distance the axis moved at the fragment's centroid height, millimetres.
    pub shift_mm: f64,
    /// True when the criterion did not improve on the start axis, which is returned.
    pub kept_start: bool,
    /// True when the result should not be trusted without a look: the circles criterion
    /// left the axis's radial position undetermined (Eq. 2 rises too little when the axis
    /// moves 2 mm along the fragment's radius), the automatic refinement found nothing to refine by and kept its start, or the
    /// tangent plane asked for by name turned the axis to or past the search bound.
    #[serde(default)]
    pub flagged: bool,
    /// Why the result is flagged.
    #[serde(default)]
    pub flag_reason: Option<String>,
    /// Horizontal sections placed.
    pub section_count: usize,
    /// Vertices on the skins used.
    pub skin_vertex_count: usize,
    /// Timings.
    pub timings: RefineTimings,
}

/// The refined axis, the report, and the Pareto front when that criterion ran.
#[derive(Clone, Debug)]
pub struct Refinement {
    /// The refined axis (scan frame, base to rim as the start axis).
    pub axis: Axis,
    /// What happened.
    pub report: RefineReport,
    /// The non-dominated solutions, for the Pareto criterion.
    pub pareto_front: Option<Vec<ParetoPoint>>,
    /// The Pareto solution chosen (one of `pareto_front` or their mean).
    pub pareto_chosen: Option<ParetoPoint>,
}

impl Refinement {
    /// The Pareto front drawn as an SVG plot ([`pareto::front_svg`]), the chosen solution
    /// circled; `None` when the criterion was not Pareto or the front is empty.
    pub fn pareto_plot_svg(&self) -> Option<String> {
        let front = self.pareto_front.as_deref().filter(|front| !front.is_empty())?;
        Some(pareto::front_svg(front, self.pareto_chosen.as_ref()))
    }
}

/// The flag of an automatic refinement that kept its start because nothing fixes a better
/// axis.
fn nothing_to_refine_by() -> String {
    format!(
        "nothing to refine the axis by: no level rim or base, and fewer than {MIN_REFINING_SECTIONS} horizontal sections cut a wall skin (a floor, the underside of a shallow dish, the foot of a wall); the axis is the start's"
    )
}

/// Largest search bound a refinement accepts, degrees: past it the tilts leave the
/// neighbourhood the pre-orientation vouches for.
pub const MAX_SEARCH_BOUND_DEG: f64 = 45.0;

/// Most horizontal sections a refinement accepts: a section every 0.1 mm of a 1 m sherd.
/// Each section is a pass over the skins per cost evaluation, so the bound keeps a
/// hostile option value from asking for unbounded time and memory.
pub const MAX_SECTION_COUNT: usize = 10_000;

pub(crate) fn validate(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Result<()> {
    if !axis.point.iter().chain(axis.direction.iter()).all(|c| c.is_finite()) {
        return Err(Error::InvalidArgument(format!("start axis is not finite: {:?}", axis.record())));
    }
    if !(options.search_bound_deg > 0.0 && options.search_bound_deg <= MAX_SEARCH_BOUND_DEG) {
        return Err(Error::InvalidArgument(format!(
            "search_bound_deg must be in (0, {MAX_SEARCH_BOUND_DEG}], got {}",
            options.search_bound_deg
        )));
    }
    if !(options.tangent_tolerance_mm > 0.0) {
        return Err(Error::InvalidArgument(format!(
            "tangent_tolerance_mm must be positive, got {}",
            options.tangent_tolerance_mm
        )));
    }
    if options.section_count == Some(0) {
        return Err(Error::InvalidArgument("section_count must be at least 1".into()));
    }
    options.profile_method.validated()?;
    options.pareto.validated()?;
    if let Some(count) = options.section_count.filter(|&c| c > MAX_SECTION_COUNT) {
        return Err(Error::InvalidArgument(format!("section_count must be at most {MAX_SECTION_COUNT}, got {count}")));
    }
    if let Some((i, p)) = mesh.positions.iter().enumerate().find(|(_, p)| !p.iter().all(|c| c.is_finite())) {
        return Err(Error::InvalidArgument(format!("vertex {i} is not finite: {p:?}")));
    }
    Ok(())
}

/// Refines `axis` (a pre-orientation of `mesh`) by the criterion of `options`.
///
/// The result is never worse than the start by the criterion's own measure: when the
/// search does not improve on it, the start axis is returned and the report says so.
pub fn refine(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Result<Refinement> {
    refine_placing_on(mesh, mesh, axis, options)
}

/// [`refine`], with the tangent plane's axis placed by the circles criterion on
/// `placement_mesh` (a decimated copy of `mesh`) instead of `mesh`. The pipeline levels
/// a rim on the full-resolution scan, since Eq. 7 rests on its few highest points, and
/// places it on the copy: Eq. 2 averages thousands of section points, and on a 200k-face
/// scan the placement was nine tenths of the refinement's time. Every other criterion
/// runs on `mesh` alone.
pub fn refine_placing_on(mesh: &Mesh, placement_mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Result<Refinement> {
    let started = Instant::now();
    validate(mesh, axis, options)?;
    let surface = PreparedSurface::new(mesh, axis, options.surface, options.section_count)?;
    let prepare_ms = started.elapsed().as_secs_f64() * 1e3;
    let search_started = Instant::now();
    let Choice { criterion: method, reason, edge, levelled: levelled_by_detection } = choose_criterion(&surface, options);
    let bound = options.search_bound_deg.to_radians();
    let settings = SearchSettings { free: options.free, tilt_bound_rad: bound, ..Default::default() };
    let start = [0.0; 4];
    let mut pareto_front = None;
    let mut pareto_chosen = None;
    let mut flag = None;
    let mut flat_face = None;
    let mut averaged_reason = None;
    let CriterionRun { parameters, start_cost, cost, iterations, kept_start } = match method {
        Criterion::Circles | Criterion::Auto => {
            let objective = circles::CirclesObjective::new(&surface);
            let start_cost = objective.value(&start);
            if options.criterion == Criterion::Auto && (!start_cost.is_finite() || usable_section_count(&objective, &start) < MIN_REFINING_SECTIONS) {
                // Asked to choose, `refine` says the fragment gives it nothing to work
                // with rather than failing: the caller keeps the pre-orientation, flagged.
                flag = Some(nothing_to_refine_by());
                CriterionRun { parameters: start, start_cost, cost: start_cost, iterations: 0, kept_start: true }
            } else {
                // Asked to choose, the profile criterion runs beside Eq. 2 (on the other
                // core where there is one: neither needs the other's result).
                let asked_to_choose = options.criterion == Criterion::Auto && options.free == FreeParameters::All;
                let (result, by_profile) = match asked_to_choose {
                    true => rayon::join(|| run_guarded(&objective, start, &settings), || profile_from_start(&surface, options, &settings)),
                    false => (run_guarded(&objective, start, &settings), None),
                };
                let mut result = result?;
                if !result.kept_start {
                    let averaged = by_profile.and_then(|by_profile| averaged_with_profile(&objective, &result, by_profile, &settings));
                    if let Some(averaged) = averaged {
                        result = CriterionRun { parameters: averaged.parameters, cost: averaged.cost, iterations: result.iterations + averaged.iterations, kept_start: false, ..result };
                        averaged_reason = Some(format!(
                            "no level rim or base: horizontal circles (Eq. 2) and profile superposition (Eq. {}), {:.2} degrees apart, their directions averaged and {}",
                            match options.profile_method {
                                ProfileMethod::ReferenceProfile { .. } => 5,
                                _ => 6,
                            },
                            averaged.between_deg,
                            match averaged.placed_by_circles {
                                true => "placed by Eq. 2",
                                false => "turned about the circles' axis at the fragment's centroid height (Eq. 2 holds the averaged axis's position less than half as firmly as the circles' own)",
                            }
                        ));
                    }
                }
                let curvature = radial_curvature(&objective, &result.parameters);
                if curvature < MIN_PLACING_CURVATURE {
                    flag = Some(format!(
                        "the skins barely fix the axis's position: moving it {PLACING_PROBE_MM} mm nearer to or farther from the pre-oriented axis raises Eq. 2 {curvature:.1}-fold (at least {MIN_PLACING_CURVATURE} wanted)"
                    ));
                }
                result
            }
        }
        Criterion::Profile => {
            let objective = superposition::ProfileObjective { surface: &surface, method: options.profile_method };
            run_guarded(&objective, start, &settings)?
        }
        Criterion::Tangent => {
            let edge = edge.expect("the tangent criterion always has an edge");
            let levelled = levelling::level_and_place(mesh, placement_mesh, &surface, options, edge, levelled_by_detection, &settings)?;
            (flag, flat_face) = (levelled.flag, levelled.flat_face);
            levelled.run
        }
        Criterion::Pareto => {
            let search = pareto::search(&surface, [0.0, 0.0], bound, &options.pareto).ok_or_else(|| {
                Error::DegenerateGeometry(format!(
                    "no tilt within {} degrees gives two horizontal sections with at least {} points and {} degrees of arc",
                    options.search_bound_deg, options.pareto.min_section_points, options.pareto.min_sector_angle_deg
                ))
            })?;
            let at_start = pareto::evaluate(&surface, 0.0, 0.0, &options.pareto);
            let chosen = pareto::evaluate(&surface, search.chosen[0], search.chosen[1], &options.pareto)
                .unwrap_or(ParetoPoint { parameters: search.chosen, ..search.front[0] });
            // Keep the start when it dominates the chosen solution.
            let start_dominates = at_start.is_some_and(|s| {
                s.centre_dispersion_mm2 <= chosen.centre_dispersion_mm2 && s.circle_residual_mm2 <= chosen.circle_residual_mm2
            });
            let start_cost = at_start.map_or(f64::INFINITY, |s| s.circle_residual_mm2);
            pareto_front = Some(search.front.clone());
            pareto_chosen = Some(chosen);
            let (parameters, cost) = match (start_dominates, at_start) {
                (true, Some(s)) => (s.parameters, s.circle_residual_mm2),
                _ => (chosen.parameters, chosen.circle_residual_mm2),
            };
            CriterionRun { parameters, start_cost, cost, iterations: search.evaluations as u64, kept_start: start_dominates }
        }
    };
    let refined = surface.axis_of(&parameters);
    let refined = orient_like(&refined, axis);
    // The start frame's origin: the start axis's point level with the centroid.
    let start_at_centroid_height = surface.start_frame.inverse() * crate::mesh::Point::origin();
    let report = RefineReport {
        method,
        reason: match flat_face {
            Some(face) => format!(
                "{reason}; tilted by the plane of its flat {} ({} vertices within {:.2} mm)",
                match edge {
                    Some(Edge::Rim) => "upper face",
                    _ => "underside",
                },
                face.vertices.len(),
                face.band_mm
            ),
            None => averaged_reason.unwrap_or(reason),
        },
        surface: options.surface,
        parameters: options.clone(),
        edge,
        iterations,
        start_residual_mm: start_cost.max(0.0).sqrt(),
        residual_mm: cost.max(0.0).sqrt(),
        tilt_deg: refined.line_angle_to_deg(axis),
        shift_mm: (refined.closest_point(&start_at_centroid_height) - start_at_centroid_height).norm(),
        kept_start,
        flagged: flag.is_some(),
        flag_reason: flag,
        section_count: surface.section_heights_mm.len(),
        skin_vertex_count: surface.skin_vertex_count(),
        timings: RefineTimings {
            prepare_ms,
            search_ms: search_started.elapsed().as_secs_f64() * 1e3,
            total_ms: started.elapsed().as_secs_f64() * 1e3,
        },
    };
    Ok(Refinement { axis: refined, report, pareto_front, pareto_chosen })
}

/// `axis` pointing the same way (base to rim) as `reference`.
fn orient_like(axis: &Axis, reference: &Axis) -> Axis {
    if axis.direction.dot(&reference.direction) < 0.0 { axis.flipped() } else { *axis }
}

/// Horizontal sections with points that the automatic refinement needs to run the circles
/// criterion. Fewer leave Eq. 2 free to fit its four parameters to a patch, such as the
/// few points at the foot of a base's wall (`docs/calibration.md`).
const MIN_REFINING_SECTIONS: usize = 5;
