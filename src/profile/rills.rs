//! Wheel rills: the grooves a potter's fingers leave on a wheel-thrown wall, each at one
//! height all round the vessel. Putting the rills horizontal is how an archaeologist
//! orients a body sherd by hand (and the feature the paper's manual pre-orientation picks
//! three points on, section 2.2), so their slope in the frame of an axis is an independent
//! check of that axis: a turn of the axis about the sherd's radial direction slants every
//! rill by the same angle.
//!
//! The tracer works on the unrolled skin of the wall (the floor and a flat lip, whose
//! normals lie along the axis, carry no rills). Per vertical strip of the arc, the radius
//! as a function of height is smoothed at the scale of a groove and the wall's own profile
//! (a much wider smoothing) taken away; grooves are the minima of what is left, into the
//! wall, deeper than their surroundings by [`RillOptions::min_depth_mm`] and than the dip
//! the wall's own bend leaves there, and not where the wall turns as at a corner (a neck
//! or a lip's shoulder is not a rill). Minima of neighbouring strips at about the same
//! height are linked into rills, and a straight line through each rill's heights against
//! the arc gives its slope. Any other groove cut into the surface of revolution (a lip's
//! groove, an incised line) is horizontal on the vessel too, and is traced and counted
//! alike.

use serde::{Deserialize, Serialize};

use crate::mesh::normals::{compute_vertex_normals, NormalWeighting};
use crate::mesh::{Mesh, Point};
use crate::orient::{Axis, Skin};
use crate::statistics::least_squares_line;

/// Settings of [`trace_rills`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RillOptions {
    /// Width of the vertical strips along the arc, mm.
    pub strip_width_mm: f64,
    /// Height of the bins a strip's radii are averaged in, mm.
    pub bin_mm: f64,
    /// Gaussian smoothing of a strip's radii at the scale of a groove, mm (scan noise).
    pub groove_smoothing_mm: f64,
    /// Gaussian smoothing that gives the wall's own profile, mm: what it takes away is
    /// relief narrower than this.
    pub wall_smoothing_mm: f64,
    /// Least depth of a groove below the highest relief within 2 mm on both sides, mm.
    pub min_depth_mm: f64,
    /// Greatest depth of a groove, mm: deeper "grooves" are the profile's own corners (a
    /// floor meeting the wall, a neck), which the wall's smoothing cannot follow.
    pub max_depth_mm: f64,
    /// Largest change of height between the grooves of neighbouring strips that are linked
    /// into one rill, mm.
    pub max_step_mm: f64,
    /// Fewest strips a rill runs through.
    pub min_strips: usize,
}

impl Default for RillOptions {
    /// Rills of wheel-thrown pottery are 0.1-1 mm deep and 3-10 mm apart (so 1.5 mm keeps
    /// the deepest with room for the scan's noise); strips of 3 mm
    /// hold a few hundred vertices of a scan at 0.3 mm spacing. A step of 0.8 mm per strip
    /// follows rills slanted by up to 15 degrees.
    fn default() -> Self {
        RillOptions {
            strip_width_mm: 3.0,
            bin_mm: 0.25,
            groove_smoothing_mm: 0.5,
            wall_smoothing_mm: 3.0,
            min_depth_mm: 0.05,
            max_depth_mm: 1.5,
            max_step_mm: 0.8,
            min_strips: 4,
        }
    }
}

/// One traced rill.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Rill {
    /// The skin it runs on.
    pub skin: Skin,
    /// The bottom of the groove in each strip it runs through, in the scan's frame, along
    /// the arc: points a user can pick for a manual orientation.
    pub points: Vec<[f64; 3]>,
    /// Length along the arc between its first and last strip, mm.
    pub arc_length_mm: f64,
    /// Mean radius of its bottom in the axis frame, mm.
    pub radius_mm: f64,
    /// Mean height in the axis frame, mm.
    pub height_mm: f64,
    /// Slope against the horizontal of the axis frame, degrees, positive rising with the
    /// angle about the axis: 0 for a rill the axis puts horizontal.
    pub slope_deg: f64,
    /// Median depth below the relief around it, mm.
    pub depth_mm: f64,
    /// Root mean square of the heights about the straight line through them, mm.
    pub straightness_rms_mm: f64,
}

