//! The vertices of each vertical section that may be its extreme under a candidate
//! frame, ordered so that the search for the extreme can stop early on a bound.

use super::Edge;
use crate::mesh::{planar_length, Point};
use crate::refine::sections::CandidateFrame;

/// The vertices of one vertical section that may be its extreme, ordered from the
/// extreme in the start frame inwards (highest first for a rim, lowest first for a base),
/// so that the search under a candidate frame stops once no later vertex can beat the
/// best found (see [`SectionCandidates::extreme`]).
pub(super) struct SectionCandidates {
    /// Start-frame points, extreme first.
    points: Vec<Point>,
    /// Each point's position in the section's vertex order (ties go as they did there).
    order: Vec<usize>,
    /// Mean `(x, y)` of the section's points, start frame.
    centre_xy: [f64; 2],
    /// `reach_mm[i]`: the largest horizontal distance to `centre_xy` among `points[i..]`.
    reach_mm: Vec<f64>,
    /// Rounding allowance of the bound, mm (far above the rounding of a coordinate).
    slack_mm: f64,
}

impl SectionCandidates {
    pub(super) fn new(mut points: Vec<(usize, Point)>, edge: Edge) -> Self {
        // Ties in section order: what a stable sort of the points as they come (in that
        // order) gives, at the cost of an unstable sort.
        match edge {
            Edge::Rim => points.sort_unstable_by(|a, b| b.1.z.total_cmp(&a.1.z).then(a.0.cmp(&b.0))),
            Edge::Base => points.sort_unstable_by(|a, b| a.1.z.total_cmp(&b.1.z).then(a.0.cmp(&b.0))),
        }
        let count = points.len().max(1) as f64;
        let centre_xy = [
            points.iter().map(|(_, p)| p.x).sum::<f64>() / count,
            points.iter().map(|(_, p)| p.y).sum::<f64>() / count,
        ];
        let mut reach_mm: Vec<f64> =
            points.iter().map(|(_, p)| planar_length(p.x - centre_xy[0], p.y - centre_xy[1])).collect();
        for i in (0..reach_mm.len().saturating_sub(1)).rev() {
            reach_mm[i] = reach_mm[i].max(reach_mm[i + 1]);
        }
        let magnitude = points.iter().map(|(_, p)| p.coords.amax()).fold(0.0, f64::max);
        SectionCandidates {
            order: points.iter().map(|&(i, _)| i).collect(),
            points: points.into_iter().map(|(_, p)| p).collect(),
            centre_xy,
            reach_mm,
            slack_mm: 1e-9 * (1.0 + magnitude),
        }
    }

    /// The largest height signed outward (up for a rim, down for a base) that a point
    /// from the `i`-th on can reach under `frame`, as a function of `i` (see [`Self::extreme`]);
    /// `None` for an upside-down frame (never searched), which would reverse the order:
    /// every point is moved then.
    fn outward_bound(&self, frame: &CandidateFrame, edge: Edge) -> Option<impl Fn(usize) -> f64 + '_> {
        let d = frame.direction();
        if !(d.z > 0.0) {
            return None;
        }
        let offset = frame.apply(&Point::origin()).z;
        let tilt = d.x.hypot(d.y);
        let centred = d.x * self.centre_xy[0] + d.y * self.centre_xy[1] + offset;
        let outward = edge.outward();
        Some(move |i: usize| outward * (d.z * self.points[i].z + centred) + (tilt * self.reach_mm[i] + self.slack_mm))
    }

    /// The extreme point under `frame`, the same as the `max_by`/`min_by` over all
    /// points in their section order (the last highest, the first lowest), found
    /// without moving most of them: under a frame with direction `d` and offset `o`
    /// (the height of the start origin), a point's height is `d . p + o`, at most
    /// `d_z p_z + d_xy . c + |d_xy| reach + o` (at least, with `-|d_xy| reach`, for a
    /// base); the points come extreme first, so the bound only shrinks along them.
    pub(super) fn extreme(&self, frame: &CandidateFrame, edge: Edge) -> Option<Point> {
        let bound = self.outward_bound(frame, edge);
        // (height under the frame, order, index): only the heights are compared, the
        // winner alone is moved whole.
        let mut best: Option<(f64, usize, usize)> = None;
        for (i, (p, &order)) in self.points.iter().zip(&self.order).enumerate() {
            if let (Some(bound), Some((found_z, _, _))) = (&bound, &best) {
                if bound(i) < edge.outward() * found_z {
                    break;
                }
            }
            let height = frame.height(p);
            let better = match &best {
                None => true,
                Some((found_z, found_order, _)) => match (edge, height.total_cmp(found_z)) {
                    (_, std::cmp::Ordering::Equal) => match edge {
                        Edge::Rim => order > *found_order,
                        Edge::Base => order < *found_order,
                    },
                    (Edge::Rim, ordering) => ordering.is_gt(),
                    (Edge::Base, ordering) => ordering.is_lt(),
                },
            };
            if better {
                best = Some((height, order, i));
            }
        }
        best.map(|(_, _, i)| frame.apply(&self.points[i]))
    }

    /// The extreme point under `frame` and the section's points within `band_mm` of it,
    /// both in the candidate frame. `None` for an empty section.
    pub(super) fn lip_band(&self, frame: &CandidateFrame, edge: Edge, band_mm: f64) -> Option<(Point, Vec<Point>)> {
        let extreme = self.extreme(frame, edge)?;
        let outward = edge.outward();
        let bound = self.outward_bound(frame, edge);
        let lowest = outward * extreme.z - band_mm;
        let mut band = Vec::new();
        for (i, p) in self.points.iter().enumerate() {
            if bound.as_ref().is_some_and(|bound| bound(i) < lowest) {
                break;
            }
            let q = frame.apply(p);
            if outward * q.z >= lowest {
                band.push(q);
            }
        }
        Some((extreme, band))
    }
}

