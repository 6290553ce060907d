//! Spatial indices: a k-d tree for nearest points ([`KdTree`]) and a bounding volume
//! hierarchy over triangles for ray casts and closest points ([`Bvh`]).
//!
//! Both are hand-written rather than taken from a crate, for reasons measured or checked:
//! * they work directly on the crate's `f64` [`Point`](super::Point)s and
//!   [`Mesh`](super::Mesh) and return original indices, without copying into a crate's
//!   own types (parry3d and the `bvh` crate are `f32` by default and want their own shape
//!   traits; `bvh` also stores a node index in every shape, which a `Mesh` has no room for);
//! * speed: on the 250k vertices of the 500k-face benchmark mesh this k-d tree answers
//!   nearest, 16-nearest and radius queries as fast as kiddo 5's `ImmutableKdTree` (within
//!   the noise of a shared machine) and 3-6 times faster than kiddo's mutable `KdTree`;
//!   kiddo's immutable build is about 1.5 times faster (`benches/kiddo_comparison`, figures
//!   in `BENCHMARKS.md`, "Mesh processing"). Parity did not justify a dependency;
//! * the layouts are flat arrays without a `Box` per node, and both builds split the work
//!   with `rayon::join`; the queries the pipeline needs (two-sided ray hits with a distance
//!   bound for occlusion, allocation-free radius visits for vertex merging, closest points
//!   for Hausdorff distances) are a few dozen lines each on top of that layout.
//!
//! The k-d tree is in `kd_tree`, the BVH in `bvh`; `coords` holds the little both share
//! (arithmetic on flat `[f64; 3]` coordinates, the size from which a build runs in parallel).

mod bvh;
mod coords;
mod kd_tree;

pub use bvh::{Bvh, ClosestPoint, Hit};
pub use kd_tree::{KdTree, Neighbour};
