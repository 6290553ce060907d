//! The rim and base a fragment keeps: each levelled by the tangent plane (Eq. 7, see
//! [`super::tangent`]) from the start axis, or by the flat face a base stands on
//! ([`super::flat_face`]), and then tested for being an edge, level along the arc, not
//! sagging, not a floor's face, found inside the search bound. The automatic
//! refinement takes the tangent plane where one passes, and the measurements report a rim
//! or base diameter only where one does.

use super::objective::{Minimum, Objective, SearchSettings};
use super::sections::{AxisParameters, PreparedSurface};
use super::flat_face::{flat_face, FlatFace};
use super::tangent::{self, Edge};
use super::{FreeParameters, RefineOptions};

/// The rim and base the fragment keeps around the start axis of `surface`.
///
/// A rim or base is recognised after levelling it: the tangent criterion tilts the axis
/// to make the extremes of the vertical sections level, and the edge counts when
/// [`EDGE_LEVEL_FRACTION`] of them then lie within 1 mm (`EDGE_LEVEL_TOLERANCE_MM`) of their
/// median. Tested at the start axis, a rim 3 degrees off on a 70 mm chord rises by 3.5 mm
/// and would be missed.
pub fn detect_edges(surface: &PreparedSurface, options: &RefineOptions) -> Vec<tangent::EdgeEvidence> {
    detect_edges_over(surface, options, [EDGE_LEVEL_FRACTION; 2])
}

/// [`detect_edges`] accepting the rim (base) level over `min_level_fraction[0]` (`[1]`)
/// of the vertical sections. Measuring a rim needs less than choosing the tangent criterion: a rim kept
/// over a third of the arc gives its radius, while its short chord leaves the tilt about
/// it poorly fixed for Eq. 7.
pub fn detect_edges_over(surface: &PreparedSurface, options: &RefineOptions, min_level_fraction: [f64; 2]) -> Vec<tangent::EdgeEvidence> {
    detect_edges_levelled(surface, options, min_level_fraction).into_iter().map(|(evidence, _)| evidence).collect()
}

/// How a detected edge was levelled: Eq. 7's minimum, its tilts the flat face's where one
/// gives them, and that face.
#[derive(Clone, Debug)]
pub(crate) struct Levelling {
    pub minimum: Minimum,
    pub face: Option<FlatFace>,
}

/// [`detect_edges_over`] with each detected edge's levelling (`None` when the options
/// hold the tilts).
pub(crate) fn detect_edges_levelled(
    surface: &PreparedSurface,
    options: &RefineOptions,
    min_level_fraction: [f64; 2],
) -> Vec<(tangent::EdgeEvidence, Option<Levelling>)> {
    let settings = SearchSettings {
        free: FreeParameters::TiltsOnly,
        tilt_bound_rad: options.search_bound_deg.to_radians(),
        ..Default::default()
    };
    [Edge::Rim, Edge::Base]
        .into_iter()
        .filter_map(|edge| {
            let minimum = if options.free == FreeParameters::ShiftsOnly {
                None
            } else {
                Some(
                    tangent::level_edge(
                        surface,
                        edge,
                        options.tangent_tolerance_mm,
                        options.vertical_section_count,
                        [0.0; 4],
                        &settings,
                        None,
                    )
                    .ok()?,
                )
            };
            let min_level_fraction = min_level_fraction[usize::from(edge == Edge::Base)];
            // A floor has no rim: its highest points lie on its upper face, which passes
            // for one only where it is flat (its underside, when the start axis holds the
            // floor upside down).
            let floor_top = edge == Edge::Rim && is_floor(surface);
            // The flat face a base stands on gives its tilts, wherever Eq. 7 led; a base
            // that sags is still a base where its face holds its plane.
            let face = face_for_levelling(surface, options, edge, &minimum.as_ref().map_or([0.0; 4], |m| m.parameters));
            let face_holds = face.is_some();
            let passes = |e: &tangent::EdgeEvidence| {
                e.level_fraction >= min_level_fraction
                    && e.spread_mm <= EDGE_MAX_SPREAD_MM
                    && match floor_top {
                        true => face_holds,
                        false => e.sag_mm.abs() <= EDGE_MAX_SAG_MM || face_holds,
                    }
            };
            let minimum = match (minimum, &face) {
                (Some(eq7), Some(face)) => {
                    let parameters = [face.tilts[0], face.tilts[1], eq7.parameters[2], eq7.parameters[3]];
                    let objective = tangent::TangentObjective::new(surface, edge, options.tangent_tolerance_mm, options.vertical_section_count);
                    Some(Minimum { parameters, value: objective.value(&parameters), ..eq7 })
                }
                (minimum, _) => minimum,
            };
            let levelled = minimum.map_or([0.0; 4], |m| m.parameters);
            let levelling = |minimum: Option<Minimum>| minimum.map(|minimum| Levelling { minimum, face: face.clone() });
            let evidence = |parameters: &AxisParameters| {
                tangent::edge_evidence(surface, edge, EDGE_LEVEL_TOLERANCE_MM, options.vertical_section_count, parameters)
            };
            let at_levelled = evidence(&levelled);
            // A rim whose levelling passes but for its sag is taken turned onto the plane
            // of its level extremes where that flattens it and passes. Not one that fails
            // the level test otherwise: turned onto its own extremes, a body sherd's break
            // line passed as a rim (synthetic_sherd 30 went 14 degrees off).
            let passes_but_for_sag = passes(&tangent::EdgeEvidence { sag_mm: 0.0, ..at_levelled });
            let relevelled = minimum.as_ref().filter(|_| passes_but_for_sag && !face_holds).and_then(|m| {
                flatter_by_plane(surface, options, edge, m, &at_levelled).filter(|(at_polished, _)| passes(at_polished))
            });
            if let Some((at_polished, polished)) = relevelled {
                return Some((at_polished, levelling(Some(polished))));
            }
            // Eq. 7 held at the search's bound found no level plane inside it: what lies
            // level there is whatever the bound left, such as the flank of a rounded
            // underside (a floor piece levelled 7.4 degrees off at a 10 degree bound). A
            // plane that takes over from there, the rim's plane of level extremes above or
            // a flat underside, is judged where it leads (and the refinement flags an
            // axis past the bound).
            if minimum.as_ref().is_some_and(|m| reaches_bound(&m.parameters, settings.tilt_bound_rad)) && !face_holds {
                return None;
            }
            if passes(&at_levelled) {
                return Some((at_levelled, levelling(minimum)));
            }
            // A partial edge is level from its top, and levelling it lets the rising break
            // lines pull the plane off it: it is also tested at the axis as given.
            if min_level_fraction >= EDGE_LEVEL_FRACTION {
                return None;
            }
            let partial = |parameters: &AxisParameters| {
                tangent::edge_evidence_anchored(surface, edge, EDGE_LEVEL_TOLERANCE_MM, options.vertical_section_count, parameters, true)
            };
            [levelled, [0.0; 4]].iter().map(partial).find(passes).map(|evidence| (evidence, levelling(minimum)))
        })
        .collect()
}

