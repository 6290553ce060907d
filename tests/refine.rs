//! Refinement criteria on analytic fixtures: a patch of a revolved wall (inner and outer
//! skins, a flat lip on top) with a known axis, moved by a rigid motion, refined from a
//! start axis a few degrees off.

#[path = "support/evaluation.rs"]
mod evaluation;

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use sherd::mesh::{Mesh, Point, Vector};
use sherd::orient::{mean_point_distance_mm, Axis};
use sherd::refine::{refine, Criterion, RefineOptions, Surface};

/// Outer radius of the fixture vessel at height z (a gently curved wall).
fn outer_radius(z: f64) -> f64 {
    70.0 + 0.25 * z - 0.004 * z * z
}

/// A sherd: `sector_deg` of arc, `height` mm of wall 6 mm thick with a flat lip on top
/// when `lip` (otherwise a wavy broken top; the bottom is always broken), deformed radially by `ovality` (r * (1 + ovality cos 2 theta)).
fn fixture(sector_deg: f64, height: f64, lip: bool, ovality: f64) -> Mesh {
    let (columns, rows) = (((sector_deg * 1.5) as usize).max(8), (height as usize).max(8));
    let thickness = 6.0;
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let radius = |z: f64, theta: f64, inner: bool| {
        (outer_radius(z) - if inner { thickness } else { 0.0 }) * (1.0 + ovality * (2.0 * theta).cos())
    };
    let point = |z: f64, theta: f64, inner: bool| {
        let r = radius(z, theta, inner);
        Point::new(r * theta.cos(), r * theta.sin(), z)
    };
    let grid = |inner: bool, positions: &mut Vec<Point>, triangles: &mut Vec<[u32; 3]>| {
        let base = positions.len() as u32;
        for i in 0..=rows {
            for j in 0..=columns {
                let fraction = j as f64 / columns as f64;
                // Broken edges wander; only a lip is level.
                let bottom = 4.0 * (9.0 * fraction).sin();
                let top = if lip { height } else { height + 4.0 * (7.0 * fraction + 1.0).cos() };
                let z = bottom + (top - bottom) * i as f64 / rows as f64;
                let theta = (sector_deg * fraction).to_radians();
                positions.push(point(z, theta, inner));
            }
        }
        let index = |i: usize, j: usize| base + (i * (columns + 1) + j) as u32;
        for i in 0..rows {
            for j in 0..columns {
                let (a, b, c, d) = (index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j));
                if inner {
                    triangles.push([a, c, b]);
                    triangles.push([a, d, c]);
                } else {
                    triangles.push([a, b, c]);
                    triangles.push([a, c, d]);
                }
            }
        }
    };
    grid(false, &mut positions, &mut triangles);
    grid(true, &mut positions, &mut triangles);
    if lip {
        // A flat lip: a strip of three rings from the inner to the outer top edge.
        let base = positions.len() as u32;
        for k in 0..=3 {
            for j in 0..=columns {
                let theta = (sector_deg * j as f64 / columns as f64).to_radians();
                let r = radius(height, theta, true) + thickness * k as f64 / 3.0;
                positions.push(Point::new(r * theta.cos(), r * theta.sin(), height));
            }
        }
        for k in 0..3 {
            for j in 0..columns {
                let index = |k: usize, j: usize| base + (k * (columns + 1) + j) as u32;
                triangles.push([index(k, j), index(k + 1, j), index(k + 1, j + 1)]);
                triangles.push([index(k, j), index(k + 1, j + 1), index(k, j + 1)]);
            }
        }
    }
    Mesh::new(positions, triangles)
}

fn motion(seed: u64) -> Isometry3<f64> {
    let s = seed as f64;
    Isometry3::from_parts(
        Translation3::new(10.0 * s.sin(), -25.0 + s, 40.0 * (0.3 * s).cos()),
        UnitQuaternion::from_euler_angles(0.7 + s, -0.4 * s, 1.1 * s),
    )
}

/// The fixture moved by a rigid motion, its true axis, and a start axis `tilt_deg` and
/// `shift_mm` off.
fn placed(mesh: &Mesh, seed: u64, tilt_deg: f64, shift_mm: f64) -> (Mesh, Axis, Axis) {
    let motion = motion(seed);
    let mut moved = mesh.clone();
    moved.transform(&motion);
    let truth = Axis::new(motion * Point::origin(), motion * Vector::z());
    let tilt = UnitQuaternion::from_axis_angle(&Vector::x_axis(), tilt_deg.to_radians() * 0.8)
        * UnitQuaternion::from_axis_angle(&Vector::y_axis(), tilt_deg.to_radians() * 0.6);
    let start_local = Axis::new(Point::new(shift_mm * 0.6, -shift_mm * 0.8, 20.0), tilt * Vector::z());
    let start = Axis::new(motion * start_local.point, motion * start_local.direction.into_inner());
    (moved, truth, start)
}

/// A fixed start for corpus fragment `id`: its true axis turned 3 degrees about its point
/// level with the centroid and shifted 2 mm, in directions set by the id.
fn corpus_start(id: u64, sherd: &sherd::synth::SynthSherd) -> Axis {
    let centroid = sherd.mesh.centroid().unwrap();
    let azimuth = (id as f64 * 2.4).rem_euclid(std::f64::consts::TAU);
    evaluation::perturbed_axis(&sherd.truth.axis.normalized(&centroid), azimuth, 3.0, azimuth + 1.0, 2.0)
}

