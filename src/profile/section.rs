//! The profile section (Wilczek et al. 2018, section 2.4.2): the cut of the oriented mesh by
//! the half-plane that contains the rotation axis at a given angle, as curves in the
//! rz-plane (`r_mm` = distance from the axis, `z_mm` = height along it, base to rim).
//!
//! Each triangle crossing the plane contributes one segment; segments are chained through
//! the mesh edges they cross, so a watertight fragment gives closed loops and a scan with
//! holes gives open chains ([`ProfileSection::closed_outlines`] closes those across the gaps,
//! the way an illustrator closes a section across a missing fracture face).

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

use nalgebra::Isometry3;
use rayon::prelude::*;

use crate::mesh::{planar_length, Mesh, Point};
use crate::orient::Axis;
use crate::{Error, Result};

/// One chained curve of a section, in the rz-plane.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileCurve {
    /// `[r_mm, z_mm]` points in order along the curve.
    pub points: Vec<[f64; 2]>,
    /// True when the curve is a loop (the last point joins the first, not repeated).
    pub closed: bool,
}

impl ProfileCurve {
    /// Length of the curve in millimetres, the closing segment included for loops.
    pub fn length_mm(&self) -> f64 {
        let open: f64 = self.points.windows(2).map(|w| distance(w[0], w[1])).sum();
        match (self.closed, self.points.first(), self.points.last()) {
            (true, Some(&first), Some(&last)) => open + distance(first, last),
            _ => open,
        }
    }

    /// Signed area (shoelace) of the polygon the points make, positive counter-clockwise
    /// in the (r, z) plane. Open curves are treated as if closed.
    pub fn signed_area_mm2(&self) -> f64 {
        polygon_signed_area(&self.points)
    }
}

/// The cut of a mesh by one half-plane through the axis.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileSection {
    /// Angle of the half-plane about the axis, in the frame [`oriented_frame`] gives
    /// (0 = the half-plane through the fragment's centroid).
    pub angle_rad: f64,
    /// The chained curves, longest first.
    pub curves: Vec<ProfileCurve>,
}

impl ProfileSection {
    /// True when the half-plane missed the mesh.
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty()
    }

    /// `(r_min, r_max, z_min, z_max)` of all points, or `None` when empty.
    pub fn bounds(&self) -> Option<(f64, f64, f64, f64)> {
        let mut points = self.curves.iter().flat_map(|c| c.points.iter());
        let first = *points.next()?;
        Some(points.fold((first[0], first[0], first[1], first[1]), |(r0, r1, z0, z1), p| {
            (r0.min(p[0]), r1.max(p[0]), z0.min(p[1]), z1.max(p[1]))
        }))
    }

    /// Total length of all curves, in millimetres.
    pub fn length_mm(&self) -> f64 {
        self.curves.iter().map(ProfileCurve::length_mm).sum()
    }

    /// Closed polygons ready to fill: the loops as they are, and the open chains (a scan
    /// with holes, or a cut through a missing fracture face) joined end to start by
    /// their nearest free ends into loops, across the gaps.
    pub fn closed_outlines(&self) -> Vec<Vec<[f64; 2]>> {
        let mut outlines: Vec<Vec<[f64; 2]>> =
            self.curves.iter().filter(|c| c.closed && c.points.len() >= 3).map(|c| c.points.clone()).collect();
        let mut open: Vec<Vec<[f64; 2]>> =
            self.curves.iter().filter(|c| !c.closed && c.points.len() >= 2).map(|c| c.points.clone()).collect();
        while let Some(mut chain) = open.pop() {
            // Greedily append the open chain whose nearer end is closest to this chain's
            // end, until the chain's own start is the closest end.
            loop {
                let end = *chain.last().expect("chains have points");
                let start = chain[0];
                let mut best: Option<(f64, usize, bool)> = None;
                for (i, other) in open.iter().enumerate() {
                    let head = distance(end, other[0]);
                    let tail = distance(end, *other.last().expect("chains have points"));
                    let (d, reversed) = if head <= tail { (head, false) } else { (tail, true) };
                    if best.is_none_or(|(b, _, _)| d < b) {
                        best = Some((d, i, reversed));
                    }
                }
                match best {
                    Some((d, i, reversed)) if d < distance(end, start) => {
                        let mut next = open.swap_remove(i);
                        if reversed {
                            next.reverse();
                        }
                        chain.extend(next);
                    }
                    _ => break,
                }
            }
            if chain.len() >= 3 {
                outlines.push(chain);
            }
        }
        outlines
    }

    /// The section as CSV: `curve,index,r_mm,z_mm,closed`, one line per point.
    pub fn to_csv(&self) -> String {
        let mut csv = String::from("curve,index,r_mm,z_mm,closed\n");
        for (c, curve) in self.curves.iter().enumerate() {
            for (i, p) in curve.points.iter().enumerate() {
                let _ = writeln!(csv, "{c},{i},{:.6},{:.6},{}", p[0], p[1], curve.closed);
            }
        }
        csv
    }

    /// Writes [`ProfileSection::to_csv`] to `path` atomically.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        crate::mesh::atomic::write_bytes_atomically(path, self.to_csv().as_bytes())
    }

    /// The curves as the `d` attribute of an SVG path, in millimetres times
    /// `units_per_mm`, x = r and y = -z (SVG's y points down, so the rim stays at the top).
    /// Loops end with `Z`.
    pub fn to_svg_path(&self, units_per_mm: f64) -> String {
        let mut d = String::new();
        for curve in &self.curves {
            for (i, p) in curve.points.iter().enumerate() {
                let command = if i == 0 { 'M' } else { 'L' };
                let _ = write!(d, "{command}{:.4} {:.4} ", p[0] * units_per_mm, -p[1] * units_per_mm);
            }
            if curve.closed {
                d.push_str("Z ");
            }
        }
        d.truncate(d.trim_end().len());
        d
    }
}

