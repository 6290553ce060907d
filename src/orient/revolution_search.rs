//! Whole-sphere search for the axis (the pre-orientation's first step): every direction of
//! an even cover of the hemisphere is scored by how well the fragment is a surface of
//! revolution about the best axis of that direction, the lowest valleys of that landscape
//! are followed down, and the valleys are returned best first for the verdict to compare.
//!
//! The score of an axis is the paper's two zeroth-order properties of a surface of
//! revolution at once (Wilczek et al. 2018, Fig. 1 b and c): horizontal sections are
//! circles about the axis (Eq. 2) and the profiles of all vertical sections superpose
//! (Eq. 5). Each point is put in the rz half-plane of the axis, with its normal's radial
//! and axial parts; a point whose normal is mostly radial (a wall) belongs to the band of
//! points of its skin at its height, one whose normal is mostly axial (a floor, a flat
//! lip, a plate) to the band of its side at its radius, and each band is a short straight
//! piece of the profile: the score is the robust mean of the points' distances to their
//! band's total-least-squares line. Equation 2 is the wall bands with the line held
//! vertical; the line's slope lets a flaring wall's band be as thin as a vertical one, and
//! the radial bands let the floors and lips that Eq. 2 cannot use speak. A point whose
//! normal turns away from the meridian plane by more than [`MAX_TANGENTIAL_NORMAL`]
//! (a break face, or any point under a wrong axis) costs as much as a large residual.
//!
//! For a given direction the axis's position is solved, not searched: first where the
//! normal lines projected on the horizontal plane meet (Halíř 1999, Eq. 1 of the paper),
//! then by the linearised circle condition of the wall bands (Kåsa's fit shared by all
//! bands, each with its own radius and slope), which is exact for a surface of revolution
//! and needs no start. Only the two angles of the direction are searched.

use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

use super::axis::Axis;
use super::halir::perpendicular_frame;
use super::normal_lines::NormalLines;
use crate::mesh::{Point, Vector};

/// Largest component of a unit normal across the meridian plane of a point on the surface
/// (the sine of its turn out of that plane) for the point to count as on the surface of
/// revolution: a normal 30 degrees out of the meridian plane belongs to a break face, or
/// the axis is wrong there.
pub const MAX_TANGENTIAL_NORMAL: f64 = 0.5;

/// The cost of a point off the surface of revolution, in the units of the robust loss:
/// that of a residual three loss scales long, so that a break face weighs as a point
/// three scales off its band.
pub const OUTLIER_LOSS: f64 = 0.9;

/// The robust loss of a residual `r`, given by its square, at scale `s` (Geman and
/// McClure): `r^2 / (r^2 + s^2)`, quadratic near zero and bounded by 1, so that no point
/// weighs more than a break.
fn robust_loss(r_squared: f64, s: f64) -> f64 {
    let q = r_squared / (s * s);
    q / (1.0 + q)
}

/// The weight of a residual in a reweighted least-squares step on [`robust_loss`].
fn robust_weight(r: f64, s: f64) -> f64 {
    1.0 / (1.0 + (r / s).powi(2)).powi(2)
}

/// Points farther from a candidate axis than this are off its surface of revolution, mm.
/// No thrown vessel is a metre wide, and without a bound a flat or nearly flat piece would
/// be a surface of revolution about axes far away on either side (a plane is the limit of
/// cylinders of growing radius) as well as about its true axis, across it.
pub const MAX_RADIUS_MM: f64 = 500.0;

/// Scale of the angle by which a normal line may miss the axis in the robust fit of the
/// axis's position (Cauchy weights): a smoothed scan's normals scatter by a few degrees.
const NORMAL_LINE_SCALE_RAD: f64 = 0.05;

/// Second over first eigenvalue of the projected normals' scatter under which a piece is
/// a short arc, whose break faces' normal lines [`normal_line_centre`] first weighs down:
/// the skins' normals over an arc of 2a spread with a ratio of about `a^2 / 3`, so this is
/// an arc of about 110 degrees.
const SHORT_ARC_SPREAD: f64 = 0.3;

/// Fewest points of a band for its line to be fitted; the points of smaller bands cost
/// as outliers (a wrong axis scatters the points into many small bands).
const MIN_BAND_POINTS: usize = 4;

/// The fragment's points, normals and area weights, centred on their centroid, ready to
/// be scored against any axis.
#[derive(Clone, Debug)]
pub struct RevolutionSamples {
    /// Positions relative to `centroid`, mm.
    pub points: Vec<Vector>,
    /// Unit normals.
    pub normals: Vec<Vector>,
    /// Area weights, mean 1.
    pub weights: Vec<f64>,
    /// The centroid subtracted, scan frame.
    pub centroid: Point,
    /// Width of a band along the profile, mm.
    pub band_mm: f64,
}

impl RevolutionSamples {
    /// At most `max_count` of `lines` (an even stride through them), with bands wide enough
    /// to hold several points of each skin: `band_factor` times the typical spacing of the
    /// points kept, at least `min_band_mm`.
    pub fn from_lines(lines: &NormalLines, max_count: usize, band_factor: f64, min_band_mm: f64) -> Option<Self> {
        let n = lines.len();
        if n < 2 * MIN_BAND_POINTS {
            return None;
        }
        let count = n.min(max_count.max(1));
        let picked: Vec<usize> = (0..count).map(|k| (k * n) / count).collect();
        let total_weight: f64 = picked.iter().map(|&i| lines.weights[i]).sum();
        if !(total_weight > 0.0) {
            return None;
        }
        let centroid = Point::from(
            picked.iter().map(|&i| lines.points[i].coords * lines.weights[i]).sum::<Vector>() / total_weight,
        );
        let mean_weight = total_weight / count as f64;
        // The surface area of all lines, shared by the kept points.
        let area: f64 = lines.weights.iter().sum();
        let spacing_mm = if lines.weights.iter().all(|w| *w == 1.0) {
            // A point cloud carries no areas: its spread stands in.
            let spread = picked.iter().map(|&i| (lines.points[i] - centroid).norm_squared()).sum::<f64>() / count as f64;
            (4.0 * spread / count as f64).sqrt()
        } else {
            (area / count as f64).sqrt()
        };
        Some(RevolutionSamples {
            points: picked.iter().map(|&i| lines.points[i] - centroid).collect(),
            normals: picked.iter().map(|&i| lines.directions[i]).collect(),
            weights: picked.iter().map(|&i| lines.weights[i] / mean_weight).collect(),
            centroid,
            band_mm: (band_factor * spacing_mm).max(min_band_mm),
        })
    }

