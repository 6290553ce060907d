//! The level-edge cue: the two ends of the profile over the vertical sections about the
//! axis, how level each lies, and whether the level one is a rim, a base's centre or
//! neither.

use crate::axis::Axis;
use crate::mesh::{Point, Vector};
use crate::statistics::upper_median;

/// Width of a vertical section along the circumference, mm: wide enough to hold a few
/// vertices of a decimated scan along the rim, narrow enough to follow a break.
const SECTION_WIDTH_MM: f64 = 3.0;
/// An end of the profile whose position wanders less than this over the sections (once
/// a tilt of up to [`MAX_EDGE_TILT`] is allowed for) can be a rim: noise and a hand-made
/// rim's unevenness; rough breaks wander more (`docs/calibration.md`), mm.
const LEVEL_SPREAD_MM: f64 = 0.5;
/// Smallest fraction of the sections whose end lies on the level edge: a rim preserved
/// along under 40% of the piece's arc is not trusted (a stretch of break can be as level).
const MIN_LEVEL_FRACTION: f64 = 0.4;
/// Least share of the points at a level end that lie on the surface of revolution for the
/// end to be a finished edge (a lip or a foot) rather than a break.
const MIN_FINISHED_SHARE: f64 = 0.5;
/// Smallest ratio of the spreads of the two ends for the level-edge cue to speak.
const LEVEL_MIN_RATIO: f64 = 3.0;
/// Ratio of the spreads at which the level-edge cue is certain (log-linear from
/// [`LEVEL_MIN_RATIO`]).
const LEVEL_FULL_RATIO: f64 = 10.0;
/// The level end must lie at least this far above or below the other along the axis for
/// the sense to follow from it, mm.
const MIN_RISE_MM: f64 = 1.0;
/// An end of the profile nearer the axis than this fraction of the piece's largest
/// radius closes onto the axis: the centre of a base, not a rim.
const BASE_CENTRE_RADIUS_FRACTION: f64 = 0.25;

/// A point of the rz half-plane with the section's angle.
struct Cylindrical {
    radius: f64,
    height: f64,
    angle: f64,
}

fn cylindrical(points: &[Point], axis: &Axis) -> Vec<Cylindrical> {
    let d = axis.direction.into_inner();
    let centroid = points.iter().fold(Vector::zeros(), |sum, p| sum + p.coords) / points.len().max(1) as f64;
    let to_centroid = centroid - axis.point.coords;
    let mut e1 = to_centroid - d * to_centroid.dot(&d);
    if e1.norm() < 1e-9 {
        e1 = if d.x.abs() < 0.9 { Vector::x() } else { Vector::y() };
        e1 -= d * e1.dot(&d);
    }
    let e1 = e1.normalize();
    let e2 = d.cross(&e1);
    points
        .iter()
        .map(|p| {
            let q = p - axis.point;
            let height = q.dot(&d);
            let (x, y) = (q.dot(&e1), q.dot(&e2));
            Cylindrical { radius: x.hypot(y), height, angle: y.atan2(x) }
        })
        .collect()
}

/// Where the two ends of the profile lie and how much they wander from one vertical
/// section to the next.
#[derive(Clone, Debug)]
pub struct ProfileEnds {
    /// Robust spread (median absolute deviation) of the upper end's position along the
    /// profile over the sections, mm.
    pub upper_spread_mm: f64,
    /// The same for the lower end.
    pub lower_spread_mm: f64,
    /// Largest fraction of the sections whose upper end lies on one level edge.
    pub upper_level_fraction: f64,
    /// The same for the lower end.
    pub lower_level_fraction: f64,
    /// Share of the points near the upper end (within a few spacings of each section's
    /// end) that lie on the surface of revolution: high at a lip, low at a break; NaN when
    /// not measured.
    pub upper_finished_share: f64,
    /// The same for the lower end.
    pub lower_finished_share: f64,
    /// Median `(radius, height)` of the upper end, mm.
    pub upper: [f64; 2],
    /// Median `(radius, height)` of the lower end, mm.
    pub lower: [f64; 2],
    /// Largest radius of the piece, mm.
    pub max_radius_mm: f64,
    /// Typical distance between neighbouring points, mm.
    pub point_spacing_mm: f64,
    /// Sections that held enough points.
    pub section_count: usize,
}

