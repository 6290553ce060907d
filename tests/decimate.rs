//! Quadric edge-collapse decimation: target reached, topology and boundary kept, no
//! flipped faces, attributes (and texture coordinates through seams) interpolated, surface
//! followed. MeshLab comparisons are in
//! `tests/meshlab_decimation.rs`.

mod support;
#[path = "support/decimation_vessel.rs"]
mod vessel;

use sherd::mesh::decimate::{decimate, decimate_with_options, BoundaryPolicy, DecimateOptions};
use sherd::mesh::{Mesh, Point, Vector};
use sherd::Error;

/// Edges (as sorted vertex pairs) with the number of faces on each.
fn edge_face_counts(mesh: &Mesh) -> Vec<((u32, u32), usize)> {
    let mut edges: Vec<(u32, u32)> = mesh
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(x, y)| (x.min(y), x.max(y)))
        .collect();
    edges.sort_unstable();
    edges.chunk_by(|x, y| x == y).map(|run| (run[0], run.len())).collect()
}

fn euler_characteristic(mesh: &Mesh) -> i64 {
    let mut used = vec![false; mesh.vertex_count()];
    mesh.triangles.iter().flatten().for_each(|&v| used[v as usize] = true);
    let vertices = used.iter().filter(|&&u| u).count() as i64;
    vertices - edge_face_counts(mesh).len() as i64 + mesh.face_count() as i64
}

fn boundary_length_mm(mesh: &Mesh) -> f64 {
    edge_face_counts(mesh)
        .into_iter()
        .filter(|&(_, faces)| faces == 1)
        .map(|((a, b), _)| (mesh.positions[a as usize] - mesh.positions[b as usize]).norm())
        .sum()
}

/// Every edge has one or two faces, and every vertex's faces form one fan (the edges
/// of its link, counted over its faces, form a single path or cycle).
fn assert_manifold(mesh: &Mesh) {
    let edges = edge_face_counts(mesh);
    let worst = edges.iter().map(|&(_, faces)| faces).max().unwrap_or(0);
    assert!(worst <= 2, "an edge has {worst} faces");
    // For a manifold vertex, faces - link edges with two faces = 0 (closed fan) or 1 (open fan).
    let mut faces_at = vec![0i64; mesh.vertex_count()];
    let mut interior_edges_at = vec![0i64; mesh.vertex_count()];
    mesh.triangles.iter().flatten().for_each(|&v| faces_at[v as usize] += 1);
    for ((a, b), faces) in edges {
        if faces == 2 {
            interior_edges_at[a as usize] += 1;
            interior_edges_at[b as usize] += 1;
        }
    }
    for v in 0..mesh.vertex_count() {
        if faces_at[v] > 0 {
            let gaps = faces_at[v] - interior_edges_at[v];
            assert!(gaps == 0 || gaps == 1, "vertex {v} is not manifold ({gaps} gaps in its fan)");
        }
    }
}

fn radial_direction(p: &Point) -> Vector {
    Vector::new(p.x, p.y, 0.0).normalize()
}

#[test]
fn reaches_the_target_and_keeps_topology_and_boundary() {
    let input = vessel::noisy_vessel(40_000, 0.2, 1);
    let before = (euler_characteristic(&input), boundary_length_mm(&input));
    let (output, report) = decimate_with_options(&input, &DecimateOptions::with_target_faces(2_000)).unwrap();
    assert!(report.reached_target, "{report:?}");
    assert!((1_999..=2_000).contains(&output.face_count()), "{} faces", output.face_count());
    assert_eq!(report.output_faces, output.face_count());
    assert_eq!(report.output_vertices, output.vertex_count());
    assert!(output.validate().is_ok());
    assert_manifold(&output);
    assert_eq!(euler_characteristic(&output), before.0, "topology changed");
    let after = boundary_length_mm(&output);
    // The noisy boundary zig-zags: decimation may straighten it a little, not cut corners.
    assert!((after - before.1).abs() < 0.03 * before.1, "boundary {:.1} mm -> {after:.1} mm", before.1);
    assert_eq!(report.boundary_edges_after, edge_face_counts(&output).iter().filter(|e| e.1 == 1).count());
}

