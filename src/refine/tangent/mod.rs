//! Tangent plane to rim or base (Wilczek et al. 2018, section 2.3.4, Eq. 7): the way an
//! archaeologist lays a rim on the table. In each vertical section (angular sector
//! about the candidate axis) the highest point (rim) or lowest point (base) is taken,
//! and the tilts minimise
//! `sum_j delta_j (z_j - max z)^2 / sum_j delta_j`, where `delta_j` drops the sections
//! whose extreme lies more than `epsilon` below the highest (a damaged rim).
//!
//! The plane fixes only the direction; the position comes from the circles criterion
//! with the direction held (two shifts, as after a manual pre-orientation).
//!
//! One file a concept, around the objective here: `candidates` (the vertices of each
//! vertical section that may be its extreme), `crests` (the crests of rounded lips),
//! `plane` (levelling by the plane through the level crests) and `evidence` (whether a
//! fragment keeps a level edge at all).

mod candidates;
mod crests;
mod evidence;
mod plane;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::objective::{minimize, FreeParameters, Minimum, Objective, SearchSettings};
use super::circle_fit::{fit_circle, CircleFitMethod};
use super::sections::{axis_through, vertical_sections, AxisParameters, CandidateFrame, PreparedSurface};
use crate::mesh::Point;
use candidates::{SectionCandidates, CANDIDATE_BAND_MM};

pub use evidence::{edge_evidence, edge_evidence_anchored, edge_sag_mm, EdgeEvidence};
pub use plane::{level_by_plane, plane_section_count};

/// Which horizontal edge of the vessel the fragment preserves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Edge {
    /// The top: highest point per vertical section.
    Rim,
    /// The bottom: lowest point per vertical section.
    Base,
}

crate::vocabulary! {
    /// The edge the tangent plane (Eq. 7) rests on, as options name it: one of the
    /// [`Edge`]s, or the one whose extremes are level.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub enum EdgeChoice: "edge", "edges" {
        /// The edge whose extremes are level (the default).
        #[default]
        Detect = "detect" => "The rim or base whose extremes are level",
        /// The rim.
        Rim = "rim" => "The tangent plane on the rim's highest points",
        /// The base.
        Base = "base" => "The tangent plane on the base's lowest points",
    }
}

impl EdgeChoice {
    /// The edge chosen, `None` to detect it (`RefineOptions::edge`).
    pub fn edge(self) -> Option<Edge> {
        match self {
            EdgeChoice::Detect => None,
            EdgeChoice::Rim => Some(Edge::Rim),
            EdgeChoice::Base => Some(Edge::Base),
        }
    }

    /// The choice that gives `edge` (`None`: detect it).
    pub fn of(edge: Option<Edge>) -> EdgeChoice {
        match edge {
            None => EdgeChoice::Detect,
            Some(Edge::Rim) => EdgeChoice::Rim,
            Some(Edge::Base) => EdgeChoice::Base,
        }
    }
}

impl Edge {
    /// +1 for the rim, -1 for the base: the sign of a height (or of a normal's component
    /// along the axis) that points away from the piece at this edge.
    pub(crate) fn outward(self) -> f64 {
        match self {
            Edge::Rim => 1.0,
            Edge::Base => -1.0,
        }
    }
}

/// Eq. 7 on a prepared fragment.
pub struct TangentObjective {
    /// Candidate extremes of each vertical section (fixed in the start frame: the tilts
    /// searched are a few degrees, far too little to move a vertex to another sector),
    /// shared by every objective on the same surface, edge and section count.
    sections: Arc<Vec<SectionCandidates>>,
    /// Rim or base.
    pub edge: Edge,
    /// The tolerance epsilon, millimetres.
    pub tolerance_mm: f64,
    /// Optional weight per section, as a bootstrap draws them.
    pub section_weights: Option<Vec<f64>>,
}

impl TangentObjective {
    /// Divides the fragment into `section_count` vertical sections about the start axis.
    pub fn new(surface: &PreparedSurface, edge: Edge, tolerance_mm: f64, section_count: usize) -> Self {
        let section_count = section_count.max(3);
        // The level tests and the levelling ask for the same sections many times.
        let key = (section_count as u64) << 1 | u64::from(edge == Edge::Base);
        let sections = surface.derived(key, || candidate_sections(surface, edge, section_count));
        TangentObjective { sections, edge, tolerance_mm, section_weights: None }
    }

    /// Number of vertical sections.
    pub fn section_count(&self) -> usize {
        self.sections.len()
    }