#[test]
fn every_criterion_recovers_the_axis_of_a_perfect_rim_sherd() {
    let mesh = fixture(40.0, 45.0, true, 0.0);
    for criterion in [Criterion::Circles, Criterion::Profile, Criterion::Tangent, Criterion::Pareto, Criterion::Auto] {
        let (moved, truth, start) = placed(&mesh, 3, 3.0, 2.0);
        let options = RefineOptions { criterion, ..Default::default() };
        let result = refine(&moved, &start, &options).unwrap();
        let angle = result.axis.line_angle_to_deg(&truth);
        let distance = mean_point_distance_mm(&moved.positions, &result.axis, &truth);
        let start_distance = mean_point_distance_mm(&moved.positions, &start, &truth);
        assert!(angle < 0.3, "{criterion:?}: {angle} deg off ({:?})", result.report);
        if result.report.method == Criterion::Tangent {
            // The plane fixes the direction; the position stays the start's by default.
            assert!(distance < start_distance, "{criterion:?}: {distance} mm, start {start_distance} mm");
        } else {
            assert!(distance < 0.5 && distance < start_distance / 4.0, "{criterion:?}: {distance} mm, start {start_distance} mm");
        }
        assert!(result.axis.direction.dot(&start.direction) > 0.0, "direction must stay base to rim");
    }
}

#[test]
fn tangent_plane_then_circles_places_the_axis_when_asked() {
    let mesh = fixture(40.0, 45.0, true, 0.0);
    let (moved, truth, start) = placed(&mesh, 3, 3.0, 2.0);
    let options = RefineOptions { criterion: Criterion::Tangent, tangent_places_by_circles: true, ..Default::default() };
    let result = refine(&moved, &start, &options).unwrap();
    assert!(result.axis.line_angle_to_deg(&truth) < 0.3);
    assert!(mean_point_distance_mm(&moved.positions, &result.axis, &truth) < 0.5);
}

#[test]
fn auto_uses_the_tangent_plane_on_rims_and_circles_on_body_sherds() {
    let rim = fixture(40.0, 45.0, true, 0.0);
    let (moved, _, start) = placed(&rim, 5, 3.0, 1.0);
    let report = refine(&moved, &start, &RefineOptions::default()).unwrap().report;
    assert_eq!(report.method, Criterion::Tangent, "{}", report.reason);
    let body = fixture(40.0, 45.0, false, 0.0);
    let (moved, _, start) = placed(&body, 5, 3.0, 1.0);
    let report = refine(&moved, &start, &RefineOptions::default()).unwrap().report;
    assert_eq!(report.method, Criterion::Circles, "{}", report.reason);
}

#[test]
fn shifts_only_keeps_a_manual_direction() {
    let mesh = fixture(50.0, 40.0, false, 0.0);
    let (moved, truth, start) = placed(&mesh, 7, 0.0, 3.0);
    let options = RefineOptions {
        criterion: Criterion::Circles,
        free: sherd::refine::FreeParameters::ShiftsOnly,
        ..Default::default()
    };
    let result = refine(&moved, &start, &options).unwrap();
    assert!(result.axis.line_angle_to_deg(&start) < 1e-9);
    assert!(mean_point_distance_mm(&moved.positions, &result.axis, &truth) < 0.1);
}

#[test]
fn each_surface_choice_works_alone() {
    let mesh = fixture(40.0, 45.0, false, 0.0);
    for surface in [Surface::Inner, Surface::Outer, Surface::Both] {
        let (moved, truth, start) = placed(&mesh, 11, 2.5, 1.5);
        let options = RefineOptions { criterion: Criterion::Circles, surface, ..Default::default() };
        let result = refine(&moved, &start, &options).unwrap();
        assert!(result.axis.line_angle_to_deg(&truth) < 0.3, "{surface:?}: {}", result.axis.line_angle_to_deg(&truth));
    }
}

#[test]
fn refinement_never_returns_an_axis_its_criterion_rates_worse() {
    // Started on the truth, a criterion may move only if it finds a lower cost.
    let mesh = fixture(30.0, 40.0, true, 0.01);
    for criterion in [Criterion::Circles, Criterion::Profile, Criterion::Tangent] {
        let (moved, truth, _) = placed(&mesh, 13, 0.0, 0.0);
        let result = refine(&moved, &truth, &RefineOptions { criterion, ..Default::default() }).unwrap();
        assert!(result.report.residual_mm <= result.report.start_residual_mm, "{:?}", result.report);
    }
}

#[test]
fn criteria_agree_on_a_regular_sherd_and_disagree_on_a_deformed_one() {
    let spread = |ovality: f64| {
        let mesh = fixture(60.0, 45.0, true, ovality);
        let (moved, _, start) = placed(&mesh, 17, 2.0, 1.0);
        let axes: Vec<Axis> = [Criterion::Circles, Criterion::Profile, Criterion::Tangent]
            .into_iter()
            .map(|criterion| {
                // Each criterion as a full estimator: the tangent plane placed by circles.
                let options = RefineOptions { criterion, tangent_places_by_circles: true, ..Default::default() };
                refine(&moved, &start, &options).unwrap().axis
            })
            .collect();
        let mut largest: f64 = 0.0;
        for a in &axes {
            for b in &axes {
                largest = largest.max(mean_point_distance_mm(&moved.positions, a, b));
            }
        }
        largest
    };
    let regular = spread(0.0);
    let deformed = spread(0.04);
    assert!(regular < 0.3, "criteria should agree on a regular sherd, differ by {regular} mm");
    assert!(deformed > 3.0 * regular.max(0.1), "criteria should disagree on an oval sherd: {deformed} vs {regular} mm");
}

