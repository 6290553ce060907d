//! How well the refinement corpus's own surfaces fix their axes: the floor under issue 4's
//! accuracy goals.
//!
//! Each fragment of the corpus of `refine_accuracy` (10 vessels of 34 fragments, the same
//! seeds, deformation and scan noise) is fitted to its vessel's true, undeformed profiles:
//! the axis (two tilts, three shifts) that brings the skin vertices closest, in least
//! squares, to the outer and inner profile curves the generator revolved. No method that
//! must also find the profile can expect to do better than this one, which is given it:
//! what separates its axis from the true one is what the vessel's ovality, rim tilt and
//! wobble (and the noise) make of a fragment's surface.
//!
//! `DEFORMATION_FLOOR_KNOTS_MM=K` takes the profiles away: they are fitted at every
//! candidate frame as cubic splines `r = f(z)` with knots `K` mm apart (the profile
//! criterion's model, Eq. 6), the fit still started at the true axis and solved to its
//! least-squares minimum; what it loses against the given profiles is the price of not
//! knowing them.
//!
//! `DEFORMATION_FLOOR_NORMALS=1` fits the normal lines instead (Eq. 1: each skin vertex's
//! normal line should meet the axis), from the true axis too.
//!
//! Run: `cargo run --release --example deformation_floor [VESSELS]`; the environment
//! variables `REFINE_ACCURACY_DEFORMATION`, `REFINE_ACCURACY_NOISE_MM` and `REFINE_ACCURACY_CELL_MM` set the
//! corpus as for `refine_accuracy` (the cells here 2 mm by default, as in the figures of
//! BENCHMARKS.md, "Refinement: accuracy on the synthetic corpus"). Prints, per part and for all, the share within 4 mm
//! mean point distance, the share within 0.3 degrees (the median goal needs half),
//! the median and 90th percentile angle error.

#[path = "../tests/support/evaluation.rs"]
mod evaluation;

use nalgebra::{DMatrix, DVector, Rotation3, Vector3};
use rayon::prelude::*;
use sherd::mesh::{segment_distance, Point};
use evaluation::refinement_corpus;
use sherd::orient::{mean_point_distance_mm, Axis};
use sherd::refine::superposition::SplineProfile;
use sherd::statistics::nearest_rank_quantile;
use sherd::synth::truth::SurfaceKind;
use sherd::synth::SynthSherd;

/// A number from the environment variable `name`, or `default`.
fn env_number(name: &str, default: f64) -> f64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// Distance from `q` to the polyline `curve`, searching from segment `hint` outwards while
/// the distance falls (the fitted frames move points by a fraction of a millimetre, so
/// the nearest segment is next to the last one). Returns the distance and the segment.
fn distance_to_curve(curve: &[[f64; 2]], q: [f64; 2], hint: usize) -> (f64, usize) {
    let segment = |i: usize| segment_distance(q, curve[i], curve[i + 1]);
    let last = curve.len() - 2;
    let mut best = (segment(hint.min(last)), hint.min(last));
    for step in [-1isize, 1] {
        let mut i = best.1 as isize;
        loop {
            i += step;
            if i < 0 || i as usize > last {
                break;
            }
            let d = segment(i as usize);
            // Walk on through a few worse segments: a polyline's distance is not unimodal
            // along it at a sharp turn (the lip).
            if d < best.0 {
                best = (d, i as usize);
            } else if (i - best.1 as isize).abs() > 8 {
                break;
            }
        }
    }
    best
}

/// The nearest segment of `curve` to `q` over the whole curve.
fn nearest_segment(curve: &[[f64; 2]], q: [f64; 2]) -> usize {
    (0..curve.len() - 1)
        .map(|i| (segment_distance(q, curve[i], curve[i + 1]), i))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or(0, |(_, i)| i)
}

/// A fragment's skin vertices in the vessel frame with the profile each belongs on.
struct KnownProfileFit<'a> {
    points: Vec<Vector3<f64>>,
    /// Unit vertex normals (vessel frame), for the normal-line fit.
    normals: Vec<Vector3<f64>>,
    on_outer: Vec<bool>,
    outer: &'a [[f64; 2]],
    inner: &'a [[f64; 2]],
    centroid: Vector3<f64>,
    /// `Some(knot spacing)`: the profiles are not given but fitted, at every frame, as
    /// cubic splines `r = f(z)` with knots this far apart (what a refinement can do).
    unknown_profile_knots_mm: Option<f64>,
    /// Height range of the fitted splines' knots (fixed, so that the cost is smooth).
    knot_range_mm: [f64; 2],
    /// Fit the normal lines instead of the profiles.
    normal_lines: bool,
}

