//! What the k-d tree and the BVH share: squared distances and box growth on the flat
//! `[f64; 3]` coordinates both store, and the size from which both builds run in parallel.

/// Subtrees with more elements than this are built in parallel with `rayon::join`.
pub(super) const PARALLEL_BUILD_MIN: usize = 8_192;

pub(super) fn squared_distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let (dx, dy, dz) = (a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    dx * dx + dy * dy + dz * dz
}

/// Widens the box `lo..hi` to contain the box `min..max`.
pub(super) fn grow(lo: &mut [f64; 3], hi: &mut [f64; 3], min: &[f64; 3], max: &[f64; 3]) {
    for axis in 0..3 {
        lo[axis] = lo[axis].min(min[axis]);
        hi[axis] = hi[axis].max(max[axis]);
    }
}
