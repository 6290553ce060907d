//! Measurements of an oriented fragment (the figures an archaeologist writes next to a
//! drawing): rim and base radius and diameter with 95% intervals, the preserved arc
//! (sector angle, its share of the circumference: 360 degrees minus the largest angular
//! gap, as DACORD's "circle sector preservation indicator"), the preserved height, the
//! wall thickness along the profile and, when the profile runs from base to rim, the
//! capacity (volume inside the revolved inner profile, by frustums, which are exact for
//! the piecewise linear section where DACORD's stacked cylinders are not).
//!
//! Intervals come from [`crate::refine::uncertainty`]: the axis is refined again on
//! resampled sections and every measurement recomputed on each resampled axis.

use serde::{Deserialize, Serialize};

use super::rills::{trace_rills, Rill, RillOptions};
use super::section::{most_informative_angle, oriented_frame, profile_section};
use crate::mesh::{planar_length, Mesh, Point};
use crate::orient::{mean_point_distance_mm, Axis};
use crate::refine::sections::{sector_angle_rad, vertical_sections, PreparedSurface, Skin, Surface};
use crate::statistics::quantile;
use crate::refine::tangent::Edge;
use crate::refine::sector_jackknife::{jackknife_half_width_95, sector_jackknife_axes};
use crate::refine::uncertainty::{angle_interval_deg, bootstrap_axes, distance_interval_mm, value_interval, BootstrapOptions};
use crate::refine::{detect_edges_over, RefineOptions, EDGE_LEVEL_FRACTION};

/// Settings of [`measure`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MeasureOptions {
    /// How the axis was refined: the bootstrap repeats it.
    pub refine: RefineOptions,
    /// The bootstrap behind the intervals (`samples: 0` for none).
    pub bootstrap: BootstrapOptions,
    /// Heights at which the wall thickness is measured along the profile.
    pub wall_thickness_stations: usize,
    /// How far the axis turns (degrees) and moves across itself (mm) before it fits the
    /// sherd worse region by region, from the automatic orientation's landscape
    /// ([`crate::orient::landscape::valley_width`]); added in quadrature to the
    /// bootstrap's intervals (the turn to the distance interval as the distance it moves
    /// the sherd's points). The bootstrap resamples the scan's noise only; a vessel's
    /// ovality and wobble bias every resample alike, and widen the valley instead. A NaN
    /// turn (an axis levelled by its tangent plane, whose turn the level edge fixes)
    /// widens the position interval alone.
    pub axis_valley_width: Option<(f64, f64)>,
    /// How far the competing axes the orientation could not rule out lie
    /// ([`crate::orient::CompetitorReach`]): the intervals reach them, since the axis may
    /// lie in their valley rather than the best one's.
    pub axis_competitor_reach: Option<crate::orient::CompetitorReach>,
}

impl Default for MeasureOptions {
    fn default() -> Self {
        MeasureOptions {
            refine: RefineOptions::default(),
            bootstrap: BootstrapOptions::default(),
            wall_thickness_stations: 24,
            axis_valley_width: None,
            axis_competitor_reach: None,
        }
    }
}

/// Wall thickness at one height of the profile.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct WallThickness {
    /// Height in the oriented frame, mm.
    pub z_mm: f64,
    /// Thickness across the wall (perpendicular to the outer surface), mm.
    pub thickness_mm: f64,
}

