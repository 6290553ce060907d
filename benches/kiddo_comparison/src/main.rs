//! sherd's KdTree against kiddo 5 (its mutable KdTree and its ImmutableKdTree) on the
//! 500k-face benchmark torus's 250k vertices; the same src/mesh/spatial/ is compiled in.
//!
//!     cd benches/kiddo_comparison && cargo run --release
//!     cargo run --release -- --bvh     # only: time three BVH builds of the torus
// src/mesh/spatial/'s files refer to `super::super::{Mesh, Point, Vector}`: the crate root
// stands in for sherd's mesh module with the little it uses.
pub type Point = nalgebra::Point3<f64>;
pub type Vector = nalgebra::Vector3<f64>;
pub struct Mesh {
    pub positions: Vec<Point>,
    pub triangles: Vec<[u32; 3]>,
}
impl Mesh {
    pub fn bounding_box(&self) -> Option<(Point, Point)> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| (lo.inf(p), hi.sup(p))))
    }
}
#[allow(dead_code, unused_imports)]
#[path = "../../../src/mesh/spatial/mod.rs"]
mod spatial;
use kiddo::{KdTree, SquaredEuclidean};
use std::time::Instant;

fn bvh_only(points: &[Point]) {
    let (around, across) = (1000usize, 250usize);
    let index = |i: usize, j: usize| ((i % around) * across + (j % across)) as u32;
    let mut triangles = Vec::new();
    for i in 0..around {
        for j in 0..across {
            triangles.push([index(i, j), index(i + 1, j), index(i + 1, j + 1)]);
            triangles.push([index(i, j), index(i + 1, j + 1), index(i, j + 1)]);
        }
    }
    let mesh = Mesh { positions: points.to_vec(), triangles };
    for _ in 0..3 {
        let t = Instant::now();
        let bvh = spatial::Bvh::new(&mesh);
        println!("bvh build {:?} ({} triangles)", t.elapsed(), bvh.triangle_count());
    }
}

fn main() {
    let (around, across) = (1000usize, 250usize);
    let mut points = Vec::new();
    for i in 0..around {
        let u = i as f64 / around as f64 * std::f64::consts::TAU;
        for j in 0..across {
            let v = j as f64 / across as f64 * std::f64::consts::TAU;
            let r = 30.0 * (1.0 + 0.05 * (7.0 * u).sin() * (5.0 * v).cos());
            points.push(Point::new((100.0 + r * v.cos()) * u.cos(), (100.0 + r * v.cos()) * u.sin(), r * v.sin()));
        }
    }
    if std::env::args().any(|a| a == "--bvh") {
        bvh_only(&points);
        return;
    }
    let queries: Vec<Point> = points.iter().map(|p| p + nalgebra::Vector3::new(0.1, -0.05, 0.07)).collect();
    let arrays: Vec<[f64; 3]> = points.iter().map(|p| [p.x, p.y, p.z]).collect();
    for round in 0..3 {
        let t = Instant::now();
        let ours = spatial::KdTree::new(&points);
        let build_ours = t.elapsed();
        let t = Instant::now();
        let theirs: KdTree<f64, 3> = (&arrays).into();
        let build_theirs = t.elapsed();
        let t = Instant::now();
        let mut s = 0usize;
        for q in &queries { s += ours.nearest(q).unwrap().index; }
        let nn_ours = t.elapsed();
        let t = Instant::now();
        let mut s2 = 0usize;
        for q in &queries { s2 += theirs.nearest_one::<SquaredEuclidean>(&[q.x, q.y, q.z]).item as usize; }
        let nn_theirs = t.elapsed();
        assert_eq!(s, s2);
        let t = Instant::now();
        for q in &queries { s += ours.k_nearest(q, 16).len(); }
        let k_ours = t.elapsed();
        let t = Instant::now();
        for q in &queries { s2 += theirs.nearest_n::<SquaredEuclidean>(&[q.x, q.y, q.z], 16).len(); }
        let k_theirs = t.elapsed();
        let t = Instant::now();
        for q in &queries { s += ours.within_radius(q, 1.0).len(); }
        let r_ours = t.elapsed();
        let t = Instant::now();
        for q in &queries { s2 += theirs.within_unsorted::<SquaredEuclidean>(&[q.x, q.y, q.z], 1.0).len(); }
        let r_theirs = t.elapsed();
        assert_eq!(s, s2);
        let t = Instant::now();
        let immutable: kiddo::ImmutableKdTree<f64, 3> = kiddo::ImmutableKdTree::new_from_slice(&arrays);
        let build_immutable = t.elapsed();
        let t = Instant::now();
        let mut s3 = 0usize;
        for q in &queries { s3 += immutable.nearest_one::<SquaredEuclidean>(&[q.x, q.y, q.z]).item as usize; }
        let nn_immutable = t.elapsed();
        let t = Instant::now();
        for q in &queries { s3 += immutable.nearest_n::<SquaredEuclidean>(&[q.x, q.y, q.z], std::num::NonZero::new(16).unwrap()).len(); }
        let k_immutable = t.elapsed();
        let t = Instant::now();
        for q in &queries { s3 += immutable.within_unsorted::<SquaredEuclidean>(&[q.x, q.y, q.z], 1.0).len(); }
        let r_immutable = t.elapsed();
        assert_eq!(s3, s2);
        println!("round {round}: kiddo ImmutableKdTree build {build_immutable:?} | nearest {nn_immutable:?} | 16-nearest {k_immutable:?} | radius-1 {r_immutable:?}");
        println!("round {round}: build sherd {build_ours:?} kiddo {build_theirs:?} | 250k nearest sherd {nn_ours:?} kiddo {nn_theirs:?} | 250k 16-nearest sherd {k_ours:?} kiddo {k_theirs:?} | 250k radius-1 sherd {r_ours:?} kiddo {r_theirs:?}");
    }
}
