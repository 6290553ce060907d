//! The flat face of a base (its underside) or of a floor piece, whose plane gives the
//! axis's direction: how an archaeologist orients a base sherd, standing it on the table.
//! The tangent plane (Eq. 7, [`super::tangent`]) levels a base by its lowest points; where
//! the piece keeps a flat underside, the refinement takes the tilts from it instead
//! ([`super::edges`]).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::sections::{tilts_along, AxisParameters, CandidateFrame, PreparedSurface};
use super::tangent::Edge;
use crate::mesh::{Point, Vector};
use crate::statistics::principal_axes;

/// A vertex belongs to the face when its normal is within about 25 degrees of the axis,
/// facing away from the piece (down for the underside, up for the upper face).
const FACE_NORMAL_MIN_COSINE: f64 = 0.9;
/// Widest band (three robust standard deviations of the vertices about their plane) of a
/// face flat enough to give the tilts, mm: the scan's noise must leave the band the
/// face's vertices are counted in ([`FACE_INLIER_MM`]) mostly empty at its edges.
const FACE_MAX_BAND_MM: f64 = 0.15;
/// Half-angle of the cones in which the face's normals are sought, degrees, and how many
/// of the densest are tried at most.
const FACE_SEED_CONE_DEG: f64 = 3.0;
const FACE_MAX_SEEDS: usize = 32;
/// A face the piece stands on has at most this share of its vertices beyond its plane by
/// more than this, mm.
const FACE_MAX_BEYOND_SHARE: f64 = 0.005;
const FACE_BEYOND_MM: f64 = 0.075;
/// A face's vertex whose normal turns from the face's by more than this many times the
/// median turn is left out of its plane.
const FACE_MAX_NORMAL_TURN_FACTOR: f64 = 2.0;
/// Highest rise of a flat face's bowl ([`FittedFace::bowl_rise_mm`]), mm: a floor rises
/// a few micrometres, the lowest patch of a rounded underside tens. Not its t statistic:
/// with thousands of vertices a floor's slightest bowl is significant
/// (`docs/calibration.md`).
const FACE_MAX_BOWL_RISE_MM: f64 = 0.011;
/// Largest standard error of that rise, mm: below it the face's vertices are enough to
/// tell a floor from a bowl (`docs/calibration.md`).
const FACE_MAX_BOWL_RISE_ERROR_MM: f64 = 0.0075;
/// The sampled planes: how many, the half-width of the band that counts a vertex in, mm,
/// the least area of the sampled triangle (mm^2, as the cross product's length: twice
/// the area), at most how many vertices are counted, and the generator's seed.
const FACE_HYPOTHESES: usize = 128;
const FACE_INLIER_MM: f64 = 0.05;
const FACE_MIN_SAMPLE_AREA_MM2: f64 = 4.0;
const FACE_MAX_COUNTED: usize = 2048;
const FACE_SAMPLING_SEED: u64 = 0xf1a7;
/// A vertex is taken for the face when its normal is within this of the face's, degrees.
const FACE_NEAR_NORMAL_DEG: f64 = 6.0;
/// Fewest face vertices, and the least spread of them (standard deviation along
/// their narrowest direction, mm), for a plane.
const FACE_MIN_VERTICES: usize = 20;
const FACE_MIN_SPREAD_MM: f64 = 1.0;

/// The plane of a flat face (a base's underside, a floor's upper face), as the tilts of
/// the axis perpendicular to it.
#[derive(Clone, Debug, PartialEq)]
pub struct FlatFace {
    /// `(tilt_x, tilt_y)` of the axis perpendicular to the face (start frame).
    pub tilts: [f64; 2],
    /// Three robust standard deviations of its vertices about the plane, mm.
    pub band_mm: f64,
    /// The vertices the plane runs through (start frame).
    pub vertices: Vec<Point>,
}

impl FlatFace {
    /// The tilts of the axis across the plane of the face's vertices weighted by
    /// `weights` (one each: a bootstrap resample's counts); `None` when they weigh
    /// nothing.
    pub fn resampled_tilts(&self, weights: &[f64]) -> Option<[f64; 2]> {
        let (_, _, [normal, _, _]) = principal_axes(self.vertices.iter().zip(weights.iter().copied()))?;
        let axis = CandidateFrame::new(&[self.tilts[0], self.tilts[1], 0.0, 0.0]).direction();
        Some(tilts_along(&if normal.dot(&axis) < 0.0 { -normal } else { normal }))
    }
}