impl KnownProfileFit<'_> {
    /// The frame of parameters `[tilt_x, tilt_y, shift_x, shift_y, shift_z]`: the points
    /// turned about their centroid and shifted.
    fn moved(&self, parameters: &[f64]) -> impl Iterator<Item = Vector3<f64>> + '_ {
        let rotation = Rotation3::from_euler_angles(parameters[0], parameters[1], 0.0);
        let shift = Vector3::new(parameters[2], parameters[3], parameters[4]);
        self.points.iter().map(move |p| rotation * (p - self.centroid) + self.centroid + shift)
    }

    /// Each vertex's distance to its profile in the frame of `parameters`.
    fn residuals(&self, parameters: &[f64], hints: &mut [usize]) -> DVector<f64> {
        if self.normal_lines {
            return self.normal_line_residuals(parameters);
        }
        if let Some(spacing) = self.unknown_profile_knots_mm {
            return self.spline_residuals(parameters, spacing);
        }
        let values: Vec<f64> = self
            .moved(parameters)
            .zip(&self.on_outer)
            .zip(hints.iter_mut())
            .map(|((p, &outer), hint)| {
                let curve = if outer { self.outer } else { self.inner };
                let (d, segment) = distance_to_curve(curve, [p.x.hypot(p.y), p.z], *hint);
                *hint = segment;
                d
            })
            .collect();
        DVector::from_vec(values)
    }

    /// Each vertex's normal line's distance to the axis (Eq. 1) in the frame of `parameters`.
    fn normal_line_residuals(&self, parameters: &[f64]) -> DVector<f64> {
        let rotation = Rotation3::from_euler_angles(parameters[0], parameters[1], 0.0);
        let values = self.moved(parameters).zip(&self.normals).map(|(p, n)| {
            let across = (rotation * n).cross(&Vector3::z());
            p.dot(&across) / across.norm().max(1e-9)
        });
        DVector::from_iterator(self.points.len(), values)
    }

    /// Residuals across the least-squares spline profile of each skin (the profile
    /// criterion's model, its knots held over the fragment's heights).
    fn spline_residuals(&self, parameters: &[f64], spacing_mm: f64) -> DVector<f64> {
        let moved: Vec<[f64; 2]> = self.moved(parameters).map(|p| [p.x.hypot(p.y), p.z]).collect();
        let mut residuals = DVector::<f64>::zeros(moved.len());
        for outer in [true, false] {
            let chosen: Vec<usize> = (0..moved.len()).filter(|&i| self.on_outer[i] == outer).collect();
            let points: Vec<[f64; 2]> = chosen.iter().map(|&i| moved[i]).collect();
            let Some(profile) = SplineProfile::fit_over(&points, self.knot_range_mm, spacing_mm) else { continue };
            for &i in &chosen {
                let (radius, slope) = profile.radius_and_slope_at(moved[i][1]);
                residuals[i] = (moved[i][0] - radius) / (1.0 + slope * slope).sqrt();
            }
        }
        residuals
    }

    /// Gauss-Newton with a Levenberg damping, from the true frame (all zeros).
    fn fit(&self) -> [f64; 5] {
        let mut hints: Vec<usize> = if self.unknown_profile_knots_mm.is_some() {
            vec![0; self.points.len()]
        } else {
            self.moved(&[0.0; 5])
            .zip(&self.on_outer)
            .map(|(p, &outer)| nearest_segment(if outer { self.outer } else { self.inner }, [p.x.hypot(p.y), p.z]))
            .collect()
        };
        // With the profile fitted, a shift along the axis changes nothing.
        let free = if self.unknown_profile_knots_mm.is_some() { 4 } else { 5 };
        let mut parameters = [0.0; 5];
        let mut residual = self.residuals(&parameters, &mut hints);
        let mut damping = 1e-3;
        // Steps: 1e-5 rad of tilt and 1e-3 mm of shift are far below the answers' sizes
        // and far above the distances' rounding.
        let steps = [1e-5, 1e-5, 1e-3, 1e-3, 1e-3];
        for _ in 0..60 {
            let mut jacobian = DMatrix::<f64>::zeros(residual.len(), free);
            for k in 0..free {
                let mut probe = parameters;
                probe[k] += steps[k];
                let moved = self.residuals(&probe, &mut hints.clone());
                jacobian.set_column(k, &((moved - &residual) / steps[k]));
            }
            let normal = jacobian.transpose() * &jacobian;
            let gradient = jacobian.transpose() * &residual;
            let mut improved = false;
            for _ in 0..12 {
                let damped = &normal + DMatrix::from_diagonal(&normal.diagonal().map(|d| d * damping + 1e-12));
                let Some(step) = damped.lu().solve(&(-&gradient)) else { break };
                let mut trial = parameters;
                for k in 0..free {
                    trial[k] += step[k];
                }
                let mut trial_hints = hints.clone();
                let trial_residual = self.residuals(&trial, &mut trial_hints);
                if trial_residual.norm_squared() < residual.norm_squared() {
                    let gain = residual.norm_squared() - trial_residual.norm_squared();
                    (parameters, residual, hints) = (trial, trial_residual, trial_hints);
                    damping = (damping / 3.0).max(1e-9);
                    improved = gain > 1e-12 * residual.len() as f64;
                    break;
                }
                damping *= 10.0;
            }
            if !improved {
                break;
            }
        }
        parameters
    }

    /// The axis of the fitted frame, back in the vessel frame.
    fn axis_of(&self, parameters: &[f64; 5]) -> (Vector3<f64>, Vector3<f64>) {
        // The moved frame's axis is its z axis; a moved point m came from
        // R^T (m - c - s) + c.
        let rotation = Rotation3::from_euler_angles(parameters[0], parameters[1], 0.0);
        let shift = Vector3::new(parameters[2], parameters[3], parameters[4]);
        let back = |m: Vector3<f64>| rotation.inverse() * (m - self.centroid - shift) + self.centroid;
        let point = back(Vector3::zeros());
        let direction = back(Vector3::z()) - point;
        (point, direction)
    }
}

