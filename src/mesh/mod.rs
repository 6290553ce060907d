//! The mesh layer: the [`Mesh`] every other layer works on, and the operations the
//! paper requires before orientation (Wilczek et al. 2018, sections 2.1-2.2): reading
//! scans, repair, vertex normals, quadric decimation and Laplacian smoothing.

pub mod atomic;
pub mod decimate;
pub mod fingerprint;
pub mod io;
pub mod normal_filter;
pub mod normals;
pub(crate) mod quadric;
pub mod repair;
pub mod smooth;
pub mod spatial;
pub mod topology;

use nalgebra::{Point3, Vector3};

use crate::{Error, Result};

/// A position in the scan's frame and units (millimetres unless the file says otherwise).
pub type Point = Point3<f64>;
/// A direction or displacement in the scan's frame.
pub type Vector = Vector3<f64>;

/// Length of the planar vector `(dx, dy)`. A square root, not `f64::hypot`: hypot's guard
/// against overflow is a libm call that took 15% of a batch's time in the sections' and
/// circle fits' inner loops, and scan coordinates are nowhere near overflowing.
#[inline]
pub fn planar_length(dx: f64, dy: f64) -> f64 {
    (dx * dx + dy * dy).sqrt()
}

/// Distance from `p` to the segment from `a` to `b` in a plane (a point when `a == b`).
#[inline]
pub fn segment_distance(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0) } else { 0.0 };
    planar_length(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy)
}

/// An RGBA8 texture image, rows top to bottom, as scanners and photogrammetry export it.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes, row-major, top row first.
    pub rgba: Vec<u8>,
    /// Where the image was read from, for messages and for writers that reference it.
    pub source: Option<std::path::PathBuf>,
}

/// A triangle mesh (or a point cloud, when `triangles` is empty) with optional
/// per-vertex attributes.
///
/// Positions are `f64` because orientation compares distances of a few micrometres on
/// objects tens of centimetres wide; indices are `u32` as in every scan format.
/// Optional attributes are either absent or exactly as long as they should be
/// ([`Mesh::validate`] checks it).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Point>,
    /// Triangles as counter-clockwise (outward) vertex index triples.
    pub triangles: Vec<[u32; 3]>,
    /// Unit vertex normals, one per vertex.
    pub normals: Option<Vec<Vector>>,
    /// Vertex colours, one per vertex.
    pub colors: Option<Vec<[u8; 4]>>,
    /// Texture coordinates per triangle corner (`3 * triangles.len()`), as MeshLab's
    /// wedge coordinates: a vertex on a texture seam keeps one position.
    pub corner_uvs: Option<Vec<[f32; 2]>>,
    /// The texture the UVs refer to.
    pub texture: Option<Texture>,
    /// A scalar per vertex (MeshLab's "quality"): occlusion, regularity, distances.
    pub quality: Option<Vec<f32>>,
}

impl Mesh {
    /// A mesh from positions and triangles, without optional attributes.
    pub fn new(positions: Vec<Point>, triangles: Vec<[u32; 3]>) -> Self {
        Mesh { positions, triangles, ..Default::default() }
    }

    /// A point cloud with normals (no faces), as SfS++ surfaces or XYZ files give.
    pub fn from_points_and_normals(positions: Vec<Point>, normals: Vec<Vector>) -> Self {
        Mesh { positions, normals: Some(normals), ..Default::default() }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles.
    pub fn face_count(&self) -> usize {
        self.triangles.len()
    }

    /// True when there are no faces: only the points (and their normals) carry information.
    pub fn is_point_cloud(&self) -> bool {
        self.triangles.is_empty()
    }

    /// The three corner positions of triangle `face`.
    pub fn triangle_points(&self, face: usize) -> [Point; 3] {
        let [a, b, c] = self.triangles[face];
        [self.positions[a as usize], self.positions[b as usize], self.positions[c as usize]]
    }

    /// The (unnormalised) normal of triangle `face`: its length is twice the area.
    pub fn face_normal_scaled(&self, face: usize) -> Vector {
        let [a, b, c] = self.triangle_points(face);
        (b - a).cross(&(c - a))
    }

    /// Area of triangle `face`.
    pub fn face_area(&self, face: usize) -> f64 {
        0.5 * self.face_normal_scaled(face).norm()
    }

    /// Total surface area.
    pub fn surface_area(&self) -> f64 {
        (0..self.face_count()).map(|f| self.face_area(f)).sum()
    }

    /// Axis-aligned bounding box `(min, max)`, or `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<(Point, Point)> {
        let first = *self.positions.first()?;
        Some(self.positions.iter().fold((first, first), |(lo, hi), p| {
            (lo.inf(p), hi.sup(p))
        }))
    }