/// The flat face of `edge` (a base's underside; `Rim`: a floor's upper face) found among
/// the vertices whose normals lie within about 25 degrees of the axis `parameters`, and
/// within `max_tilt_rad` of the start axis: the axis perpendicular to it.
///
/// The underside a vessel stands on is its horizontal by definition, and its vertices
/// are many and span the floor, where Eq. 7's extremes fix the tilt about the arc's chord
/// only through the arc's sagitta. But a base sherd often keeps only a strip of floor
/// beside the wall's first gentle rise, whose vertices outnumber it and pull any plane
/// fitted to them all (and lead Eq. 7 off). The face is therefore sought as a floor is
/// recognised by hand:
/// - its normals crowd together: each of the densest 3 degree cones of normals is tried;
/// - among the vertices of a cone, the plane through three of them that holds the most
///   within 0.05 mm, after a fit to those it holds (deterministic samples);
/// - the piece could stand on it: almost none of its vertices lies beyond it;
/// - the vertices whose normals turn from the plane's by more than twice the median turn
///   (the rise's) are left out of its final total-least-squares fit;
/// - it does not curve like a bowl, as the lowest patch of a rounded underside does;
/// - of the faces that pass, the one with the most vertices.
///
/// Not for the rim of a wall: a flat rim top is cut square across the wall, so on a wall
/// that slants it is a band of a cone, whose plane over a short arc turns with the slant
/// exactly as a tilted axis would (on 200k-face synthetic rims one went from 0.29 to
/// 0.86 degrees); the rim's tangent plane is the one through its highest points, Eq. 7's.
/// A floor's upper face is for floor pieces held upside down by their start axis, which
/// show their underside there.
///
/// `None` when no face passes.
pub fn flat_face(surface: &PreparedSurface, edge: Edge, parameters: &AxisParameters, max_tilt_rad: f64) -> Option<FlatFace> {
    let frame = CandidateFrame::new(parameters);
    // The face's normals point away from the piece: down for the underside, up for the
    // upper face.
    let facing = edge.outward();
    let near_axis: Vec<(Point, Vector)> = surface
        .points
        .iter()
        .zip(&surface.normals)
        .filter(|(_, n)| facing * frame.apply_vector(n).z >= FACE_NORMAL_MIN_COSINE)
        .map(|(p, n)| (*p, *n))
        .collect();
    let support: Vec<&Point> = surface.points.iter().step_by(surface.points.len().div_ceil(FACE_MAX_COUNTED).max(1)).collect();
    // A floor's normals crowd around its own, but a conical wall's beside it may crowd
    // as densely: each of the densest directions is tried, and the flat face kept.
    let normals: Vec<Vector> = near_axis.iter().map(|(_, n)| *n).collect();
    densest_directions(&normals, FACE_SEED_CONE_DEG.to_radians().cos(), FACE_MAX_SEEDS)
        .into_iter()
        .filter_map(|face_normal| fit_flat_face(&near_axis, &support, &face_normal))
        .filter(|face| {
            face.band_mm <= FACE_MAX_BAND_MM && face.bowl_rise_mm <= FACE_MAX_BOWL_RISE_MM && face.bowl_rise_error_mm <= FACE_MAX_BOWL_RISE_ERROR_MM
        })
        .filter(|face| supports(&support, &face.mean, &face.normal))
        .map(|face| FlatFace { tilts: tilts_along(&(facing * face.normal)), band_mm: face.band_mm, vertices: face.vertices })
        .filter(|face| face.tilts.iter().all(|t| t.is_finite()) && face.tilts[0].hypot(face.tilts[1]) <= max_tilt_rad)
        .max_by_key(|face| face.vertices.len())
}

/// A plane fitted to a face: through `mean`, across the unit `normal` (facing away from
/// the piece), with what [`flat_face`] judges it by.
struct FittedFace {
    mean: Point,
    normal: Vector,
    /// Three robust standard deviations of the face's vertices about the plane, mm.
    band_mm: f64,
    /// How far the bowl `q r^2` (r from the face's centre) fitted to the vertices' offsets
    /// rises across the face, mm: the lowest patch of a rounded underside is a bowl, a
    /// floor is not.
    bowl_rise_mm: f64,
    /// The standard error of that rise, mm: a face too small or too noisy to tell a floor
    /// from a bowl has a large one.
    bowl_rise_error_mm: f64,
    vertices: Vec<Point>,
}

