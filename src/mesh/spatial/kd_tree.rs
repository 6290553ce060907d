//! The k-d tree over points: nearest, k-nearest and radius queries.
//!
//! The k-d tree is implicit: points are reordered so that every subrange `[lo, hi)` holds
//! its median at `lo + (hi - lo) / 2`, with the split axis stored beside it; subranges of
//! at most 8 points (`KD_LEAF_SIZE`) are scanned linearly.

// Relative, not `crate::mesh`: benches/kiddo_comparison compiles this directory in, with
// stand-ins for the mesh types at its crate root.
use super::super::Point;
use super::coords::{grow, squared_distance, PARALLEL_BUILD_MIN};

/// Largest number of points a k-d tree leaf scans linearly.
const KD_LEAF_SIZE: usize = 8;

/// A point found by a [`KdTree`] query.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Neighbour {
    /// Index of the point in the slice the tree was built from.
    pub index: usize,
    /// Euclidean distance from the query point.
    pub distance: f64,
}

#[derive(Clone, Copy, Debug)]
struct KdEntry {
    position: [f64; 3],
    index: u32,
}

/// A k-d tree over a set of points, for nearest-neighbour, k-nearest and radius queries.
#[derive(Clone, Debug, Default)]
pub struct KdTree {
    entries: Vec<KdEntry>,
    /// For the median position of every inner subrange: its split axis (0, 1 or 2).
    split_axes: Vec<u8>,
}

impl KdTree {
    /// Builds the tree over `points` (their indices are what queries return).
    pub fn new(points: &[Point]) -> Self {
        let mut entries: Vec<KdEntry> = points
            .iter()
            .enumerate()
            .map(|(i, p)| KdEntry { position: [p.x, p.y, p.z], index: i as u32 })
            .collect();
        let mut split_axes = vec![0u8; entries.len()];
        build_kd(&mut entries, &mut split_axes);
        KdTree { entries, split_axes }
    }

    /// Number of points in the tree.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// True when the tree holds no point.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The point nearest to `query`, or `None` for an empty tree.
    pub fn nearest(&self, query: &Point) -> Option<Neighbour> {
        let q = [query.x, query.y, query.z];
        let mut best = (f64::INFINITY, u32::MAX);
        self.nearest_in(0, self.entries.len(), &q, &mut best);
        (best.1 != u32::MAX).then(|| Neighbour { index: best.1 as usize, distance: best.0.sqrt() })
    }

    /// The `k` points nearest to `query`, nearest first (fewer when the tree is smaller).
    pub fn k_nearest(&self, query: &Point, k: usize) -> Vec<Neighbour> {
        let q = [query.x, query.y, query.z];
        let mut found: Vec<(f64, u32)> = Vec::with_capacity(k + 1);
        if k > 0 {
            self.k_nearest_in(0, self.entries.len(), &q, k, &mut found);
        }
        found
            .into_iter()
            .map(|(d2, i)| Neighbour { index: i as usize, distance: d2.sqrt() })
            .collect()
    }

    /// All points within `radius` of `query` (inclusive), in no particular order.
    pub fn within_radius(&self, query: &Point, radius: f64) -> Vec<Neighbour> {
        let mut found = Vec::new();
        self.for_each_within_radius(query, radius, |index, distance| {
            found.push(Neighbour { index, distance })
        });
        found
    }

    /// Calls `visit(index, distance)` for every point within `radius` of `query`, without
    /// allocating: the form vertex merging and density estimates use in their loops.
    pub fn for_each_within_radius(&self, query: &Point, radius: f64, mut visit: impl FnMut(usize, f64)) {
        if !(radius >= 0.0) {
            return;
        }
        let q = [query.x, query.y, query.z];
        self.radius_in(0, self.entries.len(), &q, radius * radius, &mut visit);
    }

    fn nearest_in(&self, lo: usize, hi: usize, q: &[f64; 3], best: &mut (f64, u32)) {
        let n = hi - lo;
        if n <= KD_LEAF_SIZE {
            for entry in &self.entries[lo..hi] {
                let d2 = squared_distance(&entry.position, q);
                if d2 < best.0 {
                    *best = (d2, entry.index);
                }
            }
            return;
        }
        let mid = lo + n / 2;
        let entry = &self.entries[mid];
        let d2 = squared_distance(&entry.position, q);
        if d2 < best.0 {
            *best = (d2, entry.index);
        }
        let axis = self.split_axes[mid] as usize;
        let diff = q[axis] - entry.position[axis];
        let (near, far) = if diff < 0.0 { ((lo, mid), (mid + 1, hi)) } else { ((mid + 1, hi), (lo, mid)) };
        self.nearest_in(near.0, near.1, q, best);
        if diff * diff < best.0 {
            self.nearest_in(far.0, far.1, q, best);
        }
    }