/// The ends of the profile of `points` about `axis`: each vertical section's points
/// are projected on the main direction of the profile in the rz half-plane, and the
/// extreme projections of each section are its ends. `None` with too few points or
/// sections to judge.
pub fn profile_ends(points: &[Point], axis: &Axis) -> Option<ProfileEnds> {
    profile_ends_finished(points, None, axis)
}

/// [`profile_ends`], with the share of each end's points that lie on the surface of
/// revolution (`finished[i]` for `points[i]`) where that is given.
pub fn profile_ends_finished(points: &[Point], finished: Option<&[bool]>, axis: &Axis) -> Option<ProfileEnds> {
    if points.len() < 30 {
        return None;
    }
    let samples = cylindrical(points, axis);
    let n = samples.len() as f64;
    let (mean_r, mean_h) =
        samples.iter().fold((0.0, 0.0), |(r, h), s| (r + s.radius / n, h + s.height / n));
    let (mut srr, mut srh, mut shh) = (0.0, 0.0, 0.0);
    for s in &samples {
        let (dr, dh) = (s.radius - mean_r, s.height - mean_h);
        srr += dr * dr;
        srh += dr * dh;
        shh += dh * dh;
    }
    // Main direction of the 2x2 scatter, pointing up the axis.
    let angle = 0.5 * (2.0 * srh).atan2(srr - shh);
    let (mut ur, mut uh) = (angle.cos(), angle.sin());
    if uh < 0.0 || (uh == 0.0 && ur < 0.0) {
        ur = -ur;
        uh = -uh;
    }
    let (low, high) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| (lo.min(s.angle), hi.max(s.angle)));
    let mut radii: Vec<f64> = samples.iter().map(|s| s.radius).collect();
    radii.sort_unstable_by(f64::total_cmp);
    let median_radius = radii[radii.len() / 2];
    let max_radius_mm = radii[radii.len() - 1];
    let span = (high - low).max(1e-9);
    // The typical distance between neighbouring points: both skins over the piece's arc
    // and profile length share the points. A section narrower than a few of them may
    // hold no point of the rim and take a point of the skin below for its end.
    let (along_low, along_high) = samples.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
        let along = (s.radius - mean_r) * ur + (s.height - mean_h) * uh;
        (lo.min(along), hi.max(along))
    });
    let point_spacing_mm = (2.0 * span * median_radius * (along_high - along_low) / n).sqrt();
    let section_width_mm = SECTION_WIDTH_MM * coarseness(point_spacing_mm);
    let sections = ((span * median_radius / section_width_mm).round() as usize).clamp(6, 120);
    let mut upper: Vec<Option<(f64, [f64; 2])>> = vec![None; sections];
    let mut lower: Vec<Option<(f64, [f64; 2])>> = vec![None; sections];
    let mut counts = vec![0usize; sections];
    for s in &samples {
        let k = (((s.angle - low) / span * sections as f64) as usize).min(sections - 1);
        let along = (s.radius - mean_r) * ur + (s.height - mean_h) * uh;
        let at = [s.radius, s.height];
        counts[k] += 1;
        if upper[k].is_none_or(|(v, _)| along > v) {
            upper[k] = Some((along, at));
        }
        if lower[k].is_none_or(|(v, _)| along < v) {
            lower[k] = Some((along, at));
        }
    }
    let full: Vec<usize> = (0..sections).filter(|&k| counts[k] >= 4).collect();
    if full.len() < 4 {
        return None;
    }
    // The points within a few spacings of each section's ends: a lip's are on the surface
    // of revolution (it is turned like the skins), a break's are not (rough, slanted).
    let depth = END_DEPTH_SPACINGS * point_spacing_mm.max(0.1);
    let (mut upper_finished, mut lower_finished) = ([0usize; 2], [0usize; 2]);
    if let Some(finished) = finished {
        for (i, s) in samples.iter().enumerate() {
            let k = (((s.angle - low) / span * sections as f64) as usize).min(sections - 1);
            if counts[k] < 4 {
                continue;
            }
            let along = (s.radius - mean_r) * ur + (s.height - mean_h) * uh;
            if upper[k].is_some_and(|(v, _)| along >= v - depth) {
                upper_finished[1] += 1;
                upper_finished[0] += finished[i] as usize;
            }
            if lower[k].is_some_and(|(v, _)| along <= v + depth) {
                lower_finished[1] += 1;
                lower_finished[0] += finished[i] as usize;
            }
        }
    }
    let share = |[on, all]: [usize; 2]| if all == 0 { f64::NAN } else { on as f64 / all as f64 };
    // A tilt of the axis by a small angle (t1, t2) about the two horizontal directions
    // moves a rim's end along the profile by `radius (t1 cos angle + t2 sin angle)`.
    let lever: Vec<[f64; 2]> = full
        .iter()
        .map(|&k| {
            let angle = low + (k as f64 + 0.5) / sections as f64 * span;
            [median_radius * angle.cos(), median_radius * angle.sin()]
        })
        .collect();
    let end = |ends: &[Option<(f64, [f64; 2])>], outward: f64| {
        let values: Vec<f64> = full.iter().map(|&k| outward * ends[k].expect("counted").0).collect();
        let radii: Vec<f64> = full.iter().map(|&k| ends[k].expect("counted").1[0]).collect();
        let heights: Vec<f64> = full.iter().map(|&k| ends[k].expect("counted").1[1]).collect();
        let (spread, fraction) = level_measures(&values, &lever, level_band_mm(point_spacing_mm));
        (spread, fraction, [upper_median(&radii), upper_median(&heights)])
    };
    let (upper_spread_mm, upper_level_fraction, upper) = end(&upper, 1.0);
    let (lower_spread_mm, lower_level_fraction, lower) = end(&lower, -1.0);
    Some(ProfileEnds {
        upper_spread_mm,
        lower_spread_mm,
        upper_level_fraction,
        lower_level_fraction,
        upper_finished_share: share(upper_finished),
        lower_finished_share: share(lower_finished),
        upper,
        lower,
        max_radius_mm,
        point_spacing_mm,
        section_count: full.len(),
    })
}