/// The face of the vertices of `near_axis` (points with their normals, facing away from
/// the piece) whose normals lie near `face_normal`: the plane through three of them that
/// holds most of them within [`FACE_INLIER_MM`] with no more of `support` beyond it than
/// a face the piece stands on would leave (deterministic random samples), then the
/// total-least-squares plane of those it holds, twice, and once more without those whose
/// normals turn from it by more than [`FACE_MAX_NORMAL_TURN_FACTOR`] times the median
/// turn; with the bowl fitted to its vertices' offsets. A floor is a minority among its
/// piece's outward normals when the piece keeps the turn into the wall: a plane fitted to
/// them all leans onto the wall, and one through the most of them may cut across the
/// floor onto the wall's first gentle rise, with the floor's edge beyond it.
fn fit_flat_face(near_axis: &[(Point, Vector)], support: &[&Point], face_normal: &Vector) -> Option<FittedFace> {
    let near_face_cosine = FACE_NEAR_NORMAL_DEG.to_radians().cos();
    let candidates: Vec<Point> = near_axis.iter().filter(|(_, n)| n.dot(face_normal) >= near_face_cosine).map(|(p, _)| *p).collect();
    if candidates.len() < FACE_MIN_VERTICES {
        return None;
    }
    let counted: Vec<&Point> = candidates.iter().step_by(candidates.len().div_ceil(FACE_MAX_COUNTED).max(1)).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(FACE_SAMPLING_SEED);
    let mut best: Option<(usize, Point, Vector)> = None;
    for _ in 0..FACE_HYPOTHESES {
        let [a, b, c] = [0; 3].map(|_| candidates[rng.random_range(0..candidates.len())]);
        let Some(normal) = (b - a).cross(&(c - a)).try_normalize(FACE_MIN_SAMPLE_AREA_MM2) else { continue };
        let normal = if normal.dot(face_normal) < 0.0 { -normal } else { normal };
        if normal.dot(face_normal) < near_face_cosine {
            continue;
        }
        let most = best.as_ref().map_or(0, |(most, _, _)| *most);
        if counted.iter().filter(|p| (**p - a).dot(&normal).abs() <= FACE_INLIER_MM).count() <= most {
            continue;
        }
        // Three close vertices fix their plane poorly: it is judged after a fit to what
        // it holds, and kept only where the piece could stand on it.
        let Some((through, normal)) = plane_of_held(&counted, &a, &normal) else { continue };
        let held = counted.iter().filter(|p| (**p - through).dot(&normal).abs() <= FACE_INLIER_MM).count();
        if held > most && supports(support, &through, &normal) {
            best = Some((held, through, normal));
        }
    }
    let (_, mut through, mut normal) = best?;
    let all: Vec<&Point> = candidates.iter().collect();
    for _ in 0..2 {
        (through, normal) = plane_of_held(&all, &through, &normal)?;
    }
    // The wall's first rise beside the floor lies within the band for a few millimetres
    // and leans the plane onto it, but its normals turn away from the floor's by more
    // than the scan's noise turns the floor's own.
    let in_band: Vec<&(Point, Vector)> =
        near_axis.iter().filter(|(p, n)| n.dot(face_normal) >= near_face_cosine && (p - through).dot(&normal).abs() <= FACE_INLIER_MM).collect();
    let mut turns: Vec<f64> = in_band.iter().map(|(_, n)| n.dot(&normal).clamp(-1.0, 1.0).acos()).collect();
    let typical_turn = crate::statistics::quantile(&mut turns, 0.5);
    let agreeing: Vec<&Point> =
        in_band.iter().filter(|(_, n)| n.dot(&normal).clamp(-1.0, 1.0).acos() <= FACE_MAX_NORMAL_TURN_FACTOR * typical_turn).map(|(p, _)| p).collect();
    (through, normal) = plane_of_held(&agreeing, &through, &normal)?;
    let held: Vec<&Point> = agreeing.iter().copied().filter(|p| (**p - through).dot(&normal).abs() <= FACE_INLIER_MM).collect();
    if held.len() < FACE_MIN_VERTICES {
        return None;
    }
    // Offsets from the plane, and the bowl fitted to them: offset = c + q (r^2 - mean r^2).
    let offsets: Vec<f64> = held.iter().map(|p| (**p - through).dot(&normal)).collect();
    let radii_squared: Vec<f64> = held.iter().map(|p| {
        let d = **p - through;
        d.norm_squared() - d.dot(&normal).powi(2)
    }).collect();
    let count = held.len() as f64;
    let mean_radius_squared = radii_squared.iter().sum::<f64>() / count;
    let (mut covariance, mut variance) = (0.0, 0.0);
    for (offset, radius_squared) in offsets.iter().zip(&radii_squared) {
        covariance += offset * (radius_squared - mean_radius_squared);
        variance += (radius_squared - mean_radius_squared).powi(2);
    }
    let bowl = if variance > 0.0 { covariance / variance } else { 0.0 };
    // Twice the standard deviation of r^2 about its mean, times the bowl: how far the
    // bowl rises across the face.
    let bowl_rise_mm = (bowl * 2.0 * (variance / count).sqrt()).abs();
    let mean_offset = offsets.iter().sum::<f64>() / count;
    let residual_variance = offsets
        .iter()
        .zip(&radii_squared)
        .map(|(offset, radius_squared)| (offset - mean_offset - bowl * (radius_squared - mean_radius_squared)).powi(2))
        .sum::<f64>()
        / (count - 2.0).max(1.0);
    // The rise's standard error: 2 sd(r^2) times the bowl's, sqrt(residual variance / sum
    // of squares of r^2), which is twice the residual deviation over sqrt(count).
    let bowl_rise_error_mm = 2.0 * (residual_variance / count).sqrt();
    let mut deviations: Vec<f64> = offsets.iter().map(|r| (r - mean_offset).abs()).collect();
    // 1.4826 turns a median absolute deviation into a normal standard deviation.
    let band_mm = 3.0 * 1.4826 * crate::statistics::quantile(&mut deviations, 0.5);
    Some(FittedFace { mean: through, normal, band_mm, bowl_rise_mm, bowl_rise_error_mm, vertices: held.into_iter().copied().collect() })
}