/// The oriented frame every profile, measurement and drawing of `mesh` uses: the axis on
/// z (base to rim) and the fragment's centroid on the +x half-plane (angle 0). For a
/// whole vessel the centroid lies on the axis and angle 0 is arbitrary.
pub fn oriented_frame(mesh: &Mesh, axis: &Axis) -> Isometry3<f64> {
    let reference = mesh.centroid().unwrap_or(axis.point);
    axis.to_oriented_frame(&reference)
}

/// The mesh's vertex positions in [`oriented_frame`].
pub fn oriented_positions(mesh: &Mesh, axis: &Axis) -> Vec<Point> {
    let frame = oriented_frame(mesh, axis);
    mesh.positions.par_iter().map(|p| frame * p).collect()
}

/// The section of `mesh` by the half-plane at `angle_rad` about `axis` (angle 0 passes
/// through the centroid, see [`oriented_frame`]).
pub fn profile_section(mesh: &Mesh, axis: &Axis, angle_rad: f64) -> ProfileSection {
    section_of_oriented(mesh, &oriented_positions(mesh, axis), angle_rad)
}

/// [`profile_section`] for positions already in the oriented frame (`oriented[i]` is
/// vertex `i`), so that callers cutting many angles transform the mesh once.
pub fn section_of_oriented(mesh: &Mesh, oriented: &[Point], angle_rad: f64) -> ProfileSection {
    let segments = crossing_segments(mesh, oriented, angle_rad);
    let mut curves = chain_segments(&segments);
    curves.sort_by(|a, b| b.length_mm().total_cmp(&a.length_mm()));
    ProfileSection { angle_rad, curves }
}

/// The angle of the most informative profile: among cuts across the fragment's angular
/// extent, those with the tallest section (within 1% of the tallest), and of these the
/// one nearest the middle of the run, away from the fracture faces where cuts graze.
pub fn most_informative_angle(mesh: &Mesh, axis: &Axis) -> f64 {
    let oriented = oriented_positions(mesh, axis);
    let (low, high) = angular_extent(&oriented);
    const SAMPLES: usize = 96;
    let angles: Vec<f64> = (0..SAMPLES).map(|i| low + (high - low) * (i as f64 + 0.5) / SAMPLES as f64).collect();
    let heights = section_heights(mesh, &oriented, low, high, SAMPLES);
    let best = heights.iter().copied().fold(0.0, f64::max);
    if best <= 0.0 {
        return 0.0;
    }
    // The longest run of consecutive near-best angles, and its middle.
    let good: Vec<bool> = heights.iter().map(|&h| h >= 0.99 * best).collect();
    let (mut best_run, mut run_start) = ((0usize, 0usize), None);
    for i in 0..=SAMPLES {
        match (i < SAMPLES && good.get(i) == Some(&true), run_start) {
            (true, None) => run_start = Some(i),
            (false, Some(s)) => {
                if i - s > best_run.1 - best_run.0 {
                    best_run = (s, i);
                }
                run_start = None;
            }
            _ => {}
        }
    }
    angles[(best_run.0 + best_run.1 - 1) / 2]
}

