//! Tangent plane to rim or base (Wilczek et al. 2018, section 2.3.4, Eq. 7): the way an
//! archaeologist lays a rim on the table. In each vertical section (angular sector
//! about the candidate axis) the highest point (rim) or lowest point (base) is taken,
//! and the tilts minimise
//! `sum_j delta_j (z_j - max z)^2 / sum_j delta_j`, where `delta_j` drops the sections
//! whose extreme lies more than `epsilon` below the highest (a damaged rim).
//!
//! The plane fixes only the direction; the position comes from the circles criterion
//! with the direction held (two shifts, as after a manual pre-orientation).

use serde::{Deserialize, Serialize};

use super::objective::{minimize, FreeParameters, Minimum, Objective, SearchSettings};
use super::circle_fit::{fit_circle, CircleFitMethod};
use super::sections::{axis_through, tilts_along, vertical_sections, AxisParameters, CandidateFrame, PreparedSurface};
use crate::mesh::{planar_length, Point};

/// Which horizontal edge of the vessel the fragment preserves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Edge {
    /// The top: highest point per vertical section.
    Rim,
    /// The bottom: lowest point per vertical section.
    Base,
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
    /// searched are a few degrees, far too little to move a vertex to another sector).
    sections: Vec<SectionCandidates>,
    /// Rim or base.
    pub edge: Edge,
    /// The tolerance epsilon, millimetres.
    pub tolerance_mm: f64,
    /// Optional weight per section, as a bootstrap draws them.
    pub section_weights: Option<Vec<f64>>,
}

/// The vertices of one vertical section that may be its extreme, ordered from the
/// extreme in the start frame inwards (highest first for a rim, lowest first for a base),
/// so that the search under a candidate frame stops once no later vertex can beat the
/// best found (see [`SectionCandidates::extreme`]).
struct SectionCandidates {
    /// Start-frame points, extreme first.
    points: Vec<Point>,
    /// Each point's position in the section's vertex order (ties go as they did there).
    order: Vec<usize>,
    /// Mean `(x, y)` of the section's points, start frame.
    centre_xy: [f64; 2],
    /// `reach_mm[i]`: the largest horizontal distance to `centre_xy` among `points[i..]`.
    reach_mm: Vec<f64>,
    /// Rounding allowance of the bound, mm (far above the rounding of a coordinate).
    slack_mm: f64,
}

impl SectionCandidates {
    fn new(mut points: Vec<(usize, Point)>, edge: Edge) -> Self {
        match edge {
            Edge::Rim => points.sort_by(|a, b| b.1.z.total_cmp(&a.1.z)),
            Edge::Base => points.sort_by(|a, b| a.1.z.total_cmp(&b.1.z)),
        }
        let count = points.len().max(1) as f64;
        let centre_xy = [
            points.iter().map(|(_, p)| p.x).sum::<f64>() / count,
            points.iter().map(|(_, p)| p.y).sum::<f64>() / count,
        ];
        let mut reach_mm: Vec<f64> =
            points.iter().map(|(_, p)| planar_length(p.x - centre_xy[0], p.y - centre_xy[1])).collect();
        for i in (0..reach_mm.len().saturating_sub(1)).rev() {
            reach_mm[i] = reach_mm[i].max(reach_mm[i + 1]);
        }
        let magnitude = points.iter().map(|(_, p)| p.coords.amax()).fold(0.0, f64::max);
        SectionCandidates {
            order: points.iter().map(|&(i, _)| i).collect(),
            points: points.into_iter().map(|(_, p)| p).collect(),
            centre_xy,
            reach_mm,
            slack_mm: 1e-9 * (1.0 + magnitude),
        }
    }