/// The total-least-squares plane (through the mean, across the normal oriented like
/// `normal`) of the vertices of `points` within [`FACE_INLIER_MM`] of the plane through
/// `through` across `normal`; `None` when they are fewer than [`FACE_MIN_VERTICES`] or
/// spread less than [`FACE_MIN_SPREAD_MM`] across their narrowest direction in the plane.
fn plane_of_held(points: &[&Point], through: &Point, normal: &Vector) -> Option<(Point, Vector)> {
    let held: Vec<(&Point, f64)> = points.iter().filter(|p| (***p - through).dot(normal).abs() <= FACE_INLIER_MM).map(|p| (*p, 1.0)).collect();
    if held.len() < FACE_MIN_VERTICES {
        return None;
    }
    let (mean, [_, narrowest_spread_squared, _], [fitted, _, _]) = principal_axes(held)?;
    (narrowest_spread_squared >= FACE_MIN_SPREAD_MM * FACE_MIN_SPREAD_MM).then(|| (mean, if fitted.dot(normal) < 0.0 { -fitted } else { fitted }))
}

/// Whether a piece whose vertices `support` samples could stand on the plane through
/// `through` across `normal` (facing away from the piece): at most
/// [`FACE_MAX_BEYOND_SHARE`] of them lie beyond it by more than [`FACE_BEYOND_MM`].
/// A floor is the piece's extreme; a plane across a floor onto the wall's first rise,
/// or through a flat-looking patch of a curved wall, has vertices beyond it.
fn supports(support: &[&Point], through: &Point, normal: &Vector) -> bool {
    let beyond = support.iter().filter(|p| (**p - through).dot(normal) > FACE_BEYOND_MM).count();
    beyond as f64 <= FACE_MAX_BEYOND_SHARE * support.len() as f64
}