/// How deep below each section's end the points of the end reach, in point spacings.
const END_DEPTH_SPACINGS: f64 = 2.0;

/// Steepest tilt of a level edge allowed for the error of the axis and a hand-made
/// rim's slant (tangent of about 3 degrees).
const MAX_EDGE_TILT: f64 = 0.05;
/// A run of level sections goes on across this many consecutive sections out of the
/// band: a rough lip's end leaves the band in single sections (a spike of roughness, a
/// hole of the scan), which cut its arc into short runs that no longer tell it from a
/// break.
const MAX_RUN_GAP_SECTIONS: usize = 1;
/// Band below the outermost end within which a section's end counts as on the level
/// edge, mm, for points spaced under a millimetre (a decimated scan of an ordinary sherd).
const LEVEL_BAND_MM: f64 = 0.3;

/// The level band for points `spacing_mm` apart: much coarser points sample a rounded
/// rim's crest less closely, so the band widens with them (and so do the other
/// millimetre limits of the cue, by the same factor).
fn level_band_mm(spacing_mm: f64) -> f64 {
    LEVEL_BAND_MM * coarseness(spacing_mm)
}

/// How much coarser than usual the points are: 1 up to 3 mm apart (decimated scans and
/// the synthetic corpus, where wider sections and bands were measured to take breaks
/// for rims), then in proportion (a scan in centimetres read as millimetres).
fn coarseness(spacing_mm: f64) -> f64 {
    (spacing_mm / 3.0).max(1.0)
}

