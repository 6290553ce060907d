//! Vertical profile superposition (Wilczek et al. 2018, section 2.3.3). Every skin point
//! projected on the rz-plane of a candidate axis should lie on one profile curve:
//!
//! * Eq. 5: the sum of squared distances from each point to the nearest point of the
//!   reference profile, the longest vertical section (angular sector) of the skin;
//! * Eq. 6: the sum of squared residuals `r_i - f(z_i)` of a polynomial profile `f`,
//!   one per skin, fitted by least squares at every candidate axis; by default a
//!   piecewise polynomial (cubic spline), whose residuals are taken across the profile.
//!
//! The polynomial is written in Legendre polynomials of the height scaled to [-1, 1]:
//! the original's monomials of order 12 make the normal equations singular to machine
//! precision on a 100 mm sherd, Legendre polynomials keep them well conditioned.

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::objective::Objective;
use super::sections::{vertical_sections, AxisParameters, CandidateFrame, PreparedSurface, Skin};
use crate::mesh::{planar_length, Point};

/// The two forms of the criterion.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum ProfileMethod {
    /// Eq. 5: distance to the longest vertical section, with this many sections.
    ReferenceProfile {
        /// Number of vertical sections (angular sectors) the arc is divided into.
        vertical_sections: usize,
    },
    /// Eq. 6: residuals of a polynomial profile of this degree per skin.
    Polynomial {
        /// Degree of r(z).
        degree: usize,
    },
    /// Eq. 6 with a piecewise polynomial: a cubic spline profile per skin with knots
    /// this far apart, and each residual measured across the profile (divided by
    /// `sqrt(1 + f'(z)^2)`).
    Spline {
        /// Distance between knots along the height, mm.
        knot_spacing_mm: f64,
    },
}

crate::vocabulary! {
    /// The forms of [`ProfileMethod`], by name (without their parameter).
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub enum ProfileMethodKind: "profile method", "profile methods" {
        /// [`ProfileMethod::ReferenceProfile`]; its parameter is the number of vertical sections.
        Reference = "reference" => "Eq. 5: distance to the longest vertical section",
        /// [`ProfileMethod::Polynomial`]; its parameter is the degree.
        Polynomial = "polynomial" => "Eq. 6: a polynomial r(z) per skin",
        /// [`ProfileMethod::Spline`]; its parameter is the knot spacing, mm.
        Spline = "spline" => "Eq. 6 as a cubic spline r(z) per skin",
    }
}

impl Default for ProfileMethod {
    /// The spline with knots 1.5 mm apart: fine enough for a lip's rounding and a
    /// carination, so that what is left at the vessel's axis is the scan's noise and the
    /// vessel's irregularity, not the profile model's stiffness. A stiffer profile (a
    /// polynomial, knots farther apart) leaves lips and carinations misfitted, and the
    /// tilt that best spreads that misfit lies degrees off (figures in
    /// `docs/calibration.md`).
    fn default() -> Self {
        ProfileMethod::Spline { knot_spacing_mm: 1.5 }
    }
}

impl ProfileMethod {
    /// The method if its parameter is in range (Eq. 5: 2 to 1000 vertical sections; Eq. 6:
    /// a degree of 1 to 20, knots 0.1 to 1000 mm apart), else why not.
    pub fn validated(self) -> crate::Result<Self> {
        let problem = match self {
            ProfileMethod::ReferenceProfile { vertical_sections } if !(2..=1000).contains(&vertical_sections) => {
                format!("the reference profile's vertical sections must be 2 to 1000, got {vertical_sections}")
            }
            ProfileMethod::Polynomial { degree } if !(1..=20).contains(&degree) => {
                format!("the profile polynomial's degree must be 1 to 20, got {degree}")
            }
            ProfileMethod::Spline { knot_spacing_mm } if !(0.1..=1000.0).contains(&knot_spacing_mm) => {
                format!("the profile spline's knot spacing must be 0.1 to 1000 mm, got {knot_spacing_mm}")
            }
            _ => return Ok(self),
        };
        Err(crate::Error::InvalidArgument(problem))
    }
}