    /// Root mean square distance of the points to their centroid, mm.
    pub fn size_mm(&self) -> f64 {
        let total: f64 = self.weights.iter().sum();
        (self.points.iter().zip(&self.weights).map(|(p, w)| p.norm_squared() * w).sum::<f64>() / total.max(1e-300)).sqrt()
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// True when there are no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

/// The best axis of one direction and its score.
#[derive(Clone, Copy, Debug)]
pub struct DirectionFit {
    /// Unit direction (sense arbitrary).
    pub direction: Vector,
    /// The axis's point in the plane through the centroid perpendicular to `direction`,
    /// relative to the centroid, mm.
    pub centre: Vector,
    /// The robust mean loss per unit weight (dimensionless, 0 for a perfect surface of
    /// revolution, [`OUTLIER_LOSS`] when no point is on one).
    pub cost: f64,
    /// Share of the weight on the surface of revolution (normal in the meridian plane, in
    /// a band of enough points).
    pub inlier_share: f64,
    /// Whether the points fix the axis's position for this direction (the wall bands or
    /// the normal lines); a flat piece's do not.
    pub position_fixed: bool,
}

/// A point in the frame of a candidate direction: height along it, position in the
/// perpendicular plane, and the normal's parts.
#[derive(Clone, Copy)]
struct Projected {
    height: f64,
    planar: Vector2<f64>,
    normal_planar: Vector2<f64>,
    normal_axial: f64,
    weight: f64,
}

/// The band of a point under an axis: wall bands by height, flat bands by radius, each
/// side apart.
#[derive(Clone, Copy, PartialEq, Eq)]
enum BandKey {
    Wall { outward: bool, index: i64 },
    Flat { upward: bool, index: i64 },
}

/// The line sums of one band in the rz half-plane.
#[derive(Clone, Copy, Default)]
struct LineSums {
    count: usize,
    w: f64,
    r: f64,
    z: f64,
    rr: f64,
    rz: f64,
    zz: f64,
}

impl LineSums {
    fn add(&mut self, r: f64, z: f64, w: f64) {
        self.count += 1;
        self.w += w;
        self.r += w * r;
        self.z += w * z;
        self.rr += w * r * r;
        self.rz += w * r * z;
        self.zz += w * z * z;
    }

    /// The total-least-squares line: its mean point and unit normal.
    fn line(&self) -> Option<([f64; 2], [f64; 2])> {
        if self.count < MIN_BAND_POINTS || !(self.w > 0.0) {
            return None;
        }
        let (mr, mz) = (self.r / self.w, self.z / self.w);
        let crr = self.rr / self.w - mr * mr;
        let crz = self.rz / self.w - mr * mz;
        let czz = self.zz / self.w - mz * mz;
        // The normal is the eigenvector of the smaller eigenvalue of the 2x2 scatter.
        let angle = 0.5 * (2.0 * crz).atan2(crr - czz); // direction of the line
        Some(([mr, mz], [-angle.sin(), angle.cos()]))
    }
}

/// Band tables indexed by key: a vector per kind and side, offset by the least index.
struct Bands<T> {
    wall: [Vec<T>; 2],
    flat: [Vec<T>; 2],
    wall_low: i64,
    flat_low: i64,
}

impl<T: Default + Clone> Bands<T> {
    fn new(wall_range: (i64, i64), flat_range: (i64, i64)) -> Self {
        let wall_len = (wall_range.1 - wall_range.0 + 1).max(0) as usize;
        let flat_len = (flat_range.1 - flat_range.0 + 1).max(0) as usize;
        Bands {
            wall: [vec![T::default(); wall_len], vec![T::default(); wall_len]],
            flat: [vec![T::default(); flat_len], vec![T::default(); flat_len]],
            wall_low: wall_range.0,
            flat_low: flat_range.0,
        }
    }

    fn get_mut(&mut self, key: BandKey) -> &mut T {
        match key {
            BandKey::Wall { outward, index } => &mut self.wall[outward as usize][(index - self.wall_low) as usize],
            BandKey::Flat { upward, index } => &mut self.flat[upward as usize][(index - self.flat_low) as usize],
        }
    }

    fn get(&self, key: BandKey) -> &T {
        match key {
            BandKey::Wall { outward, index } => &self.wall[outward as usize][(index - self.wall_low) as usize],
            BandKey::Flat { upward, index } => &self.flat[upward as usize][(index - self.flat_low) as usize],
        }
    }
}

/// A point in the rz half-plane of a candidate axis with its band, or `None` off the
/// surface of revolution.
#[derive(Clone, Copy)]
struct Placed {
    radius: f64,
    height: f64,
    /// The normal's turn out of the meridian plane (its component across it) times the
    /// band width: a residual in millimetres beside the distance to the band's line.
    tangential_mm: f64,
    key: Option<BandKey>,
}

/// `value.floor() as i64` without `f64::floor`, which is a call into libm on the baseline
/// target and was a twentieth of the search's instructions (placing every point in its
/// band, for every candidate axis).
fn floor_index(value: f64) -> i64 {
    let truncated = value as i64;
    truncated.saturating_sub(((truncated as f64) > value) as i64)
}

fn place(p: &Projected, centre: &Vector2<f64>, band_mm: f64) -> Placed {
    let offset = p.planar - centre;
    let radius = offset.norm();
    if !(radius > 1e-9) || radius > MAX_RADIUS_MM {
        return Placed { radius, height: p.height, tangential_mm: 0.0, key: None };
    }
    let radial = offset / radius;
    let normal_radial = p.normal_planar.dot(&radial);
    let normal_tangential = p.normal_planar.x * radial.y - p.normal_planar.y * radial.x;
    let tangential_mm = normal_tangential * band_mm;
    if normal_tangential.abs() > MAX_TANGENTIAL_NORMAL {
        return Placed { radius, height: p.height, tangential_mm, key: None };
    }
    let key = if normal_radial.abs() >= p.normal_axial.abs() {
        BandKey::Wall { outward: normal_radial > 0.0, index: floor_index(p.height / band_mm) }
    } else {
        BandKey::Flat { upward: p.normal_axial > 0.0, index: floor_index(radius / band_mm) }
    };
    Placed { radius, height: p.height, tangential_mm, key: Some(key) }
}

/// Solves the 2x2 system `a x = b` when it is well conditioned (smaller eigenvalue at
/// least `relative` times the larger).
fn solve_conditioned(a: &Matrix2<f64>, b: &Vector2<f64>, relative: f64) -> Option<Vector2<f64>> {
    let trace = a[(0, 0)] + a[(1, 1)];
    let det = a.determinant();
    let disc = ((a[(0, 0)] - a[(1, 1)]).powi(2) + 4.0 * a[(0, 1)] * a[(1, 0)]).max(0.0).sqrt();
    let (small, large) = ((trace - disc) / 2.0, (trace + disc) / 2.0);
    if !(large > 0.0) || !(small >= relative * large) || det == 0.0 {
        return None;
    }
    a.try_inverse().map(|inverse| inverse * b)
}

/// Where the normal lines, projected on the plane perpendicular to the direction, meet:
/// the weighted least-squares point, reweighted by the angle at which each line misses it
/// (Cauchy, `scale_rad`). `None` when the projected normals are nearly parallel (a flat
/// piece).
///
/// The skins' normals are mostly radial, those of the breaks between them mostly across
/// the radius: on a short arc the skins' lines are nearly parallel, and the breaks' lines,
/// which run through the sherd, would pin the point onto the sherd. So where the projected
/// normals keep to one direction (the second eigenvalue of their scatter under
/// [`SHORT_ARC_SPREAD`] of the first), each line is first weighted by the fourth power of
/// its alignment with it (the mean radial direction).
fn normal_line_centre(points: &[Projected], scale_rad: f64) -> Option<Vector2<f64>> {
    let mut scatter = Matrix2::zeros();
    for p in points {
        scatter += p.normal_planar * p.normal_planar.transpose() * p.weight;
    }
    let eigen = nalgebra::SymmetricEigen::new(scatter);
    let (large, small) = if eigen.eigenvalues[0] >= eigen.eigenvalues[1] { (0, 1) } else { (1, 0) };
    let main = eigen.eigenvectors.column(large);
    let main = Vector2::new(main[0], main[1]);
    let short_arc = eigen.eigenvalues[small] < SHORT_ARC_SPREAD * eigen.eigenvalues[large];
    let prior: Vec<f64> = points
        .iter()
        .map(|p| {
            let length = p.normal_planar.norm();
            let alignment = if length > 1e-9 { p.normal_planar.dot(&main) / length } else { 0.0 };
            if short_arc { p.weight * alignment.powi(4) } else { p.weight }
        })
        .collect();
    let mut centre: Option<Vector2<f64>> = None;
    for _ in 0..3 {
        let (mut a, mut b) = (Matrix2::zeros(), Vector2::zeros());
        for (p, prior) in points.iter().zip(&prior) {
            // The line through `planar` along `normal_planar`: its normal is `perp`.
            let perp = Vector2::new(p.normal_planar.y, -p.normal_planar.x);
            let mut w = *prior;
            if let Some(c) = centre {
                let length = perp.norm();
                let reach = (c - p.planar).norm();
                if length < 1e-6 || reach < 1e-9 {
                    continue;
                }
                let angle = perp.dot(&(c - p.planar)) / (length * reach);
                w /= 1.0 + (angle / scale_rad).powi(2);
            }
            a += perp * perp.transpose() * w;
            b += perp * perp.dot(&p.planar) * w;
        }
        centre = Some(solve_conditioned(&a, &b, 1e-4)?);
    }
    centre
}

/// The position from the circles of the wall bands, linearised (Kåsa): in every band the
/// squared radius about the axis is `|q|^2 - 2 q.c + |c|^2`, a line in the height with the
/// band's own coefficients, so after the band's own mean and slope are projected out
/// `|q|^2` is linear in `c` alone. Solved about `start`; `None` when the bands do not fix
/// it (too few, or all on one short arc in one direction).
fn wall_circles_centre(points: &[Projected], start: &Vector2<f64>, band_mm: f64) -> Option<Vector2<f64>> {
    // Per band: sums of w times 1, h, h^2, and of x, y, Q and their products with h, and
    // the cross products, for the projection onto the complement of [1, h].
    #[derive(Clone, Copy, Default)]
    struct KasaSums {
        count: usize,
        s: [f64; 14],
    }
    let placed: Vec<Placed> = points.iter().map(|p| place(p, start, band_mm)).collect();
    let (low, high) = placed.iter().fold((i64::MAX, i64::MIN), |(lo, hi), p| match p.key {
        Some(BandKey::Wall { index, .. }) => (lo.min(index), hi.max(index)),
        _ => (lo, hi),
    });
    if low > high {
        return None;
    }
    let mut bands: Bands<KasaSums> = Bands::new((low, high), (0, -1));
    for (p, at) in points.iter().zip(&placed) {
        let Some(key @ BandKey::Wall { .. }) = at.key else { continue };
        let q = p.planar - start;
        let (x, y, h) = (q.x, q.y, p.height);
        let big_q = x * x + y * y;
        let w = p.weight;
        let sums = bands.get_mut(key);
        sums.count += 1;
        let s = &mut sums.s;
        s[0] += w;
        s[1] += w * h;
        s[2] += w * h * h;
        s[3] += w * x;
        s[4] += w * y;
        s[5] += w * big_q;
        s[6] += w * h * x;
        s[7] += w * h * y;
        s[8] += w * h * big_q;
        s[9] += w * x * x;
        s[10] += w * x * y;
        s[11] += w * y * y;
        s[12] += w * x * big_q;
        s[13] += w * y * big_q;
    }
    let (mut a, mut b) = (Matrix2::zeros(), Vector2::zeros());
    let mut used = 0;
    for sums in bands.wall.iter().flatten() {
        if sums.count < MIN_BAND_POINTS {
            continue;
        }
        let s = &sums.s;
        // A band whose points all lie at one height (one row of a regular grid) has no
        // slope to project out, and its moment matrix is singular up to rounding: only
        // its mean is projected out there.
        let height_variance = s[2] / s[0] - (s[1] / s[0]).powi(2);
        let m_inverse = if height_variance > 1e-6 * band_mm * band_mm {
            let Some(inverse) = Matrix2::new(s[0], s[1], s[1], s[2]).try_inverse() else { continue };
            inverse
        } else {
            Matrix2::new(1.0 / s[0], 0.0, 0.0, 0.0)
        };
        // Projected covariance of u and v: S_uv - [S_u, S_hu] M^-1 [S_v, S_hv]^T.
        let first = |u_sum: f64, hu_sum: f64| Vector2::new(u_sum, hu_sum);
        let (fx, fy, fq) = (first(s[3], s[6]), first(s[4], s[7]), first(s[5], s[8]));
        let cov = |uv: f64, fu: &Vector2<f64>, fv: &Vector2<f64>| uv - fu.dot(&(m_inverse * fv));
        let cxx = cov(s[9], &fx, &fx);
        let cxy = cov(s[10], &fx, &fy);
        let cyy = cov(s[11], &fy, &fy);
        let cxq = cov(s[12], &fx, &fq);
        let cyq = cov(s[13], &fy, &fq);
        // Algebraic residuals of squared radii are 2 r times the geometric ones.
        let mean_square_radius = (s[5] / s[0]).max(1e-12);
        let band_weight = 1.0 / (4.0 * mean_square_radius);
        a += Matrix2::new(cxx, cxy, cxy, cyy) * band_weight;
        b += Vector2::new(cxq, cyq) * band_weight;
        used += 1;
    }
    if used < 2 {
        return None;
    }
    solve_conditioned(&a, &(b / 2.0), 1e-6).map(|shift| start + shift)
}

/// A band's total-least-squares line in the rz half-plane: its mean point and unit normal.
type BandLine = ([f64; 2], [f64; 2]);

/// The points of a candidate axis in its rz half-plane, their bands' lines and the score.
struct BandEvaluation {
    placed: Vec<Placed>,
    lines: Bands<Option<BandLine>>,
    cost: f64,
    inlier_share: f64,
}

impl BandEvaluation {
    /// The line of a placed point's band, if it has one.
    fn line_of(&self, at: &Placed) -> Option<BandLine> {
        at.key.and_then(|key| *self.lines.get(key))
    }
}

fn residual(at: &Placed, (mean, normal): BandLine) -> f64 {
    (at.radius - mean[0]) * normal[0] + (at.height - mean[1]) * normal[1]
}

/// The robust loss of a point on its band: its distance to the band's line and its
/// normal's turn out of the meridian plane (Wilczek et al. 2018, Fig. 1 a and c at once).
fn point_loss(at: &Placed, line: BandLine, loss_scale_mm: f64) -> f64 {
    robust_loss(residual(at, line).powi(2) + at.tangential_mm.powi(2), loss_scale_mm)
}

/// The robust mean loss of the points about the axis through `centre` along the frame's
/// direction, with the share of the weight on the surface of revolution.
fn evaluate_bands(points: &[Projected], centre: &Vector2<f64>, band_mm: f64, loss_scale_mm: f64) -> BandEvaluation {
    let placed: Vec<Placed> = points.iter().map(|p| place(p, centre, band_mm)).collect();
    let (mut wall, mut flat) = ((i64::MAX, i64::MIN), (i64::MAX, i64::MIN));
    for p in &placed {
        match p.key {
            Some(BandKey::Wall { index, .. }) => wall = (wall.0.min(index), wall.1.max(index)),
            Some(BandKey::Flat { index, .. }) => flat = (flat.0.min(index), flat.1.max(index)),
            None => {}
        }
    }
    let mut bands: Bands<LineSums> = Bands::new(wall, flat);
    for (p, at) in points.iter().zip(&placed) {
        if let Some(key) = at.key {
            bands.get_mut(key).add(at.radius, at.height, p.weight);
        }
    }
    let lines: Bands<Option<BandLine>> = Bands {
        wall: bands.wall.map(|v| v.iter().map(LineSums::line).collect()),
        flat: bands.flat.map(|v| v.iter().map(LineSums::line).collect()),
        wall_low: bands.wall_low,
        flat_low: bands.flat_low,
    };
    let mut evaluation = BandEvaluation { placed, lines, cost: 0.0, inlier_share: 0.0 };
    let (mut total, mut weight, mut inlier) = (0.0, 0.0, 0.0);
    for (p, at) in points.iter().zip(&evaluation.placed) {
        weight += p.weight;
        match evaluation.line_of(at) {
            Some(line) => {
                total += p.weight * point_loss(at, line, loss_scale_mm);
                inlier += p.weight;
            }
            None => total += p.weight * OUTLIER_LOSS,
        }
    }
    evaluation.cost = total / weight.max(1e-300);
    evaluation.inlier_share = inlier / weight.max(1e-300);
    evaluation
}

/// One robust Gauss-Newton step of the axis's position on the band residuals: each
/// residual moves with the centre by the band line's radial normal times the radial
/// direction, less its band's mean move (the band's line follows its points' mean), and
/// the Cauchy weights of the loss. `None` when the bands do not fix the position.
fn position_step(points: &[Projected], evaluation: &BandEvaluation, centre: &Vector2<f64>, loss_scale_mm: f64) -> Option<Vector2<f64>> {
    #[derive(Clone, Copy, Default)]
    struct MeanMove {
        weight: f64,
        sum: Vector2<f64>,
    }
    let mut moves: Bands<MeanMove> = Bands {
        wall: evaluation.lines.wall.clone().map(|v| vec![MeanMove::default(); v.len()]),
        flat: evaluation.lines.flat.clone().map(|v| vec![MeanMove::default(); v.len()]),
        wall_low: evaluation.lines.wall_low,
        flat_low: evaluation.lines.flat_low,
    };
    let mut rows: Vec<(Option<BandKey>, Vector2<f64>, f64, f64)> = Vec::with_capacity(points.len());
    for (p, at) in points.iter().zip(&evaluation.placed) {
        let Some(line) = evaluation.line_of(at) else {
            rows.push((None, Vector2::zeros(), 0.0, 0.0));
            continue;
        };
        let r = residual(at, line);
        let radial = (p.planar - centre) / at.radius;
        let jacobian = -radial * line.1[0];
        let w = p.weight * robust_weight(r, loss_scale_mm);
        let key = at.key.expect("a line has a band");
        let entry = moves.get_mut(key);
        entry.weight += w;
        entry.sum += jacobian * w;
        rows.push((Some(key), jacobian, r, w));
    }
    let (mut normal, mut rhs) = (Matrix2::zeros(), Vector2::zeros());
    for (key, jacobian, r, w) in rows {
        let Some(key) = key else { continue };
        let mean = moves.get(key);
        let centred = jacobian - mean.sum / mean.weight.max(1e-300);
        normal += centred * centred.transpose() * w;
        rhs += centred * (r * w);
    }
    solve_conditioned(&normal, &(-rhs), 1e-6)
}

/// The position polished by robust Gauss-Newton steps from `start`, each kept only where
/// it lowers the score (halved up to three times otherwise).
fn polish_position(points: &[Projected], start: Vector2<f64>, band_mm: f64, loss_scale_mm: f64, steps: usize) -> (Vector2<f64>, BandEvaluation) {
    let mut centre = start;
    let mut evaluation = evaluate_bands(points, &centre, band_mm, loss_scale_mm);
    for _ in 0..steps {
        let Some(step) = position_step(points, &evaluation, &centre, loss_scale_mm) else { break };
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..4 {
            let candidate = centre + step * scale;
            let trial = evaluate_bands(points, &candidate, band_mm, loss_scale_mm);
            if trial.cost < evaluation.cost {
                centre = candidate;
                evaluation = trial;
                improved = true;
                break;
            }
            scale *= 0.5;
        }
        if !improved || (step * scale).norm() < 1e-3 {
            break;
        }
    }
    (centre, evaluation)
}

/// The best axis along `direction` and its score: the position where the normal lines
/// meet, then by the wall bands' circles, the better of the two polished by robust
/// Gauss-Newton steps on the score itself.
pub fn fit_direction(samples: &RevolutionSamples, direction: &Vector, loss_scale_mm: f64) -> DirectionFit {
    fit_direction_with(samples, direction, loss_scale_mm, POLISH_STEPS)
}

/// Gauss-Newton steps of [`fit_direction`].
const POLISH_STEPS: usize = 4;

fn fit_direction_with(samples: &RevolutionSamples, direction: &Vector, loss_scale_mm: f64, polish_steps: usize) -> DirectionFit {
    let d = direction.normalize();
    let (e1, e2) = perpendicular_frame(&d);
    let points = project(samples, &d, &e1, &e2);
    let band = samples.band_mm;
    let (centre, position_fixed) = match normal_line_centre(&points, NORMAL_LINE_SCALE_RAD) {
        Some(by_normals) => {
            // The circles' fit is exact on a surface of revolution and the normals' is not;
            // where the walls give no circles the polish starts from the normals'.
            (wall_circles_centre(&points, &by_normals, band).unwrap_or(by_normals), true)
        }
        // No position: a flat piece, scored about its centroid's line.
        None => (Vector2::zeros(), false),
    };
    let (centre, evaluation) = if position_fixed {
        polish_position(&points, centre, band, loss_scale_mm, polish_steps)
    } else {
        let evaluation = evaluate_bands(&points, &centre, band, loss_scale_mm);
        (centre, evaluation)
    };
    DirectionFit {
        direction: d,
        centre: e1 * centre.x + e2 * centre.y,
        cost: evaluation.cost,
        inlier_share: evaluation.inlier_share,
        position_fixed,
    }
}

/// Each sample's robust loss under `axis` (no position solved): [`OUTLIER_LOSS`] off the
/// surface of revolution, the loss of its distance to its band's line on it.
pub fn point_losses(samples: &RevolutionSamples, axis: &Axis, loss_scale_mm: f64) -> Vec<f64> {
    let d = axis.direction.into_inner();
    let (e1, e2) = perpendicular_frame(&d);
    let points = project(samples, &d, &e1, &e2);
    let offset = axis.point - samples.centroid;
    let centre = Vector2::new(offset.dot(&e1), offset.dot(&e2));
    let evaluation = evaluate_bands(&points, &centre, samples.band_mm, loss_scale_mm);
    evaluation
        .placed
        .iter()
        .map(|at| evaluation.line_of(at).map_or(OUTLIER_LOSS, |line| point_loss(at, line, loss_scale_mm)))
        .collect()
}

fn project(samples: &RevolutionSamples, d: &Vector, e1: &Vector, e2: &Vector) -> Vec<Projected> {
    samples
        .points
        .iter()
        .zip(&samples.normals)
        .zip(&samples.weights)
        .map(|((p, n), w)| Projected {
            height: p.dot(d),
            planar: Vector2::new(p.dot(e1), p.dot(e2)),
            normal_planar: Vector2::new(n.dot(e1), n.dot(e2)),
            normal_axial: n.dot(d),
            weight: *w,
        })
        .collect()
}

/// Directions spread evenly over the upper hemisphere (a Fibonacci spiral), `count` of
/// them.
pub fn hemisphere_directions(count: usize) -> Vec<Vector> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (i as f64 + 0.5) / count as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            Vector::new(r * phi.cos(), r * phi.sin(), z)
        })
        .collect()
}

