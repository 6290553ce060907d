//! The tangent criterion's run (Eq. 7, [`super::tangent`]): the edge levelled from the
//! start (by its extremes, by a flat face, or by the plane through finer sections), never
//! worse than the start by Eq. 7, then placed by the circles criterion where the skins
//! hold the position, or by a floor's normal lines.

use super::circles;
use super::edges::{face_for_levelling, flatter_by_plane, reaches_bound, Levelling, EDGE_LEVEL_TOLERANCE_MM};
use super::flat_face::FlatFace;
use super::normal_line_placement;
use super::objective::{CriterionRun, FreeParameters, Minimum, Objective, SearchSettings};
use super::placement::place_by_circles;
use super::sections::PreparedSurface;
use super::tangent::{self, Edge};
use super::{validate, RefineOptions};
use crate::mesh::Mesh;
use crate::Result;

/// Largest turn of a levelled rim's axis by its plane through the finer vertical sections,
/// degrees. A short rim's plane is barely held about its chord, and the finer sections let
/// it slide there further; within a degree the finer sections' gain stays and no rim runs
/// off (`docs/calibration.md`).
const MAX_RIM_PLANE_TURN_DEG: f64 = 1.0;

/// What [`level_and_place`] gives beside the criterion's run.
pub(super) struct LevelledRun {
    pub(super) run: CriterionRun,
    /// Why the result should not be trusted without a look, if it should not.
    pub(super) flag: Option<String>,
    /// The flat face whose plane gave the tilts, if one did.
    pub(super) flat_face: Option<FlatFace>,
}

/// Levels `edge` of `surface` from its start frame and places the levelled axis (on
/// `placement_mesh`'s copy of the skins where it is not `mesh`); `levelled_by_detection`
/// is the edge detection's own levelling from the same start, reused.
pub(super) fn level_and_place(
    mesh: &Mesh,
    placement_mesh: &Mesh,
    surface: &PreparedSurface,
    options: &RefineOptions,
    edge: Edge,
    levelled_by_detection: Option<Levelling>,
    settings: &SearchSettings,
) -> Result<LevelledRun> {
    let start = [0.0; 4];
    let bound = options.search_bound_deg.to_radians();
    let mut flag = None;
    let mut flat_face = None;
    let tangent = tangent::TangentObjective::new(surface, edge, options.tangent_tolerance_mm, options.vertical_section_count);
    let tangent_start = tangent.value(&start);
    let (tilted, tangent_cost, tangent_iterations, tangent_kept) = if options.free == FreeParameters::ShiftsOnly {
        (start, tangent_start, 0, true)
    } else {
        // The detection levelled the edge from this start with these settings.
        let Levelling { minimum: levelled, face } = match levelled_by_detection {
            Some(levelled) => levelled,
            None => {
                let levelled = tangent::level_edge(
                    surface,
                    edge,
                    options.tangent_tolerance_mm,
                    options.vertical_section_count,
                    start,
                    settings,
                    None,
                )?;
                let face = face_for_levelling(surface, options, edge, &levelled.parameters);
                let flatter = (edge == Edge::Rim && face.is_none()).then(|| {
                    let at_levelled = tangent::edge_evidence(surface, edge, EDGE_LEVEL_TOLERANCE_MM, options.vertical_section_count, &levelled.parameters);
                    flatter_by_plane(surface, options, edge, &levelled, &at_levelled)
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
            let sections = tangent::plane_section_count(surface, edge, options.vertical_section_count);
            let levelled = Minimum { parameters: tilted, value: cost, iterations };
            let polished = tangent::level_by_plane(surface, edge, options.tangent_tolerance_mm, sections, &levelled)
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
        true if std::ptr::eq(mesh, placement_mesh) => place_by_circles(&circles::CirclesObjective::new(surface), tilted, settings),
        true => {
            // The copy's own start frame (its centroid differs a little), then back.
            let tilted_axis = surface.axis_of(&tilted);
            validate(placement_mesh, &tilted_axis, options)?;
            let placement = PreparedSurface::new(placement_mesh, &tilted_axis, options.surface, options.section_count)?;
            place_by_circles(&circles::CirclesObjective::new(&placement), [0.0; 4], settings)
                .map(|(placed, iterations)| (surface.parameters_of(&placement.axis_of(&placed)), iterations))
        }
    };
    // A floor with only the turn of its foot gives Eq. 2 no sections to use; its
    // normals still meet the axis. Not a rim's: the vessel's ovality is largest
    // there and turns its normals off the axis (by a millimetre or two at the
    // axis on the synthetic rims), while the base keeps its shape on the wheel.
    let placed = placed.or_else(|| {
        let by_normals = (options.tangent_places_by_circles && edge == tangent::Edge::Base)
            .then(|| normal_line_placement::place_by_normal_lines(mesh, surface, tilted));
        by_normals.flatten().map(|placement| (placement.parameters, 0))
    });
    let placed = placed.unwrap_or((tilted, 0));
    let run = CriterionRun { parameters: placed.0, start_cost: tangent_start, cost: tangent_cost, iterations: tangent_iterations + placed.1, kept_start: tangent_kept };
    Ok(LevelledRun { run, flag, flat_face })
}
