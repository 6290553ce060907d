//! Wheel rills traced on a wall with known grooves, under the true axis and under axes
//! turned about the sherd's radial and tangential directions, and on the real scan A011.

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use sherd::mesh::{Mesh, Point, Vector};
use sherd::orient::{segment_surfaces, Axis};
use sherd::profile::rills::{trace_rills, trace_rills_under, RillOptions};
use sherd::synth::{generate_vessel, synthetic_sherd, SherdOptions, SherdPart, VesselOptions};

/// The default seed of `sherd demo`.
const SEED_OF_THE_DEMO: u64 = 6;

/// Radius of the outer skin at height `z` of `wall`: flaring at `flare` mm/mm and bending
/// by `bend` (its radius's second derivative, per mm), with grooves 0.3 mm deep every 6 mm
/// (a cosine bump 2 mm wide) when `grooved`, and a corrugation `corrugation_mm` deep from
/// crest to trough every 5 mm.
fn outer_radius(z: f64, wall: &Wall, grooved: bool) -> f64 {
    let phase = z.rem_euclid(6.0) - 3.0;
    let groove = if grooved && phase.abs() < 1.0 { 0.15 * (1.0 + (std::f64::consts::PI * phase).cos()) } else { 0.0 };
    let corrugation = 0.5 * wall.corrugation_mm * (std::f64::consts::TAU * z / 5.0).cos();
    60.0 + wall.flare * z + 0.5 * wall.bend * z * z - groove + corrugation
}

/// A 60-degree wall sherd 30 mm high.
#[derive(Clone, Copy)]
struct Wall {
    grooved: bool,
    /// Deterministic noise on every coordinate, up to this much either way, mm.
    noise_mm: f64,
    /// Distance between neighbouring points, mm.
    spacing_mm: f64,
    /// How much the radius grows per mm of height at mid-height.
    flare: f64,
    /// How much the flare grows per mm of height: the profile's bend (positive: the outer
    /// skin bends into the wall, as at a neck).
    bend: f64,
    /// Depth of a corrugation of the outer skin every 5 mm (rills thrown close together),
    /// crest to trough, mm.
    corrugation_mm: f64,
}

impl Wall {
    fn grooved(noise_mm: f64) -> Wall {
        Wall { grooved: true, noise_mm, spacing_mm: 0.3, flare: 0.3, bend: 0.0, corrugation_mm: 0.0 }
    }
}