/// What the rills of a sherd say of an axis: how far from horizontal it puts them.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RillCheck {
    /// Number of rills traced.
    pub count: usize,
    /// Their slope, degrees, the mean weighted by arc length: near 0 when the axis puts
    /// them horizontal. A turn of the axis about the sherd's radial direction moves it by
    /// the turn; a tilt in the sherd's meridian plane hardly at all (rills cannot see it).
    pub slope_deg: f64,
    /// The arc-weighted standard deviation of their slopes, degrees: rills are not
    /// perfectly level on a thrown pot, and this is by how much they disagree.
    pub slope_spread_deg: f64,
    /// Arc length of the longest, mm.
    pub longest_arc_mm: f64,
}

/// The summary of `rills`; `None` when there are none.
pub fn rill_check(rills: &[Rill]) -> Option<RillCheck> {
    let total: f64 = rills.iter().map(|r| r.arc_length_mm).sum();
    if rills.is_empty() || !(total > 0.0) {
        return None;
    }
    let slope = rills.iter().map(|r| r.slope_deg * r.arc_length_mm).sum::<f64>() / total;
    let variance = rills.iter().map(|r| (r.slope_deg - slope).powi(2) * r.arc_length_mm).sum::<f64>() / total;
    Some(RillCheck {
        count: rills.len(),
        slope_deg: slope,
        slope_spread_deg: variance.sqrt(),
        longest_arc_mm: rills.iter().map(|r| r.arc_length_mm).fold(0.0, f64::max),
    })
}

/// Three points on `rill` for a manual orientation: the bottoms of its first, middle and
/// last grooves (scan frame). The circle through them is the rill's, whatever axis traced it.
pub fn three_points_on(rill: &Rill) -> [Point; 3] {
    let point = |k: usize| Point::new(rill.points[k][0], rill.points[k][1], rill.points[k][2]);
    [point(0), point(rill.points.len() / 2), point(rill.points.len() - 1)]
}

/// The rills under `axis` on the skins [`crate::orient::segment_surfaces`] finds about it,
/// longest first; empty where it finds none. Under the axis of a sherd the orientation
/// declines, they are where to pick three points ([`three_points_on`] the longest).
pub fn trace_rills_under(mesh: &Mesh, axis: &Axis, options: &RillOptions) -> Vec<Rill> {
    crate::orient::segment_surfaces(mesh, axis).map(|skins| trace_rills(mesh, axis, &skins, options)).unwrap_or_default()
}

/// The rills of both skins under `axis` (`skins` from [`crate::orient::segment_surfaces`]),
/// longest first. Empty on a smooth wall: the depth test keeps scan noise out, and the
/// bend test the profile's own bends.
pub fn trace_rills(mesh: &Mesh, axis: &Axis, skins: &[Skin], options: &RillOptions) -> Vec<Rill> {
    let Some(reference) = mesh.centroid() else { return Vec::new() };
    let frame = axis.to_oriented_frame(&reference);
    // A point cloud's own normals, a mesh's from its faces (as the skins were segmented).
    let computed = (!mesh.is_point_cloud()).then(|| compute_vertex_normals(mesh, NormalWeighting::Area));
    let normals = computed.as_deref().or(mesh.normals.as_deref());
    // Rills run round the wall. A floor or a flat lip, whose normals lie closer to the axis
    // than across it, carries none, and its turn into the wall is a corner of the profile.
    let on_wall = |i: usize| {
        normals.and_then(|normals| normals.get(i)).is_none_or(|n| {
            let axial = n.dot(&axis.direction).abs();
            axial * axial <= 0.5 * n.norm_squared()
        })
    };
    let mut rills = Vec::new();
    for skin in [Skin::Inner, Skin::Outer] {
        let vertices: Vec<(usize, f64, f64, f64)> = mesh
            .positions
            .iter()
            .enumerate()
            .filter(|(i, _)| skins.get(*i) == Some(&skin) && on_wall(*i))
            .map(|(i, p)| {
                let (radius, height, angle) = Axis::cylindrical(&frame, p);
                (i, radius, height, angle)
            })
            .collect();
        rills.extend(trace_skin(mesh, skin, &vertices, options));
    }
    rills.sort_by(|a, b| b.arc_length_mm.total_cmp(&a.arc_length_mm));
    rills
}

