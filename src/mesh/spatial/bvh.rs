//! The bounding volume hierarchy over a mesh's triangles: ray hits and closest points.
//!
//! The BVH is built with a binned surface area heuristic and stored depth-first: a node's
//! left child follows it, the right child's offset is stored in the node; leaves refer to a
//! run of triangles stored in leaf order.

use nalgebra::Unit;

// Relative, not `crate::mesh`: benches/kiddo_comparison compiles this directory in, with
// stand-ins for the mesh types at its crate root.
use super::super::{Mesh, Point, Vector};
use super::coords::{grow, squared_distance, PARALLEL_BUILD_MIN};

/// Largest number of triangles in a BVH leaf.
const BVH_MAX_LEAF_SIZE: usize = 8;
/// BVH nodes with at most this many triangles are leaves without weighing a split: the
/// binning's fixed cost dominated the build for the many small nodes.
const BVH_MIN_SPLIT_SIZE: usize = 4;
/// Largest number of bins of the binned surface area heuristic (fewer for small nodes).
const SAH_BIN_COUNT: usize = 16;

/// Where a ray met a triangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Index of the triangle in the mesh the [`Bvh`] was built from.
    pub face: usize,
    /// Distance from the ray origin to the hit point, in the mesh's units.
    pub distance: f64,
    /// The hit point.
    pub point: Point,
    /// Barycentric coordinates of the hit point with respect to the triangle's three
    /// corners, in the order of the mesh's triangle.
    pub barycentric: [f64; 3],
}

/// The point of a mesh closest to a query point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestPoint {
    /// Index of the triangle the point lies on.
    pub face: usize,
    /// The closest point.
    pub point: Point,
    /// Its distance to the query.
    pub distance: f64,
}

#[derive(Clone, Copy, Debug)]
struct BvhNode {
    min: [f64; 3],
    max: [f64; 3],
    /// For a leaf: index of its first triangle in leaf order. For an inner node: offset
    /// from this node to its right child (the left child is the next node).
    start_or_right_offset: u32,
    /// Number of triangles of a leaf; 0 for an inner node.
    count: u32,
}

#[derive(Clone, Copy, Debug)]
struct PrimitiveRef {
    min: [f64; 3],
    max: [f64; 3],
    face: u32,
}

impl PrimitiveRef {
    /// Centre of the box (not stored: the build is bound by memory traffic).
    fn centroid(&self) -> [f64; 3] {
        [0, 1, 2].map(|axis| 0.5 * (self.min[axis] + self.max[axis]))
    }
}

/// A bounding volume hierarchy over a mesh's triangles: closest and any ray hits, and
/// closest points. Rays hit triangles from both sides.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<BvhNode>,
    /// Original face index of every triangle, in leaf order.
    faces: Vec<u32>,
    /// Corner positions of every triangle, in leaf order, for cache-friendly tests.
    corners: Vec<[[f64; 3]; 3]>,
    /// Hits nearer than this to the origin are ignored, so that a ray leaving a surface
    /// does not hit the triangle it starts on (1e-9 of the bounding box diagonal).
    min_distance: f64,
}

impl Bvh {
    /// Builds the hierarchy over the triangles of `mesh` (none for a point cloud).
    pub fn new(mesh: &Mesh) -> Self {
        let mut refs: Vec<PrimitiveRef> = mesh
            .triangles
            .iter()
            .enumerate()
            .map(|(f, tri)| {
                let [a, b, c] = tri.map(|v| mesh.positions[v as usize]);
                let min = [a.x.min(b.x).min(c.x), a.y.min(b.y).min(c.y), a.z.min(b.z).min(c.z)];
                let max = [a.x.max(b.x).max(c.x), a.y.max(b.y).max(c.y), a.z.max(b.z).max(c.z)];
                PrimitiveRef { min, max, face: f as u32 }
            })
            .collect();
        let mut nodes = Vec::with_capacity(2 * refs.len() / 3 + 1);
        if !refs.is_empty() {
            build_bvh(&mut refs, 0, &mut nodes);
        }
        let faces: Vec<u32> = refs.iter().map(|r| r.face).collect();
        drop(refs);
        let corners = faces
            .iter()
            .map(|&f| mesh.triangles[f as usize].map(|v| {
                let p = mesh.positions[v as usize];
                [p.x, p.y, p.z]
            }))
            .collect();
        let diagonal = mesh.bounding_box().map(|(lo, hi)| (hi - lo).norm()).unwrap_or(0.0);
        Bvh { nodes, faces, corners, min_distance: 1e-9 * diagonal }
    }

    /// Number of triangles indexed.
    pub fn triangle_count(&self) -> usize {
        self.faces.len()
    }