/// Both skins of `wall` as points with normals, the inner skin 5 mm inside and smooth,
/// moved by a fixed pose. Returns the cloud and the true axis.
fn wall_sherd(wall: Wall) -> (Mesh, Axis) {
    let pose = Isometry3::from_parts(
        Translation3::new(12.0, -7.0, 30.0),
        UnitQuaternion::from_euler_angles(0.4, -0.7, 1.1),
    );
    let (mut positions, mut normals) = (Vec::new(), Vec::new());
    let mut seed = 0u64;
    let mut noise = || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * wall.noise_mm
    };
    let rows = (30.0 / wall.spacing_mm).round() as usize;
    let columns = (60f64.to_radians() * 60.0 / wall.spacing_mm).round() as usize;
    for row in 0..=rows {
        let z = -15.0 + 30.0 * row as f64 / rows as f64;
        for column in 0..=columns {
            let angle = (-30.0 + 60.0 * column as f64 / columns as f64).to_radians();
            let (c, s) = (angle.cos(), angle.sin());
            let slope = wall.flare + wall.bend * z;
            let smooth = Wall { corrugation_mm: 0.0, ..wall };
            for (radius, outward) in [(outer_radius(z, &wall, wall.grooved), 1.0), (outer_radius(z, &smooth, false) - 5.0, -1.0)] {
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
    let (mesh, truth) = wall_sherd(Wall::grooved(0.02));
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
    // Fine and clean; coarse and steep (where a bin's vertices stand off its centre by as
    // much as the slope makes a shallow groove of); coarse and rough, as a hand-held
    // scanner gives.
    for (noise_mm, spacing_mm, flare) in [(0.03, 0.3, 0.3), (0.02, 0.8, 0.8), (0.25, 1.2, 0.3)] {
        let (mesh, truth) = wall_sherd(Wall { grooved: false, noise_mm, spacing_mm, flare, bend: 0.0, corrugation_mm: 0.0 });
        let skins = segment_surfaces(&mesh, &truth).unwrap();
        let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
        assert!(rills.is_empty(), "noise {noise_mm} mm, spacing {spacing_mm} mm, flare {flare}: {rills:?}");
    }
}

#[test]
fn grooves_on_a_bending_wall_are_traced() {
    // A belly's or a neck's steady bend (a profile radius of 45 mm either way) leaves the
    // wall's smoothing a shallow dip or bump all along, which the grooves stand out of.
    for bend in [1.0 / 45.0, -1.0 / 45.0] {
        let (mesh, truth) = wall_sherd(Wall { bend, ..Wall::grooved(0.02) });
        let skins = segment_surfaces(&mesh, &truth).unwrap();
        let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
        assert!(rills.len() >= 3, "bend {bend:.3}: {} rills: {rills:?}", rills.len());
        assert!(rills.iter().all(|rill| rill.slope_deg.abs() < 0.3), "bend {bend:.3}: {rills:?}");
    }
}

#[test]
fn a_deep_close_corrugation_is_traced() {
    // Rills 1 mm deep (the deepest) and 5 mm apart: their flanks turn the wall by about
    // 20 degrees across each trough, short of a profile's corner.
    let (mesh, truth) = wall_sherd(Wall { grooved: false, corrugation_mm: 1.0, ..Wall::grooved(0.02) });
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
    assert!(rills.len() >= 4, "{} rills: {rills:?}", rills.len());
    assert!(rills.iter().all(|rill| rill.slope_deg.abs() < 0.3), "{rills:?}");
}

/// The demo's sherd (`sherd demo`, its default seed) has a smooth wall whose inner lip
/// shoulder bends sharply: no rill is traced on it.
#[test]
fn the_demo_sherd_has_no_rills() {
    let options = SherdOptions { target_faces: 200_000, part: Some(SherdPart::Rim), noise_mm: 0.01, ..SherdOptions::default() };
    let sherd = synthetic_sherd(SEED_OF_THE_DEMO, &options);
    let rills = trace_rills_under(&sherd.mesh, &sherd.truth.axis, &RillOptions::default());
    assert!(rills.is_empty(), "{rills:?}");
}

/// The tuning generator cuts no rills: under the true axis, none is traced on its vessels'
/// fragments, whose profiles bend at necks and lips and turn from floor to wall.
#[test]
fn the_generators_vessels_have_no_rills() {
    for seed in [100, 101] {
        let vessel = generate_vessel(seed, &VesselOptions { cell_size_mm: 0.8, random_motion: true, ..VesselOptions::default() });
        for (index, fragment) in vessel.fragments.iter().enumerate() {
            let rills = trace_rills_under(&fragment.mesh, &fragment.truth.axis, &RillOptions::default());
            assert!(rills.is_empty(), "vessel {seed} fragment {index} ({:?}): {rills:?}", fragment.truth.part);
        }
    }
}

#[test]
fn grooves_stand_out_of_a_rough_coarse_scan() {
    let (mesh, truth) = wall_sherd(Wall { grooved: true, noise_mm: 0.1, spacing_mm: 0.5, flare: 0.8, bend: 0.0, corrugation_mm: 0.0 });
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &truth, &skins, &RillOptions::default());
    assert!(rills.len() >= 3, "{} rills: {rills:?}", rills.len());
    assert!(rills.iter().all(|rill| rill.slope_deg.abs() < 1.0), "{rills:?}");
}

#[test]
fn an_axis_turned_about_the_radial_direction_slants_every_rill_by_the_turn() {
    let (mesh, truth) = wall_sherd(Wall::grooved(0.02));
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
    let (mesh, truth) = wall_sherd(Wall::grooved(0.02));
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let rills = trace_rills(&mesh, &turned(&mesh, &truth, false, 5.0), &skins, &RillOptions::default());
    assert!(rills.len() >= 3);
    for rill in &rills {
        assert!(rill.slope_deg.abs() < 0.6, "slope {:.2} deg", rill.slope_deg);
    }
}