/// A valley of the landscape followed to its bottom.
#[derive(Clone, Copy, Debug)]
pub struct Valley {
    /// Its best axis.
    pub fit: DirectionFit,
    /// The score of the coarse direction it was followed from.
    pub coarse_cost: f64,
}

impl Valley {
    /// The valley's axis in the scan frame (sense arbitrary).
    pub fn axis(&self, samples: &RevolutionSamples) -> Axis {
        Axis::new(samples.centroid + self.fit.centre, self.fit.direction)
    }
}

/// Settings of [`search`].
#[derive(Clone, Copy, Debug)]
pub struct SearchOptions {
    /// Directions of the coarse cover of the hemisphere.
    pub coarse_directions: usize,
    /// Points the coarse cover is scored on.
    pub coarse_points: usize,
    /// Valleys followed down from the coarse cover's lowest local minima.
    pub valleys: usize,
    /// Points the valleys are followed down on.
    pub descent_points: usize,
    /// Valleys, lowest first, followed to their bottom on all the points (at most
    /// `final_points`) and returned.
    pub final_valleys: usize,
    /// Points of the final descent.
    pub final_points: usize,
    /// Two valleys whose bottoms lie closer than this are one, degrees.
    pub distinct_deg: f64,
    /// The robust loss's scale, as a share of the band width.
    pub loss_scale_bands: f64,
    /// Band width in typical point spacings.
    pub band_spacings: f64,
    /// Least band width, mm.
    pub min_band_mm: f64,
    /// Gauss-Newton steps of the position at each direction of the coarse cover, of the
    /// descents and of the final descents.
    pub polish_steps: [usize; 3],
    /// Nelder-Mead iterations of the descents and of the final descents.
    pub iterations: [usize; 2],
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            coarse_directions: 700,
            coarse_points: 1200,
            valleys: 5,
            descent_points: 2500,
            final_valleys: 3,
            final_points: 6000,
            distinct_deg: 5.0,
            loss_scale_bands: 0.25,
            band_spacings: 2.5,
            min_band_mm: 1.0,
            polish_steps: [2, 2, 3],
            iterations: [40, 25],
        }
    }
}