/// The measurements of one oriented fragment.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Measurements {
    /// Outer radius at the rim, mm, when a level rim is preserved.
    pub rim_radius_mm: Option<f64>,
    /// Twice the rim radius, mm.
    pub rim_diameter_mm: Option<f64>,
    /// 95% interval of the rim diameter, mm.
    pub rim_diameter_interval_mm: Option<[f64; 2]>,
    /// Outer radius where the base leaves its standing plane, mm, when a level base is preserved.
    pub base_radius_mm: Option<f64>,
    /// Twice the base radius, mm.
    pub base_diameter_mm: Option<f64>,
    /// 95% interval of the base diameter, mm.
    pub base_diameter_interval_mm: Option<[f64; 2]>,
    /// Arc of the circumference the whole fragment spans, degrees: for a rim sherd whose
    /// breaks slope away from the rim this is more than the rim it preserves.
    pub sector_angle_deg: f64,
    /// The same as a share of the full circle, percent.
    pub sector_percent: f64,
    /// Arc of the rim itself the fragment preserves, degrees, when a rim is measured: what
    /// "12% of rim" in a publication (or a rim chart) means.
    #[serde(default)]
    pub rim_sector_deg: Option<f64>,
    /// Arc of the base's edge the fragment preserves, degrees, when a base is measured.
    #[serde(default)]
    pub base_sector_deg: Option<f64>,
    /// Preserved height along the axis, mm.
    pub height_mm: f64,
    /// Median wall thickness along the profile, mm.
    pub wall_thickness_mm: Option<f64>,
    /// Wall thickness at heights along the profile.
    pub wall_thickness_profile: Vec<WallThickness>,
    /// Volume inside the revolved inner profile, litres, when the profile runs from base to rim.
    pub capacity_litres: Option<f64>,
    /// 95% interval `[0, upper]` of the angle between the true and the given axis, degrees.
    pub axis_angle_interval_deg: Option<[f64; 2]>,
    /// 95% interval `[0, upper]` of the paper's mean point distance between the true and
    /// the given axis, mm ([`crate::refine::uncertainty::distance_interval_mm`]).
    pub axis_distance_interval_mm: Option<[f64; 2]>,
    /// The axis is uncertain: its angle interval reaches beyond
    /// [`MAX_UNFLAGGED_AXIS_INTERVAL_DEG`], its distance interval beyond
    /// [`MAX_UNFLAGGED_AXIS_DISTANCE_MM`], or refined without a quarter of its arc it
    /// moves more than [`MAX_UNFLAGGED_SECTOR_MOVE_MM`] (tested with the intervals, when
    /// the bootstrap runs). Such an axis and its figures want a look before they are used.
    pub axis_uncertain: bool,
    /// Why the axis is uncertain, one sentence per test it failed (empty when it is not).
    pub axis_doubts: Vec<String>,
    /// The grooves of revolution (wheel rills) traced under the axis, longest first.
    pub rills: Vec<Rill>,
    /// What could not be measured, and why.
    pub notes: Vec<String>,
}

/// An axis whose 95% angle interval reaches further than this is reported uncertain,
/// degrees. The bootstrap's spread is what tells a wrong axis from a right one where the
/// criterion itself cannot: on short body arcs the circles criterion prefers a wrong
/// axis, and then resampled sections scatter widely. The price is flagging body sherds
/// whose axis is right but not known to be (`docs/calibration.md`).
pub const MAX_UNFLAGGED_AXIS_INTERVAL_DEG: f64 = 4.0;

/// An axis whose 95% distance interval reaches further than this is reported uncertain,
/// mm. The paper calls an axis wrong when it moves the sherd's points by more than 4 mm on
/// average; the bootstrap sees a position the skins barely fix as replicates that slide
/// along the radius; it catches more wrong axes than the refinement's own placement test
/// and flags fewer right ones on dense scans, where Eq. 2 is flatter along the radius
/// (`docs/calibration.md`).
pub const MAX_UNFLAGGED_AXIS_DISTANCE_MM: f64 = 5.0;

/// An axis that moves further than this when the fragment is refined again without one
/// quarter of its arc ([`sector_jackknife_axes`]) is reported uncertain, mm of mean point
/// distance. The bootstrap resamples sections that each span the whole arc, and on a
/// clean scan they agree about an axis the vessel's deformation put off; leaving out part
/// of the arc changes what the deformation says. Set on the synthetic corpus without scan
/// noise, where right axes moved 0.16 mm on median (`docs/calibration.md`).
pub const MAX_UNFLAGGED_SECTOR_MOVE_MM: f64 = 1.5;

/// How each of [`Measurements::axis_doubts`] begins when it is repeated among the notes.
pub const AXIS_DOUBT_NOTE: &str = "the axis is uncertain: ";

/// The doubt on an axis that too few of the bootstrap's resamples could refine again to
/// give it intervals (`refined` of `samples`): the refinement does not repeat on the
/// fragment's own sections drawn again, so nothing says how far the axis may be off, and
/// it is not given as sure.
fn unrepeatable_doubt(refined: usize, samples: usize) -> String {
    format!("only {refined} of {samples} resamples of its sections could be refined again: its precision is unknown")
}

