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

use serde::{Deserialize, Serialize};

use crate::axis::Axis;
use super::normal_lines::NormalLines;
use crate::mesh::{Point, Vector};
use crate::statistics::{upper_median, weighted_median, weighted_quantile};

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
/// (jar shoulders and necks, the upper half of globular bodies) are common. On the
/// synthetic corpus the opening decided wrongly on a sixth of the pieces it decided
/// alone, all from jars, all with `|dr/dz|` under 0.86: with the verdict's limit of 0.55
/// only walls flaring by more than `|dr/dz|` 0.92 (43 degrees) are trusted.
pub const OPENING_MAX_CONFIDENCE: f64 = 0.6;
/// Wall slope `|dr/dz|` at which the opening cue reaches its full confidence.
const OPENING_FULL_SLOPE: f64 = 1.0;
/// Width of a vertical section along the circumference, mm: wide enough to hold a few
/// vertices of a decimated scan along the rim, narrow enough to follow a break.
const SECTION_WIDTH_MM: f64 = 3.0;
/// An end of the profile whose position wanders less than this over the sections (once
/// a tilt of up to [`MAX_EDGE_TILT`] is allowed for) can be a rim: noise and a hand-made
/// rim's unevenness; rough breaks wander more (measured on the synthetic corpus: rims
/// 0.01-0.3 mm, breaks that happened to look level 0.3-1 mm), mm.
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
fn level_edge_cue(ends: &ProfileEnds) -> (f64, String) {
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

/// Share of the surface a flat part must have to decide the sense as a floor.
const MIN_FLOOR_SHARE: f64 = 0.05;
/// Share of the surface a flat part needs to veto a level edge that says the other way.
/// A base piece whose wall rises 56 mm from a 3%-wide strip of its underside (`sherd synth
/// --seed 26 --part base`) was oriented upside down: its level foot read as a level rim.
const MIN_SMALL_FLOOR_SHARE: f64 = 0.02;
/// A floor reaches inside this fraction of the wall's median radius (a quarter of its
/// flat area does): a rim's flat top lies at the wall's radius.
const FLOOR_INNER_RADIUS_RATIO: f64 = 0.8;
/// The same for a small floor, which only vetoes: the strip of underside beside a foot
/// lies closer to the wall (that base: 0.82 of it on a 20k-face copy).
const SMALL_FLOOR_INNER_RADIUS_RATIO: f64 = 0.9;
/// Share of the surface the wall must have for a floor to rise into it, and for a level end
/// of the profile to be a rim: a piece of floor alone (no wall) has level ends, but no rim.
const MIN_WALL_SHARE: f64 = 0.05;

/// The share of the surface that is wall.
fn wall_share(samples: &[Sample]) -> f64 {
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    samples.iter().filter(|s| s.is_wall()).map(|s| s.weight).sum::<f64>() / total
}

/// The floor cue on the lines of the surface of revolution: `Some(sense)` when a flat
/// surface (normal within [`FLOOR_NORMAL_DEG`] of the axis) of at least `min_share` of the
/// piece reaches inside `max_inner_radius_ratio` of the median radius of the rest of the
/// piece (normals farther than [`RISE_NORMAL_DEG`] from the axis: a wall, or a plate's low
/// rise), and the rest reaches past the floor's two faces on one side more than on the
/// other: the wall rises from the floor. The rest need not be steep: a dish's floor turns into a wall a few degrees from
/// flat, which the floor's own normals already tell from it.
fn floor_cue(samples: &[Sample], min_share: f64, max_inner_radius_ratio: f64) -> Option<f64> {
    let total: f64 = samples.iter().map(|s| s.weight).sum();
    let flat_limit = FLOOR_NORMAL_DEG.to_radians().cos();
    let rise_limit = RISE_NORMAL_DEG.to_radians().cos();
    let rest: Vec<&Sample> = samples.iter().filter(|s| s.normal_axial.abs() <= rise_limit).collect();
    let flat: Vec<&Sample> = samples.iter().filter(|s| s.normal_axial.abs() > flat_limit).collect();
    let rest_weight: f64 = rest.iter().map(|s| s.weight).sum();
    let flat_weight: f64 = flat.iter().map(|s| s.weight).sum();
    if !(flat_weight > min_share * total && rest_weight > MIN_WALL_SHARE * total) {
        return None;
    }
    let rest_radius = weighted_median(rest.iter().map(|s| (s.radius, s.weight)));
    let flat_radius = weighted_median(flat.iter().map(|s| (s.radius, s.weight)));
    let flat_inner_radius = weighted_quantile(flat.iter().map(|s| (s.radius, s.weight)), 0.25);
    if flat_inner_radius >= max_inner_radius_ratio * rest_radius || flat_radius >= rest_radius {
        return None;
    }
    // The wall rises from both faces of the floor: its outer skin from the underside, its
    // inner skin from the floor's top, so the rest reaches past the floor's farther face
    // on the rim's side and not on the other. Medians mislead where the piece holds only a
    // stub of wall: the floor's two faces, weighted by what the scan kept of each, put the
    // floor's median height on either face.
    let flat_height = |fraction: f64| weighted_quantile(flat.iter().map(|s| (s.height, s.weight)), fraction);
    let rest_height = |fraction: f64| weighted_quantile(rest.iter().map(|s| (s.height, s.weight)), fraction);
    let reach_up = rest_height(1.0 - FLOOR_EXTREME_QUANTILE) - flat_height(1.0 - FLOOR_EXTREME_QUANTILE);
    let reach_down = flat_height(FLOOR_EXTREME_QUANTILE) - rest_height(FLOOR_EXTREME_QUANTILE);
    let rise = reach_up - reach_down;
    (rise.abs() >= MIN_FLOOR_RISE_MM).then(|| rise.signum())
}

/// A floor's normals keep within this angle of the axis, degrees (a flat base, a slightly
/// domed or sagging floor).
const FLOOR_NORMAL_DEG: f64 = 8.0;
/// The rest of a base piece turns farther than this from the axis, degrees: a dish's
/// floor turns into a wall rising a few degrees from flat.
const RISE_NORMAL_DEG: f64 = FLOOR_NORMAL_DEG;
/// The rest of the piece must reach at least this much farther past the floor on one side
/// than on the other, along the axis, for the floor to tell which way is up, mm: several
/// times a smoothed scan's noise, in quantiles over hundreds of points.
const MIN_FLOOR_RISE_MM: f64 = 0.25;
/// The quantile of the heights that stands for a surface's lowest (and, from the top, its
/// highest) reach: clear of single points off the scan, within the floor's faces.
const FLOOR_EXTREME_QUANTILE: f64 = 0.1;

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

    /// A base piece with only a stub of wall: the floor's top face outweighs its underside
    /// (or the other way), which puts the floor's median height on either face; the wall's
    /// reach past the faces still says which way it rises, and the reversed axis reads the
    /// other way.
    #[test]
    fn a_stub_of_wall_tells_the_floor_whichever_face_weighs_more() {
        let sample = |radius: f64, height: f64, normal_axial: f64, weight: f64| Sample {
            radius,
            height,
            normal_radial: (1.0 - normal_axial * normal_axial).sqrt(),
            normal_axial,
            weight,
        };
        for (top_weight, under_weight) in [(3.0, 1.0), (1.0, 3.0)] {
            let mut samples = Vec::new();
            for i in 0..200 {
                let radius = 10.0 + 0.2 * i as f64;
                samples.push(sample(radius, 4.0, 1.0, top_weight));
                samples.push(sample(radius, 0.0, -1.0, under_weight));
            }
            // The wall's stub at the floor's edge: the outer skin from the underside, the
            // inner skin from the top, both ending 1.5 mm above the top.
            for i in 0..30 {
                samples.push(sample(55.0, 5.5 * i as f64 / 29.0, 0.0, 1.0));
                samples.push(sample(50.0, 4.0 + 1.5 * i as f64 / 29.0, 0.0, 1.0));
            }
            let up = floor_cue(&samples, MIN_FLOOR_SHARE, FLOOR_INNER_RADIUS_RATIO);
            for s in &mut samples {
                s.height = -s.height;
                s.normal_axial = -s.normal_axial;
            }
            let down = floor_cue(&samples, MIN_FLOOR_SHARE, FLOOR_INNER_RADIUS_RATIO);
            assert_eq!((up, down), (Some(1.0), Some(-1.0)), "faces weighted {top_weight} (top) and {under_weight} (underside)");
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
