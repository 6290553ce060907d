//! Spatial indices, topology, repair, normals and smoothing on meshes whose answers are
//! known: brute-force references for the indices, counts that follow from how the
//! fixtures are built, and geometric properties (radial normals on a sphere, volume).

mod support;

use sherd::mesh::normals::{NormalWeighting, compute_vertex_normals, ensure_vertex_normals, orient_faces_outward};
use sherd::mesh::repair::{RepairOptions, repair};
use sherd::mesh::smooth::{BoundaryHandling, LaplacianWeights, SmoothOptions, hc_smooth, hc_smooth_vollmer, laplacian_smooth};
use sherd::mesh::spatial::{Bvh, KdTree};
use sherd::mesh::topology::Topology;
use sherd::mesh::{Mesh, Point, Vector};
use support::*;

fn random_points(count: usize, seed: u64) -> Vec<Point> {
    (0..count as u64)
        .map(|i| {
            let b = seed * 7919 + 3 * i;
            Point::new(50.0 * hash_unit(b), 20.0 * hash_unit(b + 1), 5.0 * hash_unit(b + 2))
        })
        .collect()
}

#[test]
fn kd_tree_matches_brute_force_on_random_points() {
    let points = random_points(5000, 1);
    let tree = KdTree::new(&points);
    for (q_index, query) in random_points(50, 2).iter().enumerate() {
        let mut brute: Vec<(f64, usize)> = points.iter().enumerate().map(|(i, p)| ((p - query).norm(), i)).collect();
        brute.sort_by(|a, b| a.0.total_cmp(&b.0));
        let nearest = tree.nearest(query).unwrap();
        assert_eq!(nearest.index, brute[0].1, "query {q_index}");
        assert!((nearest.distance - brute[0].0).abs() < 1e-12);
        let k: Vec<usize> = tree.k_nearest(query, 12).iter().map(|n| n.index).collect();
        assert_eq!(k, brute[..12].iter().map(|b| b.1).collect::<Vec<_>>());
        let radius = 4.0;
        let mut within: Vec<usize> = tree.within_radius(query, radius).iter().map(|n| n.index).collect();
        within.sort_unstable();
        let mut expected: Vec<usize> = brute.iter().take_while(|b| b.0 <= radius).map(|b| b.1).collect();
        expected.sort_unstable();
        assert_eq!(within, expected);
    }
    assert_eq!(KdTree::new(&points[..3]).k_nearest(&Point::origin(), 10).len(), 3);
    assert!(KdTree::new(&points).within_radius(&Point::origin(), -1.0).is_empty());
}

/// Brute-force closest two-sided ray hit: (face, distance).
fn brute_force_hit(mesh: &Mesh, origin: &Point, direction: &Vector) -> Option<(usize, f64)> {
    let d = direction.normalize();
    let mut best: Option<(usize, f64)> = None;
    for f in 0..mesh.face_count() {
        let [a, b, c] = mesh.triangle_points(f);
        let n = (b - a).cross(&(c - a));
        let denominator = n.dot(&d);
        if denominator.abs() < 1e-15 {
            continue;
        }
        let t = n.dot(&(a - origin)) / denominator;
        if t <= 1e-9 {
            continue;
        }
        let p = origin + d * t;
        let inside = [(a, b), (b, c), (c, a)].iter().all(|(u, v)| (v - u).cross(&(p - u)).dot(&n) >= 0.0);
        if inside && best.is_none_or(|(_, bt)| t < bt) {
            best = Some((f, t));
        }
    }
    best
}