/// Height (z extent) of the sections at `samples` angles evenly spread over
/// `[low, high]`, in one pass over the triangles: each triangle adds its z range to the
/// few angles its angular range spans (usually none or one), instead of cutting the whole
/// mesh once per angle. The z range of a crossing triangle bounds its cut segment's, so
/// heights are over-estimated by at most one triangle's size.
fn section_heights(mesh: &Mesh, oriented: &[Point], low: f64, high: f64, samples: usize) -> Vec<f64> {
    use std::f64::consts::{PI, TAU};
    let step = (high - low) / samples as f64;
    let wraps = high - low >= TAU - 1e-9;
    let theta: Vec<f64> = oriented.par_iter().map(|p| p.y.atan2(p.x)).collect();
    let empty = || vec![(f64::INFINITY, f64::NEG_INFINITY); samples];
    let ranges = mesh
        .triangles
        .par_iter()
        .fold(empty, |mut ranges, tri| {
            let t0 = theta[tri[0] as usize];
            // Unwrap the corners' angles next to the first one.
            let unwrap = |t: f64| t0 + (t - t0 + PI).rem_euclid(TAU) - PI;
            let (t1, t2) = (unwrap(theta[tri[1] as usize]), unwrap(theta[tri[2] as usize]));
            let (t_min, t_max) = (t0.min(t1).min(t2), t0.max(t1).max(t2));
            if t_max - t_min > PI / 2.0 {
                return ranges; // straddles the axis: its angles mean nothing
            }
            let zs = tri.map(|v| oriented[v as usize].z);
            let (z_min, z_max) = (zs[0].min(zs[1]).min(zs[2]), zs[0].max(zs[1]).max(zs[2]));
            // Sample i sits at low + (i + 0.5) step; try the span and, when the fragment
            // wraps round, the span shifted by a turn.
            for shift in if wraps { [-TAU, 0.0, TAU].as_slice() } else { [0.0].as_slice() } {
                let first = ((t_min + shift - low) / step - 0.5).ceil().max(0.0) as i64;
                let last = (((t_max + shift - low) / step - 0.5).floor() as i64).min(samples as i64 - 1);
                for i in first..=last {
                    let r = &mut ranges[i as usize];
                    *r = (r.0.min(z_min), r.1.max(z_max));
                }
            }
            ranges
        })
        .reduce(empty, |mut a, b| {
            for (x, y) in a.iter_mut().zip(b) {
                *x = (x.0.min(y.0), x.1.max(y.1));
            }
            a
        });
    ranges.iter().map(|&(lo, hi)| if hi >= lo { hi - lo } else { 0.0 }).collect()
}

/// Angular range `(low, high)` covered by the oriented vertices, radians around 0 (the
/// centroid's direction). A fragment wrapping most of the way round gives `(-PI, PI)`.
pub fn angular_extent(oriented: &[Point]) -> (f64, f64) {
    use std::f64::consts::PI;
    let (low, high) = oriented
        .iter()
        .filter(|p| p.x * p.x + p.y * p.y > 1e-18)
        .map(|p| p.y.atan2(p.x))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), a| (lo.min(a), hi.max(a)));
    if !(high > low) || high - low > 1.9 * PI { (-PI, PI) } else { (low, high) }
}

/// An end of a segment: the mesh edge it lies on (`None` when it was clipped at the axis)
/// and its `[r, z]`.
type SegmentEnd = (Option<(u32, u32)>, [f64; 2]);

struct Segment {
    ends: [SegmentEnd; 2],
}

