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
        // Ties in section order: what a stable sort of the points as they come (in that
        // order) gives, at the cost of an unstable sort.
        match edge {
            Edge::Rim => points.sort_unstable_by(|a, b| b.1.z.total_cmp(&a.1.z).then(a.0.cmp(&b.0))),
            Edge::Base => points.sort_unstable_by(|a, b| a.1.z.total_cmp(&b.1.z).then(a.0.cmp(&b.0))),
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

    /// The largest height signed outward (up for a rim, down for a base) that a point
    /// from the `i`-th on can reach under `frame`, as a function of `i` (see [`Self::extreme`]);
    /// `None` for an upside-down frame (never searched), which would reverse the order:
    /// every point is moved then.
    fn outward_bound(&self, frame: &CandidateFrame, edge: Edge) -> Option<impl Fn(usize) -> f64 + '_> {
        let d = frame.direction();
        if !(d.z > 0.0) {
            return None;
        }
        let offset = frame.apply(&Point::origin()).z;
        let tilt = d.x.hypot(d.y);
        let centred = d.x * self.centre_xy[0] + d.y * self.centre_xy[1] + offset;
        let outward = edge.outward();
        Some(move |i: usize| outward * (d.z * self.points[i].z + centred) + (tilt * self.reach_mm[i] + self.slack_mm))
    }

    /// The extreme point under `frame`, the same as the `max_by`/`min_by` over all
    /// points in their section order (the last highest, the first lowest), found
    /// without moving most of them: under a frame with direction `d` and offset `o`
    /// (the height of the start origin), a point's height is `d . p + o`, at most
    /// `d_z p_z + d_xy . c + |d_xy| reach + o` (at least, with `-|d_xy| reach`, for a
    /// base); the points come extreme first, so the bound only shrinks along them.
    fn extreme(&self, frame: &CandidateFrame, edge: Edge) -> Option<Point> {
        let bound = self.outward_bound(frame, edge);
        // (height under the frame, order, index): only the heights are compared, the
        // winner alone is moved whole.
        let mut best: Option<(f64, usize, usize)> = None;
        for (i, (p, &order)) in self.points.iter().zip(&self.order).enumerate() {
            if let (Some(bound), Some((found_z, _, _))) = (&bound, &best) {
                if bound(i) < edge.outward() * found_z {
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

    /// The extreme point under `frame` and the section's points within `band_mm` of it,
    /// both in the candidate frame. `None` for an empty section.
    fn lip_band(&self, frame: &CandidateFrame, edge: Edge, band_mm: f64) -> Option<(Point, Vec<Point>)> {
        let extreme = self.extreme(frame, edge)?;
        let outward = edge.outward();
        let bound = self.outward_bound(frame, edge);
        let lowest = outward * extreme.z - band_mm;
        let mut band = Vec::new();
        for (i, p) in self.points.iter().enumerate() {
            if bound.as_ref().is_some_and(|bound| bound(i) < lowest) {
                break;
            }
            let q = frame.apply(p);
            if outward * q.z >= lowest {
                band.push(q);
            }
        }
        Some((extreme, band))
    }
}

/// One section's lip band in the coordinates of its crest parabola.
struct LipBand {
    /// `[u, h, weight]` per point: `u` the distance to the axis less the extreme's, `h`
    /// the height signed outward (up for a rim, down for a base).
    coordinates: Vec<[f64; 3]>,
    /// The weighted centroid, where the crest is placed: in a frame not yet level the
    /// band reaches further along the arc on the section's higher side, and its fitted
    /// height is that of its centroid, not of its extreme.
    centroid: Point,
    /// The extreme's height, signed outward.
    extreme_height: f64,
}

impl LipBand {
    /// Each point weighs `(1 - (depth / band_mm)^2)^2` by its depth below the extreme: the
    /// weights fade to nothing at the band's floor, so that the fit, unlike a band that
    /// takes points in or drops them whole, changes smoothly as the frame turns (the
    /// extreme's height does; its `u` may jump to another vertex, which moves the origin
    /// of `u` and not the parabola's top).
    fn new(extreme: &Point, band: &[Point], outward: f64, band_mm: f64) -> Self {
        let radius_at_extreme = planar_length(extreme.x, extreme.y);
        let coordinates: Vec<[f64; 3]> = band
            .iter()
            .map(|p| {
                let depth = (outward * (extreme.z - p.z)).max(0.0) / band_mm;
                [planar_length(p.x, p.y) - radius_at_extreme, outward * p.z, (1.0 - depth * depth).max(0.0).powi(2)]
            })
            .collect();
        let weight: f64 = coordinates.iter().map(|c| c[2]).sum();
        let centroid = Point::from(band.iter().zip(&coordinates).map(|(p, c)| p.coords * c[2]).sum::<crate::mesh::Vector>() / weight.max(1e-300));
        LipBand { coordinates, centroid, extreme_height: outward * extreme.z }
    }

    /// The weighted least-squares line `value = a + b u` over the band as `[a, b]`, `None`
    /// with fewer than [`CREST_MIN_POINTS`] points of weight or no spread in `u`.
    fn line_fit(&self, value: impl Fn(&[f64; 3]) -> f64) -> Option<[f64; 2]> {
        if self.coordinates.iter().filter(|c| c[2] > 0.0).count() < CREST_MIN_POINTS {
            return None;
        }
        let weight: f64 = self.coordinates.iter().map(|c| c[2]).sum();
        let mean_u = self.coordinates.iter().map(|c| c[2] * c[0]).sum::<f64>() / weight;
        let mean_value = self.coordinates.iter().map(|c| c[2] * value(c)).sum::<f64>() / weight;
        let spread: f64 = self.coordinates.iter().map(|c| c[2] * (c[0] - mean_u).powi(2)).sum();
        if !(spread > 1e-12) {
            return None;
        }
        let slope = self.coordinates.iter().map(|c| c[2] * (c[0] - mean_u) * (value(c) - mean_value)).sum::<f64>() / spread;
        Some([mean_value - slope * mean_u, slope])
    }
}

/// The crests of the sections' lips from their bands (`(extreme, band)` as
/// [`SectionCandidates::lip_band`] gives them): at each band's centroid, the top over the
/// band's `u` of `h = a_j + b_j u + c u^2` (see [`LipBand`]), whose curvature `c` all
/// sections share and whose `a_j`, `b_j` are each section's own. `None` for a section
/// with too few points to fit. Where the lips are not rounded (`c` not below
/// `-CREST_MIN_CURVATURE_PER_MM`), or where fewer than three sections or than half of
/// them fit, every section's crest is its extreme.
///
/// A rounded lip is the same cap along the whole rim, so its shape is learnt from all
/// sections at once, while each section keeps its own crest height and radius (the
/// vessel's ovality and wobble move the crest in and out by tenths of a millimetre).
fn lip_crests(bands: Vec<(Point, Vec<Point>)>, outward: f64) -> Vec<Option<Point>> {
    let lips: Vec<LipBand> = bands.iter().map(|(extreme, band)| LipBand::new(extreme, band, outward, CREST_BAND_MM)).collect();
    fitted_crests(&lips, outward).unwrap_or_else(|| bands.into_iter().map(|(extreme, _)| Some(extreme)).collect())
}

/// [`lip_crests`] where the lips give crests: `None` where every section keeps its extreme.
fn fitted_crests(lips: &[LipBand], outward: f64) -> Option<Vec<Option<Point>>> {
    // The curvature alone, each section's own line in u taken out of u^2 and of h
    // (Frisch-Waugh), summed over sections.
    let (mut cross, mut square) = (0.0, 0.0);
    for lip in lips {
        let (Some(q), Some(h)) = (lip.line_fit(|c| c[0] * c[0]), lip.line_fit(|c| c[1])) else { continue };
        for c in &lip.coordinates {
            let residual_q = c[0] * c[0] - (q[0] + q[1] * c[0]);
            let residual_h = c[1] - (h[0] + h[1] * c[0]);
            cross += c[2] * residual_q * residual_h;
            square += c[2] * residual_q * residual_q;
        }
    }
    let curvature = cross / square;
    if !(square > 0.0 && curvature < -CREST_MIN_CURVATURE_PER_MM) {
        return None;
    }
    let crests: Vec<Option<Point>> = lips
        .iter()
        .map(|lip| {
            let [a, b] = lip.line_fit(|c| c[1] - curvature * c[0] * c[0])?;
            let (low, high) = lip.coordinates.iter().filter(|c| c[2] > 0.0).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), c| (l.min(c[0]), h.max(c[0])));
            let top_u = (-b / (2.0 * curvature)).clamp(low, high);
            let top = a + b * top_u + curvature * top_u * top_u;
            (top <= lip.extreme_height + CREST_MAX_RISE_MM).then(|| Point::new(lip.centroid.x, lip.centroid.y, outward * top))
        })
        .collect();
    // A coarse mesh leaves most lips a vertex or two in the band: the extremes then, for
    // every section, since a crest and an extreme stand at different heights (the top of
    // the parabola against the highest vertex near it) and a plane through both would tip.
    let fitted = crests.iter().flatten().count();
    (fitted >= 3 && 2 * fitted >= crests.len()).then_some(crests)
}

/// Highest a crest may stand above its section's extreme vertex, mm: the vertex nearest
/// a crest falls short of it by `(spacing / 2)^2 / (2 radius)`, 0.03 mm for a lip of
/// radius 2 mm sampled every millimetre. A parabola topping out higher has been fitted
/// to something else than a lip, such as the break face at the end of a rim, whose band
/// ran 0.7 mm above its highest point on a 200k-face synthetic rim.
const CREST_MAX_RISE_MM: f64 = 0.05;

/// Fewest points of a section's lip band for its crest.
const CREST_MIN_POINTS: usize = 3;

/// Least (negative) curvature of the lips' parabola for [`lip_crests`], per mm: a
/// cap of radius 50 mm. Flatter, the lip is a flat face and its crest the extreme.
const CREST_MIN_CURVATURE_PER_MM: f64 = 0.01;

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

    /// The crest of each vertical section's lip under a candidate frame, in the candidate
    /// frame: the top of the parabola in the distance to the axis fitted through the
    /// section's points within 0.5 mm of its extreme (weighted, fading to nothing at
    /// 0.5 mm), its curvature shared by all sections, placed at their centroid. `None`
    /// for a section with too few points; every section's extreme where the lips are not
    /// rounded or too few sections fit (see `lip_crests`).
    pub fn crest_points(&self, frame: &CandidateFrame) -> Vec<Option<Point>> {
        let bands = self.sections.iter().map(|section| section.lip_band(frame, self.edge, CREST_BAND_MM).expect("sections are not empty")).collect();
        lip_crests(bands, self.edge.outward())
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

/// Depth of the band below a section's extreme through which its crest parabola is
/// fitted, mm.
const CREST_BAND_MM: f64 = 0.5;

/// Half-height of the band about the median level crest that the plane of
/// [`TangentObjective::plane_tilts`] goes through, mm.
const PLANE_BAND_MM: f64 = 0.5;

/// Turns `(tilt_x, tilt_y)` of the axis perpendicular to the plane `z = c + a x + b y`.
fn tilts_of_plane(a: f64, b: f64) -> [f64; 2] {
    tilts_along(&crate::mesh::Vector::new(-a, -b, 1.0))
}

impl TangentObjective {
    /// The least-squares plane through the level crests (within 0.5 mm, `PLANE_BAND_MM`,
    /// of the median of those within the tolerance of the top; [`Self::crest_points`])
    /// under the axis `parameters`, each section weighted by `weights` (all 1 when
    /// `None`), as the tilts of the axis perpendicular to it. `None` when fewer than three
    /// sections with weight carry level crests, or when they are collinear.
    ///
    /// Crests rather than extremes: a short rim's tilt about its chord rests on the few
    /// hundredths of a millimetre by which its middle stands out of the chord's line (0.5
    /// mm of sagitta over 20 degrees of a 90 mm rim), and one noisy vertex per section
    /// reads that badly. On the refinement corpus (`examples/refine_accuracy.rs 20 auto`,
    /// 0.8 mm cells, 0.02 mm noise) the rims levelled by the tangent plane were on average
    /// 0.287 and 0.402 degrees off on the two sets of ten vessels through their
    /// extremes, 0.213 and 0.338 through their crests. The noise is what the crests
    /// average: on the first ten vessels without it 81 of the 83 rims levelled through
    /// their extremes came within 0.3 degrees, with it 60 (through their crests 70).
    pub fn plane_tilts(&self, parameters: &AxisParameters, weights: Option<&[f64]>) -> Option<[f64; 2]> {
        let points = self.crest_points(&CandidateFrame::new(parameters));
        let top = match self.edge {
            Edge::Rim => points.iter().flatten().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
            Edge::Base => points.iter().flatten().map(|p| p.z).fold(f64::INFINITY, f64::min),
        };
        // The plane runs through the level set only: a damaged section a millimetre or two
        // below the rim, inside epsilon, would otherwise tip a plane whose other points lie
        // near one chord about that chord.
        let mut near: Vec<f64> = points.iter().flatten().map(|p| p.z).filter(|z| (z - top).abs() < self.tolerance_mm).collect();
        let level_height = crate::statistics::quantile(&mut near, 0.5);
        let level: Vec<([f64; 3], f64)> = points
            .iter()
            .enumerate()
            .filter_map(|(index, p)| p.map(|p| ([p.x, p.y, p.z], weights.map_or(1.0, |w| w[index]))))
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
/// crests of its vertical sections ([`TangentObjective::plane_tilts`]) is horizontal;
/// `None` when those crests fix no plane.
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
    fn a_rounded_lip_is_levelled_by_its_crest_not_by_the_vertices_nearest_it() {
        use crate::mesh::{Mesh, Vector};
        use crate::orient::Axis;
        // 24 degrees of a rim 80 mm from the axis, its lip a 3 mm round cap over a wall,
        // level. Across the lip the vertices lie 0.8 mm apart; along the arc their rows
        // slide so that one row runs on the crest at both ends of the arc and the two
        // nearest straddle it 0.4 mm to each side in the middle, 0.027 mm below it: the
        // highest vertices sag like a rim tilted about its chord.
        let (crest_radius, cap_radius, step) = (80.0, 3.0, 0.8);
        let half_arc = 12f64.to_radians();
        let (mut points, mut normals) = (Vec::new(), Vec::new());
        let columns = (2.0 * half_arc * crest_radius / step) as i32;
        for column in 0..=columns {
            let along = f64::from(column) / f64::from(columns) * 2.0 - 1.0;
            let azimuth = along * half_arc;
            let phase = 0.5 * step * (1.0 - along * along);
            let (sin, cos) = azimuth.sin_cos();
            let mut put = |r: f64, z: f64, normal_r: f64, normal_z: f64| {
                points.push(Point::new(r * cos, r * sin, z));
                normals.push(Vector::new(normal_r * cos, normal_r * sin, normal_z));
            };
            for row in -8..=8 {
                // Arc length over the cap from its crest; past its quarter turns the wall.
                let arc = f64::from(row) * step + phase;
                let angle = arc / cap_radius;
                if angle.abs() <= std::f64::consts::FRAC_PI_2 {
                    put(crest_radius + cap_radius * angle.sin(), -cap_radius * (1.0 - angle.cos()), angle.sin(), angle.cos());
                } else {
                    let down = arc.abs() - cap_radius * std::f64::consts::FRAC_PI_2;
                    let side = arc.signum();
                    put(crest_radius + side * cap_radius, -cap_radius - down, side, 0.0);
                }
            }
        }
        let vertical = Axis::new(Point::origin(), Vector::z());
        let surface = PreparedSurface::new(&Mesh::from_points_and_normals(points, normals), &vertical, Surface::Both, None).unwrap();
        let sections = 30;
        let objective = TangentObjective::new(&surface, Edge::Rim, 3.0, sections);
        // The plane through the highest vertices is tipped about the chord...
        let frame = CandidateFrame::new(&[0.0; 4]);
        let extremes = objective.extreme_points(&frame).iter().map(|p| ([p.x, p.y, p.z], 1.0)).collect::<Vec<_>>();
        let plane = least_squares_plane(extremes).unwrap();
        let [tilt_x, tilt_y] = tilts_of_plane(plane[1], plane[2]);
        let through_extremes_deg = surface.axis_of(&[tilt_x, tilt_y, 0.0, 0.0]).line_angle_to_deg(&vertical);
        assert!(through_extremes_deg > 0.5, "{through_extremes_deg}");
        // ...the plane through the crests is level.
        let levelled = level_by_plane(&surface, Edge::Rim, 3.0, sections, &Minimum { parameters: [0.0; 4], value: 0.0, iterations: 0 }).unwrap();
        let angle = surface.axis_of(&levelled.parameters).line_angle_to_deg(&vertical);
        assert!(angle < 0.05, "{angle} through the crests, {through_extremes_deg} through the extremes");
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