    /// Keeps the vertices with `keep[v]` and the faces whose three corners are kept,
    /// renumbering the faces and compacting the per-vertex attributes.
    pub fn keep_vertices(&mut self, keep: &[bool]) {
        let keep_face: Vec<bool> = self.triangles.iter().map(|t| t.iter().all(|&v| keep[v as usize])).collect();
        repair::retain_faces(self, &keep_face);
        repair::retain_vertices(self, keep);
    }

    /// Centroid of the vertices.
    pub fn centroid(&self) -> Option<Point> {
        if self.positions.is_empty() {
            return None;
        }
        let sum = self.positions.iter().fold(Vector::zeros(), |s, p| s + p.coords);
        Some(Point::from(sum / self.positions.len() as f64))
    }

    /// Checks the invariants every algorithm relies on: finite coordinates, indices in
    /// range, attribute arrays of the right length, finite normals. The error names the
    /// first offending element and its value.
    pub fn validate(&self) -> Result<()> {
        let n = self.positions.len();
        if let Some(i) = self.positions.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
            let p = self.positions[i];
            return Err(Error::InvalidArgument(format!(
                "vertex {i} has a non-finite coordinate ({}, {}, {})",
                p.x, p.y, p.z
            )));
        }
        for (f, tri) in self.triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v as usize >= n) {
                return Err(Error::InvalidArgument(format!(
                    "face {f} refers to vertex {v}, but there are only {n} vertices"
                )));
            }
        }
        let check_len = |what: &str, len: usize, expected: usize| -> Result<()> {
            if len != expected {
                return Err(Error::InvalidArgument(format!(
                    "{what} has {len} entries, expected {expected}"
                )));
            }
            Ok(())
        };
        if let Some(normals) = &self.normals {
            check_len("normals", normals.len(), n)?;
            if let Some(i) = normals.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
                return Err(Error::InvalidArgument(format!("normal of vertex {i} is not finite")));
            }
        }
        if let Some(colors) = &self.colors {
            check_len("colours", colors.len(), n)?;
        }
        if let Some(quality) = &self.quality {
            check_len("quality", quality.len(), n)?;
        }
        if let Some(uvs) = &self.corner_uvs {
            check_len("texture coordinates", uvs.len(), 3 * self.triangles.len())?;
        }
        Ok(())
    }

    /// Applies a rigid (or any affine) transform to positions and normals.
    pub fn transform(&mut self, transform: &nalgebra::Isometry3<f64>) {
        for p in &mut self.positions {
            *p = transform * *p;
        }
        if let Some(normals) = &mut self.normals {
            for v in normals {
                *v = transform * *v;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> Mesh {
        Mesh::new(
            vec![
                Point::new(0.0, 0.0, 0.0),
                Point::new(1.0, 0.0, 0.0),
                Point::new(0.0, 1.0, 0.0),
                Point::new(0.0, 0.0, 1.0),
            ],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        )
    }

    #[test]
    fn validate_names_the_bad_element() {
        let mut mesh = tetrahedron();
        assert!(mesh.validate().is_ok());
        mesh.triangles[2] = [0, 3, 9];
        let message = mesh.validate().unwrap_err().to_string();
        assert!(message.contains("face 2") && message.contains("vertex 9"), "{message}");
        let mut mesh = tetrahedron();
        mesh.positions[1].y = f64::NAN;
        let message = mesh.validate().unwrap_err().to_string();
        assert!(message.contains("vertex 1"), "{message}");
    }

    #[test]
    fn area_and_bounds() {
        let mesh = tetrahedron();
        let expected = 1.5 + 3f64.sqrt() / 2.0;
        assert!((mesh.surface_area() - expected).abs() < 1e-12);
        let (lo, hi) = mesh.bounding_box().unwrap();
        assert_eq!(lo, Point::origin());
        assert_eq!(hi, Point::new(1.0, 1.0, 1.0));
    }

    #[test]
    fn keeping_vertices_drops_the_faces_of_the_others_and_keeps_the_normals_of_the_rest() {
        let positions = vec![Point::new(0.0, 0.0, 0.0), Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0)];
        let normals = (0..4).map(|i| Vector::new(0.0, i as f64, 1.0).normalize()).collect();
        let mut mesh = Mesh { normals: Some(normals), ..Mesh::new(positions, vec![[0, 1, 2], [1, 3, 2]]) };
        mesh.keep_vertices(&[false, true, true, true]);
        assert_eq!(mesh.positions, vec![Point::new(1.0, 0.0, 0.0), Point::new(0.0, 1.0, 0.0), Point::new(1.0, 1.0, 0.0)]);
        assert_eq!(mesh.triangles, vec![[0, 2, 1]]);
        assert_eq!(mesh.normals.unwrap()[2], Vector::new(0.0, 3.0, 1.0).normalize());
    }
}