    fn k_nearest_in(&self, lo: usize, hi: usize, q: &[f64; 3], k: usize, found: &mut Vec<(f64, u32)>) {
        let consider = |entry: &KdEntry, found: &mut Vec<(f64, u32)>| {
            let d2 = squared_distance(&entry.position, q);
            if found.len() < k || d2 < found[found.len() - 1].0 {
                let at = found.partition_point(|&(d, _)| d <= d2);
                found.insert(at, (d2, entry.index));
                found.truncate(k);
            }
        };
        let n = hi - lo;
        if n <= KD_LEAF_SIZE {
            for entry in &self.entries[lo..hi] {
                consider(entry, found);
            }
            return;
        }
        let mid = lo + n / 2;
        let entry = &self.entries[mid];
        consider(entry, found);
        let axis = self.split_axes[mid] as usize;
        let diff = q[axis] - entry.position[axis];
        let (near, far) = if diff < 0.0 { ((lo, mid), (mid + 1, hi)) } else { ((mid + 1, hi), (lo, mid)) };
        self.k_nearest_in(near.0, near.1, q, k, found);
        let bound = if found.len() < k { f64::INFINITY } else { found[found.len() - 1].0 };
        if diff * diff < bound {
            self.k_nearest_in(far.0, far.1, q, k, found);
        }
    }

    fn radius_in(&self, lo: usize, hi: usize, q: &[f64; 3], r2: f64, visit: &mut impl FnMut(usize, f64)) {
        let n = hi - lo;
        if n <= KD_LEAF_SIZE {
            for entry in &self.entries[lo..hi] {
                let d2 = squared_distance(&entry.position, q);
                if d2 <= r2 {
                    visit(entry.index as usize, d2.sqrt());
                }
            }
            return;
        }
        let mid = lo + n / 2;
        let entry = &self.entries[mid];
        let d2 = squared_distance(&entry.position, q);
        if d2 <= r2 {
            visit(entry.index as usize, d2.sqrt());
        }
        let axis = self.split_axes[mid] as usize;
        let diff = q[axis] - entry.position[axis];
        if diff <= 0.0 || diff * diff <= r2 {
            self.radius_in(lo, mid, q, r2, visit);
        }
        if diff >= 0.0 || diff * diff <= r2 {
            self.radius_in(mid + 1, hi, q, r2, visit);
        }
    }
}

/// Reorders `entries` into the implicit tree layout, recording split axes at medians.
fn build_kd(entries: &mut [KdEntry], split_axes: &mut [u8]) {
    let n = entries.len();
    if n <= KD_LEAF_SIZE {
        return;
    }
    let mut lo = entries[0].position;
    let mut hi = lo;
    for e in entries.iter() {
        grow(&mut lo, &mut hi, &e.position, &e.position);
    }
    let axis = (0..3).max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b]))).unwrap_or(0);
    let mid = n / 2;
    entries.select_nth_unstable_by(mid, |a, b| a.position[axis].total_cmp(&b.position[axis]));
    split_axes[mid] = axis as u8;
    let (left, rest) = entries.split_at_mut(mid);
    let right = &mut rest[1..];
    let (left_axes, rest_axes) = split_axes.split_at_mut(mid);
    let right_axes = &mut rest_axes[1..];
    if n > PARALLEL_BUILD_MIN {
        rayon::join(|| build_kd(left, left_axes), || build_kd(right, right_axes));
    } else {
        build_kd(left, left_axes);
        build_kd(right, right_axes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid_points(n: usize) -> Vec<Point> {
        let mut points = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    // A slightly irregular grid so that no two distances tie.
                    let jitter = ((i * 31 + j * 17 + k * 7) % 13) as f64 * 1e-3;
                    points.push(Point::new(i as f64 + jitter, j as f64 - jitter, k as f64 + 0.5 * jitter));
                }
            }
        }
        points
    }

    #[test]
    fn kd_tree_queries_agree_with_brute_force() {
        let points = grid_points(12);
        let tree = KdTree::new(&points);
        let queries = [Point::new(3.3, 4.7, 5.1), Point::new(-2.0, 0.5, 13.0), Point::new(5.5, 5.5, 5.5)];
        for q in &queries {
            let mut brute: Vec<(f64, usize)> =
                points.iter().enumerate().map(|(i, p)| ((p - q).norm(), i)).collect();
            brute.sort_by(|a, b| a.0.total_cmp(&b.0));
            let nearest = tree.nearest(q).unwrap();
            assert_eq!(nearest.index, brute[0].1);
            let k = tree.k_nearest(q, 10);
            assert_eq!(k.iter().map(|n| n.index).collect::<Vec<_>>(), brute[..10].iter().map(|b| b.1).collect::<Vec<_>>());
            let mut within: Vec<usize> = tree.within_radius(q, 2.5).iter().map(|n| n.index).collect();
            within.sort();
            let mut expected: Vec<usize> = brute.iter().filter(|b| b.0 <= 2.5).map(|b| b.1).collect();
            expected.sort();
            assert_eq!(within, expected);
        }
        assert!(KdTree::new(&[]).nearest(&Point::origin()).is_none());
    }
}
