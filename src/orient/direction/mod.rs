//! Which way the axis points: from the base to the rim. The normals fix the axis as a
//! line; its sense comes from the shape of the vessel seen in the rz half-plane, from
//! three cues of different strength:
//! - the level edge: a rim is a circle about the axis, so in every vertical section
//!   (angular sector about the axis) the end of the profile lies at the same point of the
//!   rz half-plane, while a break wanders along the profile from section to section (the
//!   idea of the tangent plane to the rim, Wilczek et al. 2018, Eq. 7: the highest point
//!   of each section lies in one plane). The more level end is the rim, unless it closes
//!   onto the axis (the centre of a base);
//! - a floor: surface facing along the axis that reaches in towards the axis from the
//!   wall is a base, and the wall rises from it;
//! - the opening: a vessel widens from its base more often than it narrows (jar shoulders
//!   and necks narrow), the weakest cue, trusted alone only when the wall flares clearly.
//!
//! The cues are combined into a signed score whose magnitude is the confidence in the
//! sense; two strong cues that disagree give no sense at all (confidence 0), and the
//! verdict flags a sense that is not confident (see [`super::verdict`]).

mod floor;
mod level_edge;

use serde::{Deserialize, Serialize};

use crate::axis::Axis;
use super::normal_lines::NormalLines;
use crate::mesh::{Point, Vector};
use floor::{floor_cue, FLOOR_INNER_RADIUS_RATIO, MIN_FLOOR_SHARE, MIN_SMALL_FLOOR_SHARE, SMALL_FLOOR_INNER_RADIUS_RATIO};
use level_edge::level_edge_cue;
pub use level_edge::{profile_ends, profile_ends_finished, ProfileEnds};

/// The evidence for the sense of an axis.
#[derive(Clone, Debug)]
pub struct DirectionEvidence {
    /// Positive when the axis as given points from base to rim; its magnitude is the
    /// confidence in that sense, 0 to 1 (1 for a clear floor or level rim, 0 when the
    /// strong cues disagree, at most [`OPENING_MAX_CONFIDENCE`] for the opening alone).
    pub score: f64,
    /// Which cue decided, or why none could, for the report.
    pub cue: String,
    /// Each cue's figures, for the report.
    pub cues: SenseCues,
}

/// The figures of each sense cue, signed like [`DirectionEvidence::score`] (positive:
/// the axis as given points from base to rim; 0: the cue is silent).
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct SenseCues {
    /// Floor cue: +-1 when a floor was found, else 0.
    pub floor: f64,
    /// A floor too small to decide the sense alone (2-5% of the surface), +-1, else
    /// 0: it only vetoes a level edge that says the other way.
    #[serde(default)]
    pub small_floor: f64,
    /// Level-edge cue, -1 to 1.
    pub level_edge: f64,
    /// Spread of the upper end of the profile over the vertical sections, mm.
    pub upper_end_spread_mm: f64,
    /// Spread of the lower end of the profile over the vertical sections, mm.
    pub lower_end_spread_mm: f64,
    /// Fraction of the vertical sections whose upper end lies on one level edge.
    pub upper_level_fraction: f64,
    /// The same for the lower end.
    pub lower_level_fraction: f64,
    /// Share of the points at the upper end that lie on the surface of revolution (a
    /// lip's do, a break's do not); NaN when not measured.
    #[serde(default)]
    pub upper_finished_share: f64,
    /// The same for the lower end.
    #[serde(default)]
    pub lower_finished_share: f64,
    /// Opening cue, -[`OPENING_MAX_CONFIDENCE`] to [`OPENING_MAX_CONFIDENCE`].
    pub opening: f64,
    /// Area-weighted mean slope `dr/dz` of the wall.
    pub wall_slope: f64,
}

/// The most the opening cue alone can make of the sense: vessels that narrow upwards
/// (jar shoulders and necks, the upper half of globular bodies) are common, so with the
/// verdict's limit of 0.55 only walls flaring by more than `|dr/dz|` 0.92 (43 degrees)
/// are trusted (`docs/calibration.md`).
pub const OPENING_MAX_CONFIDENCE: f64 = 0.6;
/// Wall slope `|dr/dz|` at which the opening cue reaches its full confidence.
const OPENING_FULL_SLOPE: f64 = 1.0;