#[test]
fn bad_options_are_reported() {
    let mesh = fixture(40.0, 45.0, true, 0.0);
    let (moved, _, start) = placed(&mesh, 1, 1.0, 1.0);
    let bad = RefineOptions { search_bound_deg: -1.0, ..Default::default() };
    let error = refine(&moved, &start, &bad).unwrap_err().to_string();
    assert!(error.contains("search_bound_deg"), "{error}");
    let nan = Axis { point: Point::new(f64::NAN, 0.0, 0.0), direction: start.direction };
    assert!(refine(&moved, &nan, &RefineOptions::default()).unwrap_err().to_string().contains("not finite"));
    let tiny = Mesh::new(vec![Point::origin(); 3], vec![]);
    assert!(refine(&tiny, &start, &RefineOptions::default()).is_err());
    // The Pareto and profile settings are checked once, in the library, for every host.
    let mut pareto = RefineOptions { criterion: Criterion::Pareto, ..Default::default() };
    pareto.pareto.min_section_points = 2;
    assert!(refine(&moved, &start, &pareto).unwrap_err().to_string().contains("min_points"));
    pareto.pareto = sherd::refine::pareto::ParetoOptions {
        choice: sherd::refine::pareto::ParetoChoice::MeanOfBest(0),
        ..Default::default()
    };
    assert!(refine(&moved, &start, &pareto).unwrap_err().to_string().contains("at least 1"));
    let polynomial = RefineOptions { profile_method: sherd::refine::superposition::ProfileMethod::Polynomial { degree: 0 }, ..Default::default() };
    assert!(refine(&moved, &start, &polynomial).unwrap_err().to_string().contains("degree"));
}

/// The refine bench's sherd (synthetic rim seed 7, 20k faces): a rounded lip at this
/// resolution turns by a degree or two per face, and the inner and outer skins once
/// joined through it into one smooth region with no skin at all, so that the circles,
/// profile and Pareto criteria refused the sherd.
#[test]
fn skins_stay_apart_across_a_finely_meshed_rounded_lip() {
    use sherd::refine::sections::{PreparedSurface, Skin};
    use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
    let sherd = synthetic_sherd(7, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Rim) });
    let surface = PreparedSurface::new(&sherd.mesh, &sherd.truth.axis, Surface::Both, None).unwrap();
    for skin in [Skin::Inner, Skin::Outer] {
        let count = surface.skins.iter().filter(|s| **s == Some(skin)).count();
        assert!(count > sherd.mesh.vertex_count() / 4, "{skin:?} skin: {count} of {} vertices", sherd.mesh.vertex_count());
    }
    for criterion in [Criterion::Circles, Criterion::Profile, Criterion::Pareto] {
        let refined = refine(&sherd.mesh, &sherd.truth.axis, &RefineOptions { criterion, ..Default::default() });
        assert!(refined.is_ok(), "{criterion:?}: {:?}", refined.err());
    }
}

/// The sherd of the Python pipeline test (synthetic rim seed 13, 12k faces) from the
/// automatic pre-orientation, 0.4 degrees off: the polynomial profile of degree 6 misfits
/// its lip by 0.7 mm RMS and moved the axis to 6.1 degrees; the spline profile keeps it
/// within 1.5.
#[test]
fn profile_criterion_keeps_a_well_oriented_rim() {
    use sherd::orient::{orient_automatic, OrientOptions};
    use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
    let sherd = synthetic_sherd(13, &SherdOptions { target_faces: 12_000, noise_mm: 0.02, ..SherdOptions::for_part(SherdPart::Rim) });
    let start = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap().axis;
    let refined = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Profile, ..Default::default() }).unwrap();
    let angle = refined.axis.line_angle_to_deg(&sherd.truth.axis);
    assert!(angle < 2.0, "profile criterion: {angle} deg from the truth (start {} deg)", start.line_angle_to_deg(&sherd.truth.axis));
}

#[test]
fn pareto_search_stays_within_the_tilt_bound() {
    // The truth lies 12 degrees off the start, outside a 5-degree cone: every front point
    // and the chosen axis must stay inside the cone (the box's corners reach 7.1 degrees),
    // and the search must still move towards the truth.
    let mesh = fixture(40.0, 45.0, true, 0.0);
    let (moved, truth, start) = placed(&mesh, 5, 12.0, 1.0);
    let bound_deg = 5.0;
    let options = RefineOptions { criterion: Criterion::Pareto, search_bound_deg: bound_deg, ..Default::default() };
    let result = refine(&moved, &start, &options).unwrap();
    let front = result.pareto_front.as_ref().expect("the Pareto criterion reports its front");
    assert!(!front.is_empty());
    for p in front {
        let norm_deg = p.tilt_x_deg.hypot(p.tilt_y_deg);
        let (x, y) = (p.tilt_x_deg, p.tilt_y_deg);
        assert!(norm_deg <= bound_deg + 1e-9, "front point at tilts {x:.3}, {y:.3} deg ({norm_deg:.3} deg)");
    }
    let moved_deg = result.axis.line_angle_to_deg(&start);
    assert!(moved_deg <= bound_deg + 1e-9, "the chosen axis is {moved_deg} deg off the start");
    let start_error_deg = start.line_angle_to_deg(&truth);
    let error_deg = result.axis.line_angle_to_deg(&truth);
    assert!(error_deg < start_error_deg - 3.0, "{error_deg} deg off the truth, the start {start_error_deg} deg");
}

