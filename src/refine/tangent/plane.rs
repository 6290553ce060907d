//! Levelling by the least-squares plane through the level crests of the vertical
//! sections: unlike Eq. 7, it gives a short rim nothing for tipping about its chord.

use super::{Edge, TangentObjective};
use crate::mesh::planar_length;
use crate::refine::objective::{Minimum, Objective};
use crate::refine::sections::{tilts_along, AxisParameters, CandidateFrame, PreparedSurface};

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
    /// reads that badly; a crest averages the scan's noise away (figures in
    /// `docs/calibration.md`).
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

/// Eq. 7's levelling `levelled` turned until the least-squares plane through the level
/// crests of its vertical sections ([`TangentObjective::plane_tilts`]) is horizontal;
/// `None` when those crests fix no plane.
///
/// Eq. 7 measures every section from the single highest (lowest) extreme and drops those
/// more than epsilon from it: a tilt that pushes a damaged section out of epsilon lowers
/// the criterion, and a short rim's plane turns about its chord to do so. The plane through
/// the level extremes (within 0.5 mm of their median) does not reward that
/// (`docs/calibration.md`). It is not used on bases: a base's plane comes from
/// its flat underside where it has one, and a rounded underside's extremes move with the
/// plane ([`edge_sag_mm`](super::edge_sag_mm)).
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
    let (_, gap) = crate::refine::sections::largest_angular_gap(&angles);
    let mut radii: Vec<f64> = surface.points.iter().map(|p| planar_length(p.x, p.y)).collect();
    let arc_mm = (std::f64::consts::TAU - gap) * crate::statistics::quantile(&mut radii, 0.5);
    let count = (arc_mm / (PLANE_SECTION_EDGES * edge_mm)).round();
    if !count.is_finite() {
        return at_least;
    }
    (count as usize).clamp(at_least, MAX_PLANE_SECTIONS.max(at_least))
}

/// Width of the vertical sections of a rim's plane, in mean edge lengths: as the
/// horizontal sections are spaced, neighbours share no vertex (`docs/calibration.md`).
const PLANE_SECTION_EDGES: f64 = 2.0;
/// Most vertical sections of a rim's plane.
const MAX_PLANE_SECTIONS: usize = 60;

/// Most turns of [`level_by_plane`]: each turn leaves a tenth to a five-hundredth of the
/// last one's tilt (the level set changes little as the plane turns). Of 100 rims of the
/// refinement corpus levelled from 3 degrees off, 82 came within 1e-7 radians in three
/// turns, all but two within seven, and those two to 2e-7 in eight.
const PLANE_LEVELLING_ROUNDS: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Point;
    use crate::refine::sections::Surface;

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
}
