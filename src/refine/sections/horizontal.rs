//! Horizontal sections: the chosen skins cut by planes perpendicular to a candidate axis,
//! exact plane cuts of the skin triangles, or slabs of vertices for a point cloud.

use rayon::prelude::*;

use super::frame::CandidateFrame;
use super::skins::Surface;
use super::surface::PreparedSurface;
use super::vertical::sector_angle_rad;
use crate::mesh::{planar_length, Point};
use crate::orient::Skin;

/// Skin triangles cut by one task of [`PreparedSurface::horizontal_sections`]: small
/// meshes stay in one or two tasks.
const TRIANGLES_PER_TASK: usize = 16_384;
/// Fewest skin triangles for which an evaluation's steps run on the thread pool. Each
/// parallel step hands its work to the pool and waits for it to come back; on a 20k-face
/// body sherd (2 cores) those hand-overs took more than half of an evaluation (kernel
/// scheduling under `perf`): cutting its sections took 452 us in parallel and 189 us on
/// one thread, and the circles refinement 360 ms against 150. On 2 cores one thread was
/// still 10-15% faster at 95k and 193k skin triangles, where more cores would win.
const PARALLEL_MIN_SKIN_TRIANGLES: usize = 4 * TRIANGLES_PER_TASK;

/// One horizontal section of one skin: points of the cut in the candidate frame's
/// xy-plane, with weights (cut segment lengths, or 1 per vertex in a slab).
#[derive(Clone, Debug, Default)]
pub struct HorizontalSection {
    /// Height of the plane in the candidate frame, millimetres.
    pub height_mm: f64,
    /// The skin cut.
    pub skin: Option<Skin>,
    /// Points of the cut, `[x, y]` in the candidate frame.
    pub points: Vec<[f64; 2]>,
    /// One positive weight per point.
    pub weights: Vec<f64>,
}

impl HorizontalSection {
    /// The preserved arc of the section about the candidate axis, radians: the full turn
    /// minus the largest angular gap between its points.
    pub fn sector_angle_rad(&self) -> f64 {
        sector_angle_rad(self.points.iter().map(|p| p[1].atan2(p[0])).collect())
    }
}

