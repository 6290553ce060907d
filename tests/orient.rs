//! Orientation on analytic sherds built here (a wall patch of a revolved profile with
//! both skins and fracture faces, noisy, moved to a random pose), and bad input.

#[path = "support/evaluation.rs"]
mod evaluation;

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use sherd::mesh::{Mesh, Point, Vector};
use sherd::orient::{
    orient_automatic, orient_from_three_points, segment_surfaces, Axis, ManualOptions, OrientOptions, Skin, Verdict,
};
use sherd::Error;

/// A closed wall patch: outer skin `r = profile(z)`, inner skin `thickness` inside, over
/// `sector_deg` and `z` in `[z0, z1]`, `n_theta x n_z` grid per skin, side faces closing it.
/// Returned in the oriented frame (axis = z through the origin), then posed.
fn wall_patch(
    profile: impl Fn(f64) -> f64,
    z_range: (f64, f64),
    sector_deg: f64,
    thickness: f64,
    grid: (usize, usize),
    noise_mm: f64,
    seed: u64,
) -> (Mesh, Axis) {
    let (n_theta, n_z) = grid;
    let mut positions = Vec::new();
    let sector = sector_deg.to_radians();
    let slope = |z: f64| (profile(z + 1e-4) - profile(z - 1e-4)) / 2e-4;
    for skin in 0..2 {
        for j in 0..n_z {
            let z = z_range.0 + (z_range.1 - z_range.0) * j as f64 / (n_z - 1) as f64;
            for i in 0..n_theta {
                let theta = sector * i as f64 / (n_theta - 1) as f64;
                let r = profile(z);
                // Inner skin: offset along the profile's inward normal by the thickness.
                let (nr, nz) = { let s = slope(z); let l = (1.0 + s * s).sqrt(); (1.0 / l, -s / l) };
                let (rr, zz) = if skin == 0 { (r, z) } else { (r - thickness * nr, z - thickness * nz) };
                positions.push(Point::new(rr * theta.cos(), rr * theta.sin(), zz));
            }
        }
    }
    let index = |skin: usize, i: usize, j: usize| (skin * n_theta * n_z + j * n_theta + i) as u32;
    let mut triangles = Vec::new();
    let mut quad = |a: u32, b: u32, c: u32, d: u32, outward: Vector, positions: &Vec<Point>| {
        let normal = (positions[b as usize] - positions[a as usize]).cross(&(positions[c as usize] - positions[a as usize]));
        if normal.dot(&outward) >= 0.0 {
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        } else {
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
        }
    };
    for skin in 0..2 {
        for j in 0..n_z - 1 {
            for i in 0..n_theta - 1 {
                let p = positions[index(skin, i, j) as usize];
                let radial = Vector::new(p.x, p.y, 0.0).normalize();
                let outward = if skin == 0 { radial } else { -radial };
                quad(index(skin, i, j), index(skin, i + 1, j), index(skin, i + 1, j + 1), index(skin, i, j + 1), outward, &positions);
            }
        }
    }
    for j in 0..n_z - 1 {
        for (i, outward) in [(0, Vector::new(0.0, -1.0, 0.0)), (n_theta - 1, Vector::new(-sector.sin(), sector.cos(), 0.0))] {
            quad(index(0, i, j), index(0, i, j + 1), index(1, i, j + 1), index(1, i, j), outward, &positions);
        }
    }
    for i in 0..n_theta - 1 {
        for (j, outward) in [(0, -Vector::z()), (n_z - 1, Vector::z())] {
            quad(index(0, i, j), index(0, i + 1, j), index(1, i + 1, j), index(1, i, j), outward, &positions);
        }
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    if noise_mm > 0.0 {
        let normal = Normal::new(0.0, noise_mm).unwrap();
        for p in &mut positions {
            *p += Vector::new(normal.sample(&mut rng), normal.sample(&mut rng), normal.sample(&mut rng));
        }
    }
    let mut mesh = Mesh::new(positions, triangles);
    let pose = random_pose(&mut rng);
    mesh.transform(&pose);
    (mesh, Axis::z().transformed(&pose))
}

fn random_pose(rng: &mut ChaCha8Rng) -> Isometry3<f64> {
    let uniform = Normal::new(0.0, 1.0).unwrap();
    let axis = Vector::new(uniform.sample(rng), uniform.sample(rng), uniform.sample(rng));
    let angle = 2.0 * uniform.sample(rng);
    let rotation = UnitQuaternion::from_scaled_axis(axis.normalize() * angle);
    let shift = Translation3::new(100.0 * uniform.sample(rng), 100.0 * uniform.sample(rng), 100.0 * uniform.sample(rng));
    Isometry3::from_parts(shift, rotation)
}

fn bowl(z: f64) -> f64 {
    60.0 + 0.45 * z + 0.004 * z * z
}

#[test]
fn bowl_wall_is_oriented_within_two_degrees() {
    for seed in 0..4 {
        let (mesh, truth) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (60, 40), 0.03, seed);
        let orientation = orient_automatic(&mesh, &OrientOptions::default()).unwrap();
        let error = orientation.axis.line_angle_to_deg(&truth);
        assert!(error < 2.0, "seed {seed}: {error} deg, report {:?}", orientation.report);
        // The band is cut level at both ends, so only its flare (dr/dz 0.45-0.85) tells up
        // from down, which jars' shoulders contradict: the line must be accepted, the
        // sense may be flagged, and if it is not it must be right.
        match &orientation.verdict {
            Verdict::Oriented => assert!(orientation.axis.angle_to_deg(&truth) < 90.0, "seed {seed}: upside down"),
            Verdict::SenseUncertain { reason } => {
                assert!(reason.contains("which way is up"), "seed {seed}: {reason} {:?}", orientation.report)
            }
            Verdict::NeedsManualOrientation { reason } => panic!("seed {seed}: the line was refused: {reason}"),
        }
        let distance = truth.distance_to(&orientation.axis.point);
        assert!(distance < 3.0, "seed {seed}: axis point {distance} mm off");
    }
}