/// Marks the axis uncertain when it has doubts, and repeats each among the notes.
fn publish_axis_doubts(measurements: &mut Measurements) {
    measurements.axis_uncertain = !measurements.axis_doubts.is_empty();
    let doubts: Vec<String> = measurements.axis_doubts.iter().map(|d| format!("{AXIS_DOUBT_NOTE}{d}")).collect();
    measurements.notes.extend(doubts);
}

/// A rim is measured when it is level over this share of the vertical sections (a rim
/// preserved over a third of a sherd whose other end is a rising break line). Bases keep
/// the stricter share of the refinement: a horizontal break low on a rim sherd is as
/// level over a third of the arc as a base.
const MIN_MEASURED_RIM_FRACTION: f64 = 0.3;
/// Vertical sections used to find the rim and base edges.
const EDGE_SECTIONS: usize = 24;
/// Points this close below the top (above the bottom) of their section belong to the rim (base) edge, mm.
const EDGE_BAND_MM: f64 = 1.0;

/// The outer radius of `edge` under an axis (`oriented`: the vertices in its frame).
/// Rim: per vertical section, the lip's outer edge as a radius chart reads it: the
/// larger of the highest outer-skin vertex's radius (the edge of a lip that slopes
/// outwards and down, whose inner edge is the higher) and the largest radius within
/// [`EDGE_BAND_MM`] below the section's top (the edge of a flat lip, across which the
/// highest vertex lies anywhere), or where the lip's outer edge lies lower, under a bead
/// or an everted lip, that edge ([`bead_radius`]). Base: per
/// vertical section, the radius of the outer-skin vertex nearest to [`EDGE_BAND_MM`]
/// above the standing plane (where the outer skin leaves it). The median over sections.
fn edge_radius(oriented: &[Point], outer_skin: &[bool], edge: Edge, wall_mm: f64) -> Option<f64> {
    let sections = vertical_sections(oriented, EDGE_SECTIONS);
    let standing = oriented.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    // A base sherd holding the floor's centre keeps the wall on some sides only: the
    // sections with floor alone would give their break's radius (on the synthetic corpus
    // 35-90 mm short in diameter), so only sections rising into the wall count.
    let wall_from = if edge == Edge::Base { wall_height(oriented) } else { f64::NEG_INFINITY };
    let mut radii: Vec<f64> = sections
        .iter()
        .filter(|indices| indices.iter().any(|&i| oriented[i].z > wall_from))
        .filter_map(|indices| {
            let radius = |p: &Point| planar_length(p.x, p.y);
            match edge {
                Edge::Rim => {
                    let highest_outer = indices.iter().filter(|&&i| outer_skin[i]).map(|&i| oriented[i]).max_by(|a, b| a.z.total_cmp(&b.z));
                    let top = indices.iter().map(|&i| oriented[i].z).fold(f64::NEG_INFINITY, f64::max);
                    let widest_at_top = indices.iter().map(|&i| oriented[i]).filter(|p| p.z >= top - EDGE_BAND_MM).map(|p| radius(&p)).max_by(f64::total_cmp);
                    let at_top = highest_outer.map(|p| radius(&p)).into_iter().chain(widest_at_top).max_by(f64::total_cmp)?;
                    // A bead counts where it stands out beyond the top's edge; a wall
                    // bulging a little below its lip (an incurving rim) is read at the lip.
                    Some(match (bead_radius(oriented, outer_skin, indices, top, wall_mm), widest_at_top) {
                        (Some(bead), Some(widest)) if bead > widest + MIN_BEAD_MM => bead.max(at_top),
                        _ => at_top,
                    })
                }
                // The outer skin where it has risen by the band above the standing plane.
                Edge::Base => indices
                    .iter()
                    .filter(|&&i| outer_skin[i])
                    .map(|&i| oriented[i])
                    .min_by(|a, b| ((a.z - standing) - EDGE_BAND_MM).abs().total_cmp(&((b.z - standing) - EDGE_BAND_MM).abs()))
                    .filter(|p| ((p.z - standing) - EDGE_BAND_MM).abs() <= EDGE_BAND_MM)
                    .map(|p| radius(&p))
                    // Where the skin test left the corner out: the widest point of the band.
                    .or_else(|| {
                        indices
                            .iter()
                            .map(|&i| oriented[i])
                            .filter(|p| p.z - standing <= EDGE_BAND_MM)
                            .map(|p| radius(&p))
                            .max_by(f64::total_cmp)
                    }),
            }
        })
        .collect();
    (!radii.is_empty()).then(|| quantile(&mut radii, 0.5))
}