#[test]
fn a_levelled_base_whose_sections_do_not_fix_it_is_placed_by_its_normals() {
    // Bases of the synthetic corpus (vessel, fragment) whose floor gives Eq. 2 too few
    // usable sections: before, the tangent criterion levelled them and left the axis
    // where it started.
    use sherd::synth::{generate_vessel, VesselOptions};
    for (vessel_seed, fragment) in [(9, 19), (1, 9)] {
        let vessel = generate_vessel(vessel_seed, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
        let sherd = &vessel.fragments[fragment];
        let truth = &sherd.truth.axis;
        let centroid = sherd.mesh.positions.iter().fold(Point::origin(), |sum, p| sum + p.coords / sherd.mesh.positions.len() as f64);
        let towards = (centroid - truth.closest_point(&centroid)).normalize();
        let start = Axis::new(truth.point + towards * 10.0, truth.direction.into_inner());
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).expect("refined");
        let distance = mean_point_distance_mm(&sherd.mesh.positions, &refined.axis, truth);
        assert_eq!(format!("{:?}", refined.report.method), "Tangent");
        assert!(distance < 2.0, "vessel {vessel_seed} fragment {fragment}: {distance:.2} mm from the true axis (start 10 mm off)");
    }
}

/// The profile criterion (Eq. 6, the default spline) recovers the axis of perfect solids
/// of revolution broken by the synthetic corpus's fracture from 3 degrees off. With its
/// knots 5 mm apart the spline missed the lips and carinations by more than a scan would,
/// and the tilt that spread that misfit won: vessel 0's fragment 8 ended 2.9 degrees
/// (11 mm) off, vessel 5's fragments 7 and 4 12.1 and 3.3 degrees (34 and 9 mm). With
/// knots 1.5 mm apart they end at most 0.7 degrees and 2.8 mm off.
#[test]
fn the_profile_criterion_recovers_perfect_solids_of_the_synthetic_corpus() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, deformation_scale: 0.0, noise_mm: 0.0, ..Default::default() };
    for (vessel_seed, fragment) in [(0u64, 8usize), (5, 7), (5, 4), (2, 29)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        let truth = sherd.truth.axis;
        // The true axis turned by 3 degrees about a horizontal line and shifted by 2 mm.
        let start = evaluation::perturbed_axis(&truth, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
        let refined = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Profile, ..Default::default() }).unwrap();
        let angle = refined.axis.line_angle_to_deg(&truth);
        let distance = mean_point_distance_mm(&sherd.mesh.positions, &refined.axis, &truth);
        println!("vessel {vessel_seed} fragment {fragment}: {angle:.3} deg, {distance:.2} mm");
        assert!(angle < 1.0 && distance < 3.0, "vessel {vessel_seed} fragment {fragment}: {angle:.2} deg, {distance:.2} mm");
    }
}

/// On a base the tangent plane takes its tilts from the plane of the flat underside, where
/// the fragment has one: Eq. 7's one lowest vertex per vertical section fixes the tilt
/// about a short arc's chord only through the arc's sagitta, and the scan's noise reaches
/// each extreme whole. Bases of the refinement corpus (deformed vessels, 0.02 mm noise)
/// levelled from 3 degrees off by Eq. 7 alone ended 0.16-1.04 degrees off; their
/// undersides' planes bring them within 0.1.
#[test]
fn a_flat_underside_gives_the_tangent_plane_its_tilts() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    for (vessel_seed, fragment) in [(6u64, 22usize), (8, 31), (3, 28), (3, 18)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        let truth = sherd.truth.axis;
        let start = evaluation::perturbed_axis(&truth, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
        let angle = refined.axis.line_angle_to_deg(&truth);
        println!("vessel {vessel_seed} fragment {fragment}: {angle:.3} deg, {}", refined.report.reason);
        assert!(refined.report.reason.contains("plane of its flat underside"), "{}", refined.report.reason);
        assert!(angle < 0.1, "vessel {vessel_seed} fragment {fragment}: {angle:.2} deg");
    }
}

/// A rounded underside whose standing ring broke off has a lowest point in every
/// vertical section too, and a plane tilted onto it touches the middle of the arc: Eq. 7
/// levelled such bases of the refinement corpus 3.7-12 degrees off and called them level
/// bases (their extremes within 0.07 mm). Their extremes rise towards both ends of the
/// arc by 0.2-0.4 mm, which no preserved base does: they are no edge, and with no wall
/// skin to cut either, the automatic refinement keeps its start and says so.
#[test]
fn a_rounded_underside_is_not_taken_for_a_base() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    for (vessel_seed, fragment) in [(2u64, 6usize), (7, 5), (7, 27)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        let truth = sherd.truth.axis;
        let start = evaluation::perturbed_axis(&truth, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
        let surface = sherd::refine::sections::PreparedSurface::new(&sherd.mesh, &start, Surface::Both, None).unwrap();
        let edges = sherd::refine::detect_edges(&surface, &RefineOptions::default());
        assert!(edges.is_empty(), "vessel {vessel_seed} fragment {fragment}: {edges:?}");
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
        println!("vessel {vessel_seed} fragment {fragment}: {:?} {:?}", refined.report.method, refined.report.flag_reason);
        assert_eq!(refined.report.method, Criterion::Circles);
        assert!(refined.report.flagged && refined.report.kept_start, "{:?}", refined.report);
        assert!(refined.report.flag_reason.as_deref().unwrap_or("").contains("nothing to refine the axis by"));
        // Asked for the circles criterion, the same fragment is an error, not a guess.
        let asked = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Circles, ..Default::default() });
        assert!(asked.is_err());
    }
}