/// How level one end is: the smallest median absolute deviation of the sections' ends
/// (`values`, outward positive, in order round the axis) and the largest fraction of
/// sections in one run whose ends lie in the band `band_mm` wide that holds the most of
/// them, over the tilts up to [`MAX_EDGE_TILT`]
/// about either horizontal direction (`lever`: what a unit tilt about each moves a
/// section's end by).
fn level_measures(values: &[f64], lever: &[[f64; 2]], band_mm: f64) -> (f64, f64) {
    let steps = 8;
    let mut best_spread = f64::INFINITY;
    let mut best_fraction: f64 = 0.0;
    let mut detilted = vec![0.0; values.len()];
    for step1 in -steps..=steps {
        for step2 in -steps..=steps {
            let tilt = [step1, step2].map(|step| MAX_EDGE_TILT * step as f64 / steps as f64);
            for ((out, v), l) in detilted.iter_mut().zip(values).zip(lever) {
                *out = v - tilt[0] * l[0] - tilt[1] * l[1];
            }
            let centre = upper_median(&detilted);
            let deviations: Vec<f64> = detilted.iter().map(|v| (v - centre).abs()).collect();
            best_spread = best_spread.min(upper_median(&deviations));
            // The edge is the band holding the most sections' ends (the outermost ends can
            // be a corner where a break meets the lip, or a spike of the scan); a rim is
            // one arc: the longest run of neighbouring sections in that band, across
            // single sections out of it.
            let top = detilted
                .iter()
                .copied()
                .max_by(|a, b| {
                    let count = |c: f64| detilted.iter().filter(|v| **v <= c && **v >= c - band_mm).count();
                    count(*a).cmp(&count(*b)).then(a.total_cmp(b))
                })
                .expect("sections");
            let (mut run, mut gap, mut longest) = (0usize, 0usize, 0usize);
            for v in &detilted {
                if *v <= top && *v >= top - band_mm {
                    run += 1;
                    gap = 0;
                } else {
                    gap += 1;
                    if gap > MAX_RUN_GAP_SECTIONS {
                        run = 0;
                    }
                }
                longest = longest.max(run);
            }
            best_fraction = best_fraction.max(longest as f64 / values.len() as f64);
        }
    }
    (best_spread, best_fraction)
}