/// Up to `count` unit directions around which `directions` (unit vectors) crowd within
/// cones of cosine `min_cosine`, densest first: the densest of cones centred on (up to
/// 128 of) the directions themselves, moved to the mean of what it holds, then the
/// densest of those outside the cones found.
fn densest_directions(directions: &[Vector], min_cosine: f64, count: usize) -> Vec<Vector> {
    const MAX_CENTRES: usize = 128;
    const MAX_COUNTED: usize = 4096;
    let counted: Vec<&Vector> = directions.iter().step_by(directions.len().div_ceil(MAX_COUNTED).max(1)).collect();
    let within = |centre: &Vector| counted.iter().filter(|d| d.dot(centre) >= min_cosine).count();
    let mut centres: Vec<(usize, &Vector)> =
        directions.iter().step_by(directions.len().div_ceil(MAX_CENTRES).max(1)).map(|centre| (within(centre), centre)).collect();
    centres.sort_by_key(|(held, _)| std::cmp::Reverse(*held));
    let mut found: Vec<Vector> = Vec::new();
    for (_, centre) in centres {
        if found.len() == count {
            break;
        }
        // A cone twice as wide: the found peak and its flanks.
        if found.iter().any(|f| f.dot(centre) >= (2.0 * min_cosine.acos()).cos()) {
            continue;
        }
        let mut peak = *centre;
        for _ in 0..2 {
            let sum = counted.iter().filter(|d| d.dot(&peak) >= min_cosine).fold(Vector::zeros(), |sum, d| sum + **d);
            match sum.try_normalize(1e-12) {
                Some(mean) => peak = mean,
                None => break,
            }
        }
        found.push(peak);
    }
    found
}


#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh;
    use crate::orient::Axis;
    use crate::refine::sections::Surface;

    /// An underside on a 1 mm grid, `height(r)` above the plane z = 0, with its downward
    /// normals, as seen from a start axis turned 3 degrees off z.
    fn underside(radius_mm: f64, height: impl Fn(f64) -> f64, slope: impl Fn(f64) -> f64) -> PreparedSurface {
        let (mut points, mut normals) = (Vec::new(), Vec::new());
        let steps = radius_mm as i32;
        for i in -steps..=steps {
            for j in -steps..=steps {
                let (x, y) = (f64::from(i), f64::from(j));
                let r = x.hypot(y);
                if r > radius_mm {
                    continue;
                }
                points.push(Point::new(x, y, height(r)));
                // The surface z = h(r) faces down: normal along (h' x / r, h' y / r, -1).
                let (nx, ny) = if r > 0.0 { (slope(r) * x / r, slope(r) * y / r) } else { (0.0, 0.0) };
                normals.push(Vector::new(nx, ny, -1.0).normalize());
            }
        }
        let start = Axis::new(Point::new(0.0, 0.0, 0.0), Vector::new(3f64.to_radians().sin(), 0.0, 3f64.to_radians().cos()));
        PreparedSurface::new(&Mesh::from_points_and_normals(points, normals), &start, Surface::Both, None).unwrap()
    }

    fn tilt_from_z_deg(surface: &PreparedSurface, face: &FlatFace) -> f64 {
        let axis = surface.axis_of(&[face.tilts[0], face.tilts[1], 0.0, 0.0]);
        axis.line_angle_to_deg(&Axis::new(Point::origin(), Vector::z()))
    }

    /// A floor 10 mm across beside a wall rising gently from it (`(r - 10)^3`, 2 mm at
    /// r = 30): the wall's vertices outnumber the floor's, and the face is the floor.
    #[test]
    fn a_small_floor_beside_a_gentle_rise_is_the_face() {
        let rise = |r: f64| 2.0 * ((r - 10.0).max(0.0) / 20.0).powi(3);
        let rise_slope = |r: f64| 6.0 * (r - 10.0).max(0.0).powi(2) / 8000.0;
        let surface = underside(30.0, rise, rise_slope);
        let face = flat_face(&surface, Edge::Base, &[0.0; 4], 10f64.to_radians()).expect("the floor");
        assert!(tilt_from_z_deg(&surface, &face) < 0.01, "{face:?}");
        assert!(face.vertices.len() >= 300 && face.vertices.len() < 1000, "{} vertices", face.vertices.len());
    }

    /// The lowest patch of a rounded underside (a sphere of 150 mm radius) is flat within
    /// a tenth of a millimetre over 10 mm, but it curves like a bowl: no face.
    #[test]
    fn a_rounded_underside_has_no_flat_face() {
        let sphere = |r: f64| 150.0 - (150f64.powi(2) - r * r).sqrt();
        let sphere_slope = |r: f64| r / (150f64.powi(2) - r * r).sqrt();
        let surface = underside(30.0, sphere, sphere_slope);
        assert_eq!(flat_face(&surface, Edge::Base, &[0.0; 4], 10f64.to_radians()), None);
    }
}