#[test]
fn bvh_hits_and_closest_points_match_brute_force() {
    let mut mesh = icosphere(3, 10.0, Point::new(2.0, 0.0, -1.0));
    add_noise(&mut mesh, 0.4, 3);
    // Plus 80 long triangles across the ball (an icosphere's connectivity over the first
    // 42 vertices of the outer sphere): rays from inside meet crossing candidates.
    mesh.triangles.extend(icosphere(1, 1.0, Point::origin()).triangles);
    let bvh = Bvh::new(&mesh);
    assert_eq!(bvh.triangle_count(), mesh.face_count());
    let mut hits = 0;
    for i in 0..300u64 {
        let origin = Point::new(15.0 * hash_unit(10 * i), 15.0 * hash_unit(10 * i + 1), 15.0 * hash_unit(10 * i + 2));
        // Aimed near the sphere, so most rays hit and some graze or miss.
        let target = Point::new(2.0, 0.0, -1.0) + Vector::new(hash_unit(10 * i + 3), hash_unit(10 * i + 4), hash_unit(10 * i + 5)) * 12.0;
        let direction = target - origin;
        let ours = bvh.closest_hit(&origin, &direction);
        let expected = brute_force_hit(&mesh, &origin, &direction);
        match (ours, expected) {
            (Some(hit), Some((face, distance))) => {
                hits += 1;
                assert!((hit.distance - distance).abs() < 1e-9, "ray {i}: {} vs {distance}", hit.distance);
                assert!(hit.face == face || (hit.distance - distance).abs() < 1e-12);
                let [a, b, c] = mesh.triangle_points(hit.face);
                let from_barycentric = Point::from(a.coords * hit.barycentric[0] + b.coords * hit.barycentric[1] + c.coords * hit.barycentric[2]);
                assert!((from_barycentric - hit.point).norm() < 1e-9);
                assert!(bvh.any_hit(&origin, &direction, distance + 1e-6));
                assert!(!bvh.any_hit(&origin, &direction, distance - 1e-6));
            }
            (None, None) => assert!(!bvh.any_hit(&origin, &direction, f64::INFINITY)),
            (ours, expected) => panic!("ray {i}: BVH {ours:?}, brute force {expected:?}"),
        }
        let query = origin + direction * 0.3;
        let closest = bvh.closest_point(&query).unwrap();
        let brute = (0..mesh.face_count())
            .map(|f| {
                // Sample the triangle densely: an upper bound of the true distance.
                let [a, b, c] = mesh.triangle_points(f);
                let mut d = f64::INFINITY;
                for s in 0..=20 {
                    for t in 0..=(20 - s) {
                        let (u, v) = (s as f64 / 20.0, t as f64 / 20.0);
                        d = d.min((a + (b - a) * u + (c - a) * v - query).norm());
                    }
                }
                d
            })
            .fold(f64::INFINITY, f64::min);
        assert!(closest.distance <= brute + 1e-12, "closest point {} beyond sampled {brute}", closest.distance);
        assert!(closest.distance >= brute - 0.2, "closest point {} far below sampled {brute}", closest.distance);
        assert!(((closest.point - query).norm() - closest.distance).abs() < 1e-12);
    }
    assert!(hits > 150, "only {hits} rays hit: the test would not test much");
    assert!(Bvh::new(&Mesh::default()).closest_hit(&Point::origin(), &Vector::x()).is_none());
    assert!(bvh.closest_hit(&Point::origin(), &Vector::zeros()).is_none());
}

#[test]
fn topology_of_sphere_grid_and_two_pieces() {
    let sphere = icosphere(2, 1.0, Point::origin());
    let topology = Topology::new(&sphere);
    assert!(topology.is_watertight());
    assert_eq!(topology.edge_count(), 3 * sphere.face_count() / 2);
    assert_eq!(sphere.vertex_count() + sphere.face_count() - topology.edge_count(), 2, "Euler characteristic");
    assert!(topology.non_manifold_vertices().is_empty());

    let sheet = grid(7, 4, |_, _| 0.0);
    let topology = Topology::new(&sheet);
    assert!(!topology.is_watertight());
    assert_eq!(topology.boundary_edges().len(), 2 * (7 + 4));
    let mask = topology.boundary_vertex_mask();
    assert_eq!(mask.iter().filter(|b| **b).count(), 2 * (7 + 4));
    assert!(!mask[9 + 1], "vertex (1, 1) is interior");

    let mut two = icosphere(1, 1.0, Point::origin());
    let small = icosphere(0, 0.2, Point::new(5.0, 0.0, 0.0));
    let offset = two.vertex_count() as u32;
    two.positions.extend(small.positions);
    two.triangles.extend(small.triangles.iter().map(|t| t.map(|v| v + offset)));
    let components = Topology::new(&two).connected_components();
    assert_eq!(components.face_counts, vec![80, 20]);
    assert_eq!(components.largest(), Some(0));
}

