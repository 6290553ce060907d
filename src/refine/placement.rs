//! Placing an axis whose direction is held (two shifts) by the circles criterion (Eq. 2),
//! and the test of whether the skins fix that position at all: the tangent plane, the
//! averaged criteria and the bootstrap's resamples place their axes here.

use super::circles;
use super::objective::{minimize, FreeParameters, Objective, SearchSettings};
use super::sections::{self, AxisParameters};

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
pub(super) fn usable_section_count(circles: &circles::CirclesObjective, parameters: &AxisParameters) -> usize {
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
/// Not the rise towards the fragment at every `p`: the valley of Eq. 2 along the meridian
/// tilt and the radius is so flat that right and wrong axes alike rise little that way.
/// Along the placement's own move, a search that wandered far along the valley is probed
/// along it and rises little (figures in `docs/calibration.md`).
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
pub(super) const PLACING_PROBE_MM: f64 = 2.0;
/// Least relative rise of Eq. 2 over that move for the placement to count: placements
/// that wandered along the valley rise less, those near the truth far more
/// (`docs/calibration.md`).
pub(crate) const MIN_PLACING_CURVATURE: f64 = 12.0;

/// Horizontal sections with points that the circles criterion needs to place a levelled
/// axis.
const MIN_PLACING_SECTIONS: usize = 6;
