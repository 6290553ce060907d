//! Which criterion a refinement runs: the one asked for, or, for [`Criterion::Auto`], the
//! tangent plane where the fragment keeps a level rim or base and the circles (with the
//! profile) otherwise.

use super::edges::{detect_edges_levelled, Levelling, EDGE_LEVEL_FRACTION, EDGE_LEVEL_TOLERANCE_MM};
use super::sections::PreparedSurface;
use super::{validate, Criterion, Edge, RefineOptions};
use crate::mesh::Mesh;
use crate::orient::Axis;
use crate::Result;

/// The criterion [`super::refine`] would run on `mesh` from `axis` (the one of `options`, or
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