/// Eq. 7 measures every vertical section from the single highest extreme and drops those
/// more than epsilon below it, so a tilt that pushes a damaged section out of epsilon
/// lowers it. From its automatic pre-orientation (3.9 degrees off) rim 3 of vessel 2 was
/// levelled 3.4 degrees off that way, its ends sagging 0.24 mm below the plane; turned
/// onto the least-squares plane of its level extremes it is within half a degree.
#[test]
fn a_damaged_section_inside_epsilon_does_not_tip_a_rim() {
    use sherd::orient::{orient_automatic, OrientOptions};
    use sherd::synth::{generate_vessel, VesselOptions};
    let vessel = generate_vessel(2, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
    let sherd = &vessel.fragments[3];
    let start = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap().axis;
    let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
    let angle = refined.axis.line_angle_to_deg(&sherd.truth.axis);
    println!("start {:.2} deg, refined {angle:.2} deg: {}", start.line_angle_to_deg(&sherd.truth.axis), refined.report.reason);
    assert_eq!(refined.report.method, Criterion::Tangent);
    assert!(angle < 0.5, "{angle:.2} deg off");
    // Asked for the tangent plane on the rim, without the detection, the same.
    let asked = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Tangent, edge: Some(sherd::refine::Edge::Rim), ..Default::default() }).unwrap();
    assert!(asked.axis.line_angle_to_deg(&sherd.truth.axis) < 0.5, "{:.2} deg off", asked.axis.line_angle_to_deg(&sherd.truth.axis));
}

/// A floor piece has no wall and no rim: its highest points lie on its upper face, which
/// Eq. 7 levels as readily as an edge. On the refinement corpus two floors were levelled
/// by their curved upper faces, 4.8 and 7.4 degrees off, and called level rims. The upper
/// face counts only where it is flat, as a floor's underside is when the start axis holds
/// the piece upside down: then its plane gives the axis.
#[test]
fn a_floor_has_no_rim_but_a_flat_face() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    let start_of = |truth: &Axis| evaluation::perturbed_axis(truth, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
    for (vessel_seed, fragment) in [(0u64, 14usize), (2, 28)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        let start = start_of(&sherd.truth.axis);
        let surface = sherd::refine::sections::PreparedSurface::new(&sherd.mesh, &start, Surface::Both, None).unwrap();
        let edges = sherd::refine::detect_edges(&surface, &RefineOptions::default());
        assert!(edges.iter().all(|e| e.edge != sherd::refine::Edge::Rim), "vessel {vessel_seed} fragment {fragment}: {edges:?}");
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
        let angle = refined.axis.line_angle_to_deg(&sherd.truth.axis);
        println!("vessel {vessel_seed} fragment {fragment}: {angle:.2} deg, {:?}, {}, {:?}", refined.report.method, refined.report.reason, refined.report.flag_reason);
        assert!(refined.report.edge != Some(sherd::refine::Edge::Rim), "{}", refined.report.reason);
        assert!(angle < 3.5 || refined.report.flagged, "vessel {vessel_seed} fragment {fragment}: {angle:.2} deg off, not flagged");
    }
    // A flat floor held upside down: its underside is on top.
    let sherd = &generate_vessel(0, &options).fragments[1];
    let upside_down = Axis::new(sherd.truth.axis.point, -sherd.truth.axis.direction.into_inner());
    let refined = refine(&sherd.mesh, &start_of(&upside_down), &RefineOptions::default()).unwrap();
    let angle = refined.axis.line_angle_to_deg(&sherd.truth.axis);
    println!("vessel 0 fragment 1 upside down: {angle:.3} deg, {}", refined.report.reason);
    assert!(refined.report.reason.contains("plane of its flat upper face"), "{}", refined.report.reason);
    assert!(angle < 0.1, "{angle:.3} deg off");
}

