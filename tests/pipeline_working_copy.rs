//! The pipeline's decimated copy of a large scan: the pre-orientation, the refinement and
//! the bootstrap of the intervals work on it (the refinement on the full mesh when
//! `refine_on_full_resolution` asks; the tangent plane levels on the full mesh and places
//! on the copy), and the measurements never (they are taken on the full-resolution mesh).

#[path = "support/evaluation.rs"]
mod evaluation;

use sherd::orient::{decimated_copy, OrientOptions};
use sherd::pipeline::{analyse, PipelineOptions};
use sherd::refine::{refine, refine_placing_on, Criterion, RefineOptions};
use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};

fn options() -> PipelineOptions {
    PipelineOptions { refine: Some(RefineOptions::default()), ..Default::default() }
}

#[test]
fn pre_orientation_and_bootstrap_use_the_copy_and_measurements_the_full_mesh() {
    // A rim piece of ~50k faces, more than the 20k-face working copy.
    let sherd = synthetic_sherd(0, &SherdOptions { target_faces: 50_000, ..SherdOptions::for_part(SherdPart::Rim) });
    let copy_faces = 2 * OrientOptions::default().target_vertex_count;
    assert!(sherd.mesh.face_count() > 2 * copy_faces, "{} faces", sherd.mesh.face_count());

    let default = analyse(sherd.mesh.clone(), &options()).unwrap();
    assert!(default.is_oriented(), "{:?}", default.orientation.verdict);
    let full_bootstrap = analyse(sherd.mesh.clone(), &PipelineOptions { bootstrap_on_full_resolution: true, ..options() }).unwrap();
    let full_refine = analyse(sherd.mesh.clone(), &PipelineOptions { refine_on_full_resolution: true, ..options() }).unwrap();

    // The pre-orientation works on the copy whatever the options.
    assert_eq!(default.orientation.report.working_vertex_count, full_refine.orientation.report.working_vertex_count);
    assert!(default.orientation.report.working_vertex_count < default.mesh.vertex_count() / 2);
    assert_eq!(default.orientation.axis, full_bootstrap.orientation.axis);
    assert_eq!(default.orientation.axis, full_refine.orientation.axis);

    // By default the refinement runs on the copy (the tangent plane on the full mesh):
    // the same axis as refining that mesh directly, whatever the bootstrap does.
    assert_eq!(default.axis(), full_bootstrap.axis());
    assert_refined_on_the_mesh_its_criterion_wants(&default);
    // Asked to, it runs on the full mesh.
    let start = &default.orientation.axis;
    assert_eq!(&refine(&full_refine.mesh, start, &RefineOptions::default()).unwrap().axis, full_refine.axis());
    let apart_deg = full_refine.axis().line_angle_to_deg(default.axis());
    assert!(apart_deg < 1.0, "refined on the copy {apart_deg} deg from the full-resolution refinement");

    // The measurements are taken on the full mesh: only the intervals depend on where the
    // bootstrap ran, and both give one.
    let (m, m_full) = (default.measurements.as_ref().unwrap(), full_bootstrap.measurements.as_ref().unwrap());
    assert_eq!(m.sector_angle_deg, m_full.sector_angle_deg);
    assert_eq!(m.height_mm, m_full.height_mm);
    assert_eq!(m.rim_radius_mm, m_full.rim_radius_mm);
    assert_eq!(m.wall_thickness_mm, m_full.wall_thickness_mm);
    let (interval, interval_full) = (m.axis_angle_interval_deg.unwrap(), m_full.axis_angle_interval_deg.unwrap());
    assert!(interval[1] > 0.0 && interval_full[1] > 0.0, "{interval:?} {interval_full:?}");
}