/// The wall thickness assumed where the profile section gives none, mm.
const DEFAULT_WALL_MM: f64 = 6.0;
/// How far below the top a lip's outer edge is looked for, in wall thicknesses: a bead
/// (thickened lip) or an everted lip's hanging edge lies within about one.
const LIP_DEPTH_WALLS: f64 = 1.5;
/// How much the skin must narrow under a lip's outer edge below its top, and how far that
/// edge must stand out beyond the top's, mm: more than a rough surface's bumps, less
/// than a bead a potter forms.
const MIN_BEAD_MM: f64 = 1.0;

/// The radius of a lip's outer edge that lies below its top (a bead, an everted lip's
/// hanging edge) in one vertical section (`indices` of `oriented`, whose highest point is
/// at `top`): the widest point within [`LIP_DEPTH_WALLS`] wall thicknesses of the top,
/// where the outer skin under it, within as much again, narrows by [`MIN_BEAD_MM`]. A wall
/// that keeps widening downwards (a jar's neck into its shoulder) has no such edge.
fn bead_radius(oriented: &[Point], outer_skin: &[bool], indices: &[usize], top: f64, wall_mm: f64) -> Option<f64> {
    let radius = |p: &Point| planar_length(p.x, p.y);
    let depth = LIP_DEPTH_WALLS * wall_mm;
    let widest = indices.iter().map(|&i| oriented[i]).filter(|p| p.z >= top - depth).max_by(|a, b| radius(a).total_cmp(&radius(b)))?;
    let edge_radius = radius(&widest);
    // The skin's radius at each height under the edge is the widest outer-skin vertex of
    // a slab of that height: the narrowest of these says whether the skin comes back in.
    let outer: Vec<Point> = indices.iter().filter(|&&i| outer_skin[i]).map(|&i| oriented[i]).collect();
    let slabs = (depth / UNDER_LIP_SLAB_MM).ceil() as usize;
    let narrowest_under = (1..=slabs)
        .filter_map(|k| {
            let centre = widest.z - k as f64 * UNDER_LIP_SLAB_MM;
            let in_slab = outer.iter().filter(|p| (p.z - centre).abs() <= 0.5 * UNDER_LIP_SLAB_MM);
            let (count, widest_in_slab) = in_slab.fold((0, f64::NEG_INFINITY), |(n, r), p| (n + 1, r.max(radius(p))));
            (count >= 2).then_some(widest_in_slab)
        })
        .min_by(f64::total_cmp)?;
    (narrowest_under < edge_radius - MIN_BEAD_MM).then_some(edge_radius)
}

/// Height of the slabs in which [`bead_radius`] follows the skin under a lip, mm.
const UNDER_LIP_SLAB_MM: f64 = 1.0;

/// Height below the rim's level (above the base's) within which a vertex counts as part
/// of that edge when its preserved arc is measured, mm: wider than the lip's rounding
/// and a scan's noise, narrower than the drop of a break leaving the rim.
const EDGE_SECTOR_BAND_MM: f64 = 1.5;