/// The flat face that gives `edge` its tilts after Eq. 7 levelled it to `eq7_levelled`:
/// a base's underside, or a floor's upper face ([`flat_face`]), within the search bound;
/// never the rim of a wall, whose flat top slants with the wall. A flat face holds the
/// edge's tilts better than Eq. 7's extremes, and still finds them where the wall's
/// first rise beside a small floor led Eq. 7 off.
pub(crate) fn face_for_levelling(surface: &PreparedSurface, options: &RefineOptions, edge: Edge, eq7_levelled: &AxisParameters) -> Option<FlatFace> {
    (edge == Edge::Base || is_floor(surface)).then(|| flat_face(surface, edge, eq7_levelled, options.search_bound_deg.to_radians())).flatten()
}

/// A rim's levelling `levelled` (with its evidence `at_levelled`) turned onto the plane of
/// its level extremes ([`tangent::level_by_plane`]), with the evidence there, when that
/// leaves its extremes sagging less; `None` for a base, or when it does not.
pub(crate) fn flatter_by_plane(
    surface: &PreparedSurface,
    options: &RefineOptions,
    edge: Edge,
    levelled: &Minimum,
    at_levelled: &tangent::EdgeEvidence,
) -> Option<(tangent::EdgeEvidence, Minimum)> {
    if edge != Edge::Rim {
        return None;
    }
    let polished = tangent::level_by_plane(surface, edge, options.tangent_tolerance_mm, options.vertical_section_count, levelled)?;
    let at_polished = tangent::edge_evidence(surface, edge, EDGE_LEVEL_TOLERANCE_MM, options.vertical_section_count, &polished.parameters);
    (at_polished.sag_mm.abs() < at_levelled.sag_mm.abs()).then_some((at_polished, polished))
}

/// A rim or base is level when this share of vertical sections has its extreme within
/// 1 mm (`EDGE_LEVEL_TOLERANCE_MM`) of the median extreme.
pub const EDGE_LEVEL_FRACTION: f64 = 0.6;
/// ...and their median absolute deviation is at most this, mm: between a levelled rim's
/// or base's spread and a levelled break line's (`docs/calibration.md`).
const EDGE_MAX_SPREAD_MM: f64 = 0.08;
/// ...and their ends sag from the plane by at most this, mm ([`tangent::edge_sag_mm`]),
/// unless a flat underside holds the base's plane: a rounded underside rocks, and Eq. 7
/// levels it degrees off while its extremes still look level (`docs/calibration.md`).
const EDGE_MAX_SAG_MM: f64 = 0.15;
/// A piece with less than this share of its vertices on a wall skin (facing away from or
/// towards the axis) is a floor ([`is_floor`]), whose curved upper face Eq. 7 would
/// otherwise level as a rim (`docs/calibration.md`).
const MIN_WALL_SHARE: f64 = 0.02;

/// Whether the piece is a floor, with (almost) no wall: its highest points lie on its
/// upper face, which Eq. 7 levels as readily as an edge.
fn is_floor(surface: &PreparedSurface) -> bool {
    surface.wall_share() < MIN_WALL_SHARE
}

/// A levelling whose tilt reaches this share of the search bound stopped at the bound.
const AT_BOUND_SHARE: f64 = 0.99;

/// Whether the tilts of `parameters` reach the search bound `bound_rad` (at
/// [`AT_BOUND_SHARE`] of it) or lie past it.
pub(crate) fn reaches_bound(parameters: &AxisParameters, bound_rad: f64) -> bool {
    parameters[0].hypot(parameters[1]) >= AT_BOUND_SHARE * bound_rad
}

/// Height tolerance of the level test, millimetres.
pub(crate) const EDGE_LEVEL_TOLERANCE_MM: f64 = 1.0;