/// The landscape's valleys, lowest first: the coarse cover scored on a subsample of the
/// lines, its local minima (no neighbour lower) followed down on a larger subsample, and
/// the lowest of them followed to their bottom on all the lines (at most
/// [`SearchOptions::final_points`]). The valleys' costs are comparable with each other
/// (the same points and loss), and with [`Landscape::samples`]' scores.
pub fn search(lines: &NormalLines, options: &SearchOptions) -> Option<Landscape> {
    let sampled = |count: usize| RevolutionSamples::from_lines(lines, count, options.band_spacings, options.min_band_mm);
    let coarse = sampled(options.coarse_points)?;
    let descent = sampled(options.descent_points)?;
    let samples = sampled(options.final_points)?;
    let directions = hemisphere_directions(options.coarse_directions.max(8));
    let coarse_scale = options.loss_scale_bands * coarse.band_mm;
    let fits: Vec<DirectionFit> = directions.par_iter().map(|d| fit_direction_with(&coarse, d, coarse_scale, options.polish_steps[0])).collect();
    // Neighbours: within 1.8 spacings of the cover (a line's two senses are one direction).
    let spacing = (2.0 * std::f64::consts::PI / directions.len() as f64).sqrt();
    let near = (1.8 * spacing).cos();
    let mut minima: Vec<usize> = (0..directions.len())
        .filter(|&i| {
            directions.iter().enumerate().all(|(j, d)| j == i || d.dot(&directions[i]).abs() < near || fits[j].cost >= fits[i].cost)
        })
        .collect();
    minima.sort_by(|&a, &b| fits[a].cost.total_cmp(&fits[b].cost));
    let distinct = options.distinct_deg.to_radians().cos();
    let mut starts: Vec<usize> = Vec::new();
    for i in minima {
        if starts.iter().all(|&s| directions[s].dot(&directions[i]).abs() < distinct) {
            starts.push(i);
        }
        if starts.len() >= options.valleys {
            break;
        }
    }
    let descent_scale = options.loss_scale_bands * descent.band_mm;
    // Beside the cover's minima, the two directions the normals point to without a search:
    // across all of them (a cylinder's or a cone's axis: the least eigenvector of their
    // scatter) and along most of them (a floor's normal: the largest). A valley narrower
    // than the cover's spacing (a base whose position only its small foot fixes) is
    // reached from there.
    let mut start_directions: Vec<(Vector, f64)> = starts.iter().map(|&i| (directions[i], fits[i].cost)).collect();
    for direction in normal_scatter_axes(&coarse) {
        if start_directions.iter().all(|(d, _)| d.dot(&direction).abs() < distinct) {
            start_directions.push((direction, f64::NAN));
        }
    }
    let mut followed: Vec<(DirectionFit, f64)> = start_directions
        .par_iter()
        .map(|(direction, coarse_cost)| {
            let fit = descend(&descent, direction, 1.2 * spacing, DESCENT_TOLERANCE_DEG.to_radians(), descent_scale, options.polish_steps[1], options.iterations[0]);
            (fit, *coarse_cost)
        })
        .collect();
    followed.sort_by(|a, b| a.0.cost.total_cmp(&b.0.cost));
    let followed = distinct_fits(followed, distinct);
    let scale = options.loss_scale_bands * samples.band_mm;
    let mut valleys: Vec<(DirectionFit, f64)> = followed
        .par_iter()
        .take(options.final_valleys)
        .map(|(fit, coarse_cost)| {
            (descend(&samples, &fit.direction, FINAL_STEP_DEG.to_radians(), FINAL_TOLERANCE_DEG.to_radians(), scale, options.polish_steps[2], options.iterations[1]), *coarse_cost)
        })
        .collect();
    valleys.sort_by(|a, b| a.0.cost.total_cmp(&b.0.cost));
    let valleys = distinct_fits(valleys, distinct).into_iter().map(|(fit, coarse_cost)| Valley { fit, coarse_cost }).collect();
    Some(Landscape { valleys, samples, loss_scale_mm: scale })
}

