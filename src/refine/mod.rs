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

pub mod circle_fit;
pub mod circles;
pub mod edges;
pub mod flat_face;
pub mod normal_line_placement;
pub mod objective;
pub mod pareto;
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
use edges::{detect_edges_levelled, face_for_levelling, flatter_by_plane, reaches_bound, Levelling, EDGE_LEVEL_TOLERANCE_MM};
use objective::{minimize, Minimum, Objective, SearchSettings};
use sections::{AxisParameters, PreparedSurface};

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
    /// left the axis's radial position undetermined (on the synthetic corpus this flags
    /// 9 of the 10 circles results more than 4 mm off (3 vessels) and 3 of 25 good ones),
    /// the automatic refinement found nothing to refine by and kept its start, or the
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
    options.pareto.clone().validated()?;
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
    let (parameters, start_cost, cost, iterations, kept_start) = match method {
        Criterion::Circles | Criterion::Auto => {
            let objective = circles::CirclesObjective::new(&surface);
            let start_cost = objective.value(&start);
            if options.criterion == Criterion::Auto && (!start_cost.is_finite() || usable_section_count(&objective, &start) < MIN_REFINING_SECTIONS) {
                // Asked to choose, `refine` says the fragment gives it nothing to work
                // with rather than failing: the caller keeps the pre-orientation, flagged.
                flag = Some(nothing_to_refine_by());
                (start, start_cost, start_cost, 0, true)
            } else {
                // Asked to choose, the profile criterion runs beside Eq. 2 (on the other
                // core where there is one: neither needs the other's result).
                let asked_to_choose = options.criterion == Criterion::Auto && options.free == FreeParameters::All;
                let (result, by_profile) = match asked_to_choose {
                    true => rayon::join(|| run_guarded(&objective, start, &settings), || profile_from_start(&surface, options, &settings)),
                    false => (run_guarded(&objective, start, &settings), None),
                };
                let mut result = result?;
                if !result.4 {
                    let averaged = by_profile.and_then(|by_profile| averaged_with_profile(&objective, &result, by_profile, &settings));
                    if let Some(averaged) = averaged {
                        result = (averaged.parameters, result.1, averaged.cost, result.3 + averaged.iterations, false);
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
                let curvature = radial_curvature(&objective, &result.0);
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
            let tangent = tangent::TangentObjective::new(&surface, edge, options.tangent_tolerance_mm, options.vertical_section_count);
            let tangent_start = tangent.value(&start);
            let (tilted, tangent_cost, tangent_iterations, tangent_kept) = if options.free == FreeParameters::ShiftsOnly {
                (start, tangent_start, 0, true)
            } else {
                // The detection levelled the edge from this start with these settings.
                let Levelling { minimum: levelled, face } = match levelled_by_detection {
                    Some(levelled) => levelled,
                    None => {
                        let levelled = tangent::level_edge(
                            &surface,
                            edge,
                            options.tangent_tolerance_mm,
                            options.vertical_section_count,
                            start,
                            &settings,
                            None,
                        )?;
                        let face = face_for_levelling(&surface, options, edge, &levelled.parameters);
                        let flatter = (edge == Edge::Rim && face.is_none()).then(|| {
                            let at_levelled = tangent::edge_evidence(&surface, edge, EDGE_LEVEL_TOLERANCE_MM, options.vertical_section_count, &levelled.parameters);
                            flatter_by_plane(&surface, options, edge, &levelled, &at_levelled)
                        });
                        Levelling { minimum: flatter.flatten().map_or(levelled, |(_, polished)| polished), face }
                    }
                };
                // Never worse than the start by Eq. 7 itself.
                let (mut tilted, mut cost, iterations, kept) = if levelled.value <= tangent_start || !tangent_start.is_finite() {
                    (levelled.parameters, levelled.value, levelled.iterations, false)
                } else {
                    (start, tangent_start, levelled.iterations, true)
                };
                // A flat underside (or a floor's flat face) holds the tilts better than its
                // sections' extremes.
                if let Some(face) = face {
                    tilted = [face.tilts[0], face.tilts[1], tilted[2], tilted[3]];
                    flat_face = Some(face);
                } else if edge == Edge::Rim && !kept {
                    // Eq. 7 and the edge's tests keep the paper's 12 vertical sections;
                    // the rim's plane is fitted through as many as the mesh resolves
                    // (`tangent::plane_section_count`), each extreme one more sample of
                    // the short arc's sagitta, which alone fixes its tilt about its chord.
                    // Not where it never beats the start by Eq. 7, nor where it turns the
                    // levelled axis by more than `MAX_RIM_PLANE_TURN_DEG`.
                    let sections = tangent::plane_section_count(&surface, edge, options.vertical_section_count);
                    let levelled = Minimum { parameters: tilted, value: cost, iterations };
                    let polished = tangent::level_by_plane(&surface, edge, options.tangent_tolerance_mm, sections, &levelled)
                        .map(|polished| (polished.parameters, tangent.value(&polished.parameters)))
                        .filter(|(_, polished_cost)| *polished_cost <= tangent_start || !tangent_start.is_finite())
                        .filter(|(parameters, _)| (parameters[0] - tilted[0]).hypot(parameters[1] - tilted[1]) <= MAX_RIM_PLANE_TURN_DEG.to_radians());
                    if let Some((parameters, polished_cost)) = polished {
                        (tilted, cost) = (parameters, polished_cost);
                    }
                }
                // The plane of level extremes and a flat underside are not bounded: an
                // axis they carry to or past the bound lies where the search was told
                // not to look.
                if reaches_bound(&tilted, bound) {
                    flag = Some(format!(
                        "the tangent plane turned the axis {:.1} degrees from the start, at or past the search bound ({} degrees): the start, or the {edge:?} taken as level, is off",
                        tilted[0].hypot(tilted[1]).to_degrees(),
                        options.search_bound_deg
                    ));
                }
                (tilted, cost, iterations, kept)
            };
            let placed = match options.tangent_places_by_circles {
                false => None,
                true if std::ptr::eq(mesh, placement_mesh) => place_by_circles(&circles::CirclesObjective::new(&surface), tilted, &settings),
                true => {
                    // The copy's own start frame (its centroid differs a little), then back.
                    let tilted_axis = surface.axis_of(&tilted);
                    validate(placement_mesh, &tilted_axis, options)?;
                    let placement = PreparedSurface::new(placement_mesh, &tilted_axis, options.surface, options.section_count)?;
                    place_by_circles(&circles::CirclesObjective::new(&placement), [0.0; 4], &settings)
                        .map(|(placed, iterations)| (surface.parameters_of(&placement.axis_of(&placed)), iterations))
                }
            };
            // A floor with only the turn of its foot gives Eq. 2 no sections to use; its
            // normals still meet the axis. Not a rim's: the vessel's ovality is largest
            // there and turns its normals off the axis (by a millimetre or two at the
            // axis on the synthetic rims), while the base keeps its shape on the wheel.
            let placed = placed.or_else(|| {
                let by_normals = (options.tangent_places_by_circles && edge == tangent::Edge::Base)
                    .then(|| normal_line_placement::place_by_normal_lines(mesh, &surface, tilted));
                by_normals.flatten().map(|placement| (placement.parameters, 0))
            });
            let placed = placed.unwrap_or((tilted, 0));
            (placed.0, tangent_start, tangent_cost, tangent_iterations + placed.1, tangent_kept)
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
            (parameters, start_cost, cost, search.evaluations as u64, start_dominates)
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

/// Largest angle between the axes of the circles criterion and of the profile
/// superposition that [`averaged_with_profile`] averages, degrees: farther apart, one of
/// them at least has run off (on the refinement corpus the pairs 6-16 degrees apart
/// averaged to axes 2.7-7.6 degrees off).
const MAX_CRITERIA_DISAGREEMENT_DEG: f64 = 5.0;

/// At most this many skin vertices carry the profile criterion that [`Criterion::Auto`]
/// averages with Eq. 2 (every k-th skin vertex): the deformation, not the count, limits
/// what a fragment's profile says about its axis, and on the 10k-vertex body sherd of
/// `benches/refine.rs` the profile search took 177 ms on all 8,000 skin vertices.
const PROFILE_MAX_SKIN_VERTICES: usize = 3000;

/// The profile superposition (Eq. 5 or 6, [`ProfileMethod`]) minimised from the start of
/// `surface` over at most [`PROFILE_MAX_SKIN_VERTICES`] of its skin vertices: the
/// parameters and the iterations; `None` when it fails or keeps the start.
fn profile_from_start(surface: &PreparedSurface, options: &RefineOptions, settings: &SearchSettings) -> Option<(AxisParameters, u64)> {
    let thinned = surface.with_skin_vertices_at_most(PROFILE_MAX_SKIN_VERTICES);
    let objective = superposition::ProfileObjective { surface: &thinned, method: options.profile_method };
    let (by_profile, _, _, iterations, kept) = run_guarded(&objective, [0.0; 4], settings).ok()?;
    (!kept).then_some((by_profile, iterations))
}

/// The circles criterion's result `circles_result` (Eq. 2 minimised from the start, as
/// [`run_guarded`] gives it) with its direction averaged with the profile criterion's
/// `by_profile` (its parameters and iterations, [`profile_from_start`]) and placed again by
/// Eq. 2 (two shifts) where Eq. 2 holds it (see [`MIN_AVERAGED_PLACING_HOLD`]), otherwise
/// turned about the circles' axis where it crosses the fragment's centroid height. `None`
/// when the two lie more than [`MAX_CRITERIA_DISAGREEMENT_DEG`] apart, or when the averaged
/// axis's Eq. 2 is worse than the start's.
///
/// On a fragment with no level rim or base the two criteria read different evidence: Eq. 2
/// the horizontal sections' circles, the profile criterion the vertical sections' shape.
/// The vessel's deformation misleads them differently (the ovality moves a short arc's
/// circle centres, the wobble bends its profiles), so their errors partly cancel. On the
/// refinement corpus (`examples/refine_accuracy.rs`) the average brings more fragments
/// within 0.3 degrees, on vessels not used to set it too; within 4 mm it gains on some
/// vessels and loses on others: the gain is the direction's.
fn averaged_with_profile(
    circles: &circles::CirclesObjective,
    circles_result: &(AxisParameters, f64, f64, u64, bool),
    (by_profile, profile_iterations): (AxisParameters, u64),
    settings: &SearchSettings,
) -> Option<Averaged> {
    let &(by_circles, start_cost, _, _, _) = circles_result;
    let circles_direction = sections::CandidateFrame::new(&by_circles).direction();
    let profile_direction = sections::CandidateFrame::new(&by_profile).direction();
    let between_deg = crate::orient::angle_between_deg(&circles_direction, &profile_direction);
    if between_deg > MAX_CRITERIA_DISAGREEMENT_DEG {
        return None;
    }
    let [tilt_x, tilt_y] = sections::tilts_along(&(circles_direction + profile_direction));
    // The shifts are the crossing of the start frame's z = 0, the centroid's height.
    let turned = [tilt_x, tilt_y, by_circles[2], by_circles[3]];
    let (placed, placing_iterations) = search_shifts(circles, turned, settings)?;
    let holds = radial_curvature(circles, &placed) >= MIN_AVERAGED_PLACING_HOLD * radial_curvature(circles, &by_circles);
    // Turned only where that is no worse than the start by Eq. 2, as every result is.
    let turned_cost = (!holds).then(|| circles.value(&turned)).filter(|cost| *cost <= start_cost);
    let (parameters, cost, placed_by_circles) = match turned_cost {
        Some(cost) => (turned, cost, false),
        None => (placed, circles.value(&placed), true),
    };
    (cost <= start_cost).then_some(Averaged {
        parameters,
        cost,
        iterations: profile_iterations + placing_iterations,
        between_deg,
        placed_by_circles,
    })
}

/// The axis [`averaged_with_profile`] gives.
struct Averaged {
    parameters: AxisParameters,
    /// Eq. 2 at `parameters`.
    cost: f64,
    /// The profile search's and the placement's iterations.
    iterations: u64,
    /// The angle between the circles criterion's and the profile criterion's axes, degrees.
    between_deg: f64,
    /// Placed by Eq. 2; otherwise turned about the circles' axis at the centroid's height.
    placed_by_circles: bool,
}

/// Least share of the circles criterion's own [`radial_curvature`] that Eq. 2 must keep
/// at the averaged axis of [`averaged_with_profile`] for that axis to be placed by Eq. 2.
/// Where the averaged direction lies across the valley of Eq. 2 less than half as firmly,
/// the placement slides along the fragment's radius, and an axis Eq. 2 alone had near the
/// truth ends farther off; turned about the circles' axis at the fragment instead, it
/// keeps the averaged direction and the position Eq. 2 fixed there. The fragments the
/// average placed by Eq. 2 took out of 4 mm had mostly lost more than half the
/// curvature (figures in `docs/calibration.md`); the directions, and so the median
/// angle, are those of the average either way.
const MIN_AVERAGED_PLACING_HOLD: f64 = 0.5;

/// The axis with the tilts of `tilted` placed by the circles criterion (two shifts), and
/// the iterations, when the skins fix its position: enough horizontal sections cut them,
/// and moving the placed axis [`PLACING_PROBE_MM`] along the start axis's radius through
/// it raises Eq. 2 at least [`MIN_PLACING_CURVATURE`]-fold ([`radial_curvature`]). On a
/// short arc of a deformed vessel Eq. 2 barely changes along the fragment's radius (each
/// section's radius follows the centre), and the placement wanders 5-10 mm along it,
/// where the probe then runs; `None` then, and the plane's direction
/// turns about the start axis's point at the centroid's height.
pub(crate) fn place_by_circles(
    circles: &circles::CirclesObjective,
    tilted: AxisParameters,
    settings: &SearchSettings,
) -> Option<(AxisParameters, u64)> {
    place_with(circles, tilted, |tilted| search_shifts(circles, tilted, settings))
}

/// The two shifts minimising Eq. 2 with the tilts of `tilted` held, by Nelder-Mead, and
/// the iterations; no test of whether the skins fix them (see [`place_with`]).
pub(crate) fn search_shifts(
    circles: &circles::CirclesObjective,
    tilted: AxisParameters,
    settings: &SearchSettings,
) -> Option<(AxisParameters, u64)> {
    minimize(circles, tilted, &SearchSettings { free: FreeParameters::ShiftsOnly, ..*settings })
        .ok()
        .map(|placed| (placed.parameters, placed.iterations))
}

/// [`place_by_circles`] with the two shifts found by `place` instead of a Nelder-Mead
/// search (the bootstrap places its resamples by Newton steps), under the same conditions.
pub(crate) fn place_with(
    circles: &circles::CirclesObjective,
    tilted: AxisParameters,
    place: impl FnOnce(AxisParameters) -> Option<(AxisParameters, u64)>,
) -> Option<(AxisParameters, u64)> {
    let (placed, iterations) = place_where_sections_allow(circles, tilted, place)?;
    (radial_curvature(circles, &placed) >= MIN_PLACING_CURVATURE).then_some((placed, iterations))
}

/// The two shifts found by `place` where enough horizontal sections cut the skins,
/// whether or not they fix the position: [`place_with`] without its curvature test.
pub(crate) fn place_where_sections_allow(
    circles: &circles::CirclesObjective,
    tilted: AxisParameters,
    place: impl FnOnce(AxisParameters) -> Option<(AxisParameters, u64)>,
) -> Option<(AxisParameters, u64)> {
    if usable_section_count(circles, &tilted) < MIN_PLACING_SECTIONS {
        return None;
    }
    place(tilted)
}

/// The horizontal sections under the axis `parameters` with the points Eq. 2 needs.
fn usable_section_count(circles: &circles::CirclesObjective, parameters: &AxisParameters) -> usize {
    circles
        .surface
        .horizontal_sections(&sections::CandidateFrame::new(parameters))
        .iter()
        .filter(|s| s.points.len() >= circles::MIN_SECTION_POINTS)
        .count()
}

/// The rise of Eq. 2 when the axis `p` moves [`PLACING_PROBE_MM`] along the radius of
/// the start axis through its crossing of the start frame's z = 0 (the line from where the
/// pre-orientation put the axis to where `p` puts it; towards the fragment where `p` has
/// not moved), both ways, mean of both, relative to Eq. 2 at `p` or to the square of
/// [`MIN_PLACING_RESIDUAL_MM`] where that is larger: how well the skins hold the axis
/// where the search took it. Infinite where Eq. 2 is zero at `p`.
///
/// Not the rise towards the fragment at every `p`: measured that way, Eq. 2 rose less
/// than [`MIN_PLACING_CURVATURE`]-fold for 330 of the 351 fragments [`Criterion::Auto`]
/// refined by circles on the 20-vessel refinement corpus, right and wrong alike (a
/// median of 0.5-fold: the valley of Eq. 2 along the meridian tilt and the radius is
/// that flat). Along the placement's own move the test tells something: a search that
/// wandered far along that valley is probed along it and rises little, one that stayed
/// near the start is probed in whatever direction its small shift took. Of those 351 it
/// flagged 101, 26 of the 34 that ended more than 4 mm off.
pub(crate) fn radial_curvature(circles: &circles::CirclesObjective, p: &AxisParameters) -> f64 {
    let at = circles.value(p);
    // The start axis is the start frame's z axis (the fragment's centroid lies on +x at
    // height 0): the probe runs from the start axis's crossing of z = 0 through `p`'s.
    let distance = p[2].hypot(p[3]);
    if !(at > 0.0) || !at.is_finite() {
        return if at == 0.0 { f64::INFINITY } else { 0.0 };
    }
    let (x, y) = if distance < 1e-9 { (1.0, 0.0) } else { (p[2] / distance, p[3] / distance) };
    let moved = |step_mm: f64| circles.value(&[p[0], p[1], p[2] - step_mm * x, p[3] - step_mm * y]);
    ((moved(PLACING_PROBE_MM) + moved(-PLACING_PROBE_MM)) / 2.0 - at) / at.max(MIN_PLACING_RESIDUAL_MM.powi(2))
}

/// The least residual of Eq. 2 (root mean square, mm) that [`radial_curvature`] measures
/// its rise against. Below the residual a scan's noise leaves, what remains is the
/// vessel's deformation, which is systematic: the rise over it says how far the
/// deformation lets the axis slide, not how firmly the sections hold it, and the
/// threshold [`MIN_PLACING_CURVATURE`] was set on scans with noise. The floor lies under
/// the residuals a noisy scan leaves, so a noisy scan is judged as before, and more of a
/// clean scan's flat valleys are flagged, though not all (`docs/calibration.md`).
const MIN_PLACING_RESIDUAL_MM: f64 = 0.012;

/// How far the placed axis is moved along the radial line to test its conditioning, mm.
const PLACING_PROBE_MM: f64 = 2.0;
/// Least relative rise of Eq. 2 over that move for the placement to count. On the
/// synthetic corpus (3 vessels, `REFINE_ACCURACY_DUMP`) placements that wandered 5-10 mm
/// rose 0.04-11-fold, those that brought the axis within 1 mm of the truth 13-900-fold.
pub(crate) const MIN_PLACING_CURVATURE: f64 = 12.0;

/// `axis` pointing the same way (base to rim) as `reference`.
fn orient_like(axis: &Axis, reference: &Axis) -> Axis {
    if axis.direction.dot(&reference.direction) < 0.0 { axis.flipped() } else { *axis }
}

/// Minimises and keeps the start when the search does not beat it:
/// `(parameters, start cost, cost, iterations, kept start)`.
fn run_guarded<O: Objective>(
    objective: &O,
    start: AxisParameters,
    settings: &SearchSettings,
) -> Result<(AxisParameters, f64, f64, u64, bool)> {
    let start_cost = objective.value(&start);
    let Minimum { parameters, value, iterations } = minimize(objective, start, settings)?;
    if value < start_cost {
        Ok((parameters, start_cost, value, iterations, false))
    } else {
        Ok((start, start_cost, start_cost, iterations, true))
    }
}

/// The criterion [`refine`] would run on `mesh` from `axis` (the one of `options`, or
/// the one `Criterion::Auto` picks: the tangent plane where a level rim or base is
/// preserved, the circles (with the profile) otherwise), without running it.
pub fn chosen_criterion(mesh: &Mesh, axis: &Axis, options: &RefineOptions) -> Result<Criterion> {
    validate(mesh, axis, options)?;
    let surface = PreparedSurface::new(mesh, axis, options.surface, options.section_count)?;
    Ok(choose_criterion(&surface, options).criterion)
}

/// The criterion [`choose_criterion`] picked.
pub(crate) struct Choice {
    /// The criterion to run.
    pub criterion: Criterion,
    /// Why.
    pub reason: String,
    /// The edge for the tangent criterion.
    pub edge: Option<Edge>,
    /// The edge levelled from the start axis, where the detection already did it (the
    /// tangent criterion's own first step, with the same settings), with the flat face
    /// that gave its tilts.
    pub levelled: Option<Levelling>,
}

/// The criterion to run, why, the edge for the tangent criterion and, where the edge was
/// detected, its levelling.
pub(crate) fn choose_criterion(surface: &PreparedSurface, options: &RefineOptions) -> Choice {
    let detect = || {
        detect_edges_levelled(surface, options, [EDGE_LEVEL_FRACTION; 2])
            .into_iter()
            .min_by(|a, b| a.0.spread_mm.total_cmp(&b.0.spread_mm))
    };
    match options.criterion {
        Criterion::Auto => match options.edge.map(|edge| (edge, None)).or_else(|| detect().map(|e| (e.0.edge, Some(e)))) {
            Some((edge, detected)) => Choice {
                criterion: Criterion::Tangent,
                reason: match &detected {
                    Some((e, _)) => format!(
                        "a level {:?}: {:.0}% of vertical sections within {EDGE_LEVEL_TOLERANCE_MM} mm, spread {:.2} mm",
                        e.edge,
                        e.level_fraction * 100.0,
                        e.spread_mm
                    ),
                    None => format!("{edge:?} given"),
                },
                edge: Some(edge),
                levelled: detected.and_then(|(_, levelled)| levelled),
            },
            None => Choice {
                criterion: Criterion::Circles,
                reason: "no level rim or base: horizontal circles".into(),
                edge: None,
                levelled: None,
            },
        },
        Criterion::Tangent => {
            let detected = if options.edge.is_some() { None } else { detect() };
            let edge = options.edge.or(detected.as_ref().map(|e| e.0.edge)).unwrap_or(Edge::Rim);
            Choice { criterion: Criterion::Tangent, reason: "asked for".into(), edge: Some(edge), levelled: detected.and_then(|(_, l)| l) }
        }
        other => Choice { criterion: other, reason: "asked for".into(), edge: None, levelled: None },
    }
}

/// Largest turn of a levelled rim's axis by its plane through the finer vertical sections,
/// degrees. A short rim's plane is barely held about its chord, and the finer sections let
/// it slide there further (on the refinement corpus, 30 vessels in 0.8 mm cells: a rim
/// levelled 1.9 degrees off went to 8.9, and the root mean square of the rims' errors
/// rose 0.95 -> 1.03 degrees while their median fell 0.212 -> 0.199); within a degree
/// the median gain stays (0.199, 194 of 251 rims within 0.3 degrees instead of 185) and
/// the root mean square is 0.95.
const MAX_RIM_PLANE_TURN_DEG: f64 = 1.0;

/// Horizontal sections with points that the circles criterion needs to place a levelled
/// axis.
const MIN_PLACING_SECTIONS: usize = 6;
/// Horizontal sections with points that the automatic refinement needs to run the circles
/// criterion. Fewer leave Eq. 2 free to fit its four parameters to a patch: on the
/// refinement corpus in 0.8 mm cells, bases with one section of seven or eight points at
/// the foot of their wall were fitted to a hundredth of the true axis's residual 10-28 mm
/// off it, five of them unflagged; every such runaway had four sections or fewer, in 2 mm
/// cells too. With five, SfS++ pot C piece 3 (200 points) is still refined from 3.0 to
/// 2.0 degrees off its reference (six keep its start).
const MIN_REFINING_SECTIONS: usize = 5;