impl PreparedSurface {
    /// The horizontal sections of the chosen skins under a candidate frame.
    pub fn horizontal_sections(&self, frame: &CandidateFrame) -> Vec<HorizontalSection> {
        let skins: &[Skin] = match self.surface {
            Surface::Inner => &[Skin::Inner],
            Surface::Outer => &[Skin::Outer],
            Surface::Both => &[Skin::Inner, Skin::Outer],
        };
        let mut sections: Vec<HorizontalSection> = skins
            .iter()
            .flat_map(|&skin| {
                self.section_heights_mm.iter().map(move |&h| HorizontalSection {
                    height_mm: h,
                    skin: Some(skin),
                    ..Default::default()
                })
            })
            .collect();
        let count = self.section_heights_mm.len();
        let slot = |skin: Skin| if skins.len() == 2 && skin == Skin::Outer { count } else { 0 };
        let heights = &self.section_heights_mm;
        if self.has_faces() {
            // Every evaluation of a criterion moves all skin vertices and cuts all skin
            // triangles: on a large scan this is the whole cost of refinement, so it runs
            // on all cores, over contiguous runs of triangles whose cuts are appended in
            // their order (the sections are the same, point for point, as in one pass).
            // Each moved vertex carries the number of planes at or below it, so that the
            // planes a triangle crosses are the range between its corners' counts, and
            // the many triangles between two planes are passed over on three integers.
            // The moved vertices and their counts are kept apart: most triangles lie
            // between two planes and are passed over on their corners' counts alone
            // (4 bytes each, where a moved point takes 24), the points read only for
            // the triangles that are cut. Vertices off the skins are never read.
            // Below [`PARALLEL_MIN_SKIN_TRIANGLES`] it all runs on the calling thread.
            let parallel = self.skin_triangles.len() > PARALLEL_MIN_SKIN_TRIANGLES;
            let move_vertex = |(p, s): (&Point, &Option<Skin>)| if s.is_some() { frame.apply(p) } else { Point::origin() };
            let moved: Vec<Point> = if parallel {
                self.points.par_iter().zip(self.skins.par_iter()).map(move_vertex).collect()
            } else {
                self.points.iter().zip(&self.skins).map(move_vertex).collect()
            };
            let locate = PlaneLocator::new(heights);
            // Vertices off the skins are in no skin triangle: their rank is never read.
            let rank = |(q, s): (&Point, &Option<Skin>)| if s.is_some() { locate.planes_at_or_below(q.z) as u32 } else { 0 };
            let ranks: Vec<u32> = if parallel {
                moved.par_iter().zip(self.skins.par_iter()).map(rank).collect()
            } else {
                moved.iter().zip(&self.skins).map(rank).collect()
            };
            let cut_run = |run: &[([u32; 3], Skin)]| {
                // Room for a cut per four triangles spares most regrowths (they were
                // 5% of a 200k-face rim sherd's time under `perf record`).
                let mut cuts = Vec::with_capacity(run.len() / 4);
                for (triangle, skin) in run {
                    let ranks = triangle.map(|v| ranks[v as usize]);
                    let first_crossed = ranks[0].min(ranks[1]).min(ranks[2]) as usize;
                    let past_crossed = ranks[0].max(ranks[1]).max(ranks[2]) as usize;
                    if first_crossed == past_crossed {
                        continue;
                    }
                    // Plane `index` is crossed when one corner lies below it (count <=
                    // index) and one at or above it (count > index).
                    let corners = triangle.map(|v| moved[v as usize]);
                    for (index, &h) in heights.iter().enumerate().take(past_crossed).skip(first_crossed) {
                        if let Some((a, b)) = cut_triangle(&corners, h) {
                            let length = planar_length(a[0] - b[0], a[1] - b[1]);
                            if length > 0.0 {
                                cuts.push((slot(*skin) + index, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], length));
                            }
                        }
                    }
                }
                cuts
            };
            let cuts: Vec<Vec<(usize, [f64; 2], f64)>> = if parallel {
                self.skin_triangles.par_chunks(TRIANGLES_PER_TASK).map(cut_run).collect()
            } else {
                vec![cut_run(&self.skin_triangles)]
            };
            let mut cut_counts = vec![0usize; sections.len()];
            for (section_index, _, _) in cuts.iter().flatten() {
                cut_counts[*section_index] += 1;
            }
            for (section, &count) in sections.iter_mut().zip(&cut_counts) {
                section.points.reserve_exact(count);
                section.weights.reserve_exact(count);
            }
            for (section_index, point, length) in cuts.into_iter().flatten() {
                let section = &mut sections[section_index];
                section.points.push(point);
                section.weights.push(length);
            }
        } else {
            let half = self.slab_half_thickness_mm;
            for (p, skin) in self.skin_points_in(frame) {
                // Only the planes about `p.z` can hold it (the slabs are thinner than the
                // spacing); one plane of margin on each side, the exact test decides.
                let nearest = heights.partition_point(|&h| h < p.z - half).saturating_sub(1);
                let past = (heights.partition_point(|&h| h <= p.z + half) + 1).min(count);
                for (index, h) in heights.iter().enumerate().take(past).skip(nearest) {
                    if (p.z - h).abs() <= half {
                        let section = &mut sections[slot(skin) + index];
                        section.points.push([p.x, p.y]);
                        section.weights.push(1.0);
                    }
                }
            }
        }
        sections
    }
}

/// Counts the section planes at or below a height: a triangle's corners with counts
/// `i < j` lie on either side of planes `i..j` and of no other.
struct PlaneLocator<'a> {
    /// Plane heights, ascending.
    heights: &'a [f64],
    /// Planes per millimetre when they are evenly spaced (as `PreparedSurface::new`
    /// places them), 0 otherwise.
    planes_per_mm: f64,
}

impl<'a> PlaneLocator<'a> {
    fn new(heights: &'a [f64]) -> Self {
        let span = match heights {
            [first, .., last] => last - first,
            _ => 0.0,
        };
        let planes_per_mm = if span > 0.0 && span.is_finite() { (heights.len() - 1) as f64 / span } else { 0.0 };
        PlaneLocator { heights, planes_per_mm }
    }

    /// The number of planes at or below `z`, exactly `heights.partition_point(|&h| h <= z)`.
    /// Evenly spaced planes give the count from the spacing and a step or two of
    /// correction against the heights themselves (a binary search per vertex and per
    /// evaluation was a fifth of the refinement's time); any other spacing searches.
    fn planes_at_or_below(&self, z: f64) -> usize {
        let heights = self.heights;
        if self.planes_per_mm == 0.0 || !z.is_finite() {
            return heights.partition_point(|&h| h <= z);
        }
        // Truncation of a positive estimate is the floor (`f64::floor` is a call into
        // libm on the baseline target, `f64::clamp` checks its bounds on every call);
        // the loops below make any estimate exact.
        let estimate = (z - heights[0]) * self.planes_per_mm + 1.0;
        let mut count = if estimate > 0.0 { (estimate as usize).min(heights.len()) } else { 0 };
        while count > 0 && heights[count - 1] > z {
            count -= 1;
        }
        while count < heights.len() && heights[count] <= z {
            count += 1;
        }
        count
    }
}