    /// The extreme point under `frame`, the same as the `max_by`/`min_by` over all
    /// points in their section order (the last highest, the first lowest), found
    /// without moving most of them: under a frame with direction `d` and offset `o`
    /// (the height of the start origin), a point's height is `d . p + o`, at most
    /// `d_z p_z + d_xy . c + |d_xy| reach + o` (at least, with `-|d_xy| reach`, for a
    /// base); the points come extreme first, so the bound only shrinks along them.
    fn extreme(&self, frame: &CandidateFrame, edge: Edge) -> Option<Point> {
        let d = frame.direction();
        let offset = frame.apply(&Point::origin()).z;
        let tilt = d.x.hypot(d.y);
        let centred = d.x * self.centre_xy[0] + d.y * self.centre_xy[1] + offset;
        // Upside-down frames (never searched) would reverse the order: scan them all.
        let bounded = d.z > 0.0;
        // (height under the frame, order, index): only the heights are compared, the
        // winner alone is moved whole.
        let mut best: Option<(f64, usize, usize)> = None;
        for (i, (p, &order)) in self.points.iter().zip(&self.order).enumerate() {
            if let (true, Some((found_z, _, _))) = (bounded, &best) {
                let spread = tilt * self.reach_mm[i] + self.slack_mm;
                let beyond = match edge {
                    Edge::Rim => d.z * p.z + centred + spread < *found_z,
                    Edge::Base => d.z * p.z + centred - spread > *found_z,
                };
                if beyond {
                    break;
                }
            }
            let height = frame.height(p);
            let better = match &best {
                None => true,
                Some((found_z, found_order, _)) => match (edge, height.total_cmp(found_z)) {
                    (_, std::cmp::Ordering::Equal) => match edge {
                        Edge::Rim => order > *found_order,
                        Edge::Base => order < *found_order,
                    },
                    (Edge::Rim, ordering) => ordering.is_gt(),
                    (Edge::Base, ordering) => ordering.is_lt(),
                },
            };
            if better {
                best = Some((height, order, i));
            }
        }
        best.map(|(_, _, i)| frame.apply(&self.points[i]))
    }
}

/// Vertices farther than this from the start frame's extreme cannot become the extreme
/// of their section for tilts within the search bound on fragments up to ~0.5 m.
const CANDIDATE_BAND_MM: f64 = 40.0;