struct Sample {
    radius: f64,
    height: f64,
    normal_radial: f64,
    normal_axial: f64,
    weight: f64,
}

impl Sample {
    /// On the wall: its normal mostly radial.
    fn is_wall(&self) -> bool {
        self.normal_radial.abs() > 0.5
    }
}

/// Share of the surface the wall must have for a floor to rise into it, and for a level end
/// of the profile to be a rim: a piece of floor alone (no wall) has level ends, but no rim.
const MIN_WALL_SHARE: f64 = 0.05;

/// The share of the surface that is wall.
fn wall_share(samples: &[Sample]) -> f64 {
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    samples.iter().filter(|s| s.is_wall()).map(|s| s.weight).sum::<f64>() / total
}

/// The area-weighted mean slope `dr/dz` of the wall. The tangent `(dr, dz)` of the
/// profile is normal to `(n_r, n_z)` on either skin (the inner skin's normal is the
/// outer's reversed), so `dr/dz = -n_z / n_r` on both.
fn wall_slope(samples: &[Sample]) -> Option<f64> {
    let wall: Vec<&Sample> = samples.iter().filter(|s| s.is_wall()).collect();
    let wall_weight: f64 = wall.iter().map(|s| s.weight).sum();
    if !(wall_weight > 0.0) {
        return None;
    }
    let slope = wall.iter().map(|s| (-s.normal_axial / s.normal_radial).clamp(-2.0, 2.0) * s.weight).sum::<f64>();
    Some(slope / wall_weight)
}

/// Weighs the cues for `axis`: the floor and the opening on the lines that lie on the
/// surface of revolution (`lines` with `on_surface[i]`), the level edge on all the
/// points of the piece (`all_points`: breaks and rim included).
pub fn direction_evidence(lines: &NormalLines, on_surface: &[bool], all_points: &[Point], axis: &Axis) -> DirectionEvidence {
    direction_evidence_finished(lines, on_surface, all_points, None, axis)
}

/// [`direction_evidence`], the level-edge cue told which of `all_points` lie on the
/// surface of revolution (`all_finished`), so that a level break is not taken for a rim.
/// Without it the level-edge cue goes by levelness alone.
pub fn direction_evidence_finished(
    lines: &NormalLines,
    on_surface: &[bool],
    all_points: &[Point],
    all_finished: Option<&[bool]>,
    axis: &Axis,
) -> DirectionEvidence {
    let d = axis.direction.into_inner();
    let samples: Vec<Sample> = (0..lines.len())
        .filter(|&i| on_surface[i])
        .map(|i| {
            let q = lines.points[i] - axis.point;
            let height = q.dot(&d);
            let radial: Vector = q - d * height;
            let radius = radial.norm();
            let e_r = if radius > 0.0 { radial / radius } else { Vector::zeros() };
            let n = lines.directions[i];
            Sample { radius, height, normal_radial: n.dot(&e_r), normal_axial: n.dot(&d), weight: lines.weights[i] }
        })
        .collect();
    let mut cues = SenseCues::default();
    let mut level_text = String::new();
    if let Some(ends) = profile_ends_finished(all_points, all_finished, axis) {
        cues.upper_end_spread_mm = ends.upper_spread_mm;
        cues.lower_end_spread_mm = ends.lower_spread_mm;
        cues.upper_level_fraction = ends.upper_level_fraction;
        cues.lower_level_fraction = ends.lower_level_fraction;
        cues.upper_finished_share = ends.upper_finished_share;
        cues.lower_finished_share = ends.lower_finished_share;
        (cues.level_edge, level_text) = level_edge_cue(&ends);
    }
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    if samples.is_empty() || !(total > 0.0) {
        return DirectionEvidence { score: 0.0, cue: "no surface of revolution to judge from".into(), cues };
    }
    cues.floor = floor_cue(&samples, MIN_FLOOR_SHARE, FLOOR_INNER_RADIUS_RATIO).unwrap_or(0.0);
    if cues.floor == 0.0 {
        cues.small_floor = floor_cue(&samples, MIN_SMALL_FLOOR_SHARE, SMALL_FLOOR_INNER_RADIUS_RATIO).unwrap_or(0.0);
    }
    if wall_share(&samples) < MIN_WALL_SHARE {
        cues.level_edge = 0.0;
        level_text.clear();
    }
    if let Some(slope) = wall_slope(&samples) {
        cues.wall_slope = slope;
        cues.opening = OPENING_MAX_CONFIDENCE * (slope / OPENING_FULL_SLOPE).clamp(-1.0, 1.0);
    }
    combine(cues, level_text)
}