#[test]
fn follows_the_surface_and_flips_no_face() {
    let noise_mm = 0.2;
    let input = vessel::noisy_vessel(40_000, noise_mm, 2);
    let output = decimate(&input, 4_000).unwrap();
    let radial_errors: Vec<f64> = output
        .positions
        .iter()
        .map(|p| (Vector::new(p.x, p.y, 0.0).norm() - vessel::vessel_radius_mm(p.z)).abs())
        .collect();
    let mean = radial_errors.iter().sum::<f64>() / radial_errors.len() as f64;
    let max = radial_errors.iter().cloned().fold(0.0, f64::max);
    // Uniform noise of ±0.2 mm has a mean deviation of 0.1 mm; collapses average it.
    assert!(mean < 0.1, "mean distance to the true surface {mean:.3} mm");
    assert!(max < 2.0 * noise_mm, "max distance to the true surface {max:.3} mm");
    // Faces may turn by at most 60° from their input normals, which the noise tilts
    // by up to about 20° from the true surface: none may come near flipping.
    let mut worst_cos: f64 = 1.0;
    for face in 0..output.face_count() {
        let [a, b, c] = output.triangle_points(face);
        let centre = Point::from((a.coords + b.coords + c.coords) / 3.0);
        let normal = output.face_normal_scaled(face).normalize();
        worst_cos = worst_cos.min(normal.dot(&true_normal(&centre)));
    }
    assert!(worst_cos > 80f64.to_radians().cos(), "a face turned by {:.1}°", worst_cos.acos().to_degrees());
}

/// The outward normal of the noise-free vessel at the height and angle of `p`.
fn true_normal(p: &Point) -> Vector {
    let slope = (vessel::vessel_radius_mm(p.z + 1e-4) - vessel::vessel_radius_mm(p.z - 1e-4)) / 2e-4;
    (radial_direction(p) - Vector::z() * slope).normalize()
}

#[test]
fn interpolates_colours_and_normals() {
    let input = vessel::noisy_vessel(20_000, 0.05, 3);
    let output = decimate(&input, 1_000).unwrap();
    let colors = output.colors.as_ref().expect("colours kept");
    let normals = output.normals.as_ref().expect("normals kept");
    for (v, p) in output.positions.iter().enumerate() {
        let expected_red = 255.0 * p.z / vessel::HEIGHT_MM;
        assert!((f64::from(colors[v][0]) - expected_red).abs() < 4.0, "vertex {v}: red {} at z {:.2}", colors[v][0], p.z);
        assert!((normals[v].norm() - 1.0).abs() < 1e-9);
        let expected = true_normal(p);
        assert!(normals[v].dot(&expected) > 0.99, "vertex {v}: normal {:?}, true {expected:?}", normals[v]);
    }
}

#[test]
fn keeps_a_closed_synthetic_sherd_closed() {
    let options = sherd::synth::SherdOptions { target_faces: 40_000, ..Default::default() };
    let input = sherd::synth::synthetic_sherd(3, &options).mesh;
    let euler = euler_characteristic(&input);
    let boundary_before = edge_face_counts(&input).iter().filter(|e| e.1 == 1).count();
    let (output, report) = decimate_with_options(&input, &DecimateOptions::with_target_vertices(2_000)).unwrap();
    assert!(report.reached_target, "{report:?}");
    assert_manifold(&output);
    assert_eq!(euler_characteristic(&output), euler, "topology changed: {report:?}");
    assert_eq!(report.boundary_edges_before, boundary_before);
    // The generator breaks a closed wall into closed fragments (a sphere, topologically).
    assert_eq!((euler, boundary_before), (2, 0));
    assert_eq!(report.boundary_edges_after, 0, "a closed sherd was opened");
}

#[test]
fn stops_at_a_vertex_target() {
    let input = vessel::noisy_vessel(20_000, 0.1, 6);
    let (output, report) = decimate_with_options(&input, &DecimateOptions::with_target_vertices(1_000)).unwrap();
    assert!(report.reached_target, "{report:?}");
    assert_eq!(output.vertex_count(), 1_000);
    assert_manifold(&output);
}