    /// The nearest triangle the ray from `origin` along `direction` (any length) hits,
    /// or `None`. `distance` is in the mesh's units.
    pub fn closest_hit(&self, origin: &Point, direction: &Vector) -> Option<Hit> {
        let ray = Ray::new(origin, direction)?;
        let mut best: Option<(f64, usize, f64, f64)> = None;
        let mut best_t = f64::INFINITY;
        self.traverse(&ray, |bvh, first, count, best_so_far| {
            for slot in first..first + count {
                if let Some((t, u, v)) = ray.intersect(&bvh.corners[slot], bvh.min_distance)
                    && t < *best_so_far
                {
                    *best_so_far = t;
                    best = Some((t, slot, u, v));
                }
            }
            false
        }, &mut best_t);
        best.map(|(t, slot, u, v)| Hit {
            face: self.faces[slot] as usize,
            distance: t,
            point: origin + ray.direction.into_inner() * t,
            barycentric: [1.0 - u - v, u, v],
        })
    }

    /// True when the ray from `origin` along `direction` hits a triangle closer than
    /// `max_distance`: the cheaper query of occlusion and visibility.
    pub fn any_hit(&self, origin: &Point, direction: &Vector, max_distance: f64) -> bool {
        let Some(ray) = Ray::new(origin, direction) else { return false };
        let mut bound = max_distance;
        self.traverse(&ray, |bvh, first, count, bound| {
            (first..first + count).any(|slot| {
                ray.intersect(&bvh.corners[slot], bvh.min_distance).is_some_and(|(t, _, _)| t < *bound)
            })
        }, &mut bound)
    }

    /// Depth-first traversal of the nodes the ray enters before `bound`, near child
    /// first. `leaf(self, first, count, bound)` tests a leaf, may lower `bound`, and
    /// returns true to stop. Returns whether a leaf asked to stop.
    fn traverse(
        &self,
        ray: &Ray,
        mut leaf: impl FnMut(&Bvh, usize, usize, &mut f64) -> bool,
        bound: &mut f64,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        if let Some(t) = ray.enter(&self.nodes[0], *bound) {
            stack.push((0, t));
        }
        while let Some((index, entry)) = stack.pop() {
            if entry >= *bound {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.count > 0 {
                if leaf(self, node.start_or_right_offset as usize, node.count as usize, bound) {
                    return true;
                }
                continue;
            }
            let left = index + 1;
            let right = index + node.start_or_right_offset;
            let left_entry = ray.enter(&self.nodes[left as usize], *bound);
            let right_entry = ray.enter(&self.nodes[right as usize], *bound);
            match (left_entry, right_entry) {
                (Some(l), Some(r)) => {
                    // Far child first on the stack, so the near one is popped first.
                    if l <= r {
                        stack.push((right, r));
                        stack.push((left, l));
                    } else {
                        stack.push((left, l));
                        stack.push((right, r));
                    }
                }
                (Some(l), None) => stack.push((left, l)),
                (None, Some(r)) => stack.push((right, r)),
                (None, None) => {}
            }
        }
        false
    }

    /// The point of the mesh closest to `query`, or `None` when there are no triangles:
    /// distances to a surface (Hausdorff distances, regularity).
    pub fn closest_point(&self, query: &Point) -> Option<ClosestPoint> {
        if self.nodes.is_empty() {
            return None;
        }
        let q = [query.x, query.y, query.z];
        let mut best_d2 = f64::INFINITY;
        let mut best: Option<(usize, [f64; 3])> = None;
        let mut stack: Vec<(u32, f64)> = vec![(0, box_squared_distance(&self.nodes[0], &q))];
        while let Some((index, d2_box)) = stack.pop() {
            if d2_box >= best_d2 {
                continue;
            }
            let node = &self.nodes[index as usize];
            if node.count > 0 {
                let first = node.start_or_right_offset as usize;
                for slot in first..first + node.count as usize {
                    let p = closest_point_on_triangle(&q, &self.corners[slot]);
                    let d2 = squared_distance(&p, &q);
                    if d2 < best_d2 {
                        best_d2 = d2;
                        best = Some((slot, p));
                    }
                }
                continue;
            }
            let left = index + 1;
            let right = index + node.start_or_right_offset;
            let dl = box_squared_distance(&self.nodes[left as usize], &q);
            let dr = box_squared_distance(&self.nodes[right as usize], &q);
            if dl <= dr {
                stack.push((right, dr));
                stack.push((left, dl));
            } else {
                stack.push((left, dl));
                stack.push((right, dr));
            }
        }
        best.map(|(slot, p)| ClosestPoint {
            face: self.faces[slot] as usize,
            point: Point::new(p[0], p[1], p[2]),
            distance: best_d2.sqrt(),
        })
    }
}

struct Ray {
    origin: [f64; 3],
    direction: Unit<Vector>,
    inverse_direction: [f64; 3],
}

impl Ray {
    fn new(origin: &Point, direction: &Vector) -> Option<Ray> {
        let direction = Unit::try_new(*direction, 0.0)?;
        if !direction.iter().all(|c| c.is_finite()) || !origin.iter().all(|c| c.is_finite()) {
            return None;
        }
        Some(Ray {
            origin: [origin.x, origin.y, origin.z],
            inverse_direction: [1.0 / direction.x, 1.0 / direction.y, 1.0 / direction.z],
            direction,
        })
    }