/// The tangent plane's search is bounded around the start (10 degrees by default): a
/// levelling that ends at the bound found no level plane inside it, unless a plane takes
/// over from there. The flank of a floor's curved underside was levelled at exactly the
/// bound, 7.4 degrees off, and called a level base: it is no edge now. A body sherd's
/// break line, levelled at the bound and turned 15.8 degrees from its start by the plane
/// of its extremes (18.7 off), still passes for a rim, but an axis at or past the bound is
/// flagged, by the automatic criterion as by the tangent plane asked for by name.
#[test]
fn a_levelling_at_the_search_bound_is_no_edge() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    for (vessel_seed, fragment) in [(0u64, 14usize), (1, 33)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        let start = evaluation::perturbed_axis(&sherd.truth.axis, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
        let past_bound_is_flagged = |report: &sherd::refine::RefineReport| {
            report.tilt_deg < 9.9 || report.flag_reason.as_deref().is_some_and(|r| r.contains("search bound"))
        };
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
        println!("vessel {vessel_seed} fragment {fragment}: tilt {:.2}, {:?}, {}, {:?}", refined.report.tilt_deg, refined.report.method, refined.report.reason, refined.report.flag_reason);
        assert!(past_bound_is_flagged(&refined.report), "{:?}", refined.report);
        let asked = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Tangent, ..Default::default() }).unwrap();
        println!("  asked for the tangent plane: tilt {:.2}, {:?}", asked.report.tilt_deg, asked.report.flag_reason);
        assert!(past_bound_is_flagged(&asked.report), "{:?}", asked.report);
    }
    // The floor is no base, levelled at the bound.
    let sherd = &generate_vessel(0, &options).fragments[14];
    let start = evaluation::perturbed_axis(&sherd.truth.axis, 0.8f64.atan2(0.6), 3.0, 0.0, 2.0);
    let surface = sherd::refine::sections::PreparedSurface::new(&sherd.mesh, &start, Surface::Both, None).unwrap();
    let edges = sherd::refine::detect_edges_over(&surface, &RefineOptions::default(), [0.0, 0.0]);
    assert!(edges.is_empty(), "{edges:?}");
}

/// A base sherd may keep only a little of its floor beside the wall's first gentle rise.
/// Eq. 7 levels its lowest points, which the rise leads off (vessel 6's fragment 24 was
/// levelled 10 degrees off, 3 off the truth before the face was sought by its normals),
/// and the underside's plane taken from the lowest band leans onto the rise. Its face is
/// the plane that holds most of its vertices with none beyond it (the piece can stand on
/// it) and does not curve like a bowl: from starts 3 degrees off in four directions the
/// axis is within 0.3 degrees, tilted by the underside.
#[test]
fn a_small_floor_beside_the_rising_wall_gives_the_tilts() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    for (vessel_seed, fragment) in [(6u64, 24usize), (3, 1), (1, 3)] {
        let sherd = &generate_vessel(vessel_seed, &options).fragments[fragment];
        for azimuth_deg in [0.0f64, 90.0, 180.0, 270.0] {
            let start = evaluation::perturbed_axis(&sherd.truth.axis, azimuth_deg.to_radians(), 3.0, 0.0, 2.0);
            let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
            let angle = refined.axis.line_angle_to_deg(&sherd.truth.axis);
            println!("vessel {vessel_seed} fragment {fragment}, start turned towards {azimuth_deg}: {angle:.3} deg, {}", refined.report.reason);
            assert!(refined.report.reason.contains("plane of its flat underside"), "{}", refined.report.reason);
            assert!(angle < 0.3, "vessel {vessel_seed} fragment {fragment}, start turned towards {azimuth_deg}: {angle:.3} deg off");
        }
    }
}

/// The normals that place a levelled base count by the area they cover, not one per face:
/// on the synthetic corpus meshed in 0.8 mm cells (the orientation's corpus), a face's
/// normal turns with the scan's noise by two degrees, and 5,600 of them made a short
/// base's footprint 56 mm off the axis look fixed to 0.6 mm (vessel 3, fragment 16,
/// placed 57 mm off, not flagged). Gathered into 2 mm patches they place the bases that
/// the 2 mm cells placed, and leave that one where it started.
#[test]
fn a_fine_mesh_places_a_levelled_base_by_patches_of_its_normals() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let fine = VesselOptions { fragment_count: 34, random_motion: true, cell_size_mm: 0.8, ..Default::default() };
    for (vessel_seed, fragment) in [(9u64, 19usize), (1, 9), (3, 16)] {
        let sherd = &generate_vessel(vessel_seed, &fine).fragments[fragment];
        for azimuth_deg in [0.0f64, 120.0, 240.0] {
            let start = evaluation::perturbed_axis(&sherd.truth.axis, azimuth_deg.to_radians(), 3.0, azimuth_deg.to_radians(), 2.0);
            let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
            let distance = mean_point_distance_mm(&sherd.mesh.positions, &refined.axis, &sherd.truth.axis);
            println!("vessel {vessel_seed} fragment {fragment}, start towards {azimuth_deg}: {distance:.2} mm, {}", refined.report.reason);
            assert!(distance < 4.0 || refined.report.flagged, "vessel {vessel_seed} fragment {fragment}, start towards {azimuth_deg}: {distance:.2} mm off, not flagged");
        }
    }
}

/// Eq. 2 fits four parameters: a fragment whose skins give it fewer than five usable
/// horizontal sections (a base with only the foot of its wall) has nothing to refine its
/// axis by. On the 0.8 mm corpus vessel 5's fragment 23 had one section of eight points,
/// which the circles fitted to 0.003 mm (the truth: 0.028) with the axis 17.5 mm off,
/// not flagged; vessel 2's fragment 19 went 28 mm off.
#[test]
fn a_handful_of_sections_is_nothing_to_refine_by() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let fine = VesselOptions { fragment_count: 34, random_motion: true, cell_size_mm: 0.8, ..Default::default() };
    for (vessel_seed, fragment) in [(5u64, 23usize), (2, 19), (7, 27)] {
        let sherd = &generate_vessel(vessel_seed, &fine).fragments[fragment];
        let start = evaluation::perturbed_axis(&sherd.truth.axis, 1.0, 3.0, 2.0, 2.0);
        let refined = refine(&sherd.mesh, &start, &RefineOptions::default()).unwrap();
        let distance = mean_point_distance_mm(&sherd.mesh.positions, &refined.axis, &sherd.truth.axis);
        println!("vessel {vessel_seed} fragment {fragment}: {distance:.2} mm, {:?}", refined.report.flag_reason);
        assert!(refined.report.kept_start && refined.report.flagged, "vessel {vessel_seed} fragment {fragment}: refined to {distance:.2} mm off, flagged {}", refined.report.flagged);
    }
}