/// The segments where triangles cross the half-plane at `angle_rad`. A vertex exactly on
/// the plane counts as on its positive side, so each crossing triangle has exactly two
/// crossing edges and neighbouring triangles agree on the shared one.
fn crossing_segments(mesh: &Mesh, oriented: &[Point], angle_rad: f64) -> Vec<Segment> {
    let (sin, cos) = angle_rad.sin_cos();
    let side = |p: &Point| -sin * p.x + cos * p.y;
    let radial = |p: &Point| cos * p.x + sin * p.y;
    mesh.triangles
        .par_iter()
        .filter_map(|tri| {
            let distances = tri.map(|v| side(&oriented[v as usize]));
            let positive = distances.map(|d| d >= 0.0);
            if positive[0] == positive[1] && positive[1] == positive[2] {
                return None;
            }
            let mut ends: [SegmentEnd; 2] = [(None, [0.0; 2]); 2];
            let mut count = 0;
            for k in 0..3 {
                let (i, j) = (k, (k + 1) % 3);
                if positive[i] != positive[j] {
                    let t = distances[i] / (distances[i] - distances[j]);
                    let (a, b) = (&oriented[tri[i] as usize], &oriented[tri[j] as usize]);
                    let p = a + (b - a) * t;
                    let key = (tri[i].min(tri[j]), tri[i].max(tri[j]));
                    ends[count] = (Some(key), [radial(&p), p.z]);
                    count += 1;
                }
            }
            clip_to_half_plane(ends).map(|ends| Segment { ends })
        })
        .collect()
}

/// Keeps the part of a segment with `r >= 0` (the half-plane, not the opposite one).
fn clip_to_half_plane(ends: [SegmentEnd; 2]) -> Option<[SegmentEnd; 2]> {
    let (r0, r1) = (ends[0].1[0], ends[1].1[0]);
    match (r0 >= 0.0, r1 >= 0.0) {
        (true, true) => Some(ends),
        (false, false) => None,
        (inside_first, _) => {
            let t = r0 / (r0 - r1);
            let (a, b) = (ends[0].1, ends[1].1);
            let on_axis: SegmentEnd = (None, [0.0, a[1] + (b[1] - a[1]) * t]);
            Some(if inside_first { [ends[0], on_axis] } else { [on_axis, ends[1]] })
        }
    }
}

/// Chains segments sharing mesh edges into curves.
fn chain_segments(segments: &[Segment]) -> Vec<ProfileCurve> {
    let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::with_capacity(segments.len() * 2);
    for (s, segment) in segments.iter().enumerate() {
        for end in &segment.ends {
            if let Some(key) = end.0 {
                by_edge.entry(key).or_default().push(s);
            }
        }
    }
    let mut used = vec![false; segments.len()];
    // Walks from segment `s` leaving through `exit` (0 or 1), appending far ends.
    let walk = |s: usize, exit: usize, used: &mut Vec<bool>, out: &mut Vec<[f64; 2]>| -> Option<(u32, u32)> {
        let (mut current, mut exit) = (s, exit);
        loop {
            let key = segments[current].ends[exit].0?;
            let next = by_edge[&key].iter().copied().find(|&n| !used[n]);
            let Some(next) = next else { return Some(key) };
            used[next] = true;
            let entry = if segments[next].ends[0].0 == Some(key) { 0 } else { 1 };
            exit = 1 - entry;
            out.push(segments[next].ends[exit].1);
            current = next;
        }
    };
    let mut curves = Vec::new();
    for s in 0..segments.len() {
        if used[s] {
            continue;
        }
        used[s] = true;
        let mut forward = vec![segments[s].ends[0].1, segments[s].ends[1].1];
        let end_key = walk(s, 1, &mut used, &mut forward);
        let start_key = segments[s].ends[0].0;
        let closed = end_key.is_some() && end_key == start_key && forward.len() > 3;
        if closed {
            forward.pop(); // the walk came back to the first point
        } else {
            let mut backward = Vec::new();
            walk(s, 0, &mut used, &mut backward);
            backward.reverse();
            backward.extend(forward);
            forward = backward;
        }
        curves.push(ProfileCurve { points: forward, closed });
    }
    curves
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    planar_length(a[0] - b[0], a[1] - b[1])
}

/// Shoelace area of a polygon given by its vertices (closing edge implied).
pub fn polygon_signed_area(points: &[[f64; 2]]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        * 0.5
}