#[test]
fn repair_welds_a_triangle_soup_and_keeps_attributes_with_their_vertices() {
    let mut sphere = icosphere(2, 5.0, Point::origin());
    let colour_of = |p: &Point| [(p.x * 20.0 + 128.0) as u8, (p.y * 20.0 + 128.0) as u8, (p.z * 20.0 + 128.0) as u8, 255];
    sphere.colors = Some(sphere.positions.iter().map(colour_of).collect());
    sphere.quality = Some(sphere.positions.iter().map(|p| p.z as f32).collect());
    sphere.normals = Some(sphere.positions.iter().map(|p| p.coords.normalize()).collect());
    sphere.corner_uvs = Some((0..3 * sphere.face_count()).map(|c| [c as f32, 0.5]).collect());
    let (vertices, faces) = (sphere.vertex_count(), sphere.face_count());
    let mut soup = triangle_soup(&sphere);
    let report = repair(&mut soup, &RepairOptions::default());
    assert_eq!(report.vertices_before, 3 * faces);
    assert_eq!(report.vertices_after, vertices);
    assert_eq!(report.duplicate_vertices_merged, 3 * faces - vertices);
    assert_eq!(report.faces_after, faces);
    assert_eq!(report.unreferenced_vertices_removed, 0);
    assert!(report.watertight);
    assert_eq!(report.component_face_counts, vec![faces]);
    soup.validate().unwrap();
    for (v, p) in soup.positions.iter().enumerate() {
        assert_eq!(soup.colors.as_ref().unwrap()[v], colour_of(p));
        assert_eq!(soup.quality.as_ref().unwrap()[v], p.z as f32);
        assert!((soup.normals.as_ref().unwrap()[v] - p.coords.normalize()).norm() < 1e-12);
    }
    assert_eq!(soup.corner_uvs, sphere.corner_uvs, "no face was removed, so the corner UVs are unchanged");
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["duplicate_vertices_merged"], 3 * faces - vertices);
}

#[test]
fn repair_merges_within_tolerance_drops_bad_faces_and_small_pieces() {
    let mut mesh = triangle_soup(&icosphere(1, 5.0, Point::origin()));
    // Shake every corner by at most 1e-6: no exact duplicates remain.
    add_noise(&mut mesh, 1e-6, 5);
    let big_faces = mesh.face_count();
    let speck = icosphere(0, 0.1, Point::new(20.0, 0.0, 0.0));
    let offset = mesh.vertex_count() as u32;
    mesh.positions.extend(speck.positions.iter().copied());
    mesh.triangles.extend(speck.triangles.iter().map(|t| t.map(|v| v + offset)));
    mesh.triangles.push([0, 0, 1]); // repeated corner
    mesh.triangles.push([mesh.triangles[5][2], mesh.triangles[5][1], mesh.triangles[5][0]]); // duplicate, reversed
    mesh.positions.push(Point::new(100.0, 0.0, 0.0)); // unreferenced
    mesh.corner_uvs = Some((0..3 * mesh.face_count()).map(|c| [(c / 3) as f32, 0.0]).collect());

    let mut exact_only = mesh.clone();
    let report = repair(&mut exact_only, &RepairOptions::default());
    assert_eq!(report.duplicate_vertices_merged, 0);
    assert!(!report.watertight);

    let options = RepairOptions { merge_tolerance_mm: Some(1e-4), keep_largest_component: true };
    let report = repair(&mut mesh, &options);
    assert_eq!(report.close_vertices_merged, 3 * big_faces - 42);
    assert_eq!(report.degenerate_faces_removed, 1);
    assert_eq!(report.duplicate_faces_removed, 1);
    assert_eq!(report.components_removed, 1);
    assert_eq!(report.component_faces_removed, 20);
    assert_eq!(report.unreferenced_vertices_removed, 1 + 12, "the lone vertex and the speck's vertices");
    assert_eq!((report.vertices_after, report.faces_after), (42, 80));
    assert!(report.watertight);
    mesh.validate().unwrap();
    // Corner UVs recorded their original face: the kept faces are the big sphere's, in order.
    let uvs = mesh.corner_uvs.as_ref().unwrap();
    assert!((0..80).all(|f| uvs[3 * f][0] == f as f32));
}

