//! 3D reconstruction of the preserved part of the vessel by revolution (Wilczek et al.
//! 2018, section 2.4.5): the closed outlines of a profile section turned a full turn
//! about the z axis of the oriented frame, as a watertight triangle mesh ready for PLY.

use std::f64::consts::PI;

use nalgebra::Isometry3;

use crate::mesh::{Mesh, Point};
use crate::orient::Axis;
use crate::profile::section::{oriented_frame, polygon_signed_area, ProfileSection};
use crate::{Error, Result};

/// Profile points closer to the axis than this (mm) become a single pole vertex, so that
/// a base crossing the axis stays watertight instead of making a fan of slivers.
const POLE_RADIUS_MM: f64 = 1e-6;

/// Most steps per turn of a revolution: 0.01 degree each. More only multiplies the
/// vertices (and a hostile count would exhaust memory).
pub const MAX_REVOLUTION_SEGMENTS: usize = 36_000;

/// Revolves every closed outline of `section` ([`ProfileSection::closed_outlines`]) about
/// the z axis with `segments` steps per turn. The result is in the oriented frame (axis
/// on z, rim up), watertight, with outward-facing triangles. Errors when the section has
/// no closed outline with area, or `segments` is outside 3 to [`MAX_REVOLUTION_SEGMENTS`].
pub fn revolve_profile(section: &ProfileSection, segments: usize) -> Result<Mesh> {
    if !(3..=MAX_REVOLUTION_SEGMENTS).contains(&segments) {
        return Err(Error::InvalidArgument(format!(
            "revolution needs at least 3 segments and at most {MAX_REVOLUTION_SEGMENTS}, got {segments}"
        )));
    }
    let outlines: Vec<Vec<[f64; 2]>> =
        section.closed_outlines().into_iter().filter(|o| polygon_signed_area(o).abs() > 1e-9).collect();
    if outlines.is_empty() {
        return Err(Error::DegenerateGeometry(format!(
            "the section at {:.1} deg has no closed outline to revolve",
            section.angle_rad.to_degrees()
        )));
    }
    let mut mesh = Mesh::default();
    for outline in &outlines {
        revolve_outline(outline, segments, &mut mesh);
    }
    Ok(mesh)
}

/// Appends the revolution of one closed polygon (`[r, z]`, r >= 0) to `mesh`.
fn revolve_outline(outline: &[[f64; 2]], segments: usize, mesh: &mut Mesh) {
    // Counter-clockwise in (r, z) with theta increasing gives outward normals for the
    // winding below; a clockwise outline is walked backwards.
    let mut points: Vec<[f64; 2]> = outline.iter().map(|p| [p[0].max(0.0), p[1]]).collect();
    if polygon_signed_area(&points) < 0.0 {
        points.reverse();
    }
    // Merge consecutive pole points: the axis is one vertex per height.
    points.dedup_by(|b, a| a[0] < POLE_RADIUS_MM && b[0] < POLE_RADIUS_MM && (a[1] - b[1]).abs() < 1e-12);
    let n = points.len();
    // Vertex index of profile point i at step k.
    let mut index = vec![Vec::new(); n];
    for (i, p) in points.iter().enumerate() {
        if p[0] < POLE_RADIUS_MM {
            index[i] = vec![mesh.positions.len() as u32; segments];
            mesh.positions.push(Point::new(0.0, 0.0, p[1]));
        } else {
            for k in 0..segments {
                let theta = 2.0 * PI * k as f64 / segments as f64;
                index[i].push(mesh.positions.len() as u32);
                mesh.positions.push(Point::new(p[0] * theta.cos(), p[0] * theta.sin(), p[1]));
            }
        }
    }
    for i in 0..n {
        let j = (i + 1) % n;
        for k in 0..segments {
            let l = (k + 1) % segments;
            let (a, b, c, d) = (index[i][k], index[j][k], index[j][l], index[i][l]);
            // Quad a-b-c-d; when one side is a pole its two corners coincide.
            if a != d {
                mesh.triangles.push([a, d, c]);
            }
            if b != c {
                mesh.triangles.push([a, c, b]);
            }
        }
    }
}

/// The fragment itself moved into the oriented frame (axis on z, base to rim, centroid at
/// angle 0): the "oriented model" export.
pub fn oriented_mesh(mesh: &Mesh, axis: &Axis) -> Mesh {
    let frame: Isometry3<f64> = oriented_frame(mesh, axis);
    let mut out = mesh.clone();
    out.transform(&frame);
    out
}

/// Volume enclosed by a closed, consistently oriented mesh (divergence theorem), in mm³.
pub fn enclosed_volume_mm3(mesh: &Mesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| mesh.positions[v as usize].coords);
            a.dot(&b.cross(&c))
        })
        .sum::<f64>()
        / 6.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::section::ProfileCurve;
    use std::collections::HashMap;

    fn section_of(points: Vec<[f64; 2]>) -> ProfileSection {
        ProfileSection { angle_rad: 0.0, curves: vec![ProfileCurve { points, closed: true }] }
    }

    /// Every edge used exactly twice, once in each direction.
    fn assert_watertight(mesh: &Mesh) {
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                assert_ne!(a, b, "degenerate triangle {t:?}");
                *edges.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
            }
        }
        let mut count: HashMap<(u32, u32), usize> = HashMap::new();
        for t in &mesh.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *count.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        assert!(count.values().all(|&c| c == 2), "every edge must have two faces");
        assert!(edges.values().all(|&s| s == 0), "neighbouring faces must be consistently oriented");
    }

    #[test]
    fn wall_ring_is_watertight_with_the_pappus_volume() {
        // Rectangle r 50..55, z 0..40, clockwise on purpose.
        let section = section_of(vec![[50.0, 0.0], [50.0, 40.0], [55.0, 40.0], [55.0, 0.0]]);
        let mesh = revolve_profile(&section, 720).unwrap();
        assert_watertight(&mesh);
        let exact = PI * (55.0f64.powi(2) - 50.0f64.powi(2)) * 40.0;
        let volume = enclosed_volume_mm3(&mesh);
        assert!(volume > 0.0, "outward orientation gives a positive volume");
        assert!((volume - exact).abs() / exact < 1e-4, "{volume} vs {exact}");
    }

    #[test]
    fn profile_through_the_axis_closes_at_poles() {
        // A closed dish: base crossing the axis.
        let section = section_of(vec![[0.0, 0.0], [40.0, 0.0], [42.0, 30.0], [38.0, 30.0], [35.0, 4.0], [0.0, 4.0]]);
        let mesh = revolve_profile(&section, 256).unwrap();
        assert_watertight(&mesh);
        let on_axis = mesh.positions.iter().filter(|p| p.x.hypot(p.y) < 1e-9).count();
        assert_eq!(on_axis, 2);
        assert!(enclosed_volume_mm3(&mesh) > 0.0);
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(revolve_profile(&section_of(vec![[1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]), 32).is_err());
        assert!(revolve_profile(&section_of(vec![[1.0, 0.0], [2.0, 0.0], [2.0, 1.0]]), 2).is_err());
        let empty = ProfileSection { angle_rad: 0.0, curves: vec![] };
        assert!(revolve_profile(&empty, 32).unwrap_err().to_string().contains("no closed outline"));
    }
}