/// Combines the cues. A floor decides: where the level edge says the other way, the
/// level end is the floor's own foot or centre, which is level too. Without a floor the
/// level edge decides, unless a small floor (a strip of underside beside a foot) says the
/// other way. Otherwise the small floor and the opening add up, and decide only together
/// or where the wall flares clearly.
fn combine(cues: SenseCues, level_text: String) -> DirectionEvidence {
    let floor_text = "floor: the wall rises from a flat base";
    let (floor, level) = (cues.floor, cues.level_edge);
    if floor != 0.0 {
        let cue = if level != 0.0 && level.signum() == floor.signum() {
            format!("{floor_text}, and {level_text}")
        } else if level != 0.0 {
            format!("{floor_text} (its foot is the level end of the profile)")
        } else {
            floor_text.into()
        };
        return DirectionEvidence { score: floor, cue, cues };
    }
    if cues.small_floor != 0.0 && level != 0.0 && cues.small_floor.signum() != level.signum() {
        let cue = format!("conflict: a small floor says one way, the level edge the other: a base's foot is level too ({level_text})");
        return DirectionEvidence { score: 0.0, cue, cues };
    }
    if level != 0.0 {
        return DirectionEvidence { score: level, cue: level_text, cues };
    }
    let score = (SMALL_FLOOR_WEIGHT * cues.small_floor + cues.opening).clamp(-1.0, 1.0);
    if score != 0.0 {
        let mut cue = format!("opening: the wall widens towards the rim (slope dr/dz {:.2})", cues.wall_slope.abs());
        if cues.small_floor != 0.0 {
            cue = format!("{cue}, with a small flat part at its foot");
        }
        return DirectionEvidence { score, cue, cues };
    }
    DirectionEvidence { score: 0.0, cue: "no cue to the sense: no floor, no level edge, no slope".into(), cues }
}

/// What a small floor adds to the opening's confidence: with a wall that flares by a
/// third, together they reach the verdict's limit.
const SMALL_FLOOR_WEIGHT: f64 = 0.35;

#[cfg(test)]
mod tests {
    use super::*;

    /// A floor decides against a level edge (the level end is its own foot); a small floor
    /// against a level edge gives no sense; the opening alone stays weak.
    #[test]
    fn a_floor_outweighs_the_level_edge_and_a_small_floor_vetoes_it() {
        let floor_against_edge = combine(SenseCues { floor: 1.0, level_edge: -0.9, opening: 0.6, ..Default::default() }, "level rim".into());
        assert_eq!(floor_against_edge.score, 1.0, "{}", floor_against_edge.cue);
        assert!(floor_against_edge.cue.contains("foot"), "{}", floor_against_edge.cue);
        let small_against_edge = combine(SenseCues { small_floor: -1.0, level_edge: 0.9, ..Default::default() }, "level rim".into());
        assert_eq!(small_against_edge.score, 0.0);
        assert!(small_against_edge.cue.starts_with("conflict"), "{}", small_against_edge.cue);
        let alone = combine(SenseCues { opening: -0.3, ..Default::default() }, String::new());
        assert!(alone.score.abs() <= OPENING_MAX_CONFIDENCE && alone.score < 0.0);
        let together = combine(SenseCues { opening: 0.3, small_floor: 1.0, ..Default::default() }, String::new());
        assert!(together.score > alone.score.abs() && together.score <= 1.0, "{}", together.score);
    }
}