/// The level-edge cue from the ends of the profile: signed confidence and a description.
pub(super) fn level_edge_cue(ends: &ProfileEnds) -> (f64, String) {
    let upper_is_level = ends.upper_level_fraction >= ends.lower_level_fraction;
    let (level, other, level_fraction, other_fraction, level_end, other_end) = if upper_is_level {
        (ends.upper_spread_mm, ends.lower_spread_mm, ends.upper_level_fraction, ends.lower_level_fraction, ends.upper, ends.lower)
    } else {
        (ends.lower_spread_mm, ends.upper_spread_mm, ends.lower_level_fraction, ends.upper_level_fraction, ends.lower, ends.upper)
    };
    let (level_finished, other_finished) = if upper_is_level {
        (ends.upper_finished_share, ends.lower_finished_share)
    } else {
        (ends.lower_finished_share, ends.upper_finished_share)
    };
    // A level end made of break faces is a break that ran level (along a carination or a
    // rill), not a rim: a lip is turned like the skins.
    if level_finished < MIN_FINISHED_SHARE || level_finished < other_finished {
        return (0.0, String::new());
    }
    let rise = level_end[1] - other_end[1];
    let scale = coarseness(ends.point_spacing_mm);
    if level_fraction < MIN_LEVEL_FRACTION || rise.abs() < MIN_RISE_MM * scale {
        return (0.0, String::new());
    }
    // With the rim along most of the arc the spreads compare the two ends directly; along
    // less than half of it they measure the breaks beside the rim, and only the runs of
    // level sections compare.
    let ratio = other / level.max(1e-3);
    let strength = if level_fraction >= 0.5 {
        if level > LEVEL_SPREAD_MM * scale || ratio < LEVEL_MIN_RATIO || (other_fraction > 0.5 * level_fraction && ratio < LEVEL_FULL_RATIO) {
            return (0.0, String::new());
        }
        ((ratio.ln() - LEVEL_MIN_RATIO.ln()) / (LEVEL_FULL_RATIO.ln() - LEVEL_MIN_RATIO.ln())).clamp(0.0, 1.0)
    } else {
        (1.0 - other_fraction / (0.5 * level_fraction)).clamp(0.0, 1.0)
    };
    if strength <= 0.0 {
        return (0.0, String::new());
    }
    let figures = format!(
        "{:.0}% of the sections end on it within {:.1} mm, spread {level:.2} mm against {other:.2} mm at the other end",
        100.0 * level_fraction,
        level_band_mm(ends.point_spacing_mm)
    );
    if level_end[0] < BASE_CENTRE_RADIUS_FRACTION * ends.max_radius_mm {
        return (-rise.signum() * strength, format!("base centre: one end of the profile closes onto the axis ({figures})"));
    }
    (rise.signum() * strength, format!("level rim: one end of the profile is a circle about the axis ({figures})"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};

    /// On rim pieces in the vessel's frame, the level-edge cue points up along the true
    /// axis and down along the reversed one, or stays silent; it speaks on most of them.
    #[test]
    fn level_edge_points_to_the_rim() {
        let mut decided = 0;
        for seed in 1..=8 {
            let options = SherdOptions { random_motion: false, target_faces: 6_000, ..SherdOptions::for_part(SherdPart::Rim) };
            let sherd = synthetic_sherd(seed, &options);
            let axis = sherd.truth.axis;
            let up = level_edge_cue(&profile_ends(&sherd.mesh.positions, &axis).expect("enough points")).0;
            let down = level_edge_cue(&profile_ends(&sherd.mesh.positions, &axis.flipped()).expect("enough points")).0;
            assert!(up >= 0.0 && down <= 0.0, "seed {seed}: up {up}, down {down}");
            assert!((up + down).abs() < 1e-9, "seed {seed}: the cue depends on more than the sense: {up} {down}");
            decided += (up > 0.5) as usize;
        }
        assert!(decided >= 5, "the level edge spoke on {decided} of 8 rim pieces");
    }

    /// A body piece's two ends are breaks: the level-edge cue does not take either for a rim.
    #[test]
    fn breaks_are_not_rims() {
        for seed in 1..=6 {
            let options = SherdOptions { random_motion: false, target_faces: 6_000, ..SherdOptions::for_part(SherdPart::Body) };
            let sherd = synthetic_sherd(seed, &options);
            if sherd.truth.part != SherdPart::Body {
                continue;
            }
            let ends = profile_ends(&sherd.mesh.positions, &sherd.truth.axis).expect("enough points");
            let (cue, text) = level_edge_cue(&ends);
            assert!(cue.abs() < 0.5, "body seed {seed}: {text} ({ends:?})");
        }
    }

    /// A rim whose end leaves the level band in one section (a spike of roughness, a hole)
    /// is still one arc (the section out of it not counted); two sections out of it in a
    /// row cut it.
    #[test]
    fn a_level_run_goes_on_across_one_section_out_of_the_band() {
        let lever = vec![[0.0, 0.0]; 10];
        let mut values = vec![0.0; 10];
        values[5] = -2.0;
        assert_eq!(level_measures(&values, &lever, 0.3).1, 0.9);
        values[6] = -2.0;
        assert_eq!(level_measures(&values, &lever, 0.3).1, 0.5);
    }
}