/// A rim's plane through vertical sections two edge lengths wide (as many as the mesh
/// resolves) holds its tilt better than through the paper's 12: each section's highest
/// point is one more sample of a short arc's sagitta, which alone fixes the tilt about its
/// chord. The rims of the refinement corpus (20 vessels, 0.8 mm cells) that the tangent
/// plane levels, from 3 degrees off: 134 of 189 end within 0.3 degrees of the truth
/// instead of 128.
#[test]
fn a_rims_plane_through_finer_sections_holds_its_tilt_better() {
    use sherd::refine::objective::SearchSettings;
    use sherd::refine::sections::PreparedSurface;
    use sherd::refine::tangent::{level_by_plane, level_edge, plane_section_count, Edge};
    use sherd::refine::FreeParameters;
    use sherd::synth::SherdPart;
    let corpus = evaluation::refinement_corpus(20, 1.0, 0.02, 0.8);
    let settings = SearchSettings { free: FreeParameters::TiltsOnly, tilt_bound_rad: 10f64.to_radians(), ..Default::default() };
    let (mut coarse_within, mut fine_within, mut rims) = (0, 0, 0);
    for (id, sherd) in corpus.iter().filter(|(_, s)| s.truth.part == SherdPart::Rim) {
        let azimuth = (*id as f64 * 2.4).rem_euclid(std::f64::consts::TAU);
        let start = evaluation::perturbed_axis(&sherd.truth.axis, azimuth, 3.0, azimuth + 1.0, 2.0);
        let surface = PreparedSurface::new(&sherd.mesh, &start, Surface::Both, None).unwrap();
        let Ok(levelled) = level_edge(&surface, Edge::Rim, 3.0, 12, [0.0; 4], &settings, None) else { continue };
        let angle = |sections: usize| {
            level_by_plane(&surface, Edge::Rim, 3.0, sections, &levelled)
                .map(|plane| surface.axis_of(&plane.parameters).line_angle_to_deg(&sherd.truth.axis))
        };
        let (Some(coarse), Some(fine)) = (angle(12), angle(plane_section_count(&surface, Edge::Rim, 12))) else { continue };
        // Only rims level enough for the tangent plane to hold them: within a degree.
        if coarse.min(fine) > 1.0 {
            continue;
        }
        rims += 1;
        coarse_within += usize::from(coarse < 0.3);
        fine_within += usize::from(fine < 0.3);
    }
    println!("{rims} rims: within 0.3 degrees through 12 sections {coarse_within}, through finer sections {fine_within}");
    assert!(rims >= 60, "{rims} rims");
    assert!(fine_within >= coarse_within + 3, "finer sections {fine_within}, 12 sections {coarse_within} of {rims} rims within 0.3 degrees");
}

#[test]
fn body_sherds_take_the_mean_of_the_circles_and_the_profile() {
    use sherd::synth::SherdPart;
    // Without a level rim or base, Eq. 2 reads the horizontal sections and the profile
    // criterion the vertical ones; the pot's deformation misleads them differently.
    let corpus = evaluation::refinement_corpus(6, 1.0, 0.02, 0.8);
    let (mut circles_angles, mut auto_angles) = (Vec::new(), Vec::new());
    for (id, sherd) in corpus.iter().filter(|(_, s)| s.truth.part == SherdPart::Body) {
        let start = corpus_start(*id, sherd);
        let angle = |criterion| {
            refine(&sherd.mesh, &start, &RefineOptions { criterion, ..Default::default() }).map(|r| r.axis.line_angle_to_deg(&sherd.truth.axis))
        };
        let (Ok(circles), Ok(auto)) = (angle(Criterion::Circles), angle(Criterion::Auto)) else { continue };
        circles_angles.push(circles);
        auto_angles.push(auto);
    }
    let median = |angles: &[f64]| {
        let mut sorted = angles.to_vec();
        sorted.sort_by(f64::total_cmp);
        sorted[sorted.len() / 2]
    };
    let within = |angles: &[f64], limit: f64| angles.iter().filter(|a| **a < limit).count();
    for limit in [0.3, 0.5, 1.0] {
        println!("within {limit} deg: circles {}, auto {}", within(&circles_angles, limit), within(&auto_angles, limit));
    }
    let (circles_median, auto_median) = (median(&circles_angles), median(&auto_angles));
    println!("{} body sherds: median {circles_median:.3} deg by circles, {auto_median:.3} by auto", auto_angles.len());
    assert!(auto_angles.len() >= 60, "{} body sherds", auto_angles.len());
    assert!(auto_median < 0.9 * circles_median, "auto {auto_median:.3} deg, circles {circles_median:.3} deg on median");
    let (circles_within, auto_within) = (within(&circles_angles, 1.0), within(&auto_angles, 1.0));
    assert!(auto_within >= circles_within + 4, "within a degree: auto {auto_within}, circles {circles_within}");
}

