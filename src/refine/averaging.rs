//! The automatic refinement's average of two criteria on a fragment with no level rim
//! or base: the circles criterion (Eq. 2) and the profile superposition (Eq. 5-6) read
//! different evidence, and the vessel's deformation misleads them differently.

use super::circles;
use super::objective::{run_guarded, CriterionRun, Objective, SearchSettings};
use super::placement::{radial_curvature, search_shifts};
use super::sections::{self, AxisParameters, PreparedSurface};
use super::superposition;
use super::RefineOptions;

/// Largest angle between the axes of the circles criterion and of the profile
/// superposition that [`averaged_with_profile`] averages, degrees: farther apart, one of
/// them at least has run off (`docs/calibration.md`).
const MAX_CRITERIA_DISAGREEMENT_DEG: f64 = 5.0;

/// At most this many skin vertices carry the profile criterion that [`Criterion::Auto`](crate::refine::Criterion::Auto)
/// averages with Eq. 2 (every k-th skin vertex): the deformation, not the count, limits
/// what a fragment's profile says about its axis, while the search's time grows with the
/// count (`docs/calibration.md`).
const PROFILE_MAX_SKIN_VERTICES: usize = 3000;

/// The profile superposition (Eq. 5 or 6, [`ProfileMethod`](crate::refine::superposition::ProfileMethod)) minimised from the start of
/// `surface` over at most [`PROFILE_MAX_SKIN_VERTICES`] of its skin vertices: the
/// parameters and the iterations; `None` when it fails or keeps the start.
pub(super) fn profile_from_start(surface: &PreparedSurface, options: &RefineOptions, settings: &SearchSettings) -> Option<(AxisParameters, u64)> {
    let thinned = surface.with_skin_vertices_at_most(PROFILE_MAX_SKIN_VERTICES);
    let objective = superposition::ProfileObjective { surface: &thinned, method: options.profile_method };
    let run = run_guarded(&objective, [0.0; 4], settings).ok()?;
    (!run.kept_start).then_some((run.parameters, run.iterations))
}

/// The circles criterion's result `circles_result` (Eq. 2 minimised from the start, as
/// [`super::objective::run_guarded`] gives it) with its direction averaged with the profile criterion's
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
pub(super) fn averaged_with_profile(
    circles: &circles::CirclesObjective,
    circles_result: &CriterionRun,
    (by_profile, profile_iterations): (AxisParameters, u64),
    settings: &SearchSettings,
) -> Option<Averaged> {
    let CriterionRun { parameters: by_circles, start_cost, .. } = *circles_result;
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
pub(super) struct Averaged {
    pub(super) parameters: AxisParameters,
    /// Eq. 2 at `parameters`.
    pub(super) cost: f64,
    /// The profile search's and the placement's iterations.
    pub(super) iterations: u64,
    /// The angle between the circles criterion's and the profile criterion's axes, degrees.
    pub(super) between_deg: f64,
    /// Placed by Eq. 2; otherwise turned about the circles' axis at the centroid's height.
    pub(super) placed_by_circles: bool,
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