#[test]
fn fixed_boundary_does_not_move() {
    let input = vessel::noisy_vessel(10_000, 0.2, 4);
    let options = DecimateOptions { boundary: BoundaryPolicy::Fixed, ..DecimateOptions::with_target_faces(1_500) };
    let (output, report) = decimate_with_options(&input, &options).unwrap();
    assert!(report.reached_target, "{report:?}");
    assert_eq!(report.boundary_edges_after, report.boundary_edges_before);
    assert!((boundary_length_mm(&output) - boundary_length_mm(&input)).abs() < 1e-9);
    assert_manifold(&output);
}

#[test]
fn keeps_the_hole_of_a_torus() {
    let input = support::torus(60, 30, 30.0, 10.0, 0.0);
    assert_eq!(euler_characteristic(&input), 0);
    let (output, report) = decimate_with_options(&input, &DecimateOptions::with_target_faces(12)).unwrap();
    assert_manifold(&output);
    assert_eq!(euler_characteristic(&output), 0, "genus changed: {report:?}");
    assert!(output.face_count() <= 40, "{} faces left", output.face_count());
    assert!(report.refused_for_topology > 0);
}

#[test]
fn leaves_a_small_enough_mesh_alone_and_rejects_bad_input() {
    let input = vessel::noisy_vessel(2_000, 0.1, 5);
    let output = decimate(&input, 5_000).unwrap();
    assert!(output == input, "a mesh already below the target must come back unchanged");

    let cloud = Mesh::from_points_and_normals(vec![Point::origin()], vec![Vector::z()]);
    assert!(matches!(decimate(&cloud, 10), Err(Error::InvalidArgument(m)) if m.contains("point cloud")));
    assert!(matches!(decimate(&input, 0), Err(Error::InvalidArgument(m)) if m.contains("at least one face")));
    assert!(decimate_with_options(&input, &DecimateOptions { target_vertices: Some(0), ..Default::default() }).is_err());
    let mut broken = input.clone();
    broken.triangles[7][1] = 99_999;
    assert!(matches!(decimate(&broken, 10), Err(Error::InvalidArgument(m)) if m.contains("face 7")));
    let bad_angle = DecimateOptions { max_normal_change_deg: f64::NAN, ..Default::default() };
    assert!(decimate_with_options(&input, &bad_angle).is_err());
}

/// Distance between two texture coordinates on a torus's periodic chart (0 and 1 meet).
fn periodic_distance(a: f32, b: f32) -> f32 {
    let d = (a - b).rem_euclid(1.0);
    d.min(1.0 - d)
}

/// Where a point of `support::torus(.., major, ..)` lies in the torus's own
/// parametrisation: `[around, across]`, each in [0, 1).
fn torus_parameters(p: &Point, major: f64) -> [f32; 2] {
    let around = p.y.atan2(p.x).rem_euclid(std::f64::consts::TAU);
    let across = p.z.atan2(p.x.hypot(p.y) - major).rem_euclid(std::f64::consts::TAU);
    [(around / std::f64::consts::TAU) as f32, (across / std::f64::consts::TAU) as f32]
}