#[test]
fn repair_reports_non_manifold_edges() {
    let mut mesh = grid(2, 1, |_, _| 0.0);
    mesh.positions.push(Point::new(0.5, 0.0, 1.0));
    mesh.triangles.push([1, 4, 6]); // a fin on the edge 1-4, shared by faces 0 and 3
    let report = repair(&mut mesh, &RepairOptions::default());
    assert_eq!(report.non_manifold_edge_count, 1);
    assert_eq!(report.non_manifold_edges, vec![[1, 4]]);
    assert!(!report.watertight);
}

fn radial_error_deg(mesh: &Mesh, normals: &[Vector], centre: Point) -> f64 {
    mesh.positions
        .iter()
        .zip(normals)
        .map(|(p, n)| n.angle(&(p - centre)).to_degrees())
        .fold(0.0, f64::max)
}

#[test]
fn normals_of_a_sphere_are_radial_and_faces_turn_outward() {
    let centre = Point::new(3.0, -1.0, 2.0);
    let mut sphere = icosphere(3, 8.0, centre);
    for weighting in [NormalWeighting::Angle, NormalWeighting::Area] {
        let normals = compute_vertex_normals(&sphere, weighting);
        assert!(radial_error_deg(&sphere, &normals, centre) < 1.0, "{weighting:?}");
        assert!(normals.iter().all(|n| (n.norm() - 1.0).abs() < 1e-12));
    }
    let original = sphere.triangles.clone();
    // Scramble: flip every third face, then turn the whole sphere inside out.
    for (f, tri) in sphere.triangles.iter_mut().enumerate() {
        if f % 3 != 0 {
            tri.swap(1, 2);
        }
    }
    let report = orient_faces_outward(&mut sphere);
    assert_eq!(report.components, 1);
    assert_eq!(report.inconsistent_edges, 0);
    assert_eq!(report.flipped_faces, sphere.face_count() - sphere.face_count().div_ceil(3));
    let same_orientation = |a: &[u32; 3], b: &[u32; 3]| (0..3).any(|k| [a[k], a[(k + 1) % 3], a[(k + 2) % 3]] == *b);
    assert!(sphere.triangles.iter().zip(&original).all(|(a, b)| same_orientation(a, b)));

    let mut sheet = grid(6, 6, |x, y| 0.1 * x * y);
    for tri in sheet.triangles.iter_mut().step_by(2) {
        tri.swap(1, 2);
    }
    orient_faces_outward(&mut sheet);
    let up = (0..sheet.face_count()).filter(|&f| sheet.face_normal_scaled(f).z > 0.0).count();
    assert!(up == 0 || up == sheet.face_count(), "consistent: all faces one way ({up} up)");
}

#[test]
fn ensure_vertex_normals_keeps_given_ones_and_fits_point_clouds() {
    let centre = Point::new(1.0, 1.0, 1.0);
    let mut sphere = icosphere(2, 4.0, centre);
    sphere.triangles.iter_mut().for_each(|t| t.swap(1, 2)); // inside out
    ensure_vertex_normals(&mut sphere);
    assert!(radial_error_deg(&sphere, sphere.normals.as_ref().unwrap(), centre) < 2.0);

    let given = vec![Vector::z(); sphere.vertex_count()];
    sphere.normals = Some(given.clone());
    ensure_vertex_normals(&mut sphere);
    assert_eq!(sphere.normals.as_ref().unwrap(), &given);

    let mut cloud = Mesh::new(icosphere(3, 4.0, centre).positions, Vec::new());
    ensure_vertex_normals(&mut cloud);
    assert!(radial_error_deg(&cloud, cloud.normals.as_ref().unwrap(), centre) < 5.0);
}