/// Vertices farther than this from the start frame's extreme cannot become the extreme
/// of their section for tilts within the search bound on fragments up to ~0.5 m.
pub(super) const CANDIDATE_BAND_MM: f64 = 40.0;

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::TangentObjective;
    use crate::refine::sections::{vertical_sections, PreparedSurface, Surface};
    use crate::synth::{synthetic_sherd, SherdOptions, SherdPart};

    #[test]
    fn bounded_extreme_search_finds_the_same_points_as_moving_every_candidate() {
        let options = SherdOptions { target_faces: 8_000, ..SherdOptions::for_part(SherdPart::RimToBase) };
        let sherd = synthetic_sherd(11, &options);
        let surface = PreparedSurface::new(&sherd.mesh, &sherd.truth.axis, Surface::Both, None).unwrap();
        for edge in [Edge::Rim, Edge::Base] {
            let objective = TangentObjective::new(&surface, edge, 3.0, 24);
            let sections = vertical_sections(&surface.points, 24);
            let candidates = [[0.0, 0.0, 0.0, 0.0], [0.02, -0.04, 1.0, 2.0], [-0.17, 0.15, -5.0, 0.5], [0.3, 0.0, 0.0, 0.0]];
            for parameters in candidates {
                let frame = CandidateFrame::new(&parameters);
                let found = objective.extreme_points(&frame);
                // The plain search: every candidate moved, the last highest or first lowest.
                let expected: Vec<Point> = sections
                    .iter()
                    .filter(|indices| !indices.is_empty())
                    .map(|indices| {
                        let points: Vec<Point> = indices.iter().map(|&i| surface.points[i]).collect();
                        let extreme = match edge {
                            Edge::Rim => points.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
                            Edge::Base => points.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
                        };
                        let near = points.iter().filter(|p| (p.z - extreme).abs() <= CANDIDATE_BAND_MM);
                        let moved = near.map(|p| frame.apply(p));
                        match edge {
                            Edge::Rim => moved.max_by(|a, b| a.z.total_cmp(&b.z)),
                            Edge::Base => moved.min_by(|a, b| a.z.total_cmp(&b.z)),
                        }
                        .unwrap()
                    })
                    .collect();
                assert_eq!(found.len(), expected.len());
                for (a, b) in found.iter().zip(&expected) {
                    assert_eq!(a.coords.map(f64::to_bits), b.coords.map(f64::to_bits), "{edge:?} {parameters:?}");
                }
            }
        }
    }

    #[test]
    fn ties_go_to_the_last_highest_and_the_first_lowest_as_in_section_order() {
        // Three points at one height: under the start frame the plain max_by keeps the
        // last, min_by the first.
        let points: Vec<(usize, Point)> =
            [1.0, 2.0, 3.0].iter().enumerate().map(|(i, &x)| (i, Point::new(x, 0.0, 5.0))).collect();
        let frame = CandidateFrame::new(&[0.0; 4]);
        let rim = SectionCandidates::new(points.clone(), Edge::Rim).extreme(&frame, Edge::Rim).unwrap();
        let base = SectionCandidates::new(points, Edge::Base).extreme(&frame, Edge::Base).unwrap();
        assert_eq!((rim.x, base.x), (3.0, 1.0));
    }
}