/// The arc of `edge` the fragment preserves, degrees: the angle about the axis spanned by
/// the vertices at the edge's level (within [`EDGE_SECTOR_BAND_MM`]), not by the whole
/// fragment, whose breaks may run far beyond the rim's ends below it. The level is a line
/// in the angle fitted to the highest (lowest) vertex of each degree, so that a rim tilted
/// by the potter's hand keeps its lower end. For the base only vertices near its edge
/// radius count: a floor piece holding the centre spans every angle.
fn edge_sector_deg(oriented: &[Point], edge: Edge, edge_radius_mm: f64) -> Option<f64> {
    let outward = edge.outward();
    let on_edge_ring = |p: &Point| {
        let r = planar_length(p.x, p.y);
        match edge {
            Edge::Rim => r >= 0.5 * edge_radius_mm,
            Edge::Base => r >= 0.8 * edge_radius_mm,
        }
    };
    // Height measured outwards from the piece: larger is nearer the edge.
    let candidates: Vec<(f64, f64)> =
        oriented.iter().filter(|p| on_edge_ring(p)).map(|p| (p.y.atan2(p.x), outward * p.z)).collect();
    const BINS: usize = 360;
    let bin_of = |angle: f64| (((angle + std::f64::consts::PI) / std::f64::consts::TAU * BINS as f64) as usize).min(BINS - 1);
    let mut extreme = vec![f64::NEG_INFINITY; BINS];
    for &(angle, height) in &candidates {
        let bin = &mut extreme[bin_of(angle)];
        *bin = bin.max(height);
    }
    let bins: Vec<(f64, f64)> = extreme
        .iter()
        .enumerate()
        .filter(|(_, h)| h.is_finite())
        .map(|(i, &h)| ((i as f64 + 0.5) / BINS as f64 * std::f64::consts::TAU - std::f64::consts::PI, h))
        .collect();
    let highest = bins.iter().map(|b| b.1).fold(f64::NEG_INFINITY, f64::max);
    if !highest.is_finite() {
        return None;
    }
    // The level starts flat at the highest bin and is refitted to the bins it selects.
    let (mut intercept, mut slope) = (highest, 0.0);
    for _ in 0..3 {
        let selected: Vec<(f64, f64)> = bins.iter().copied().filter(|&(a, h)| h >= intercept + slope * a - EDGE_SECTOR_BAND_MM).collect();
        // Some selected bin lies on or above the line fitted to them (their residuals sum
        // to zero), so the next selection is never empty.
        let (mean_angle, mean_height, fitted) = crate::statistics::least_squares_line(&selected, 1e-6).expect("a bin is selected");
        slope = fitted;
        intercept = mean_height - slope * mean_angle;
    }
    let angles: Vec<f64> = candidates
        .iter()
        .filter(|&&(a, h)| h >= intercept + slope * a - EDGE_SECTOR_BAND_MM)
        .map(|&(a, _)| a)
        .collect();
    Some(sector_angle_rad(angles).to_degrees())
}

/// Whether the fragment (`oriented`: the vertices under the axis) rises into the wall
/// above the base: higher than [`EDGE_BAND_MM`] above the floor's inner face (the
/// highest point at the innermost radius, as in [`capacity_litres`]). A piece of the
/// floor alone stands as level as a base, but its outer break is no base edge: the
/// widest point of its band would pass for the base radius (on the synthetic corpus
/// 15-40% short of it), so it gives no base diameter. Any vertex counts, not only the
/// outer skin's: the low flaring wall of a bowl has no skin the skin test recognises.
fn reaches_base_edge(oriented: &[Point]) -> bool {
    let wall_from = wall_height(oriented);
    oriented.iter().any(|p| p.z > wall_from)
}

/// The height above which a vertex belongs to the wall, not the floor: [`EDGE_BAND_MM`]
/// above the floor's inner face (the highest point at the innermost radius).
fn wall_height(oriented: &[Point]) -> f64 {
    let radius = |p: &Point| planar_length(p.x, p.y);
    let innermost = oriented.iter().map(radius).fold(f64::INFINITY, f64::min);
    let floor_top = oriented.iter().filter(|p| radius(p) <= innermost + EDGE_BAND_MM).map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    floor_top + EDGE_BAND_MM
}