fn radius_spread(mesh: &Mesh, centre: Point, radius: f64) -> f64 {
    (mesh.positions.iter().map(|p| ((p - centre).norm() - radius).powi(2)).sum::<f64>() / mesh.vertex_count() as f64).sqrt()
}

#[test]
fn smoothing_removes_noise_and_respects_boundary_handling() {
    let centre = Point::origin();
    let mut noisy = icosphere(3, 10.0, centre);
    add_noise(&mut noisy, 0.3, 9);
    let before = radius_spread(&noisy, centre, 10.0);
    for weights in [LaplacianWeights::Uniform, LaplacianWeights::Cotangent] {
        let mut smoothed = noisy.clone();
        laplacian_smooth(&mut smoothed, &SmoothOptions { iterations: 5, weights, boundary: BoundaryHandling::Fixed });
        let mean_radius = smoothed.positions.iter().map(|p| (p - centre).norm()).sum::<f64>() / smoothed.vertex_count() as f64;
        assert!(radius_spread(&smoothed, centre, mean_radius) < 0.5 * before, "{weights:?}");
    }
    let mut hc = noisy.clone();
    hc_smooth(&mut hc, 3);
    let mean_radius = hc.positions.iter().map(|p| (p - centre).norm()).sum::<f64>() / hc.vertex_count() as f64;
    assert!(radius_spread(&hc, centre, mean_radius) < 0.5 * before);

    let mut sheet = grid(10, 10, |x, y| ((x + y) as i64 % 2) as f64);
    let original = sheet.clone();
    laplacian_smooth(&mut sheet, &SmoothOptions { iterations: 4, weights: LaplacianWeights::Uniform, boundary: BoundaryHandling::Fixed });
    let boundary = Topology::new(&original).boundary_vertex_mask();
    for (v, &on_boundary) in boundary.iter().enumerate() {
        if on_boundary {
            assert_eq!(sheet.positions[v], original.positions[v]);
        }
    }
    assert!(sheet.positions.iter().zip(&original.positions).any(|(a, b)| a != b));
    let mut free = original.clone();
    laplacian_smooth(&mut free, &SmoothOptions { iterations: 4, weights: LaplacianWeights::Uniform, boundary: BoundaryHandling::Free });
    let corner_moved_inward = free.positions[0].x > 0.0 && free.positions[0].y > 0.0;
    assert!(corner_moved_inward, "a free corner shrinks into the sheet: {:?}", free.positions[0]);
}

#[test]
fn paper_hc_keeps_the_sphere_s_size_better_than_laplacian_and_meshlab_hc() {
    let centre = Point::origin();
    let mut noisy = icosphere(3, 10.0, centre);
    add_noise(&mut noisy, 0.3, 21);
    let before = radius_spread(&noisy, centre, 10.0);
    let mean_radius = |m: &Mesh| m.positions.iter().map(|p| (p - centre).norm()).sum::<f64>() / m.vertex_count() as f64;
    let mut laplacian = noisy.clone();
    laplacian_smooth(&mut laplacian, &SmoothOptions { iterations: 10, weights: LaplacianWeights::Uniform, boundary: BoundaryHandling::Free });
    let mut meshlab_hc = noisy.clone();
    hc_smooth(&mut meshlab_hc, 10);
    let mut paper_hc = noisy.clone();
    hc_smooth_vollmer(&mut paper_hc, 10, 0.0, 0.5);
    let shrink = |m: &Mesh| 10.0 - mean_radius(m);
    println!("shrinkage: laplacian {:.4}, MeshLab HC {:.4}, paper HC {:.4}", shrink(&laplacian), shrink(&meshlab_hc), shrink(&paper_hc));
    assert!(shrink(&paper_hc).abs() < 0.5 * shrink(&laplacian));
    assert!(shrink(&paper_hc).abs() < shrink(&meshlab_hc));
    assert!(radius_spread(&paper_hc, centre, mean_radius(&paper_hc)) < 0.5 * before, "and it still removes noise");
}