/// The least and the largest eigenvectors of the weighted scatter of the normals.
fn normal_scatter_axes(samples: &RevolutionSamples) -> [Vector; 2] {
    let mut scatter = nalgebra::Matrix3::zeros();
    for (n, w) in samples.normals.iter().zip(&samples.weights) {
        scatter += n * n.transpose() * *w;
    }
    let eigen = nalgebra::SymmetricEigen::new(scatter);
    let pick = |largest: bool| {
        let mut best = 0;
        for k in 1..3 {
            let better = if largest { eigen.eigenvalues[k] > eigen.eigenvalues[best] } else { eigen.eigenvalues[k] < eigen.eigenvalues[best] };
            if better {
                best = k;
            }
        }
        eigen.eigenvectors.column(best).into_owned()
    };
    [pick(false), pick(true)]
}

/// First simplex step of the final descent, degrees.
const FINAL_STEP_DEG: f64 = 1.0;
/// The descents stop when their simplex is smaller than this, degrees: the refinement
/// that follows the search settles the last tenths of a degree.
const DESCENT_TOLERANCE_DEG: f64 = 0.3;
/// The same for the final descents.
const FINAL_TOLERANCE_DEG: f64 = 0.05;

/// The fits (lowest first) with those closer than `distinct` (a cosine) to a lower one
/// dropped.
fn distinct_fits(fits: Vec<(DirectionFit, f64)>, distinct: f64) -> Vec<(DirectionFit, f64)> {
    let mut kept: Vec<(DirectionFit, f64)> = Vec::new();
    for (fit, coarse) in fits {
        if kept.iter().all(|(k, _)| k.direction.dot(&fit.direction).abs() < distinct) {
            kept.push((fit, coarse));
        }
    }
    kept
}