/// The segment where the plane z = `height` cuts a triangle, if it does.
fn cut_triangle(corners: &[Point; 3], height: f64) -> Option<([f64; 2], [f64; 2])> {
    let mut crossings: [[f64; 2]; 2] = [[0.0; 2]; 2];
    let mut found = 0;
    for i in 0..3 {
        let (p, q) = (corners[i], corners[(i + 1) % 3]);
        // Half-open test so that a plane through a vertex counts it once.
        if (p.z < height) != (q.z < height) {
            let t = (height - p.z) / (q.z - p.z);
            if found < 2 {
                crossings[found] = [p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)];
            }
            found += 1;
        }
    }
    (found == 2).then_some((crossings[0], crossings[1]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every skin triangle cut by every plane, or every skin vertex tested against every
    /// slab: what `horizontal_sections` must give, point for point, bit for bit.
    fn sections_by_brute_force(surface: &PreparedSurface, frame: &CandidateFrame) -> Vec<(usize, [f64; 2], f64)> {
        let count = surface.section_heights_mm.len();
        let slot = |skin: Skin| if surface.surface == Surface::Both && skin == Skin::Outer { count } else { 0 };
        let mut cuts = Vec::new();
        if surface.has_faces() {
            for (triangle, skin) in &surface.skin_triangles {
                let corners = triangle.map(|v| frame.apply(&surface.points[v as usize]));
                for (index, &h) in surface.section_heights_mm.iter().enumerate() {
                    if let Some((a, b)) = cut_triangle(&corners, h) {
                        let length = planar_length(a[0] - b[0], a[1] - b[1]);
                        if length > 0.0 {
                            cuts.push((slot(*skin) + index, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0], length));
                        }
                    }
                }
            }
        } else {
            for (p, skin) in surface.skin_points_in(frame) {
                for (index, h) in surface.section_heights_mm.iter().enumerate() {
                    if (p.z - h).abs() <= surface.slab_half_thickness_mm {
                        cuts.push((slot(skin) + index, [p.x, p.y], 1.0));
                    }
                }
            }
        }
        // Sections collect their points in triangle (vertex) order: a stable sort by
        // section keeps that order within each.
        cuts.sort_by_key(|&(index, _, _)| index);
        cuts
    }

    fn flattened(sections: &[HorizontalSection]) -> Vec<(usize, [f64; 2], f64)> {
        sections
            .iter()
            .enumerate()
            .flat_map(|(index, s)| s.points.iter().zip(&s.weights).map(move |(p, w)| (index, *p, *w)))
            .collect()
    }

    #[test]
    fn sections_cut_only_the_planes_they_reach_yet_equal_every_plane_against_every_triangle() {
        use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};
        let sherd = synthetic_sherd(7, &SherdOptions { target_faces: 6_000, ..SherdOptions::for_part(SherdPart::Rim) });
        let mut cloud = sherd.mesh.clone();
        cloud.triangles.clear();
        let start = sherd.truth.axis;
        let candidates = [[0.0, 0.0, 0.0, 0.0], [0.03, -0.05, 1.5, -2.0], [-0.12, 0.09, -4.0, 3.0]];
        for (mesh, sections) in [(&sherd.mesh, None), (&cloud, Some(15)), (&sherd.mesh, Some(40))] {
            for surface_choice in [Surface::Both, Surface::Outer] {
                let surface = PreparedSurface::new(mesh, &start, surface_choice, sections).unwrap();
                for parameters in &candidates {
                    let frame = CandidateFrame::new(parameters);
                    let found = flattened(&surface.horizontal_sections(&frame));
                    let expected = sections_by_brute_force(&surface, &frame);
                    assert!(!expected.is_empty());
                    assert_eq!(found.len(), expected.len(), "faces: {}, {parameters:?}", surface.has_faces());
                    for (a, b) in found.iter().zip(&expected) {
                        let same = a.0 == b.0 && a.1.map(f64::to_bits) == b.1.map(f64::to_bits);
                        assert!(same && a.2.to_bits() == b.2.to_bits(), "{a:?} vs {b:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn plane_counts_from_the_spacing_equal_the_binary_search() {
        let even: Vec<f64> = (0..37).map(|i| -12.3 + 41.7 * i as f64 / 36.0).collect();
        let uneven = [-3.0, -1.0, 0.5, 0.5, 7.0];
        for heights in [&even[..], &uneven[..], &[2.0][..], &[][..]] {
            let locate = PlaneLocator::new(heights);
            let mut heights_and_between: Vec<f64> = heights.to_vec();
            heights_and_between.extend(heights.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            heights_and_between.extend(heights.iter().flat_map(|&h| [h - 1e-12, h + 1e-12]));
            heights_and_between.extend([-1e9, 1e9, f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
            for z in heights_and_between {
                assert_eq!(locate.planes_at_or_below(z), heights.partition_point(|&h| h <= z), "{z} in {heights:?}");
            }
        }
    }
}