/// The crossings of the horizontal line at `z` with closed outlines, sorted by radius.
fn crossings(outlines: &[Vec<[f64; 2]>], z: f64) -> Vec<f64> {
    let mut found = Vec::new();
    for outline in outlines {
        for i in 0..outline.len() {
            let (a, b) = (outline[i], outline[(i + 1) % outline.len()]);
            if (a[1] < z) != (b[1] < z) {
                found.push(a[0] + (z - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
            }
        }
    }
    found.sort_unstable_by(f64::total_cmp);
    found
}

/// Wall thickness at stations along the profile: the horizontal width between the two
/// outermost crossings, times the cosine of the outer wall's slope there.
fn wall_thickness(outlines: &[Vec<[f64; 2]>], low: f64, high: f64, stations: usize) -> Vec<WallThickness> {
    let step = (high - low) / (stations + 1) as f64;
    (1..=stations)
        .filter_map(|k| {
            let z = low + step * k as f64;
            let here = crossings(outlines, z);
            if here.len() < 2 {
                return None;
            }
            let width = here[here.len() - 1] - here[here.len() - 2];
            let delta = (step / 2.0).min(1.0);
            let (below, above) = (crossings(outlines, z - delta), crossings(outlines, z + delta));
            let slope = match (below.last(), above.last()) {
                (Some(b), Some(a)) => (a - b) / (2.0 * delta),
                _ => 0.0,
            };
            Some(WallThickness { z_mm: z, thickness_mm: width / slope.hypot(1.0) })
        })
        .collect()
}

/// Volume inside the revolved cavity from the floor to the rim top, litres.
fn capacity_litres(outlines: &[Vec<[f64; 2]>], top: f64) -> Option<f64> {
    let points: Vec<[f64; 2]> = outlines.iter().flatten().copied().collect();
    let innermost = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    // The floor: the highest point of the section at its innermost radius (the base is
    // flat where it is broken off short of the axis).
    let floor = points.iter().filter(|p| p[0] <= innermost + 1.0).map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
    if !(top > floor) {
        return None;
    }
    let steps = ((top - floor) / 0.25).ceil().max(1.0) as usize;
    let dz = (top - floor) / steps as f64;
    let radius_at = |z: f64| crossings(outlines, z).first().copied().unwrap_or(0.0).max(0.0);
    let mut volume_mm3 = 0.0;
    let mut lower = radius_at(floor + 1e-6);
    for k in 1..=steps {
        let upper = radius_at((floor + dz * k as f64).min(top - 1e-6));
        volume_mm3 += std::f64::consts::PI * dz * (lower * lower + lower * upper + upper * upper) / 3.0;
        lower = upper;
    }
    Some(volume_mm3 * 1e-6)
}

/// Measures `mesh` oriented by `axis` (refined as `options.refine` says).
pub fn measure(mesh: &Mesh, axis: &Axis, options: &MeasureOptions) -> Measurements {
    measure_with_bootstrap_mesh(mesh, mesh, axis, options)
}

/// [`measure`], with the bootstrap of the intervals refining the axis on
/// `bootstrap_mesh` (a decimated copy of `mesh`: the pipeline's, for large scans) while
/// every measurement and its replicates are taken on `mesh` itself.
pub fn measure_with_bootstrap_mesh(mesh: &Mesh, bootstrap_mesh: &Mesh, axis: &Axis, options: &MeasureOptions) -> Measurements {
    let mut measurements = Measurements::default();
    if mesh.positions.len() < 10 {
        measurements.notes.push(format!("too few vertices to measure: {}", mesh.positions.len()));
        return measurements;
    }
    let oriented_with = |axis: &Axis| {
        let frame = oriented_frame(mesh, axis);
        mesh.positions.iter().map(|p| frame * p).collect::<Vec<Point>>()
    };
    let oriented = oriented_with(axis);
    let sector = sector_angle_rad(oriented.iter().map(|p| p.y.atan2(p.x)).collect()).to_degrees();
    measurements.sector_angle_deg = sector;
    measurements.sector_percent = sector / 360.0 * 100.0;
    let low = oriented.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
    let high = oriented.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max);
    measurements.height_mm = high - low;

    let (edges, outer_skin): (Vec<Edge>, Vec<bool>) =
        match PreparedSurface::new(mesh, axis, Surface::Both, options.refine.section_count) {
            Ok(surface) => {
                let skins: Vec<Skin> = surface.skins.iter().map(|skin| skin.unwrap_or(Skin::Other)).collect();
                measurements.rills = trace_rills(mesh, axis, &skins, &RillOptions::default());
                (
                    detect_edges_over(&surface, &options.refine, [MIN_MEASURED_RIM_FRACTION, EDGE_LEVEL_FRACTION]).into_iter().map(|e| e.edge).collect(),
                    surface.skins.iter().map(|s| *s == Some(Skin::Outer)).collect(),
                )
            }
            Err(error) => {
                measurements.notes.push(format!("no rim or base test: {error}"));
                (Vec::new(), vec![false; mesh.positions.len()])
            }
        };
    let has_rim = edges.contains(&Edge::Rim);
    let level_base = edges.contains(&Edge::Base);
    let has_base = level_base && reaches_base_edge(&oriented);
    if !has_rim {
        measurements.notes.push("no level rim preserved: no rim diameter".into());
    }
    if !level_base {
        measurements.notes.push("no level base preserved: no base diameter".into());
    } else if !has_base {
        measurements.notes.push("a piece of the floor that does not reach the base edge: no base diameter".into());
    }
    let section = profile_section(mesh, axis, most_informative_angle(mesh, axis));
    let outlines = section.closed_outlines();
    if let Some((_, _, z_low, z_high)) = section.bounds() {
        measurements.wall_thickness_profile = wall_thickness(&outlines, z_low, z_high, options.wall_thickness_stations);
        let mut values: Vec<f64> = measurements.wall_thickness_profile.iter().map(|w| w.thickness_mm).collect();
        measurements.wall_thickness_mm = (!values.is_empty()).then(|| quantile(&mut values, 0.5));
        if has_rim && has_base {
            measurements.capacity_litres = capacity_litres(&outlines, z_high);
        } else {
            measurements.notes.push("the profile does not run from base to rim: no capacity".into());
        }
    } else {
        measurements.notes.push("the profile section is empty".into());
    }
    let wall_mm = measurements.wall_thickness_mm.unwrap_or(DEFAULT_WALL_MM);
    measurements.rim_radius_mm = has_rim.then(|| edge_radius(&oriented, &outer_skin, Edge::Rim, wall_mm)).flatten();
    measurements.base_radius_mm = has_base.then(|| edge_radius(&oriented, &outer_skin, Edge::Base, wall_mm)).flatten();
    measurements.rim_diameter_mm = measurements.rim_radius_mm.map(|r| 2.0 * r);
    measurements.rim_sector_deg = measurements.rim_radius_mm.and_then(|r| edge_sector_deg(&oriented, Edge::Rim, r));
    measurements.base_sector_deg = measurements.base_radius_mm.and_then(|r| edge_sector_deg(&oriented, Edge::Base, r));
    measurements.base_diameter_mm = measurements.base_radius_mm.map(|r| 2.0 * r);

    match bootstrap_axes(bootstrap_mesh, axis, &options.refine, &options.bootstrap) {
        Ok(replicates) if !replicates.is_empty() => {
            measurements.axis_angle_interval_deg = angle_interval_deg(axis, &replicates, &options.bootstrap);
            measurements.axis_distance_interval_mm =
                distance_interval_mm(axis, &replicates, &bootstrap_mesh.positions, &options.bootstrap);
            let widen = |interval: &mut Option<[f64; 2]>, by: f64| {
                if let Some([_, upper]) = interval.as_mut().filter(|_| by.is_finite()) {
                    *upper = upper.hypot(by);
                }
            };
            if let Some((angle_deg, move_mm)) = options.axis_valley_width {
                // The turn moves the axis, at the sherd's points, by the turn times their
                // distance along the axis from their mean height, where it turns.
                let mean_height = oriented.iter().map(|p| p.z).sum::<f64>() / oriented.len() as f64;
                let along_mm = oriented.iter().map(|p| (p.z - mean_height).abs()).sum::<f64>() / oriented.len() as f64;
                let distance_mm = if angle_deg.is_finite() { move_mm.hypot(angle_deg.to_radians() * along_mm) } else { move_mm };
                widen(&mut measurements.axis_angle_interval_deg, angle_deg);
                widen(&mut measurements.axis_distance_interval_mm, distance_mm);
            }
            if let Some(reach) = options.axis_competitor_reach {
                widen(&mut measurements.axis_angle_interval_deg, reach.angle_deg);
                widen(&mut measurements.axis_distance_interval_mm, reach.distance_mm);
            }
            // The vessel's deformation, which the bootstrap does not resample, shows as
            // the axis's moves when a quarter of the arc is left out: their jackknife
            // standard error widens the intervals.
            let jackknife_axes = sector_jackknife_axes(bootstrap_mesh, axis, &options.refine);
            let jackknife_moves_mm: Vec<f64> =
                jackknife_axes.iter().map(|refined| mean_point_distance_mm(&bootstrap_mesh.positions, refined, axis)).collect();
            let jackknife_turns_deg: Vec<f64> = jackknife_axes.iter().map(|refined| refined.line_angle_to_deg(axis)).collect();
            if let Some(half_width_deg) = jackknife_half_width_95(&jackknife_turns_deg) {
                widen(&mut measurements.axis_angle_interval_deg, half_width_deg);
            }
            if let Some(half_width_mm) = jackknife_half_width_95(&jackknife_moves_mm) {
                widen(&mut measurements.axis_distance_interval_mm, half_width_mm);
            }
            if let Some([_, upper]) = measurements.axis_angle_interval_deg.filter(|i| i[1] > MAX_UNFLAGGED_AXIS_INTERVAL_DEG) {
                measurements.axis_doubts.push(format!(
                    "the axis's 95% angle interval reaches {upper:.1} degrees (more than {MAX_UNFLAGGED_AXIS_INTERVAL_DEG})"
                ));
            }
            if let Some([_, upper]) = measurements.axis_distance_interval_mm.filter(|i| i[1] > MAX_UNFLAGGED_AXIS_DISTANCE_MM) {
                measurements.axis_doubts.push(format!(
                    "the axis's 95% position interval reaches {upper:.1} mm of mean point distance (more than {MAX_UNFLAGGED_AXIS_DISTANCE_MM})"
                ));
            }
            let sector_move_mm = jackknife_moves_mm.iter().copied().reduce(f64::max);
            if let Some(moved_mm) = sector_move_mm.filter(|moved| *moved > MAX_UNFLAGGED_SECTOR_MOVE_MM) {
                measurements.axis_doubts.push(format!(
                    "refined without a quarter of the preserved arc, the axis moves by {moved_mm:.1} mm of mean point distance (more than {MAX_UNFLAGGED_SECTOR_MOVE_MM})"
                ));
            }
            if measurements.axis_angle_interval_deg.is_none() {
                measurements.axis_doubts.push(unrepeatable_doubt(replicates.len(), options.bootstrap.samples));
            }
            publish_axis_doubts(&mut measurements);
            // The rim's and the base's radii under each resampled or jackknifed axis. Each
            // axis's vertices are dropped once its radii are taken: kept all at once they
            // were 24 copies of the scan (140 MB for 500k faces).
            let radii_under = |axes: &[Axis]| -> Vec<[Option<f64>; 2]> {
                if !(has_rim || has_base) {
                    return Vec::new();
                }
                axes.iter()
                    .map(|other| {
                        let points = oriented_with(other);
                        let radius = |wanted: bool, edge: Edge| if wanted { edge_radius(&points, &outer_skin, edge, wall_mm) } else { None };
                        [radius(has_rim, Edge::Rim), radius(has_base, Edge::Base)]
                    })
                    .collect()
            };
            let replicate_radii = radii_under(&replicates);
            let jackknife_radii = radii_under(&jackknife_axes);
            let interval = |estimate: Option<f64>, edge: Edge| {
                let estimate = estimate?;
                let slot = if edge == Edge::Rim { 0 } else { 1 };
                let values: Vec<f64> = replicate_radii.iter().filter_map(|radii| radii[slot]).collect();
                let floor_fraction = match edge {
                    Edge::Rim => options.bootstrap.rim_diameter_floor_fraction,
                    Edge::Base => options.bootstrap.base_diameter_floor_fraction,
                };
                let [low, high] = value_interval(estimate, &values, estimate * floor_fraction, &options.bootstrap)?;
                let deviations: Vec<f64> = jackknife_radii.iter().filter_map(|radii| radii[slot]).map(|r| r - estimate).collect();
                let half_width = match jackknife_half_width_95(&deviations) {
                    Some(jackknife) => ((high - low) / 2.0).hypot(jackknife),
                    None => (high - low) / 2.0,
                };
                Some([2.0 * (estimate - half_width), 2.0 * (estimate + half_width)])
            };
            measurements.rim_diameter_interval_mm = interval(measurements.rim_radius_mm, Edge::Rim);
            measurements.base_diameter_interval_mm = interval(measurements.base_radius_mm, Edge::Base);
        }
        Ok(_) if options.bootstrap.samples == 0 => measurements.notes.push("no bootstrap: no intervals".into()),
        Ok(_) => {
            measurements.axis_doubts.push(unrepeatable_doubt(0, options.bootstrap.samples));
            publish_axis_doubts(&mut measurements);
        }
        Err(error) => measurements.notes.push(format!("no intervals: {error}")),
    }
    measurements
}