    /// Distance at which the ray enters the node's box, if it does before `bound`.
    fn enter(&self, node: &BvhNode, bound: f64) -> Option<f64> {
        let mut t_near = 0.0f64;
        let mut t_far = bound;
        for axis in 0..3 {
            let t1 = (node.min[axis] - self.origin[axis]) * self.inverse_direction[axis];
            let t2 = (node.max[axis] - self.origin[axis]) * self.inverse_direction[axis];
            // `min`/`max` drop the NaN of 0 * inf (origin on a slab, ray parallel to it).
            t_near = t_near.max(t1.min(t2));
            t_far = t_far.min(t1.max(t2));
        }
        (t_near <= t_far).then_some(t_near)
    }

    /// Möller-Trumbore, two-sided: `(t, u, v)` with `t > min_distance`.
    fn intersect(&self, corners: &[[f64; 3]; 3], min_distance: f64) -> Option<(f64, f64, f64)> {
        let [a, b, c] = corners;
        let e1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
        let e2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
        let d = [self.direction.x, self.direction.y, self.direction.z];
        let p = cross(&d, &e2);
        let det = dot(&e1, &p);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let inv_det = 1.0 / det;
        let s = [self.origin[0] - a[0], self.origin[1] - a[1], self.origin[2] - a[2]];
        let u = dot(&s, &p) * inv_det;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = cross(&s, &e1);
        let v = dot(&d, &q) * inv_det;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        let t = dot(&e2, &q) * inv_det;
        (t > min_distance).then_some((t, u, v))
    }
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn box_squared_distance(node: &BvhNode, q: &[f64; 3]) -> f64 {
    (0..3)
        .map(|axis| {
            let d = (node.min[axis] - q[axis]).max(0.0).max(q[axis] - node.max[axis]);
            d * d
        })
        .sum()
}

/// Closest point of triangle `abc` to `p` (Ericson, Real-Time Collision Detection, 5.1.5).
fn closest_point_on_triangle(p: &[f64; 3], corners: &[[f64; 3]; 3]) -> [f64; 3] {
    let [a, b, c] = corners;
    let sub = |x: &[f64; 3], y: &[f64; 3]| [x[0] - y[0], x[1] - y[1], x[2] - y[2]];
    let along = |base: &[f64; 3], dir: &[f64; 3], t: f64| [base[0] + dir[0] * t, base[1] + dir[1] * t, base[2] + dir[2] * t];
    let ab = sub(b, a);
    let ac = sub(c, a);
    let ap = sub(p, a);
    let d1 = dot(&ab, &ap);
    let d2 = dot(&ac, &ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = sub(p, b);
    let d3 = dot(&ab, &bp);
    let d4 = dot(&ac, &bp);
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return along(a, &ab, d1 / (d1 - d3));
    }
    let cp = sub(p, c);
    let d5 = dot(&ab, &cp);
    let d6 = dot(&ac, &cp);
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return along(a, &ac, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return along(b, &sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom == 0.0 || !denom.is_finite() {
        // A degenerate (zero-area) triangle: the nearest of its corners is good enough.
        return *[a, b, c]
            .into_iter()
            .min_by(|x, y| squared_distance(x, p).total_cmp(&squared_distance(y, p)))
            .unwrap_or(a);
    }
    let v = vb / denom;
    let w = vc / denom;
    [a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w]
}

/// The bounds of `refs` and the bounds of their centroids, in one pass.
fn union_bounds(refs: &[PrimitiveRef]) -> ([f64; 3], [f64; 3], [f64; 3], [f64; 3]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let (mut centroid_lo, mut centroid_hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for r in refs {
        grow(&mut lo, &mut hi, &r.min, &r.max);
        let centroid = r.centroid();
        grow(&mut centroid_lo, &mut centroid_hi, &centroid, &centroid);
    }
    (lo, hi, centroid_lo, centroid_hi)
}

fn half_area(lo: &[f64; 3], hi: &[f64; 3]) -> f64 {
    let d = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    if d.iter().any(|&x| x < 0.0) {
        return 0.0;
    }
    d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
}

/// Builds the subtree over `refs` (which start at `first` in the final leaf order) and
/// appends its nodes to `out` depth-first.
fn build_bvh(refs: &mut [PrimitiveRef], first: usize, out: &mut Vec<BvhNode>) {
    let (min, max, centroid_lo, centroid_hi) = union_bounds(refs);
    let n = refs.len();
    let leaf = BvhNode { min, max, start_or_right_offset: first as u32, count: n as u32 };
    if n <= BVH_MIN_SPLIT_SIZE {
        out.push(leaf);
        return;
    }
    let Some(mid) = sah_partition(refs, half_area(&min, &max), &centroid_lo, &centroid_hi) else {
        out.push(leaf);
        return;
    };
    let (left, right) = refs.split_at_mut(mid);
    let node_index = out.len();
    out.push(BvhNode { min, max, start_or_right_offset: 0, count: 0 });
    if n > PARALLEL_BUILD_MIN {
        let (left_nodes, right_nodes) = rayon::join(
            || {
                let mut nodes = Vec::with_capacity(2 * left.len() / 3 + 1);
                build_bvh(left, first, &mut nodes);
                nodes
            },
            || {
                let mut nodes = Vec::with_capacity(2 * right.len() / 3 + 1);
                build_bvh(right, first + mid, &mut nodes);
                nodes
            },
        );
        out[node_index].start_or_right_offset = 1 + left_nodes.len() as u32;
        out.extend_from_slice(&left_nodes);
        out.extend_from_slice(&right_nodes);
    } else {
        build_bvh(left, first, out);
        out[node_index].start_or_right_offset = (out.len() - node_index) as u32;
        build_bvh(right, first + mid, out);
    }
}

/// Partitions `refs` by the cheapest binned-SAH split along the axis where the
/// centroids spread most, and returns the size of the left part, or `None` when a leaf is
/// cheaper (and small enough). Binning one axis rather than three made the build about
/// three times cheaper (instruction counts of the orientation's 20k-face working copy)
/// for hierarchies whose rays cost the same to trace.
fn sah_partition(
    refs: &mut [PrimitiveRef],
    parent_half_area: f64,
    centroid_lo: &[f64; 3],
    centroid_hi: &[f64; 3],
) -> Option<usize> {
    let n = refs.len();
    let bins = n.min(SAH_BIN_COUNT);
    let extent: [f64; 3] = std::array::from_fn(|axis| centroid_hi[axis] - centroid_lo[axis]);
    let axis = if extent[0] >= extent[1] && extent[0] >= extent[2] {
        0
    } else if extent[1] >= extent[2] {
        1
    } else {
        2
    };
    if !(extent[axis] > 0.0) {
        // All centroids coincide: split in the middle so leaves stay small.
        return (n > BVH_MAX_LEAF_SIZE).then_some(n / 2);
    }
    let scale = bins as f64 / extent[axis];
    let origin = centroid_lo[axis];
    let bin_of = |r: &PrimitiveRef| {
        let centroid = 0.5 * (r.min[axis] + r.max[axis]);
        (((centroid - origin) * scale) as usize).min(bins - 1)
    };
    let mut counts = [0usize; SAH_BIN_COUNT];
    let mut bounds = [([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]); SAH_BIN_COUNT];
    for r in refs.iter() {
        let bin = bin_of(r);
        counts[bin] += 1;
        let (lo, hi) = &mut bounds[bin];
        grow(lo, hi, &r.min, &r.max);
    }
    // Sweep from the right to know each suffix's area and count, then from the left.
    let mut right_area = [0.0f64; SAH_BIN_COUNT];
    let mut right_count = [0usize; SAH_BIN_COUNT];
    let (mut lo, mut hi, mut count) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3], 0usize);
    for bin in (1..bins).rev() {
        grow(&mut lo, &mut hi, &bounds[bin].0, &bounds[bin].1);
        count += counts[bin];
        right_area[bin] = half_area(&lo, &hi);
        right_count[bin] = count;
    }
    let mut best: Option<(f64, usize)> = None; // (cost, bins on the left)
    let (mut lo, mut hi, mut count) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3], 0usize);
    for split in 1..bins {
        let bin = split - 1;
        grow(&mut lo, &mut hi, &bounds[bin].0, &bounds[bin].1);
        count += counts[bin];
        if count == 0 || right_count[split] == 0 {
            continue;
        }
        let cost = half_area(&lo, &hi) * count as f64 + right_area[split] * right_count[split] as f64;
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, split));
        }
    }
    let split_is_cheaper = |cost: f64| 1.0 + cost / parent_half_area.max(f64::MIN_POSITIVE) < n as f64;
    match best {
        Some((cost, split)) if split_is_cheaper(cost) || n > BVH_MAX_LEAF_SIZE => {
            let mut left_end = 0;
            for i in 0..n {
                if bin_of(&refs[i]) < split {
                    refs.swap(i, left_end);
                    left_end += 1;
                }
            }
            Some(left_end)
        }
        None if n > BVH_MAX_LEAF_SIZE => Some(n / 2),
        _ => None,
    }
}