/// A groove found in one strip: the strip's angle about the axis, the groove's radius and
/// height in the axis frame, its depth, and the mean scan-frame position of the vertices
/// at its bottom.
#[derive(Clone, Copy, Debug)]
struct Groove {
    angle_rad: f64,
    radius_mm: f64,
    height_mm: f64,
    depth_mm: f64,
    bottom: Point,
}

/// `vertices`: (index, radius, height, angle) of the skin's vertices in the axis frame.
fn trace_skin(mesh: &Mesh, skin: Skin, vertices: &[(usize, f64, f64, f64)], options: &RillOptions) -> Vec<Rill> {
    if vertices.len() < 50 || !(options.strip_width_mm > 0.0 && options.bin_mm > 0.0) {
        return Vec::new();
    }
    let radii: Vec<f64> = vertices.iter().map(|v| v.1).collect();
    let median_radius = crate::statistics::upper_median(&radii);
    // Into the wall is away from the axis on the inner skin, towards it on the outer.
    let into_wall = if skin == Skin::Inner { -1.0 } else { 1.0 };
    let arc_of = |angle: f64| angle * median_radius;
    let (arc_low, arc_high) = vertices.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
        (low.min(arc_of(v.3)), high.max(arc_of(v.3)))
    });
    let strip_count = ((arc_high - arc_low) / options.strip_width_mm).floor() as usize;
    let mut strips: Vec<Vec<usize>> = vec![Vec::new(); strip_count.max(1)];
    for (k, v) in vertices.iter().enumerate() {
        let strip = ((arc_of(v.3) - arc_low) / options.strip_width_mm) as usize;
        if strip < strip_count {
            strips[strip].push(k);
        }
    }
    let mut grooves: Vec<(usize, Groove)> = Vec::new();
    for (strip, members) in strips.iter().enumerate() {
        let angle_rad = (arc_low + (strip as f64 + 0.5) * options.strip_width_mm) / median_radius;
        for groove in strip_grooves(mesh, vertices, members, into_wall, angle_rad, options) {
            grooves.push((strip, groove));
        }
    }
    link_rills(skin, &grooves, options)
}