    /// The extreme height of each vertical section under a candidate frame.
    pub fn extremes(&self, frame: &CandidateFrame) -> Vec<f64> {
        self.extreme_points(frame).iter().map(|p| p.z).collect()
    }

    /// The extreme point of each vertical section, in the candidate frame.
    pub fn extreme_points(&self, frame: &CandidateFrame) -> Vec<Point> {
        self.sections
            .iter()
            .map(|section| section.extreme(frame, self.edge).expect("sections are not empty"))
            .collect()
    }
    /// The axis through the centre of the circle fitted to the level extremes (within
    /// the tolerance) with the tilts of `parameters`: the paper's "line perpendicular to
    /// the centre of the circle passing through these vertices".
    pub fn edge_circle_axis(&self, parameters: &AxisParameters) -> Option<AxisParameters> {
        let frame = CandidateFrame::new(&[parameters[0], parameters[1], 0.0, 0.0]);
        let points = self.extreme_points(&frame);
        let extreme = match self.edge {
            Edge::Rim => points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
            Edge::Base => points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
        };
        let level: Vec<&Point> = points.iter().filter(|p| (p.z - extreme).abs() < self.tolerance_mm).collect();
        let xy: Vec<[f64; 2]> = level.iter().map(|p| [p.x, p.y]).collect();
        let circle = fit_circle(&xy, CircleFitMethod::Geometric)?;
        let height = level.iter().map(|p| p.z).sum::<f64>() / level.len() as f64;
        Some(axis_through([parameters[0], parameters[1]], circle.center, height))
    }
}

/// The candidate extremes of `edge` in each of `section_count` vertical sections, those
/// with none left out.
fn candidate_sections(surface: &PreparedSurface, edge: Edge, section_count: usize) -> Vec<SectionCandidates> {
    vertical_sections(&surface.points, section_count)
        .into_iter()
        .map(|indices| {
            let points: Vec<_> = indices.iter().map(|&i| surface.points[i]).collect();
            let extreme = match edge {
                Edge::Rim => points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
                Edge::Base => points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
            };
            points.into_iter().filter(|p| (p.z - extreme).abs() <= CANDIDATE_BAND_MM).enumerate().collect()
        })
        .filter(|points: &Vec<_>| !points.is_empty())
        .map(|points| SectionCandidates::new(points, edge))
        .collect()
}

impl Objective for TangentObjective {
    fn value(&self, parameters: &AxisParameters) -> f64 {
        let extremes = self.extremes(&CandidateFrame::new(parameters));
        let extreme = match self.edge {
            Edge::Rim => extremes.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Edge::Base => extremes.iter().copied().fold(f64::INFINITY, f64::min),
        };
        let (mut total, mut weight_sum, mut kept) = (0.0, 0.0, 0);
        for (index, z) in extremes.iter().enumerate() {
            let weight = self.section_weights.as_ref().map_or(1.0, |w| w[index]);
            let d = z - extreme;
            if d.abs() < self.tolerance_mm && weight > 0.0 {
                total += weight * d * d;
                weight_sum += weight;
                kept += 1;
            }
        }
        if kept < 3 {
            return f64::INFINITY;
        }
        total / weight_sum
    }
}

/// Tolerance of the first, coarse levelling stage, mm: started a few degrees off, a rim
/// 70 mm wide rises by several millimetres across the fragment, so that with the final
/// epsilon fewer than three sections count and the cost is undefined everywhere around
/// the start.
const COARSE_TOLERANCE_MM: f64 = 30.0;

/// Levels `edge` by the tilts: Eq. 7 with a coarse tolerance first, then with
/// `tolerance_mm` from there. Returns the tilted parameters (shifts unchanged).
pub fn level_edge(
    surface: &PreparedSurface,
    edge: Edge,
    tolerance_mm: f64,
    section_count: usize,
    start: AxisParameters,
    settings: &SearchSettings,
    section_weights: Option<Vec<f64>>,
) -> crate::Result<Minimum> {
    let settings = SearchSettings { free: FreeParameters::TiltsOnly, ..*settings };
    let mut objective = TangentObjective::new(surface, edge, tolerance_mm.max(COARSE_TOLERANCE_MM), section_count);
    objective.section_weights = section_weights;
    let coarse = minimize(&objective, start, &settings)?;
    objective.tolerance_mm = tolerance_mm;
    let fine = minimize(&objective, coarse.parameters, &settings)?;
    Ok(Minimum { iterations: coarse.iterations + fine.iterations, ..fine })
}