#[test]
fn cylinder_wall_direction_and_position() {
    let (mesh, truth) = wall_patch(|_| 70.0, (0.0, 40.0), 40.0, 6.0, (50, 30), 0.03, 11);
    let orientation = orient_automatic(&mesh, &OrientOptions::default()).unwrap();
    assert!(orientation.axis.line_angle_to_deg(&truth) < 2.0, "{:?}", orientation.report);
    assert!(truth.distance_to(&orientation.axis.point) < 2.0);
}

#[test]
fn point_cloud_with_normals_is_oriented() {
    let (mesh, truth) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (60, 40), 0.0, 3);
    let lines = sherd::orient::normal_lines::NormalLines::from_mesh(&mesh).unwrap();
    let cloud = Mesh::from_points_and_normals(lines.points.clone(), lines.directions.clone());
    let orientation = orient_automatic(&cloud, &OrientOptions::default()).unwrap();
    assert!(orientation.axis.line_angle_to_deg(&truth) < 2.0, "{:?}", orientation.report);
}

#[test]
fn flat_piece_needs_manual_orientation() {
    // A slab of a base: both skins flat, normals all along the axis.
    // A 58 x 43.5 x 6 mm slab.
    let mut positions = Vec::new();
    let n = 30;
    for k in 0..2 {
        for j in 0..n {
            for i in 0..n {
                positions.push(Point::new(2.0 * i as f64, 1.5 * j as f64, 6.0 * k as f64));
            }
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let a = (j * n + i) as u32;
            let (b, c, d) = (a + 1, a + 1 + n as u32, a + n as u32);
            triangles.push([a, c, b]);
            triangles.push([a, d, c]);
            let o = (n * n) as u32;
            triangles.push([a + o, b + o, c + o]);
            triangles.push([a + o, c + o, d + o]);
        }
    }
    let mesh = Mesh::new(positions, triangles);
    let orientation = orient_automatic(&mesh, &OrientOptions::default()).unwrap();
    match &orientation.verdict {
        Verdict::NeedsManualOrientation { reason } => assert!(reason.contains("parallel"), "{reason}"),
        other => panic!("a flat slab was not refused ({other:?}): {:?}", orientation.report),
    }
}

#[test]
fn spherical_piece_needs_manual_orientation() {
    let (mesh, _) = wall_patch(|z| (90.0f64 * 90.0 - z * z).sqrt(), (-25.0, 25.0), 35.0, 5.0, (50, 40), 0.05, 8);
    let orientation = orient_automatic(&mesh, &OrientOptions::default()).unwrap();
    assert!(!orientation.verdict.is_oriented(), "a sphere patch was oriented: {:?}", orientation.report);
}