/// MeshLab's topological measures of the scan at `path` (after the same cleaning filters
/// sherd's repair applies), as JSON.
fn meshlab_topology(path: &std::path::Path) -> serde_json::Value {
    let code = "import sys, json, pymeshlab\n\
        m = pymeshlab.MeshSet(); m.load_new_mesh(sys.argv[1])\n\
        m.meshing_remove_duplicate_vertices(); m.meshing_remove_null_faces()\n\
        m.meshing_remove_duplicate_faces(); m.meshing_remove_unreferenced_vertices()\n\
        print(json.dumps(m.get_topological_measures()))";
    serde_json::from_str(&python_output(code, &[path.as_os_str()])).unwrap()
}

#[test]
fn real_scan_repair_topology_normals_and_indices() {
    let test = "real_scan_repair_topology_normals_and_indices";
    let Some(path) = shared_data_file(test, "dacord/A011.ply") else { return };
    let scan = sherd::mesh::io::read_mesh(&path).unwrap();
    let mut repaired = scan.clone();
    let report = repair(&mut repaired, &RepairOptions::default());
    println!("{}", serde_json::to_string(&report).unwrap());
    repaired.validate().unwrap();
    assert_eq!(report.component_face_counts.iter().sum::<usize>(), report.faces_after);
    assert_eq!(report.vertices_after, repaired.vertex_count());
    if pymeshlab_available(test) {
        let meshlab = meshlab_topology(&path);
        assert_eq!(report.vertices_after as u64, meshlab["vertices_number"].as_u64().unwrap());
        assert_eq!(report.faces_after as u64, meshlab["faces_number"].as_u64().unwrap());
        assert_eq!(report.component_face_counts.len() as u64, meshlab["connected_components_number"].as_u64().unwrap());
        assert_eq!(report.boundary_edge_count as u64, meshlab["boundary_edges"].as_u64().unwrap());
        assert_eq!(report.non_manifold_edge_count as u64, meshlab["non_two_manifold_edges"].as_u64().unwrap());
        assert_eq!(Topology::new(&repaired).edge_count() as u64, meshlab["edges_number"].as_u64().unwrap());
    }

    // The scanner's normals and ours from the faces agree where the surface is smooth.
    let given = scan.normals.clone().expect("A011 has normals");
    let computed = compute_vertex_normals(&scan, NormalWeighting::Area);
    let mut angles: Vec<f64> = given.iter().zip(&computed).map(|(a, b)| a.angle(b).to_degrees()).collect();
    angles.sort_by(f64::total_cmp);
    let (median, p90) = (angles[angles.len() / 2], angles[angles.len() * 9 / 10]);
    println!("A011 normals: median {median:.2} deg, 90th percentile {p90:.2} deg from the file's");
    assert!(median < 2.0 && p90 < 10.0);

    let mut oriented = scan.clone();
    let orientation = orient_faces_outward(&mut oriented);
    println!("A011 orientation: {orientation:?}");
    assert!(orientation.flipped_faces * 100 < scan.face_count(), "a scan written outward stays (almost all) as it is");

    // Every vertex is its own nearest point and lies on the surface.
    let tree = KdTree::new(&scan.positions);
    let bvh = Bvh::new(&scan);
    for v in (0..scan.vertex_count()).step_by(97) {
        let p = scan.positions[v];
        assert_eq!(tree.nearest(&p).unwrap().distance, 0.0);
        assert!(bvh.closest_point(&p).unwrap().distance < 1e-9);
        // A ray from just outside along the inward normal enters the sherd.
        let n = given[v];
        assert!(bvh.closest_hit(&(p + n * 0.01), &-n).is_some_and(|h| h.distance < 0.02));
    }
}