/// A least-squares uniform cubic spline profile `r = f(z)`, lightly smoothed (second
/// differences of the coefficients) so that knot spans without points stay defined.
#[derive(Clone, Debug)]
pub struct SplineProfile {
    coefficients: Vec<f64>,
    low_mm: f64,
    spacing_mm: f64,
    spans: usize,
}

/// Weight of the second-difference penalty relative to the points' weight per span.
const SPLINE_SMOOTHING: f64 = 1e-3;

impl SplineProfile {
    /// The span of `z_mm` and the four basis values and derivatives (per mm) there.
    fn basis(&self, z_mm: f64) -> (usize, [f64; 4], [f64; 4]) {
        let t = ((z_mm - self.low_mm) / self.spacing_mm).clamp(0.0, self.spans as f64);
        let span = (t.floor() as usize).min(self.spans - 1);
        let u = t - span as f64;
        let values = [
            (1.0 - u).powi(3) / 6.0,
            (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0,
            (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
            u * u * u / 6.0,
        ];
        let slopes = [
            -(1.0 - u).powi(2) / 2.0,
            (9.0 * u * u - 12.0 * u) / 6.0,
            (-9.0 * u * u + 6.0 * u + 3.0) / 6.0,
            u * u / 2.0,
        ]
        .map(|d| d / self.spacing_mm);
        (span, values, slopes)
    }

    /// Fits `r = f(z)` to `(r, z)` points with knots about `knot_spacing_mm` apart.
    pub fn fit(points: &[[f64; 2]], knot_spacing_mm: f64) -> Option<Self> {
        let low = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let high = points.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        Self::fit_over(points, [low, high], knot_spacing_mm)
    }

    /// [`SplineProfile::fit`] with the knots spread over the heights `range_mm` rather than
    /// over the points' own: knots that stay put while the points move (a least-squares
    /// search over the axis) keep the fit's residuals smooth in the axis. Points outside
    /// the range take the end spans' polynomials.
    pub fn fit_over(points: &[[f64; 2]], range_mm: [f64; 2], knot_spacing_mm: f64) -> Option<Self> {
        let [low, high] = range_mm;
        if points.len() < 8 || !(knot_spacing_mm > 0.0) || !(high >= low) {
            return None;
        }
        let spans = (((high - low) / knot_spacing_mm).round() as usize).clamp(1, 40).min(points.len() / 8).max(1);
        let mut profile =
            SplineProfile { coefficients: vec![0.0; spans + 3], low_mm: low, spacing_mm: ((high - low) / spans as f64).max(1e-9), spans };
        let size = spans + 3;
        let mut normal = DMatrix::<f64>::zeros(size, size);
        let mut right = DVector::<f64>::zeros(size);
        for p in points {
            let (span, values, _) = profile.basis(p[1]);
            for i in 0..4 {
                right[span + i] += values[i] * p[0];
                for j in 0..4 {
                    normal[(span + i, span + j)] += values[i] * values[j];
                }
            }
        }
        let penalty = SPLINE_SMOOTHING * points.len() as f64 / spans as f64;
        for k in 1..size - 1 {
            let row = [(k - 1, 1.0), (k, -2.0), (k + 1, 1.0)];
            for &(a, wa) in &row {
                for &(b, wb) in &row {
                    normal[(a, b)] += penalty * wa * wb;
                }
            }
        }
        let coefficients = normal.cholesky()?.solve(&right);
        profile.coefficients = coefficients.iter().copied().collect();
        Some(profile)
    }

    /// The profile radius and its slope `dr/dz` at height `z_mm`.
    pub fn radius_and_slope_at(&self, z_mm: f64) -> (f64, f64) {
        let (span, values, slopes) = self.basis(z_mm);
        let c = &self.coefficients[span..span + 4];
        (
            values.iter().zip(c).map(|(v, c)| v * c).sum(),
            slopes.iter().zip(c).map(|(d, c)| d * c).sum(),
        )
    }
}

/// Values of the Legendre polynomials `P_0..=P_degree` at `t` in [-1, 1].
fn legendre(t: f64, degree: usize, out: &mut Vec<f64>) {
    out.clear();
    out.push(1.0);
    if degree >= 1 {
        out.push(t);
    }
    for n in 2..=degree {
        let n_f = n as f64;
        let next = ((2.0 * n_f - 1.0) * t * out[n - 1] - (n_f - 1.0) * out[n - 2]) / n_f;
        out.push(next);
    }
}

/// The least-squares polynomial profile of `(r, z)` points: coefficients, and the
/// height range `[low, high]` scaled to [-1, 1].
#[derive(Clone, Debug)]
pub struct PolynomialProfile {
    coefficients: Vec<f64>,
    low_mm: f64,
    high_mm: f64,
}

impl PolynomialProfile {
    /// Fits `r = f(z)` of `degree` (lowered when there are too few points).
    pub fn fit(points: &[[f64; 2]], degree: usize) -> Option<Self> {
        if points.len() < 3 {
            return None;
        }
        let low = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
        let high = points.iter().map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        let degree = degree.min(points.len() / 3).min(20);
        let size = degree + 1;
        let mut normal = DMatrix::<f64>::zeros(size, size);
        let mut right = DVector::<f64>::zeros(size);
        let mut basis = Vec::with_capacity(size);
        let span = (high - low).max(1e-9);
        for p in points {
            legendre(2.0 * (p[1] - low) / span - 1.0, degree, &mut basis);
            for i in 0..size {
                right[i] += basis[i] * p[0];
                for j in 0..=i {
                    normal[(i, j)] += basis[i] * basis[j];
                }
            }
        }
        for i in 0..size {
            for j in 0..i {
                normal[(j, i)] = normal[(i, j)];
            }
        }
        let coefficients = normal.cholesky()?.solve(&right);
        Some(PolynomialProfile { coefficients: coefficients.iter().copied().collect(), low_mm: low, high_mm: high })
    }

    /// The profile radius at height `z_mm`.
    pub fn radius_at(&self, z_mm: f64) -> f64 {
        let mut basis = Vec::with_capacity(self.coefficients.len());
        let span = (self.high_mm - self.low_mm).max(1e-9);
        legendre(2.0 * (z_mm - self.low_mm) / span - 1.0, self.coefficients.len() - 1, &mut basis);
        basis.iter().zip(&self.coefficients).map(|(b, c)| b * c).sum()
    }
}

/// Eq. 5 or 6 on a prepared fragment.
pub struct ProfileObjective<'a> {
    /// The fragment.
    pub surface: &'a PreparedSurface,
    /// Which form.
    pub method: ProfileMethod,
}

/// The `(r, z)` of the skin points in the candidate frame, per skin.
fn profile_points(surface: &PreparedSurface, frame: &CandidateFrame) -> [Vec<(Point, [f64; 2])>; 2] {
    let mut by_skin: [Vec<(Point, [f64; 2])>; 2] = [Vec::new(), Vec::new()];
    for (p, skin) in surface.skin_points_in(frame) {
        let index = if skin == Skin::Inner { 0 } else { 1 };
        by_skin[index].push((p, [planar_length(p.x, p.y), p.z]));
    }
    by_skin
}

/// Squared distance from `q` to the nearest of `reference` (sorted by height).
fn nearest_squared(reference: &[[f64; 2]], q: [f64; 2]) -> f64 {
    let start = reference.partition_point(|p| p[1] < q[1]);
    let mut best = f64::INFINITY;
    for p in reference[start..].iter() {
        let dz = p[1] - q[1];
        if dz * dz >= best {
            break;
        }
        best = best.min(dz * dz + (p[0] - q[0]).powi(2));
    }
    for p in reference[..start].iter().rev() {
        let dz = q[1] - p[1];
        if dz * dz >= best {
            break;
        }
        best = best.min(dz * dz + (p[0] - q[0]).powi(2));
    }
    best
}

impl Objective for ProfileObjective<'_> {
    fn value(&self, parameters: &AxisParameters) -> f64 {
        let frame = CandidateFrame::new(parameters);
        let mut total = 0.0;
        let mut count = 0usize;
        for skin_points in profile_points(self.surface, &frame) {
            if skin_points.len() < 10 {
                continue;
            }
            match self.method {
                ProfileMethod::Polynomial { degree } => {
                    let rz: Vec<[f64; 2]> = skin_points.iter().map(|s| s.1).collect();
                    let Some(profile) = PolynomialProfile::fit(&rz, degree) else { continue };
                    total += rz.iter().map(|p| (p[0] - profile.radius_at(p[1])).powi(2)).sum::<f64>();
                    count += rz.len();
                }
                ProfileMethod::Spline { knot_spacing_mm } => {
                    let rz: Vec<[f64; 2]> = skin_points.iter().map(|s| s.1).collect();
                    let Some(profile) = SplineProfile::fit(&rz, knot_spacing_mm) else { continue };
                    total += rz
                        .iter()
                        .map(|p| {
                            let (radius, slope) = profile.radius_and_slope_at(p[1]);
                            (p[0] - radius).powi(2) / (1.0 + slope * slope)
                        })
                        .sum::<f64>();
                    count += rz.len();
                }
                ProfileMethod::ReferenceProfile { vertical_sections: sections } => {
                    let positions: Vec<Point> = skin_points.iter().map(|s| s.0).collect();
                    let bins = vertical_sections(&positions, sections.max(2));
                    let extent = |bin: &Vec<usize>| {
                        let zs = bin.iter().map(|&i| skin_points[i].1[1]);
                        zs.clone().fold(f64::NEG_INFINITY, f64::max) - zs.fold(f64::INFINITY, f64::min)
                    };
                    let Some(reference_bin) = bins.iter().filter(|b| b.len() >= 3).max_by(|a, b| extent(a).total_cmp(&extent(b)))
                    else {
                        continue;
                    };
                    let mut reference: Vec<[f64; 2]> = reference_bin.iter().map(|&i| skin_points[i].1).collect();
                    reference.sort_by(|a, b| a[1].total_cmp(&b[1]));
                    let mut in_reference = vec![false; skin_points.len()];
                    for &i in reference_bin {
                        in_reference[i] = true;
                    }
                    for (i, s) in skin_points.iter().enumerate() {
                        if !in_reference[i] {
                            total += nearest_squared(&reference, s.1);
                            count += 1;
                        }
                    }
                }
            }
        }
        if count == 0 { f64::INFINITY } else { total / count as f64 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polynomial_profile_reproduces_a_cubic() {
        let points: Vec<[f64; 2]> =
            (0..50).map(|i| i as f64 * 2.0).map(|z| [60.0 + 0.3 * z - 0.004 * z * z + 2e-5 * z * z * z, z]).collect();
        let profile = PolynomialProfile::fit(&points, 4).unwrap();
        for p in &points {
            assert!((profile.radius_at(p[1]) - p[0]).abs() < 1e-8);
        }
    }

    #[test]
    fn spline_profile_follows_a_lip_a_polynomial_cannot() {
        // A wall that turns out sharply into a lip over the top 8 mm of 60.
        let lip = |z: f64| 80.0 + 0.1 * z + if z > 52.0 { 0.4 * (z - 52.0).powi(2) } else { 0.0 };
        let points: Vec<[f64; 2]> = (0..600).map(|i| i as f64 * 0.1).map(|z| [lip(z), z]).collect();
        let spline = SplineProfile::fit(&points, 4.0).unwrap();
        let polynomial = PolynomialProfile::fit(&points, 6).unwrap();
        let rms = |f: &dyn Fn(f64) -> f64| (points.iter().map(|p| (p[0] - f(p[1])).powi(2)).sum::<f64>() / points.len() as f64).sqrt();
        let spline_rms = rms(&|z| spline.radius_and_slope_at(z).0);
        let polynomial_rms = rms(&|z| polynomial.radius_at(z));
        assert!(spline_rms < 0.1 && spline_rms < polynomial_rms / 4.0, "spline {spline_rms} vs polynomial {polynomial_rms}");
        let (_, slope) = spline.radius_and_slope_at(20.0);
        assert!((slope - 0.1).abs() < 0.01, "slope {slope}");
    }

    #[test]
    fn nearest_point_search_matches_brute_force() {
        let reference: Vec<[f64; 2]> = (0..40).map(|i| [50.0 + (i as f64 * 0.3).sin(), i as f64 * 0.7]).collect();
        for q in [[49.0, 3.3], [55.0, -2.0], [50.5, 40.0], [51.0, 14.1]] {
            let brute = reference.iter().map(|p| (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)).fold(f64::INFINITY, f64::min);
            assert!((nearest_squared(&reference, q) - brute).abs() < 1e-12);
        }
    }
}