#[test]
fn three_points_on_a_rim() {
    let (mesh, truth) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (60, 40), 0.0, 21);
    // The top row of the outer skin is the rim; its vertices are 40 rows up.
    let n_theta = 60;
    let rim: Vec<Point> = [0usize, 25, 59].iter().map(|i| mesh.positions[39 * n_theta + i]).collect();
    let orientation = orient_from_three_points(&mesh, [rim[0], rim[1], rim[2]], &ManualOptions::default()).unwrap();
    assert!(orientation.axis.line_angle_to_deg(&truth) < 0.01);
    assert!(truth.distance_to(&orientation.axis.point) < 0.01);
    let radius = orientation.report.circle_radius_mm.unwrap();
    assert!((radius - bowl(50.0)).abs() < 1e-6, "{radius}");
    assert!(orientation.kept_vertex_count > 0);
    // The bowl widens upwards, so the axis points to the rim (+z of the oriented frame).
    assert!(orientation.axis.angle_to_deg(&truth) < 1.0, "sense wrong");
}

#[test]
fn bad_manual_points_are_errors() {
    let (mesh, _) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (30, 20), 0.0, 2);
    let p = mesh.positions[5];
    let q = mesh.positions[17];
    let collinear = [p, q, p + (q - p) * 2.0];
    let error = orient_from_three_points(&mesh, collinear, &ManualOptions::default()).unwrap_err();
    assert!(error.to_string().contains("collinear"), "{error}");
    let error = orient_from_three_points(&mesh, [p, p, q], &ManualOptions::default()).unwrap_err();
    assert!(error.to_string().contains("coincide"), "{error}");
    let far = [p, q, mesh.positions[40] + Vector::new(500.0, 0.0, 0.0)];
    let error = orient_from_three_points(&mesh, far, &ManualOptions::default()).unwrap_err();
    assert!(error.to_string().contains("point 3"), "{error}");
}

#[test]
fn bad_meshes_are_errors() {
    let empty = Mesh::default();
    assert!(matches!(orient_automatic(&empty, &OrientOptions::default()), Err(Error::DegenerateGeometry(_))));
    let (mut mesh, _) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (30, 20), 0.0, 2);
    let count = mesh.vertex_count();
    let mut normals = vec![Vector::z(); count];
    normals[7] = Vector::new(f64::NAN, 0.0, 1.0);
    mesh.normals = Some(normals);
    let error = orient_automatic(&mesh, &OrientOptions::default()).unwrap_err();
    assert!(error.to_string().contains("vertex 7"), "{error}");
    // All points in one plane: no thickness, no curvature.
    let coplanar = Mesh::new(
        (0..100).map(|i| Point::new((i % 10) as f64, (i / 10) as f64, 0.0)).collect(),
        (0..9u32).flat_map(|j| (0..9u32).flat_map(move |i| {
            let a = j * 10 + i;
            [[a, a + 1, a + 11], [a, a + 11, a + 10]]
        })).collect(),
    );
    let error = orient_automatic(&coplanar, &OrientOptions::default()).unwrap_err();
    assert!(error.to_string().contains("plane"), "{error}");
    let cloud_without_normals = Mesh::new(vec![Point::origin(); 10], vec![]);
    assert!(orient_automatic(&cloud_without_normals, &OrientOptions::default()).is_err());
}

#[test]
fn skins_are_segmented() {
    let (mesh, truth) = wall_patch(bowl, (0.0, 50.0), 50.0, 5.0, (40, 30), 0.0, 4);
    let skins = segment_surfaces(&mesh, &truth).unwrap();
    let per_skin = 40 * 30;
    // Interior vertices of each skin (away from the borders, whose normals mix in the sides).
    let interior = |skin: usize| {
        (2..28).flat_map(move |j| (2..38).map(move |i| skin * per_skin + j * 40 + i)).collect::<Vec<_>>()
    };
    assert!(interior(0).iter().all(|&v| skins[v] == Skin::Outer));
    assert!(interior(1).iter().all(|&v| skins[v] == Skin::Inner));
}