/// The grooves of one strip: minima of the radius relief (into the wall) against height.
fn strip_grooves(
    mesh: &Mesh,
    vertices: &[(usize, f64, f64, f64)],
    members: &[usize],
    into_wall: f64,
    angle_rad: f64,
    options: &RillOptions,
) -> Vec<Groove> {
    if members.len() < 50 {
        return Vec::new();
    }
    let bin = options.bin_mm;
    let low = members.iter().map(|&k| vertices[k].2).fold(f64::INFINITY, f64::min);
    let high = members.iter().map(|&k| vertices[k].2).fold(f64::NEG_INFINITY, f64::max);
    let bin_count = ((high - low) / bin) as usize + 1;
    let bin_of = |height: f64| ((height - low) / bin) as usize;
    let Some((wall_raw, filled)) = binned_means(members.iter().map(|&k| (bin_of(vertices[k].2), vertices[k].1 * into_wall)), bin_count) else {
        return Vec::new();
    };
    let wall = gaussian_smooth(&wall_raw, options.wall_smoothing_mm / bin);
    // The relief is taken off the wall vertex by vertex, at each vertex's own height, and
    // only then averaged: a bin's mean radius stands at its vertices' mean height, not at
    // its centre, and on a sloping wall with a vertex or two per bin that offset times the
    // slope zigzags by as much as a shallow groove (0.06 mm for 0.25 mm bins on a wall
    // flaring at 0.5 mm/mm).
    // A bin's curve value at any height, linearly between bin centres.
    let at = |curve: &[f64], height: f64| {
        let t = ((height - low) / bin - 0.5).clamp(0.0, (bin_count - 1) as f64);
        let below = t.floor() as usize;
        let above = (below + 1).min(bin_count - 1);
        curve[below] + (curve[above] - curve[below]) * (t - below as f64)
    };
    let off_wall = |k: usize| vertices[k].1 * into_wall - at(&wall, vertices[k].2);
    let Some((relief_raw, _)) = binned_means(members.iter().map(|&k| (bin_of(vertices[k].2), off_wall(k))), bin_count) else {
        return Vec::new();
    };
    let relief = gaussian_smooth(&relief_raw, options.groove_smoothing_mm / bin);
    // The scatter of the vertices about the relief (the scan's noise, a rough surface's
    // roughness), robustly: a groove must stand out of what that scatter makes of the
    // few vertices its depth is read from.
    let scatter: Vec<f64> = members.iter().map(|&k| (off_wall(k) - at(&relief, vertices[k].2)).abs()).collect();
    let noise_mm = 1.4826 * crate::statistics::upper_median(&scatter);
    // The Gaussian smoothing averages about this much height: sqrt(pi) x 2 sigma.
    let window_mm = 2.0 * std::f64::consts::PI.sqrt() * options.groove_smoothing_mm;
    // Within 1 mm of the strip's ends the wall's smoothing runs off the sherd: no groove
    // is read there (fractures and the rim would make false ones).
    let margin = (1.0 / bin).ceil() as usize;
    let (first, last) = (filled[0] + margin, filled[filled.len() - 1].saturating_sub(margin));
    let reach = (2.0 / bin).round() as usize;
    let mut grooves = Vec::new();
    for b in first.max(1)..last.min(bin_count - 1) {
        if !(relief[b] < relief[b - 1] && relief[b] <= relief[b + 1]) {
            continue;
        }
        let left = relief[b.saturating_sub(reach).max(filled[0])..b].iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let right = relief[b + 1..=(b + reach).min(last + margin)].iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let depth_mm = left.min(right) - relief[b];
        if !(depth_mm >= options.min_depth_mm && depth_mm <= options.max_depth_mm) {
            continue;
        }
        let height_mm = low + (b as f64 + 0.5) * bin;
        let averaged = members.iter().filter(|&&k| (vertices[k].2 - height_mm).abs() <= 0.5 * window_mm).count();
        if depth_mm < MIN_DEPTH_T * noise_mm / (averaged.max(1) as f64).sqrt() {
            continue;
        }
        // Where the profile bends into the wall (a neck, a lip's shoulder), taking the
        // wall's smoothing off leaves a dip as deep as a rill: a groove no deeper than
        // that is the bend.
        if depth_mm <= bend_dip_mm(&wall, b, bin, options.wall_smoothing_mm) {
            continue;
        }
        // A bend sharper than the wall's smoothing leaves a dip deeper than the estimate
        // above; such a sharp turn is the profile's corner whatever the groove's depth.
        if wall_turn_rad(members.iter().map(|&k| (vertices[k].2, vertices[k].1 * into_wall)), height_mm) > MAX_WALL_TURN_RAD {
            continue;
        }
        // The groove's bottom in the scan: the vertices of the strip within a bin of it.
        let bottom: Vec<usize> = members.iter().copied().filter(|&k| (vertices[k].2 - height_mm).abs() <= bin).collect();
        if bottom.is_empty() {
            continue;
        }
        let count = bottom.len() as f64;
        let mean = bottom.iter().fold(nalgebra::Vector3::zeros(), |sum, &k| sum + mesh.positions[vertices[k].0].coords) / count;
        let radius_mm = bottom.iter().map(|&k| vertices[k].1).sum::<f64>() / count;
        grooves.push(Groove { angle_rad, radius_mm, height_mm, depth_mm, bottom: Point::from(mean) });
    }
    grooves
}