/// The valleys of the landscape, lowest first, and the points and loss they were scored
/// with.
#[derive(Clone, Debug)]
pub struct Landscape {
    /// The valleys, lowest first, their bottoms at least [`SearchOptions::distinct_deg`]
    /// apart.
    pub valleys: Vec<Valley>,
    /// The points of the final descent.
    pub samples: RevolutionSamples,
    /// The loss scale of the final descent, mm.
    pub loss_scale_mm: f64,
}

/// Follows the valley of `start` down: Nelder-Mead over two tilts of the direction, the
/// position solved for each ([`fit_direction`] with `polish_steps`), from a simplex of
/// side `step_rad`, until the simplex is smaller than `tolerance_rad` or after
/// `iterations`. Written here rather than taken from argmin, whose Nelder-Mead stops on
/// the spread of the costs only: the score jitters as points change band, and the
/// simplex went on shrinking onto that jitter long after the axis had stopped moving.
pub fn descend(samples: &RevolutionSamples, start: &Vector, step_rad: f64, tolerance_rad: f64, scale_mm: f64, polish_steps: usize, iterations: usize) -> DirectionFit {
    let start = start.normalize();
    let (e1, e2) = perpendicular_frame(&start);
    let fit = |tilts: [f64; 2]| {
        let direction = (start + e1 * tilts[0].tan() + e2 * tilts[1].tan()).normalize();
        fit_direction_with(samples, &direction, scale_mm, polish_steps)
    };
    let mut simplex: Vec<([f64; 2], DirectionFit)> =
        [[0.0, 0.0], [step_rad, 0.0], [0.0, step_rad]].into_iter().map(|t| (t, fit(t))).collect();
    for _ in 0..iterations {
        simplex.sort_by(|a, b| a.1.cost.total_cmp(&b.1.cost));
        let size = (1..3).map(|k| (simplex[k].0[0] - simplex[0].0[0]).hypot(simplex[k].0[1] - simplex[0].0[1])).fold(0.0, f64::max);
        if size < tolerance_rad {
            break;
        }
        let centroid = [(simplex[0].0[0] + simplex[1].0[0]) / 2.0, (simplex[0].0[1] + simplex[1].0[1]) / 2.0];
        let worst = simplex[2].0;
        let along = |factor: f64| [centroid[0] + factor * (worst[0] - centroid[0]), centroid[1] + factor * (worst[1] - centroid[1])];
        let reflected = along(-1.0);
        let reflected_fit = fit(reflected);
        if reflected_fit.cost < simplex[0].1.cost {
            let expanded = along(-2.0);
            let expanded_fit = fit(expanded);
            simplex[2] = if expanded_fit.cost < reflected_fit.cost { (expanded, expanded_fit) } else { (reflected, reflected_fit) };
        } else if reflected_fit.cost < simplex[1].1.cost {
            simplex[2] = (reflected, reflected_fit);
        } else {
            let contracted = if reflected_fit.cost < simplex[2].1.cost { along(-0.5) } else { along(0.5) };
            let contracted_fit = fit(contracted);
            if contracted_fit.cost < simplex[2].1.cost.min(reflected_fit.cost) {
                simplex[2] = (contracted, contracted_fit);
            } else {
                // Shrink towards the best.
                let best = simplex[0].0;
                for k in 1..3 {
                    let t = [(simplex[k].0[0] + best[0]) / 2.0, (simplex[k].0[1] + best[1]) / 2.0];
                    simplex[k] = (t, fit(t));
                }
            }
        }
    }
    simplex.into_iter().map(|(_, f)| f).min_by(|a, b| a.cost.total_cmp(&b.cost)).expect("three vertices")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_index_is_floor() {
        for value in [-2.5, -2.0, -1e-12, -0.0, 0.0, 1e-12, 0.999_999, 1.0, 3.5, 1e20, -1e20, f64::NAN] {
            assert_eq!(floor_index(value), value.floor() as i64, "{value}");
        }
    }

    /// Both skins of a wall patch of a surface of revolution about the z axis through
    /// `(ax, ay)`: radius `radius(z)` with slope `slope(z)`, over `arc` radians and `heights`.
    fn patch(ax: f64, ay: f64, radius: impl Fn(f64) -> f64, slope: impl Fn(f64) -> f64, arc: (f64, f64), heights: (f64, f64)) -> NormalLines {
        let mut lines = NormalLines::default();
        for i in 0..60 {
            for j in 0..40 {
                let t = arc.0 + (arc.1 - arc.0) * i as f64 / 59.0;
                let z = heights.0 + (heights.1 - heights.0) * j as f64 / 39.0;
                for (offset, sign) in [(0.0, 1.0), (-5.0, -1.0)] {
                    let r = radius(z) + offset;
                    let (c, s) = (t.cos(), t.sin());
                    // The outward normal of r(z) is (cos, sin, -r'(z)), normalised.
                    let n = Vector::new(c, s, -slope(z)).normalize() * sign;
                    lines.push(Point::new(ax + r * c, ay + r * s, z), n, 1.0, lines.len());
                }
            }
        }
        lines
    }

    #[test]
    fn the_true_direction_gets_the_true_position() {
        let lines = patch(30.0, -20.0, |z| 80.0 + 0.3 * z, |_| 0.3, (0.2, 0.9), (0.0, 50.0));
        let samples = RevolutionSamples::from_lines(&lines, 10_000, 2.5, 1.0).unwrap();
        let fit = fit_direction(&samples, &Vector::z(), 0.25 * samples.band_mm);
        let centre = samples.centroid + fit.centre;
        assert!((centre.x - 30.0).abs() < 0.1 && (centre.y + 20.0).abs() < 0.1, "{centre:?} cost {}", fit.cost);
        assert!(fit.cost < 0.01, "cost {}", fit.cost);
    }

    /// The search finds a cone's axis from nothing, on a 40-degree arc of it tilted away
    /// from every axis of the frame, and ranks it first: no start is given.
    #[test]
    fn the_whole_sphere_search_finds_a_cone_from_nothing() {
        let lines = patch(10.0, 5.0, |z| 60.0 + 0.5 * z, |_| 0.5, (0.0, 0.7), (0.0, 40.0));
        let rotation = nalgebra::Rotation3::from_euler_angles(0.7, -0.4, 1.1);
        let mut moved = NormalLines::default();
        for i in 0..lines.len() {
            moved.push(rotation * lines.points[i], rotation * lines.directions[i], 1.0, i);
        }
        let landscape = search(&moved, &SearchOptions::default()).expect("enough points");
        let truth = Axis::new(rotation * Point::new(10.0, 5.0, 0.0), rotation * Vector::z());
        let best = landscape.valleys[0].axis(&landscape.samples);
        assert!(best.line_angle_to_deg(&truth) < 0.2, "{:.3} deg", best.line_angle_to_deg(&truth));
        assert!(truth.distance_to(&best.closest_point(&landscape.samples.centroid)) < 0.3);
    }

    /// The coarse cover leaves no direction farther than one and a half spacings from it.
    #[test]
    fn hemisphere_directions_cover_the_sphere_evenly() {
        let directions = hemisphere_directions(500);
        assert!(directions.iter().all(|d| (d.norm() - 1.0).abs() < 1e-12 && d.z >= 0.0));
        // Every direction of the upper hemisphere lies within twice the mean spacing.
        let spacing = (2.0 * std::f64::consts::PI / 500.0).sqrt();
        for probe in hemisphere_directions(2000) {
            let nearest = directions.iter().map(|d| d.dot(&probe).clamp(-1.0, 1.0).acos()).fold(f64::INFINITY, f64::min);
            assert!(nearest < 1.5 * spacing, "{probe:?} is {nearest:.3} rad from the cover");
        }
    }
}