#[test]
fn a_clean_scan_is_flagged_where_its_axis_slides_as_a_noisy_one_is() {
    // Without scan noise Eq. 2 at the placement is the deformation's residual alone, a
    // few thousandths of a millimetre, and a valley as flat as those the placement test
    // flags on a noisy scan rose many times over it. These 8 vessels from these starts:
    // with the corpus's 0.02 mm noise 2 of the 19 fragments past 4 mm are not flagged;
    // without noise, measured against the residual alone, 14 of 19; against at least
    // `MIN_PLACING_RESIDUAL_MM`, 8 of 18.
    let corpus = evaluation::refinement_corpus(8, 1.0, 0.0, 0.8);
    let (mut wrong, mut wrong_unflagged, mut flagged, mut refined) = (0, 0, 0, 0);
    for (id, sherd) in &corpus {
        let start = corpus_start(*id, sherd);
        let Ok(refinement) = refine(&sherd.mesh, &start, &RefineOptions::default()) else { continue };
        refined += 1;
        flagged += usize::from(refinement.report.flagged);
        if mean_point_distance_mm(&sherd.mesh.positions, &refinement.axis, &sherd.truth.axis) > 4.0 {
            wrong += 1;
            wrong_unflagged += usize::from(!refinement.report.flagged);
        }
    }
    println!("{refined} fragments refined without noise: {flagged} flagged, {wrong} past 4 mm, {wrong_unflagged} of them not flagged");
    assert!(refined >= 250, "{refined} fragments");
    assert!(2 * wrong_unflagged <= wrong, "{wrong_unflagged} of {wrong} past 4 mm not flagged");
}

#[test]
fn an_averaged_direction_eq2_cannot_place_turns_about_the_circles_axis() {
    // Where the direction averaged with the profile's lies across the valley of Eq. 2 far
    // less firmly than the circles criterion's own, placing it by Eq. 2 slides it along
    // the fragment's radius: an axis Eq. 2 alone had within 4 mm ends past it. These 12
    // vessels from these starts: placed by Eq. 2 everywhere, auto had 179 within 4 mm
    // against the circles' 181; turned about the circles' axis there, 187.
    let corpus = evaluation::refinement_corpus(12, 1.0, 0.02, 0.8);
    let (mut circles_within, mut auto_within, mut compared, mut turned) = (0, 0, 0, 0);
    for (id, sherd) in &corpus {
        let start = corpus_start(*id, sherd);
        let Ok(auto) = refine(&sherd.mesh, &start, &RefineOptions::default()) else { continue };
        if auto.report.method != Criterion::Circles {
            continue;
        }
        let Ok(circles) = refine(&sherd.mesh, &start, &RefineOptions { criterion: Criterion::Circles, ..Default::default() }) else { continue };
        let within = |axis: &Axis| usize::from(mean_point_distance_mm(&sherd.mesh.positions, axis, &sherd.truth.axis) <= 4.0);
        compared += 1;
        // The report says which was done.
        turned += usize::from(auto.report.reason.contains("turned about the circles' axis"));
        circles_within += within(&circles.axis);
        auto_within += within(&auto.axis);
    }
    println!("{compared} fragments without a level edge, {turned} turned: within 4 mm by circles {circles_within}, by auto {auto_within}");
    assert!(compared >= 150, "{compared} fragments");
    assert!(turned >= 5, "{turned} fragments turned about the circles' axis");
    assert!(auto_within >= circles_within + 3, "within 4 mm: auto {auto_within}, circles {circles_within}");
}

#[test]
fn a_clean_scans_wrong_axis_moves_when_a_quarter_of_its_arc_is_left_out() {
    use sherd::profile::measure::MAX_UNFLAGGED_SECTOR_MOVE_MM;
    use sherd::refine::sector_jackknife::sector_jackknife_move_mm;
    // Without scan noise the bootstrap's resampled sections agree about an axis the
    // vessel's deformation put off; the arc without one of its quarters reads another
    // deformation.
    let corpus = evaluation::refinement_corpus(5, 1.0, 0.0, 0.8);
    let (mut wrong, mut wrong_moved, mut right, mut right_moved) = (0, 0, 0, 0);
    for (id, sherd) in &corpus {
        let start = corpus_start(*id, sherd);
        let Ok(refinement) = refine(&sherd.mesh, &start, &RefineOptions::default()) else { continue };
        if refinement.report.flagged {
            continue;
        }
        let Some(moved_mm) = sector_jackknife_move_mm(&sherd.mesh, &refinement.axis, &RefineOptions::default()) else { continue };
        let moved = usize::from(moved_mm > MAX_UNFLAGGED_SECTOR_MOVE_MM);
        if mean_point_distance_mm(&sherd.mesh.positions, &refinement.axis, &sherd.truth.axis) > 4.0 {
            wrong += 1;
            wrong_moved += moved;
        } else {
            right += 1;
            right_moved += moved;
        }
    }
    println!("not flagged by the refinement: {wrong_moved} of {wrong} past 4 mm and {right_moved} of {right} within it moved more than {MAX_UNFLAGGED_SECTOR_MOVE_MM} mm");
    assert!(right >= 80 && wrong >= 3, "{right} right, {wrong} wrong");
    assert!(2 * wrong_moved >= wrong, "{wrong_moved} of {wrong} wrong axes moved");
    assert!(5 * right_moved <= right, "{right_moved} of {right} right axes moved");
}