/// How many standard errors of the relief (the vertices' scatter over the square root of
/// how many the smoothing averages at the groove's bottom) a groove must be deep: chance
/// minima of a rough surface's relief, linked across strips, would otherwise read as
/// rills.
const MIN_DEPTH_T: f64 = 4.0;

/// The dip that taking the wall's smoothing (a Gaussian of `smoothing_mm`) off the wall
/// leaves at bin `b` where the wall bends into itself, mm: a smooth curve less its
/// Gaussian smoothing is `-smoothing^2 / 2` times its second derivative (Taylor), read here
/// off the smoothed `wall` (into the wall positive) over 1 mm either side. 0 where the
/// wall bends away: that leaves a ridge, not a groove.
fn bend_dip_mm(wall: &[f64], b: usize, bin_mm: f64, smoothing_mm: f64) -> f64 {
    let reach = (1.0 / bin_mm).round().max(1.0) as usize;
    let below = wall[b.saturating_sub(reach)];
    let above = wall[(b + reach).min(wall.len() - 1)];
    let second_derivative = (above - 2.0 * wall[b] + below) / (reach as f64 * bin_mm).powi(2);
    0.5 * smoothing_mm.powi(2) * second_derivative.max(0.0)
}

/// The turn of the wall across height `height_mm`, radians (positive: into the wall): the
/// angle of its profile over the flank from [`GROOVE_HALF_WIDTH_MM`] to [`CORNER_FLANK_MM`]
/// above less that below, each from the least-squares line of the strip's radius (into the
/// wall) against height there; 0 where either flank holds fewer than 5 vertices.
fn wall_turn_rad(values: impl Iterator<Item = (f64, f64)> + Clone, height_mm: f64) -> f64 {
    let flank = |sign: f64| {
        let pairs: Vec<(f64, f64)> = values
            .clone()
            .filter(|(height, _)| (GROOVE_HALF_WIDTH_MM..=CORNER_FLANK_MM).contains(&(sign * (height - height_mm))))
            .collect();
        if pairs.len() < 5 {
            return None;
        }
        least_squares_line(&pairs, 1e-9).map(|(_, _, slope)| slope.atan())
    };
    match (flank(-1.0), flank(1.0)) {
        (Some(below), Some(above)) => above - below,
        _ => 0.0,
    }
}

/// Half the width of a groove, which the turn of the wall across it leaves out, mm.
const GROOVE_HALF_WIDTH_MM: f64 = 1.5;
/// How far above and below a groove the turn of the wall across it is read, mm.
const CORNER_FLANK_MM: f64 = 3.0;
/// A wall that turns into itself by more than this across a groove (45 degrees within
/// 6 mm) is a corner of the profile (a lip's shoulder, a carination), not a wall with a
/// rill on it, radians.
const MAX_WALL_TURN_RAD: f64 = std::f64::consts::FRAC_PI_4;

/// The mean value per height bin of `(bin, value)` pairs, and the bins holding at least 3
/// of them; `None` when fewer than 10 do. Bins with fewer than 3 are filled by linear
/// interpolation between the nearest full ones, so that a sparse bin does not read as a
/// groove.
fn binned_means(values: impl Iterator<Item = (usize, f64)>, bin_count: usize) -> Option<(Vec<f64>, Vec<usize>)> {
    let (mut sums, mut counts) = (vec![0.0; bin_count], vec![0usize; bin_count]);
    for (b, value) in values {
        sums[b] += value;
        counts[b] += 1;
    }
    let filled: Vec<usize> = (0..bin_count).filter(|&b| counts[b] >= 3).collect();
    if filled.len() < 10 {
        return None;
    }
    let value = |f: usize| sums[f] / counts[f] as f64;
    let means = (0..bin_count)
        .map(|b| {
            if counts[b] >= 3 {
                return value(b);
            }
            let after = filled.partition_point(|&f| f < b);
            match (after.checked_sub(1).map(|i| filled[i]), filled.get(after).copied()) {
                (Some(before), Some(after)) => {
                    let t = (b - before) as f64 / (after - before) as f64;
                    value(before) * (1.0 - t) + value(after) * t
                }
                (Some(only), None) | (None, Some(only)) => value(only),
                (None, None) => 0.0,
            }
        })
        .collect();
    Some((means, filled))
}