/// A small synthetic corpus (fixed seeds): three vessels broken into 12 fragments each,
/// 0.8 mm cells, random poses.
fn small_corpus() -> Vec<evaluation::FragmentOutcome> {
    use evaluation::evaluate;
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 12, random_motion: true, cell_size_mm: 0.8, ..Default::default() };
    (0..3u64)
        .flat_map(|v| {
            let vessel = generate_vessel(1000 + v, &options);
            vessel
                .fragments
                .iter()
                .enumerate()
                .map(|(k, sherd)| evaluate(format!("vessel{v}-{k}"), sherd, &OrientOptions::default()))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn synthetic_corpus_meets_the_accuracy_goals() {
    let outcomes = small_corpus();
    assert!(outcomes.len() >= 30, "only {} fragments", outcomes.len());
    let summary = evaluation::Summary::of(&outcomes);
    println!("{}\n{}", evaluation::Summary::table_header(), summary.table_row("test corpus"));
    assert!(summary.median_angle_deg <= 2.0, "median angle error {:.2} deg", summary.median_angle_deg);
    assert!(
        summary.wrong_angle_unflagged_fraction <= 0.05,
        "{:.1}% of the fragments are more than 5 deg off and not flagged",
        100.0 * summary.wrong_angle_unflagged_fraction
    );
    assert!(summary.flagged_fraction < 0.6, "{:.0}% flagged", 100.0 * summary.flagged_fraction);
    // The paper's distance counts the sense: an upside-down piece is wrong however good
    // its axis line.
    assert!(
        summary.wrong_distance_unflagged_fraction <= 0.05,
        "{:.1}% of the fragments are more than 4 mm off (sense included) and not flagged",
        100.0 * summary.wrong_distance_unflagged_fraction
    );
    let upside_down: Vec<&str> = outcomes.iter().filter(|o| !o.flagged && !o.sense_correct).map(|o| o.id.as_str()).collect();
    assert!(upside_down.is_empty(), "oriented upside down and not flagged: {upside_down:?}");
}

/// Rim pieces (the generator's seeds 1-16): each one is either oriented within 5 degrees
/// and the right way up, or flagged; never confidently upside down (seeds 1, 8, 10, 11,
/// 14 and 15 were, before the level-rim cue).
#[test]
fn rim_pieces_are_the_right_way_up_or_flagged() {
    use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
    let mut oriented = 0;
    for seed in 1..=16 {
        let sherd = synthetic_sherd(seed, &SherdOptions::for_part(SherdPart::Rim));
        let orientation = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap();
        if !orientation.verdict.is_oriented() {
            continue;
        }
        oriented += 1;
        let line_deg = orientation.axis.line_angle_to_deg(&sherd.truth.axis);
        let direction_deg = orientation.axis.angle_to_deg(&sherd.truth.axis);
        assert!(
            line_deg < 5.0 && direction_deg < 90.0,
            "rim seed {seed} oriented {line_deg:.1} deg off, {direction_deg:.0} deg from base-to-rim: {:?}",
            orientation.report
        );
        assert!(orientation.report.direction_cue.contains("level rim"), "rim seed {seed}: {}", orientation.report.direction_cue);
    }
    // Flagging every piece would pass the loop: most rims are found.
    assert!(oriented >= 10, "only {oriented} of 16 rim pieces oriented");
}

#[test]
fn hard_presets_are_flagged() {
    use sherd::pipeline::{analyse, PipelineOptions};
    use sherd::synth::{synthetic_sherd, HardCase, SherdOptions};
    for case in [HardCase::FlatBase, HardCase::NearSpherical, HardCase::Tiny] {
        // 0..8 covers the near-spherical seeds 2, 3, 4 and 6 that an axis 60-80 degrees
        // off once passed on, and tiny pieces whose wrong axis line came with its sense
        // left open and nothing else said against it.
        for seed in 0..8 {
            let sherd = synthetic_sherd(seed, &SherdOptions::hard_case(case));
            let analysis = analyse(sherd.mesh.clone(), &PipelineOptions::default()).unwrap();
            // Declined, its axis doubted, or right (a tiny piece that keeps enough of its
            // curvature): never a wrong axis line given as found, even with its sense open.
            let verdict = &analysis.orientation.verdict;
            let right = analysis.axis().line_angle_to_deg(&sherd.truth.axis) < 5.0;
            assert!(
                !verdict.has_axis_line() || !analysis.axis_doubts().is_empty() || right,
                "{case:?} seed {seed}: {verdict:?}, {:.1} deg off, nothing against it: {:?}",
                analysis.axis().line_angle_to_deg(&sherd.truth.axis),
                analysis.orientation.report
            );
        }
    }
}

#[test]
fn synthetic_skins_match_the_generator() {
    use sherd::synth::{synthetic_sherd, SherdOptions, SurfaceKind};
    let sherd = synthetic_sherd(7, &SherdOptions::default());
    let skins = segment_surfaces(&sherd.mesh, &sherd.truth.axis).unwrap();
    let (mut agree, mut total) = (0, 0);
    for (skin, kind) in skins.iter().zip(&sherd.vertex_kinds) {
        let expected = match kind {
            SurfaceKind::Outer => Skin::Outer,
            SurfaceKind::Inner => Skin::Inner,
            _ => continue,
        };
        if *skin != Skin::Other {
            total += 1;
            agree += (*skin == expected) as usize;
        }
    }
    assert!(total > sherd.vertex_kinds.len() / 2, "only {total} vertices classified");
    assert!(agree as f64 >= 0.98 * total as f64, "{agree} of {total} agree");
}

/// The SfS++ pot C sherds (`../shared/data/sfspp_pot_C`: 200-256 points with normals each,
/// both skins), through the whole pipeline: each one is `ok` only within 5 degrees of its
/// reference axis (known to about 3 degrees); otherwise declined or doubted, never
/// confidently wrong. The base (piece 3) keeps its axis within 3 degrees.
#[test]
fn the_sfspp_sherds_are_oriented_near_their_reference_or_flagged() {
    use sherd::pipeline::{analyse, PipelineOptions, RecordStatus, SherdRecord};
    let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/data/sfspp_pot_C");
    if !folder.exists() {
        println!("SKIP: {} is absent", folder.display());
        return;
    }
    let pieces = evaluation::read_sfspp_pot_c(&folder).unwrap();
    let options = PipelineOptions { refine: Some(Default::default()), ..Default::default() };
    for (piece, evaluation::SfsppPiece { cloud, reference, .. }) in (1..).zip(pieces) {
        let analysis = analyse(cloud, &options).unwrap();
        let record = SherdRecord::from_analysis(format!("piece {piece}"), &analysis);
        let angle = analysis.axis().line_angle_to_deg(&reference);
        println!("piece {piece}: {angle:.2} deg from the reference, {} {:?}", record.status, record.reason);
        if record.status == RecordStatus::Ok {
            assert!(angle < 5.0, "piece {piece} called ok {angle:.1} deg from its reference");
        }
        if piece == 3 {
            assert!(analysis.orientation.verdict.has_axis_line() && angle < 3.0, "piece 3: {angle:.2} deg from the reference");
        }
    }
}

/// The axes the pipeline calls `ok` are never grossly wrong on the 34-fragment breakage
/// of `examples/refine_accuracy.rs` in 2 mm cells: the belly of a jar (nearly a surface of
/// revolution about the horizontal line through its profile's centre too) and small rim
/// pieces of 136-174 vertices, whose landscape has several valleys, are declined or
/// doubted. Most fragments still get an axis line.
#[test]
fn no_ok_axis_is_grossly_wrong_on_the_refinement_corpus() {
    use sherd::pipeline::{analyse, PipelineOptions, RecordStatus, SherdRecord};
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    let pipeline = PipelineOptions { refine: Some(Default::default()), ..Default::default() };
    let (mut usable, mut ok) = (0, 0);
    let mut wrong = Vec::new();
    for seed in [1u64, 6, 7] {
        let vessel = generate_vessel(seed, &options);
        for (k, sherd) in vessel.fragments.iter().enumerate().filter(|(_, s)| s.truth.hard_case.is_none()) {
            let Ok(analysis) = analyse(sherd.mesh.clone(), &pipeline) else { continue };
            let record = SherdRecord::from_analysis(format!("vessel {seed} fragment {k}"), &analysis);
            usable += analysis.orientation.verdict.has_axis_line() as usize;
            if record.status == RecordStatus::Ok {
                ok += 1;
                let angle = analysis.axis().line_angle_to_deg(&sherd.truth.axis);
                if angle > 15.0 || analysis.axis().direction.dot(&sherd.truth.axis.direction) < 0.0 {
                    wrong.push(format!("{}: {angle:.1} deg", record.file));
                }
            }
        }
    }
    // Enough ok answers for the test to mean something: 9 since the levelled axes'
    // position intervals carry the landscape's valley (right ones among them are given as
    // axis_uncertain where the skins barely place them).
    assert!(usable >= 50 && ok >= 8, "{usable} axis lines and {ok} ok of 3 vessels");
    assert!(wrong.is_empty(), "ok axes more than 15 deg off or upside down: {wrong:#?}");
}

/// An answer whose landscape holds another valley the fragment does not rule out says so
/// (a doubt) and carries how far that valley lies, for its intervals to reach; an answer
/// without such a doubt carries none.
#[test]
fn an_unresolved_competitor_is_carried_to_the_intervals() {
    use sherd::synth::{generate_vessel, VesselOptions};
    let options = VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() };
    let vessel = generate_vessel(1, &options);
    let mut carried = 0;
    for (k, sherd) in vessel.fragments.iter().enumerate().filter(|(_, s)| s.truth.hard_case.is_none()) {
        let orientation = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap();
        if !orientation.verdict.has_axis_line() {
            continue;
        }
        let doubt = orientation.doubts.iter().find(|d| d.starts_with("another axis"));
        match (doubt, orientation.competitor_reach) {
            (Some(doubt), Some(reach)) => {
                let doubted_deg: f64 = doubt.split_whitespace().nth(2).unwrap().parse().unwrap();
                assert!(reach.angle_deg >= doubted_deg - 0.5 && reach.distance_mm > 0.0, "fragment {k}: {reach:?} against {doubt}");
                carried += 1;
            }
            (None, None) => {}
            (doubt, reach) => panic!("fragment {k}: doubt {doubt:?} but reach {reach:?}"),
        }
    }
    assert!(carried >= 1, "no fragment of vessel 1 had an unresolved competitor: the test tests nothing");
}

/// A base's foot is a level circle about the axis, like a rim. Two base pieces whose wall
/// rises from a strip of underside too small to count as a floor (2-3% of the surface)
/// were oriented upside down, their level foot read as a level rim; the strip now vetoes
/// that reading (the sense is then uncertain), and no right base of the same kind is lost.
#[test]
fn a_level_foot_is_not_taken_for_a_rim() {
    use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
    for seed in [26u64, 70] {
        let sherd = synthetic_sherd(seed, &SherdOptions { target_faces: 20_000, ..SherdOptions::for_part(SherdPart::Base) });
        let orientation = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap();
        let sense = orientation.axis.direction.dot(&sherd.truth.axis.direction);
        println!("base seed {seed}: {:?}, sense {sense:.3}, {}", orientation.verdict, orientation.report.direction_cue);
        assert!(!(orientation.verdict.is_oriented() && sense < 0.0), "seed {seed} upside down: {}", orientation.report.direction_cue);
    }
}

#[test]
fn a_missing_or_malformed_sfspp_folder_is_an_error_naming_the_file_and_line() {
    let folder = tempfile::tempdir().unwrap();
    let missing = evaluation::read_sfspp_pot_c(folder.path()).unwrap_err().to_string();
    assert!(missing.contains("reference_axis_derived.txt"), "{missing}");
    std::fs::create_dir_all(folder.path().join("ground_truth")).unwrap();
    std::fs::create_dir_all(folder.path().join("surfaces_subsample")).unwrap();
    std::fs::write(
        folder.path().join("ground_truth/reference_axis_derived.txt"),
        "# reference A\nPot_C_Piece_01 0 0 0 0 0\n",
    )
    .unwrap();
    let malformed = evaluation::read_sfspp_pot_c(folder.path()).unwrap_err().to_string();
    assert!(malformed.contains("line 2") && malformed.contains("found 5 numbers"), "{malformed}");
    std::fs::write(folder.path().join("ground_truth/reference_axis_derived.txt"), "Pot_C_Piece_01 0 0 0 0 0 1\n").unwrap();
    let no_surface = evaluation::read_sfspp_pot_c(folder.path()).unwrap_err().to_string();
    assert!(no_surface.contains("Pot_C_Piece_01_Surface_*"), "{no_surface}");
}