/// The circles criterion refines on the 20k-face copy; the tangent plane levels the rim
/// on the full mesh and places it by circles on the copy, within a few hundredths of a
/// millimetre of where the full mesh places it from the same start.
fn assert_refined_on_the_mesh_its_criterion_wants(analysis: &sherd::pipeline::Analysis) -> Criterion {
    let refinement = analysis.refinement.as_ref().expect("refined");
    let method = refinement.report.method;
    let copy = decimated_copy(&analysis.mesh, &OrientOptions::default()).unwrap().expect("a copy of a 50k-face mesh");
    let start = &analysis.orientation.axis;
    if method == Criterion::Tangent {
        let expected = refine_placing_on(&analysis.mesh, &copy, start, &RefineOptions::default()).unwrap();
        assert_eq!(expected.axis, refinement.axis);
        let on_full_mesh = refine(&analysis.mesh, start, &RefineOptions::default()).unwrap().axis;
        // The same direction, to the rounding of the placement's round trip through the
        // copy's own frame.
        let turned_deg = on_full_mesh.line_angle_to_deg(&refinement.axis);
        assert!(turned_deg < 1e-9, "levelled on the full mesh: {turned_deg} deg apart");
        let centroid = analysis.mesh.centroid().expect("a centroid");
        // Where the placements are compared: from a start 3 mm off, where both must move
        // the axis. From a start a millimetre off, the Nelder-Mead search of the shifts
        // may stop in the shallow radial valley of a short rim at different points on the
        // two meshes.
        let shifted = evaluation::perturbed_axis(start, 0.0, 0.0, 0.0, 3.0);
        let on_copy = refine_placing_on(&analysis.mesh, &copy, &shifted, &RefineOptions::default()).unwrap().axis;
        let on_full_mesh = refine(&analysis.mesh, &shifted, &RefineOptions::default()).unwrap().axis;
        let unplaced = refine(&analysis.mesh, &shifted, &RefineOptions { tangent_places_by_circles: false, ..Default::default() }).unwrap().axis;
        let placing_moved_mm = (unplaced.closest_point(&centroid) - on_full_mesh.closest_point(&centroid)).norm();
        assert!(placing_moved_mm > 0.1, "the placement moved the axis {placing_moved_mm} mm: nothing to compare");
        let apart_mm = (on_full_mesh.closest_point(&centroid) - on_copy.closest_point(&centroid)).norm();
        assert!(apart_mm < 0.05, "from 3 mm off, placed {apart_mm} mm from the full mesh's placement");
    } else {
        assert_eq!(refine(&copy, start, &RefineOptions::default()).unwrap().axis, refinement.axis, "{method:?}");
    }
    method
}

#[test]
fn a_body_sherd_is_refined_on_the_copy_and_a_rim_on_the_full_mesh() {
    let methods: Vec<Criterion> = [SherdPart::Body, SherdPart::Rim]
        .into_iter()
        .map(|part| {
            let sherd = synthetic_sherd(BODY_AND_RIM_SEED, &SherdOptions { target_faces: 50_000, ..SherdOptions::for_part(part) });
            assert_refined_on_the_mesh_its_criterion_wants(&analyse(sherd.mesh, &options()).unwrap())
        })
        .collect();
    assert_eq!(methods, [Criterion::Circles, Criterion::Tangent], "both criteria, so both meshes, are checked");
}

/// A seed whose body piece is refined by the circles criterion and rim piece by the
/// tangent plane.
const BODY_AND_RIM_SEED: u64 = 1;

/// A sherd whose axis line is found but not which way is up (synthetic_sherd 30, a body
/// piece): the record says `sense_uncertain` with the reason, and still carries the axis
/// and the measurements; the drawing is not made.
#[test]
fn a_sense_uncertain_sherd_is_refined_and_measured_but_not_drawn() {
    let sherd = synthetic_sherd(30, &SherdOptions::default());
    let analysis = analyse(sherd.mesh.clone(), &options()).unwrap();
    assert!(
        matches!(analysis.orientation.verdict, sherd::orient::Verdict::SenseUncertain { .. }),
        "{:?}",
        analysis.orientation.verdict
    );
    assert!(!analysis.is_oriented());
    assert!(analysis.refinement.is_some() && analysis.measurements.is_some());
    let line_error = analysis.axis().line_angle_to_deg(&sherd.truth.axis);
    assert!(line_error < 5.0, "the axis line is {line_error} deg off");
    let record = sherd::pipeline::SherdRecord::from_analysis("s30".into(), &analysis);
    assert_eq!(record.status, sherd::pipeline::RecordStatus::SenseUncertain);
    assert!(record.reason.as_deref().is_some_and(|r| r.contains("which way is up")), "{:?}", record.reason);
    assert!(record.axis.is_some() && record.sector_angle_deg.is_some(), "{record:?}");
}