impl TangentObjective {
    /// Divides the fragment into `section_count` vertical sections about the start axis.
    pub fn new(surface: &PreparedSurface, edge: Edge, tolerance_mm: f64, section_count: usize) -> Self {
        let sections = vertical_sections(&surface.points, section_count.max(3));
        let sections = sections
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
            .collect();
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

/// Half-height of the band about the median level extreme that the plane of
/// [`TangentObjective::plane_tilts`] goes through, mm.
const PLANE_BAND_MM: f64 = 0.5;

/// Turns `(tilt_x, tilt_y)` of the axis perpendicular to the plane `z = c + a x + b y`.
fn tilts_of_plane(a: f64, b: f64) -> [f64; 2] {
    tilts_along(&crate::mesh::Vector::new(-a, -b, 1.0))
}

impl TangentObjective {
    /// The least-squares plane through the level extremes (within 0.5 mm, `PLANE_BAND_MM`, of the
    /// median of those within the tolerance of the top) under the axis `parameters`, each section weighted by `weights` (all 1 when
    /// `None`), as the tilts of the axis perpendicular to it. `None` when fewer than
    /// three sections with weight carry level extremes, or when they are collinear.
    pub fn plane_tilts(&self, parameters: &AxisParameters, weights: Option<&[f64]>) -> Option<[f64; 2]> {
        let points = self.extreme_points(&CandidateFrame::new(parameters));
        let extreme = match self.edge {
            Edge::Rim => points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
            Edge::Base => points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
        };
        // The plane runs through the level set only: a damaged section a millimetre or two
        // below the rim, inside epsilon, would otherwise tip a plane whose other points lie
        // near one chord about that chord.
        let mut near: Vec<f64> = points.iter().map(|p| p.z).filter(|z| (z - extreme).abs() < self.tolerance_mm).collect();
        let level_height = crate::statistics::quantile(&mut near, 0.5);
        let level: Vec<([f64; 3], f64)> = points
            .iter()
            .enumerate()
            .map(|(index, p)| ([p.x, p.y, p.z], weights.map_or(1.0, |w| w[index])))
            .filter(|(p, weight)| !(*weight <= 0.0 || (p[2] - level_height).abs() > PLANE_BAND_MM))
            .collect();
        if level.len() < 3 {
            return None;
        }
        let solution = least_squares_plane(level)?;
        solution.iter().all(|v| v.is_finite()).then(|| tilts_of_plane(solution[1], solution[2]))
    }
}

/// The weighted least-squares plane `z = c + a x + b y` through `points` (`[x, y, z]` and
/// a weight each), as `[c, a, b]`; `None` when they do not fix one (they lie on a line).
fn least_squares_plane(points: impl IntoIterator<Item = ([f64; 3], f64)>) -> Option<nalgebra::Vector3<f64>> {
    let mut normal = nalgebra::Matrix3::<f64>::zeros();
    let mut right = nalgebra::Vector3::<f64>::zeros();
    for ([x, y, z], weight) in points {
        let row = nalgebra::Vector3::new(1.0, x, y);
        normal += weight * row * row.transpose();
        right += weight * row * z;
    }
    Some(normal.cholesky()?.solve(&right))
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

/// Eq. 7's levelling `levelled` turned until the least-squares plane through the level
/// extremes of its vertical sections ([`TangentObjective::plane_tilts`]) is horizontal;
/// `None` when those extremes fix no plane.
///
/// Eq. 7 measures every section from the single highest (lowest) extreme and drops those
/// more than epsilon from it: a tilt that pushes a damaged section out of epsilon lowers
/// the criterion, and a short rim's plane turns about its chord to do so. The plane through
/// the level extremes (within 0.5 mm of their median) does not reward that. On the
/// refinement corpus (`examples/refine_accuracy.rs`) the rims so levelled were within 0.3
/// degrees of the truth 70% of the time instead of 54%; from the automatic
/// pre-orientation rim 3 of vessel 2, which Eq. 7 tipped 3.4 degrees (its ends sagging
/// 0.24 mm), came to 0.3 degrees. It is not used on bases: a base's plane comes from
/// its flat underside where it has one, and a rounded underside's extremes move with the
/// plane ([`edge_sag_mm`]).
pub fn level_by_plane(surface: &PreparedSurface, edge: Edge, tolerance_mm: f64, section_count: usize, levelled: &Minimum) -> Option<Minimum> {
    let objective = TangentObjective::new(surface, edge, tolerance_mm, section_count);
    let mut parameters = levelled.parameters;
    for _ in 0..PLANE_LEVELLING_ROUNDS {
        let local = objective.plane_tilts(&parameters, None)?;
        // The plane's tilts are in the candidate frame: its normal is carried to the start
        // frame and read back as tilts there.
        let normal = CandidateFrame::new(&[local[0], local[1], 0.0, 0.0]).direction();
        [parameters[0], parameters[1]] = tilts_along(&CandidateFrame::new(&parameters).vector_to_start(&normal));
        if local[0].hypot(local[1]) < 1e-7 {
            break;
        }
    }
    let value = objective.value(&parameters);
    Some(Minimum { parameters, value, iterations: levelled.iterations })
}

/// Vertical sections for the plane through the level extremes of `edge` on `surface`: for
/// a rim, as many as fit sections two mean edge lengths wide along the arc at the
/// fragment's median radius, at least `at_least` and at most 60; `at_least` for a base
/// (its tilts come from its flat underside, or from Eq. 7's sections) and for a point
/// cloud.
pub fn plane_section_count(surface: &PreparedSurface, edge: Edge, at_least: usize) -> usize {
    let Some(edge_mm) = surface.mean_edge_mm.filter(|e| *e > 0.0 && edge == Edge::Rim) else { return at_least };
    let angles: Vec<f64> = surface.points.iter().map(|p| p.y.atan2(p.x)).collect();
    let (_, gap) = super::sections::largest_angular_gap(&angles);
    let mut radii: Vec<f64> = surface.points.iter().map(|p| planar_length(p.x, p.y)).collect();
    let arc_mm = (std::f64::consts::TAU - gap) * crate::statistics::quantile(&mut radii, 0.5);
    let count = (arc_mm / (PLANE_SECTION_EDGES * edge_mm)).round();
    if !count.is_finite() {
        return at_least;
    }
    (count as usize).clamp(at_least, MAX_PLANE_SECTIONS.max(at_least))
}

/// Width of the vertical sections of a rim's plane, in mean edge lengths: as the
/// horizontal sections are spaced, neighbours share no vertex. On the refinement corpus
/// (30 vessels, the rims levelled by the tangent plane, the turn held within a degree by
/// the refinement) the rims within 0.3 degrees went from 185 to 194 of 251 in 0.8 mm cells
/// and 173 to 177 of 246 in 2 mm cells, against the paper's 12 sections; three edge
/// lengths gave 187 in 0.8 mm cells.
const PLANE_SECTION_EDGES: f64 = 2.0;
/// Most vertical sections of a rim's plane.
const MAX_PLANE_SECTIONS: usize = 60;

/// Most turns of [`level_by_plane`]: each turn leaves a tenth to a five-hundredth of the
/// last one's tilt (the level set changes little as the plane turns). Of 100 rims of the
/// refinement corpus levelled from 3 degrees off, 82 came within 1e-7 radians in three
/// turns, all but two within seven, and those two to 2e-7 in eight.
const PLANE_LEVELLING_ROUNDS: usize = 8;

/// Evidence that a fragment keeps a rim or base: the extremes of its vertical sections
/// under a given axis lie on one horizontal plane.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct EdgeEvidence {
    /// The edge tested.
    pub edge: Edge,
    /// Share of vertical sections whose extreme lies within the tolerance of the median extreme.
    pub level_fraction: f64,
    /// Spread (median absolute deviation) of the extremes of those sections, millimetres.
    pub spread_mm: f64,
    /// How far the level extremes fall away from the plane towards the ends of the arc,
    /// millimetres ([`edge_sag_mm`]): an edge lies flat, a rounded surface rocks.
    pub sag_mm: f64,
}

/// Half-width of the band about the median extreme that [`edge_sag_mm`] is fitted to in
/// the edge evidence, mm: a rim or base broken off at one end of the arc leaves its last
/// sections a millimetre or so off the plane, a step that a parabola through them would
/// read as sag (synthetic base 1003 from its pre-orientation: 0.28 mm with them, 0.05
/// without), while a rocking surface's parabola runs through the band.
const SAG_BAND_MM: f64 = 0.3;

/// How far the `level` extremes (points in the candidate frame) fall away from their
/// plane towards the two ends of the arc, in millimetres: the end value of the quadratic
/// `h(u) = a + b u + c u^2` fitted to their heights over the azimuth `u` scaled to
/// [-1, 1], `c`, signed so that positive is away from the vessel (down for a rim, up
/// for a base).
///
/// A rim or base that survives lies on its plane along the whole arc, within the scan's
/// noise and the vessel's unevenness. A rounded surface with no edge, such as the convex
/// underside of a bowl whose standing ring broke off, also has a lowest point in every
/// vertical section, and a plane tilted onto it touches it in the middle of the arc: the
/// extremes rise towards both ends, a parabola in the azimuth, whatever the tilt. On the
/// refinement corpus levelled from 3 degrees off (`examples/refine_accuracy.rs`), the
/// rims and bases that ended within a degree of the truth sagged 0.011 mm on median and
/// 0.042 mm at the 95th percentile; the rocking bases 0.17-0.33 mm, and they were 1.5-12
/// degrees off.
pub fn edge_sag_mm(level: &[Point], edge: Edge) -> f64 {
    if level.len() < 4 {
        return 0.0;
    }
    let (sum_x, sum_y) = level.iter().fold((0.0, 0.0), |(x, y), p| {
        let r = planar_length(p.x, p.y).max(1e-12);
        (x + p.x / r, y + p.y / r)
    });
    let middle = sum_y.atan2(sum_x);
    let (sin, cos) = middle.sin_cos();
    let azimuths: Vec<f64> = level.iter().map(|p| (p.y * cos - p.x * sin).atan2(p.x * cos + p.y * sin)).collect();
    let half_arc = azimuths.iter().map(|a| a.abs()).fold(0.0, f64::max);
    if !(half_arc > 1e-9) {
        return 0.0;
    }
    let away = -edge.outward();
    let mut normal = nalgebra::Matrix3::<f64>::zeros();
    let mut right = nalgebra::Vector3::<f64>::zeros();
    for (p, azimuth) in level.iter().zip(&azimuths) {
        let u = azimuth / half_arc;
        let row = nalgebra::Vector3::new(1.0, u, u * u);
        normal += row * row.transpose();
        right += row * (away * p.z);
    }
    normal.cholesky().map_or(0.0, |c| c.solve(&right)[2])
}

/// Tests whether the fragment keeps `edge` level under the axis `parameters` of `surface`.
pub fn edge_evidence(
    surface: &PreparedSurface,
    edge: Edge,
    tolerance_mm: f64,
    section_count: usize,
    parameters: &AxisParameters,
) -> EdgeEvidence {
    edge_evidence_anchored(surface, edge, tolerance_mm, section_count, parameters, false)
}

/// [`edge_evidence`], with the level set hung from the top (rim) or bottom (base)
/// extreme when `from_top` instead of from the median of all sections: where the rim
/// survives over a third of the arc, the break lines hold the median and the rim would
/// count as not level.
pub fn edge_evidence_anchored(
    surface: &PreparedSurface,
    edge: Edge,
    tolerance_mm: f64,
    section_count: usize,
    parameters: &AxisParameters,
    from_top: bool,
) -> EdgeEvidence {
    let objective = TangentObjective::new(surface, edge, tolerance_mm, section_count);
    let points = objective.extreme_points(&CandidateFrame::new(parameters));
    let mut extremes: Vec<f64> = points.iter().map(|p| p.z).collect();
    if extremes.is_empty() {
        return EdgeEvidence { edge, level_fraction: 0.0, spread_mm: f64::INFINITY, sag_mm: 0.0 };
    }
    let top = match edge {
        Edge::Rim => extremes.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        Edge::Base => extremes.iter().copied().fold(f64::INFINITY, f64::min),
    };
    let mut near_top: Vec<f64> = extremes.iter().copied().filter(|z| (z - top).abs() <= tolerance_mm).collect();
    let median = crate::statistics::quantile(if from_top { &mut near_top } else { &mut extremes }, 0.5);
    let level: Vec<f64> = extremes.iter().map(|z| (z - median).abs()).filter(|d| *d <= tolerance_mm).collect();
    let mut deviations = level.clone();
    let spread = if deviations.is_empty() { f64::INFINITY } else { crate::statistics::quantile(&mut deviations, 0.5) };
    let level_points: Vec<Point> = points.into_iter().filter(|p| (p.z - median).abs() <= tolerance_mm.min(SAG_BAND_MM)).collect();
    EdgeEvidence {
        edge,
        level_fraction: level.len() as f64 / extremes.len() as f64,
        spread_mm: spread,
        sag_mm: edge_sag_mm(&level_points, edge),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::refine::sections::Surface;
    use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};

    #[test]
    fn bounded_extreme_search_finds_the_same_points_as_moving_every_candidate() {
        let options = SherdOptions { target_faces: 8_000, ..SherdOptions::for_part(SherdPart::RimToBase) };
        let sherd = synthetic_sherd(11, &options);
        let surface = PreparedSurface::new(&sherd.mesh, &sherd.truth.axis, Surface::Both, None).unwrap();
        for edge in [Edge::Rim, Edge::Base] {
            let objective = TangentObjective::new(&surface, edge, 3.0, 24);
            let sections = vertical_sections(&surface.points, 24);
            let candidates = [[0.0, 0.0, 0.0, 0.0], [0.02, -0.04, 1.0, 2.0], [-0.17, 0.15, -5.0, 0.5], [0.3, 0.0, 0.0, 0.0]];
            for parameters in candidates {
                let frame = CandidateFrame::new(&parameters);
                let found = objective.extreme_points(&frame);
                // The plain search: every candidate moved, the last highest or first lowest.
                let expected: Vec<Point> = sections
                    .iter()
                    .filter(|indices| !indices.is_empty())
                    .map(|indices| {
                        let points: Vec<Point> = indices.iter().map(|&i| surface.points[i]).collect();
                        let extreme = match edge {
                            Edge::Rim => points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
                            Edge::Base => points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
                        };
                        let near = points.iter().filter(|p| (p.z - extreme).abs() <= CANDIDATE_BAND_MM);
                        let moved = near.map(|p| frame.apply(p));
                        match edge {
                            Edge::Rim => moved.max_by(|a, b| a.z.total_cmp(&b.z)),
                            Edge::Base => moved.min_by(|a, b| a.z.total_cmp(&b.z)),
                        }
                        .unwrap()
                    })
                    .collect();
                assert_eq!(found.len(), expected.len());
                for (a, b) in found.iter().zip(&expected) {
                    assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "{edge:?} {parameters:?}");
                }
            }
        }
    }

    #[test]
    fn a_level_arc_does_not_sag_and_a_rounded_one_does() {
        // 40 degrees of a 60 mm circle: level with 0.02 mm of alternating noise, and
        // rising by 0.3 mm towards both ends.
        let arc = |lift: &dyn Fn(f64) -> f64| -> Vec<Point> {
            (0..25)
                .map(|i| {
                    let u = i as f64 / 12.0 - 1.0;
                    let azimuth = 1.0 + u * 20f64.to_radians();
                    Point::new(60.0 * azimuth.cos(), 60.0 * azimuth.sin(), lift(u) + if i % 2 == 0 { 0.02 } else { -0.02 })
                })
                .collect()
        };
        let level = arc(&|_| 0.0);
        let rounded = arc(&|u| 0.3 * u * u);
        assert!(edge_sag_mm(&level, Edge::Base).abs() < 0.02);
        assert!((edge_sag_mm(&rounded, Edge::Base) - 0.3).abs() < 0.02);
        // For a rim "away from the vessel" is down: the same points rise, a negative sag.
        assert!((edge_sag_mm(&rounded, Edge::Rim) + 0.3).abs() < 0.02);
    }

    #[test]
    fn ties_go_to_the_last_highest_and_the_first_lowest_as_in_section_order() {
        // Three points at one height: under the start frame the plain max_by keeps the
        // last, min_by the first.
        let points: Vec<(usize, Point)> =
            [1.0, 2.0, 3.0].iter().enumerate().map(|(i, &x)| (i, Point::new(x, 0.0, 5.0))).collect();
        let frame = CandidateFrame::new(&[0.0; 4]);
        let rim = SectionCandidates::new(points.clone(), Edge::Rim).extreme(&frame, Edge::Rim).unwrap();
        let base = SectionCandidates::new(points, Edge::Base).extreme(&frame, Edge::Base).unwrap();
        assert_eq!((rim.x, base.x), (3.0, 1.0));
    }
}
