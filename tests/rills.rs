//! Wheel rills traced on a wall with known grooves, under the true axis and under axes
//! turned about the sherd's radial and tangential directions, and on the real scan A011.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use sherd::mesh::{Mesh, Point, Vector};
use sherd::orient::{segment_surfaces, Axis};
use sherd::profile::rills::{trace_rills, RillOptions};

/// Radius of the outer skin at height `z`: a wall flaring at 0.3 mm/mm with grooves
/// 0.3 mm deep every 6 mm (a cosine bump 2 mm wide) when `grooved`.
fn outer_radius(z: f64, grooved: bool) -> f64 {
    let phase = z.rem_euclid(6.0) - 3.0;
    let groove = if grooved && phase.abs() < 1.0 { 0.15 * (1.0 + (std::f64::consts::PI * phase).cos()) } else { 0.0 };
    60.0 + 0.3 * z - groove
}

/// Both skins of a 60-degree wall sherd 30 mm high as points with normals (0.3 mm
/// spacing), the inner skin 5 mm inside and smooth, with deterministic noise of
/// `noise_mm`, moved by a fixed pose. Returns the cloud and the true axis.
fn rilled_sherd(grooved: bool, noise_mm: f64) -> (Mesh, Axis) {
    let pose = Isometry3::from_parts(
        Translation3::new(12.0, -7.0, 30.0),
        UnitQuaternion::from_euler_angles(0.4, -0.7, 1.1),
    );
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    let mut seed = 0u64;
    let mut noise = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * noise_mm
    };
    for row in 0..=100 {
        let z = -15.0 + 0.3 * row as f64;
        for column in 0..=210 {
            let angle = (-30.0 + 60.0 * column as f64 / 210.0).to_radians();
            let (c, s) = (angle.cos(), angle.sin());
            for (radius, outward) in [(outer_radius(z, grooved), 1.0), (outer_radius(z, false) - 5.0, -1.0)] {
                let slope = (outer_radius(z + 0.01, false) - outer_radius(z - 0.01, false)) / 0.02;
                let normal = Vector::new(c, s, -slope).normalize() * outward;
                let point = Point::new((radius + noise()) * c, (radius + noise()) * s, z + noise());
                positions.push(pose * point);
                normals.push(pose * normal);
            }
        }
    }
    let axis = Axis::new(pose * Point::origin(), pose * Vector::z());
    (Mesh::from_points_and_normals(positions, normals), axis)
}

/// `truth` turned by `degrees` about the line through the sherd's centre (the mean of its
/// points) along its radial direction (`about_radial`) or its tangential one.
fn turned(mesh: &Mesh, truth: &Axis, about_radial: bool, degrees: f64) -> Axis {
    let centre = Point::from(mesh.positions.iter().fold(Vector::zeros(), |sum, p| sum + p.coords) / mesh.vertex_count() as f64);
    let direction = truth.direction.into_inner();
    let radial = (centre - truth.closest_point(&centre)).normalize();
    let about = if about_radial { radial } else { direction.cross(&radial) };
    let turn = UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(about), degrees.to_radians());
    Axis::new(centre + turn * (truth.point - centre), turn * direction)
}

#[test]
fn grooves_under_the_true_axis_are_horizontal() {
    let (mesh, truth) = rilled_sherd(true, 0.02);
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
    // Grooves every 6 mm over 30 mm, the outermost too near the ends: at least 3.
    assert!(rills.len() >= 3, "{} rills: {rills:?}", rills.len());
    for rill in &rills {
        assert!(rill.slope_deg.abs() < 0.3, "slope {:.2} deg at height {:.1}", rill.slope_deg, rill.height_mm);
        assert!(rill.arc_length_mm > 45.0, "a rill runs across the sherd: {:.1} mm", rill.arc_length_mm);
        assert!((rill.depth_mm - 0.3).abs() < 0.15, "depth {:.2} mm", rill.depth_mm);
    }
}

#[test]
fn a_smooth_wall_has_no_rills() {
    let (mesh, truth) = rilled_sherd(false, 0.03);
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
    assert!(rills.is_empty(), "{rills:?}");
}

#[test]
fn an_axis_turned_about_the_radial_direction_slants_every_rill_by_the_turn() {
    let (mesh, truth) = rilled_sherd(true, 0.02);
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    for degrees in [-4.0, 2.0, 6.0] {
        let axis = turned(&mesh, &truth, true, degrees);
        let rills = trace_rills(&mesh, &axis, &skins, &RillOptions::default());
        assert!(rills.len() >= 3, "turned {degrees} deg: {} rills", rills.len());
        for rill in &rills {
            // The sign follows the turn: the same for every rill, `degrees` in size.
            assert!((rill.slope_deg.abs() - degrees.abs()).abs() < 0.4, "turned {degrees} deg: slope {:.2}", rill.slope_deg);
            assert_eq!(rill.slope_deg.signum(), rills[0].slope_deg.signum(), "turned {degrees} deg: {rills:?}");
        }
    }
}

#[test]
fn an_axis_turned_in_the_meridian_plane_leaves_the_rills_nearly_horizontal() {
    // What rills cannot tell: a tilt in the plane of the axis and the sherd's centre moves
    // a rill's ends only at second order in the arc (here under 0.6 deg for a 5 deg turn).
    let (mesh, truth) = rilled_sherd(true, 0.02);
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &turned(&mesh, &truth, false, 5.0), &skins, &RillOptions::default());
    assert!(rills.len() >= 3);
    for rill in &rills {
        assert!(rill.slope_deg.abs() < 0.6, "slope {:.2} deg", rill.slope_deg);
    }
}