#[test]
fn keeps_texture_coordinates_and_colours_through_seams() {
    // A rippled torus unwrapped on one chart: seams at u = 0|1 and v = 0|1, meeting at
    // one vertex with four UVs, as scanners' atlases have them.
    let (around, across, major) = (120, 48, 30.0);
    let mut input = support::torus(around, across, major, 10.0, 0.05);
    let uv = |i: usize, j: usize| [i as f32 / around as f32, j as f32 / across as f32];
    let mut uvs = Vec::with_capacity(3 * input.face_count());
    for i in 0..around {
        for j in 0..across {
            uvs.extend([uv(i, j), uv(i + 1, j), uv(i + 1, j + 1), uv(i, j), uv(i + 1, j + 1), uv(i, j + 1)]);
        }
    }
    input.corner_uvs = Some(uvs);
    input.texture = Some(sherd::mesh::Texture { width: 1, height: 1, rgba: vec![200, 120, 80, 255], source: None });
    // A colour that depends on the place on the surface, not on the distance to it
    // (decimation moves vertices off a curved surface).
    let red_at = |p: &Point| 127.5 + 100.0 * (std::f64::consts::TAU * f64::from(torus_parameters(p, major)[1])).sin();
    input.colors = Some(input.positions.iter().map(|p| [red_at(p) as u8, 0, 0, 255]).collect());
    input.validate().unwrap();

    let (output, report) = decimate_with_options(&input, &DecimateOptions::with_target_faces(2_000)).unwrap();
    assert!(report.reached_target, "{report:?}");
    assert!(!report.texture_dropped && report.seam_vertices == around + across - 1, "{report:?}");
    assert_manifold(&output);
    assert_eq!(euler_characteristic(&output), 0);
    assert_eq!(output.texture, input.texture, "the texture goes with its coordinates");
    let uvs = output.corner_uvs.as_ref().expect("texture coordinates kept");
    assert_eq!(uvs.len(), 3 * output.face_count());

    let mut worst_error: f32 = 0.0;
    let mut total_error = 0.0;
    for (face, triangle) in output.triangles.iter().enumerate() {
        let corners = &uvs[3 * face..3 * face + 3];
        for k in 0..2 {
            // A face whose corners sit on both sides of a seam would smear the whole
            // texture across it: the collapse dragged a chart over the seam.
            let span = corners.iter().map(|c| c[k]).fold(f32::MIN, f32::max) - corners.iter().map(|c| c[k]).fold(f32::MAX, f32::min);
            assert!(span < 0.25, "face {face} spans {span} of the chart in {}: {corners:?}", ["u", "v"][k]);
        }
        for (corner, &vertex) in corners.iter().zip(triangle) {
            let expected = torus_parameters(&output.positions[vertex as usize], major);
            let error = periodic_distance(corner[0], expected[0]).max(periodic_distance(corner[1], expected[1]));
            worst_error = worst_error.max(error);
            total_error += f64::from(error);
        }
    }
    let mean_error = total_error / uvs.len() as f64;
    // One grid step is 1/120 around and 1/48 across; the faces left are about 6 steps wide.
    // (Measured: worst 0.013, mean 0.0006; interpolating along the edge alone gave 0.024
    // and 0.0021.)
    assert!(worst_error < 0.02 && mean_error < 0.0015, "UVs off the surface: worst {worst_error}, mean {mean_error}");
    // The seams are still where they were: some vertices keep both u = 0 and u = 1.
    let on_both_sides = (0..output.vertex_count()).filter(|&v| {
        let at_v = output.triangles.iter().enumerate().flat_map(|(f, t)| (0..3).filter(move |&s| t[s] == v as u32).map(move |s| uvs[3 * f + s][0]));
        let sides: Vec<f32> = at_v.collect();
        sides.contains(&0.0) && sides.contains(&1.0)
    });
    assert!(on_both_sides.count() >= 3, "the u seam was lost");

    let colors = output.colors.as_ref().expect("colours kept");
    let colour_errors: Vec<f64> = output.positions.iter().zip(colors).map(|(p, c)| (f64::from(c[0]) - red_at(p)).abs()).collect();
    let worst_colour = colour_errors.iter().copied().fold(0.0, f64::max);
    let mean_colour = colour_errors.iter().sum::<f64>() / colour_errors.len() as f64;
    assert!(worst_colour < 12.0 && mean_colour < 1.5, "colours off: worst {worst_colour}, mean {mean_colour}");

    // Asked not to, decimation drops them (and says so), and seams no longer hold it back.
    let shape_only = DecimateOptions { keep_texture_coordinates: false, ..DecimateOptions::with_target_faces(2_000) };
    let (bare, bare_report) = decimate_with_options(&input, &shape_only).unwrap();
    assert!(bare.corner_uvs.is_none() && bare.texture.is_none() && bare_report.texture_dropped);
    assert_eq!((bare_report.refused_for_texture_seams, bare_report.seam_vertices), (0, 0));
}