/// Links the grooves of neighbouring strips (at most two strips skipped) whose heights
/// differ by less than [`RillOptions::max_step_mm`] into rills; each groove joins the rill
/// whose last groove is nearest in height.
fn link_rills(skin: Skin, grooves: &[(usize, Groove)], options: &RillOptions) -> Vec<Rill> {
    let mut chains: Vec<Vec<(usize, Groove)>> = Vec::new();
    for &(strip, groove) in grooves {
        let nearest = chains
            .iter_mut()
            .filter(|chain| {
                let (last_strip, last) = chain[chain.len() - 1];
                strip > last_strip && strip - last_strip <= 3 && (groove.height_mm - last.height_mm).abs() < options.max_step_mm
            })
            .min_by(|a, b| {
                let step = |chain: &Vec<(usize, Groove)>| (groove.height_mm - chain[chain.len() - 1].1.height_mm).abs();
                step(a).total_cmp(&step(b))
            });
        match nearest {
            Some(chain) => chain.push((strip, groove)),
            None => chains.push(vec![(strip, groove)]),
        }
    }
    chains.into_iter().filter(|chain| chain.len() >= options.min_strips).map(|chain| rill_of(skin, &chain)).collect()
}

/// The rill through a chain of grooves: its heights against the arc at its own radius
/// (where a turn of the axis by `a` about the radial direction raises the groove by `a`
/// per millimetre of arc), fitted by a straight line.
fn rill_of(skin: Skin, chain: &[(usize, Groove)]) -> Rill {
    let n = chain.len() as f64;
    let radius = chain.iter().map(|(_, g)| g.radius_mm).sum::<f64>() / n;
    let arcs: Vec<f64> = chain.iter().map(|(_, g)| g.angle_rad * radius).collect();
    let heights: Vec<(f64, f64)> = chain.iter().zip(&arcs).map(|((_, g), arc)| (*arc, g.height_mm)).collect();
    // A chain runs through at least two strips 3 mm apart: its arcs always spread.
    let (mean_arc, mean_height, slope) = least_squares_line(&heights, 1e-12).expect("a chain has grooves");
    let straightness = (chain
        .iter()
        .zip(&arcs)
        .map(|((_, g), arc)| (g.height_mm - mean_height - slope * (arc - mean_arc)).powi(2))
        .sum::<f64>()
        / n)
        .sqrt();
    let depths: Vec<f64> = chain.iter().map(|(_, g)| g.depth_mm).collect();
    Rill {
        skin,
        points: chain.iter().map(|(_, g)| [g.bottom.x, g.bottom.y, g.bottom.z]).collect(),
        arc_length_mm: arcs[arcs.len() - 1] - arcs[0],
        radius_mm: radius,
        height_mm: mean_height,
        slope_deg: slope.atan().to_degrees(),
        depth_mm: crate::statistics::upper_median(&depths),
        straightness_rms_mm: straightness,
    }
}

/// Gaussian smoothing of `values` with a standard deviation of `sigma` samples, the ends
/// extended by their last value.
fn gaussian_smooth(values: &[f64], sigma: f64) -> Vec<f64> {
    let half = (3.0 * sigma).ceil() as isize;
    let weights: Vec<f64> = (-half..=half).map(|t| (-0.5 * (t as f64 / sigma.max(1e-9)).powi(2)).exp()).collect();
    let total: f64 = weights.iter().sum();
    let last = values.len() as isize - 1;
    (0..values.len() as isize)
        .map(|i| {
            (-half..=half)
                .zip(&weights)
                .map(|(t, w)| values[(i + t).clamp(0, last) as usize] * w)
                .sum::<f64>()
                / total
        })
        .collect()
}