/// Checks that `angle_rad` is finite, for entry points taking it from users.
pub fn check_angle(angle_rad: f64) -> Result<()> {
    if angle_rad.is_finite() {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!("section angle {angle_rad} is not a finite number of radians")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Vector;
    use nalgebra::{Translation3, UnitQuaternion};
    use std::f64::consts::PI;

    /// A closed polygon in the rz-plane revolved over `[theta0, theta1]` with `steps`
    /// steps; the sector's two end faces are capped with fans (so the mesh is watertight)
    /// unless the sweep is a full turn.
    fn revolved_wall(profile: &[[f64; 2]], theta0: f64, theta1: f64, steps: usize, top_tilt_mm_per_rad: f64) -> Mesh {
        let full = (theta1 - theta0 - 2.0 * PI).abs() < 1e-12;
        let rings = if full { steps } else { steps + 1 };
        let n = profile.len();
        let z_max = profile.iter().map(|p| p[1]).fold(f64::MIN, f64::max);
        let mut positions = Vec::new();
        for k in 0..rings {
            let theta = theta0 + (theta1 - theta0) * k as f64 / steps as f64;
            for p in profile {
                // Tilting the top edge makes the tallest section sit at one end.
                let lift = if (p[1] - z_max).abs() < 1e-12 { top_tilt_mm_per_rad * theta } else { 0.0 };
                positions.push(Point::new(p[0] * theta.cos(), p[0] * theta.sin(), p[1] + lift));
            }
        }
        let mut triangles = Vec::new();
        for k in 0..steps {
            let (a, b) = (k % rings, (k + 1) % rings);
            for i in 0..n {
                let j = (i + 1) % n;
                let (p0, p1, q0, q1) = (a * n + i, a * n + j, b * n + i, b * n + j);
                triangles.push([p0 as u32, q0 as u32, q1 as u32]);
                triangles.push([p0 as u32, q1 as u32, p1 as u32]);
            }
        }
        if !full {
            for (ring, flip) in [(0, true), (rings - 1, false)] {
                let base = (ring * n) as u32;
                for i in 1..n as u32 - 1 {
                    triangles.push(if flip { [base, base + i + 1, base + i] } else { [base, base + i, base + i + 1] });
                }
            }
        }
        Mesh::new(positions, triangles)
    }

    fn wall_profile() -> Vec<[f64; 2]> {
        // Outer r = 55, inner r = 50, from z = 0 to z = 40, with extra points on the
        // long sides so the wall has several rings of vertices.
        let mut p = Vec::new();
        for i in 0..=4 {
            p.push([55.0, 10.0 * i as f64]);
        }
        for i in (0..=4).rev() {
            p.push([50.0, 10.0 * i as f64]);
        }
        p
    }

    fn moved(mesh: &Mesh, axis: &Axis) -> (Mesh, Axis) {
        let motion = Isometry3::from_parts(
            Translation3::new(12.0, -30.0, 7.5),
            UnitQuaternion::from_scaled_axis(Vector::new(0.4, -0.9, 0.3)),
        );
        let mut out = mesh.clone();
        out.transform(&motion);
        (out, axis.transformed(&motion))
    }

    #[test]
    fn full_revolution_gives_one_closed_rectangle() {
        let mesh = revolved_wall(&wall_profile(), 0.0, 2.0 * PI, 180, 0.0);
        let (mesh, axis) = moved(&mesh, &Axis::z());
        for angle in [0.0, 0.3, 1.0, 2.5, -2.0] {
            let section = profile_section(&mesh, &axis, angle);
            assert_eq!(section.curves.len(), 1, "angle {angle}");
            let curve = &section.curves[0];
            assert!(curve.closed);
            let (r0, r1, z0, z1) = section.bounds().unwrap();
            // Cuts between rings see the chord: r * cos(half step) at worst.
            let chord = (PI / 180.0).cos();
            assert!(r0 > 50.0 * chord - 1e-9 && r0 <= 50.0 + 1e-9, "r0 {r0}");
            assert!(r1 > 55.0 * chord - 1e-9 && r1 <= 55.0 + 1e-9, "r1 {r1}");
            let height = z1 - z0;
            assert!((height - 40.0).abs() < 1e-9, "height {height}");
            assert!((curve.signed_area_mm2().abs() - 200.0).abs() < 200.0 * 0.002, "area {}", curve.signed_area_mm2());
            assert!((curve.length_mm() - 90.0).abs() < 0.2);
            assert_eq!(section.closed_outlines().len(), 1);
        }
    }

    #[test]
    fn sector_with_caps_is_cut_only_on_its_side_and_tallest_angle_is_found() {
        // A 60 degree sector from -30 to +30 deg whose top rises 8 mm per radian: the
        // tallest sections are at +30 deg, but the chosen angle keeps clear of the cap.
        let mesh = revolved_wall(&wall_profile(), -PI / 6.0, PI / 6.0, 60, 8.0);
        let (mesh, axis) = moved(&mesh, &Axis::z());
        let behind = profile_section(&mesh, &axis, PI);
        assert!(behind.is_empty(), "the opposite half-plane must not cut the fragment");
        let angle = most_informative_angle(&mesh, &axis);
        let section = profile_section(&mesh, &axis, angle);
        let (_, _, z0, z1) = section.bounds().unwrap();
        let tallest = 40.0 + 8.0 * PI / 6.0;
        // The centroid sits a little off 0 deg because the top is tilted; the angle is
        // within the last percent of height below the tallest.
        assert!(z1 - z0 >= 0.99 * tallest - 0.1, "height {} of {}", z1 - z0, tallest);
        assert!(section.curves[0].closed && section.curves.len() == 1);
    }

    #[test]
    fn scan_with_a_hole_gives_open_chains_closed_across_the_gap() {
        let mut mesh = revolved_wall(&wall_profile(), 0.0, 2.0 * PI, 120, 0.0);
        // Remove the faces of the outer wall's strip between z = 10 and 20 near angle 0.
        let n = wall_profile().len();
        mesh.triangles.retain(|t| {
            let ring = (t[0] as usize) / n;
            let i = (t[0] as usize) % n;
            !((ring == 0 || ring == 119) && i == 1)
        });
        // The centroid of a full turn is on the axis, so angle 0 is arbitrary: aim at the hole.
        let hole = oriented_frame(&mesh, &Axis::z()) * Point::new(55.0, 0.0, 15.0);
        let section = profile_section(&mesh, &Axis::z(), hole.y.atan2(hole.x) + 0.01);
        assert!(section.curves.iter().all(|c| !c.closed), "a hole opens the loop: {:?}", section.curves);
        let outlines = section.closed_outlines();
        assert_eq!(outlines.len(), 1);
        let area = polygon_signed_area(&outlines[0]).abs();
        assert!((area - 200.0).abs() < 1.0, "area {area}");
    }

    #[test]
    fn base_crossing_the_axis_is_clipped_at_r_zero() {
        // A closed "dish": a disc-like wall through the axis, cut at every angle.
        let profile = vec![[0.0, 0.0], [40.0, 0.0], [40.0, 5.0], [0.0, 5.0]];
        let mesh = revolved_wall(&profile, 0.0, 2.0 * PI, 64, 0.0);
        let section = profile_section(&mesh, &Axis::z(), 0.2);
        let (r0, r1, _, _) = section.bounds().unwrap();
        assert!((0.0..1e-9).contains(&r0) && (r1 - 40.0).abs() < 0.2);
    }

    #[test]
    fn exports_are_well_formed() {
        let mesh = revolved_wall(&wall_profile(), 0.0, 2.0 * PI, 36, 0.0);
        let section = profile_section(&mesh, &Axis::z(), 0.1);
        let csv = section.to_csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "curve,index,r_mm,z_mm,closed");
        assert_eq!(lines.len() - 1, section.curves[0].points.len());
        let fields: Vec<&str> = lines[1].split(',').collect();
        assert_eq!(fields.len(), 5);
        assert!(fields[2].parse::<f64>().unwrap() >= 49.0);
        let d = section.to_svg_path(2.0);
        assert!(d.starts_with('M') && d.ends_with('Z'));
        assert_eq!(d.matches('L').count() + 1, section.curves[0].points.len());
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("profile.csv");
        section.write_csv(&path).unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), csv);
        assert!(check_angle(f64::NAN).is_err());
    }
}