/// The axis fitted to the true profiles, in the scan frame, or `None` without skins.
fn fitted_axis(sherd: &SynthSherd) -> Option<Axis> {
    let to_vessel = sherd.truth.motion.isometry().inverse();
    let normal_lines = std::env::var_os("DEFORMATION_FLOOR_NORMALS").is_some();
    let (mut points, mut normals, mut on_outer) = (Vec::new(), Vec::new(), Vec::new());
    let mesh_normals = sherd.mesh.normals.as_ref()?;
    for ((p, kind), n) in sherd.mesh.positions.iter().zip(&sherd.vertex_kinds).zip(mesh_normals) {
        let outer = match kind {
            SurfaceKind::Outer => true,
            SurfaceKind::Inner => false,
            _ => continue,
        };
        let (point, normal) = ((to_vessel * p).coords, (to_vessel.rotation * n).normalize());
        // For the normal lines, the truth drops the vertices on a break's border (their
        // normals average the skin's and the break's: more than 5 degrees off the meridian
        // plane) and those whose normal line runs along the axis (a floor, a lip's top).
        let off_meridian = (point.x * normal.y - point.y * normal.x).abs() > 0.09 * point.x.hypot(point.y);
        if normal_lines && (off_meridian || normal.z.abs() > 0.95) {
            continue;
        }
        points.push(point);
        normals.push(normal);
        on_outer.push(outer);
    }
    if points.len() < 10 || sherd.truth.profile.len() < 2 || sherd.truth.inner_profile.len() < 2 {
        return None;
    }
    let centroid = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
    let low = points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min) - 2.0;
    let high = points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max) + 2.0;
    let fit = KnownProfileFit {
        points,
        normals,
        on_outer,
        outer: &sherd.truth.profile,
        inner: &sherd.truth.inner_profile,
        centroid,
        unknown_profile_knots_mm: std::env::var("DEFORMATION_FLOOR_KNOTS_MM").ok().and_then(|v| v.parse().ok()),
        knot_range_mm: [low, high],
        normal_lines,
    };
    let (point, direction) = fit.axis_of(&fit.fit());
    let to_scan = sherd.truth.motion.isometry();
    Some(Axis::new(to_scan * Point::from(point), to_scan * direction))
}

fn main() {
    let vessels: u64 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10);
    let sherds = refinement_corpus(
        vessels,
        env_number("REFINE_ACCURACY_DEFORMATION", 1.0),
        env_number("REFINE_ACCURACY_NOISE_MM", 0.02),
        env_number("REFINE_ACCURACY_CELL_MM", 2.0),
    );
    let outcomes: Vec<(String, f64, f64)> = sherds
        .par_iter()
        .filter_map(|(_, sherd)| {
            let axis = fitted_axis(sherd)?;
            let truth = &sherd.truth.axis;
            Some((
                format!("{:?}", sherd.truth.part),
                axis.line_angle_to_deg(truth),
                mean_point_distance_mm(&sherd.mesh.positions, &axis, truth),
            ))
        })
        .collect();
    println!("| part | fragments | within 4 mm | under 0.3 deg | median angle error (deg) | 90th pct angle (deg) |");
    println!("|---|---|---|---|---|---|");
    let mut parts: Vec<String> = outcomes.iter().map(|o| o.0.clone()).collect();
    parts.sort();
    parts.dedup();
    for part in std::iter::once(None).chain(parts.iter().map(Some)) {
        let chosen: Vec<&(String, f64, f64)> = outcomes.iter().filter(|o| part.is_none_or(|p| &o.0 == p)).collect();
        let mut angles: Vec<f64> = chosen.iter().map(|o| o.1).collect();
        let within = chosen.iter().filter(|o| o.2 <= 4.0).count();
        let under = chosen.iter().filter(|o| o.1 <= 0.3).count();
        let share = |count: usize| 100.0 * count as f64 / chosen.len().max(1) as f64;
        println!(
            "| {} | {} | {:.1}% | {:.1}% | {:.3} | {:.3} |",
            part.map_or("all", |p| p.as_str()),
            chosen.len(),
            share(within),
            share(under),
            nearest_rank_quantile(&mut angles, 0.5),
            nearest_rank_quantile(&mut angles, 0.9)
        );
    }
}
