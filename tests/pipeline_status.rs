//! The record's status tells an axis the pipeline stands behind (`ok`) from one it found
//! but does not pin down (`axis_uncertain`): the bootstrap's wide intervals of its
//! direction and position reach the record, so that a batch report does not present a
//! doubted axis as a confident one.

use sherd::orient::{mean_point_distance_mm, Verdict};
use sherd::pipeline::{analyse, PipelineOptions, RecordStatus, SherdRecord};
use sherd::refine::RefineOptions;
use sherd::synth::{generate_vessel, VesselOptions};

#[test]
fn an_axis_the_bootstrap_doubts_is_not_called_ok() {
    // Vessel 2 of the refinement corpus (examples/refine_accuracy.rs), as the batch runs it.
    let vessel = generate_vessel(2, &VesselOptions { fragment_count: 34, random_motion: true, ..Default::default() });
    let options = PipelineOptions { refine: Some(RefineOptions::default()), ..Default::default() };
    let (mut uncertain, mut ok_offsets_mm, mut right_given) = (0, Vec::new(), 0);
    for (index, fragment) in vessel.fragments.iter().enumerate().filter(|(_, f)| f.truth.hard_case.is_none()) {
        let analysis = analyse(fragment.mesh.clone(), &options).unwrap();
        let record = SherdRecord::from_analysis(format!("fragment {index}"), &analysis);
        let doubts = analysis.axis_doubts();
        let off_mm = mean_point_distance_mm(&fragment.mesh.positions, analysis.axis(), &fragment.truth.axis);
        let context = format!("fragment {index}: {} {:?}, {off_mm:.2} mm off, doubts {doubts:?}", record.status, record.reason);
        if analysis.orientation.verdict == Verdict::Oriented {
            assert_eq!(record.status, if doubts.is_empty() { RecordStatus::Ok } else { RecordStatus::AxisUncertain }, "{context}");
        }
        for doubt in doubts {
            assert!(record.reason.as_deref().is_some_and(|r| r.contains(doubt.as_str())), "the reason gives each doubt: {context}");
        }
        if record.status == RecordStatus::AxisUncertain {
            uncertain += 1;
            // An uncertain axis is still given (and drawn in a batch): the best guess.
            assert!(record.axis.is_some() && analysis.is_oriented(), "{context}");
        }
        if record.status == RecordStatus::Ok {
            ok_offsets_mm.push(off_mm);
        }
        if (record.status == RecordStatus::Ok || record.status == RecordStatus::AxisUncertain) && off_mm < 4.0 {
            right_given += 1;
        }
        if index == 3 {
            // Eq. 7 tipped this rim 3.4 degrees to push a damaged section out of epsilon,
            // and the record called it ok, 3.0 mm off. Levelled by the plane of its level
            // extremes it is within half a degree; where it lies the skins do not fix
            // (the circles criterion's placement fails), and the record says so.
            let angle = analysis.axis().line_angle_to_deg(&fragment.truth.axis);
            assert!(angle < 0.5, "{angle:.2} deg: {context}");
            assert_eq!(record.status, RecordStatus::AxisUncertain, "{context}");
            assert!(record.reason.as_deref().is_some_and(|r| r.contains("95% position interval")), "{context}");
        }
        if index == 7 {
            // The refinement placed this base's axis where the skins barely fix it, 16.6 mm
            // off the truth; the resampled sections slide it along the radius, and the
            // record called it ok before.
            // Now the whole-sphere search finds another axis about as good, and its sense is
            // not known either: never called ok.
            assert!(off_mm > 4.0, "{context}");
            assert_ne!(record.status, RecordStatus::Ok, "{context}");
        }
    }
    assert!(uncertain >= 3, "{uncertain} axes uncertain");
    // Before the doubts reached the record, four axes 4.4-16.6 mm off were among this
    // vessel's ok rows; those it calls ok must all be within 4 mm (fragment 3, above, was
    // the third). The intervals now also carry the sector jackknife's spread and, for
    // levelled axes, the landscape's position valley: the two right axes still called
    // ok before (2.5 and 3.6 mm off) have position intervals reaching 5.6 and 16.7 mm,
    // and are given as axis_uncertain.
    assert!(ok_offsets_mm.iter().all(|&off| off < 4.0), "ok rows' offsets {ok_offsets_mm:?} mm");
    assert!(right_given >= 4, "{right_given} axes within 4 mm given as ok or axis_uncertain");
}

/// The intervals are about the axis the pipeline gives: where it refines, the bootstrap
/// refines its resamples with the pipeline's own refinement options, whatever the
/// measurement options were given (the command and the C ABI once had to copy them over,
/// and a library caller who did not got intervals of another criterion).
#[test]
fn the_intervals_resample_the_pipelines_own_refinement() {
    use sherd::refine::Criterion;
    use sherd::synth::{synthetic_sherd, SherdOptions, SherdPart};
    let sherd = synthetic_sherd(3, &SherdOptions { target_faces: 8000, ..SherdOptions::for_part(SherdPart::Body) });
    let profile = RefineOptions { criterion: Criterion::Profile, ..Default::default() };
    let with_measure_refine = |criterion| {
        let mut options = PipelineOptions { refine: Some(profile.clone()), ..Default::default() };
        options.measure.refine = RefineOptions { criterion, ..Default::default() };
        let analysis = analyse(sherd.mesh.clone(), &options).unwrap();
        let measurements = analysis.measurements.expect("a body sherd with its axis line is measured");
        (measurements.axis_angle_interval_deg, measurements.axis_distance_interval_mm)
    };
    let given_profile = with_measure_refine(Criterion::Profile);
    assert!(given_profile.0.is_some() && given_profile.1.is_some(), "{given_profile:?}");
    assert_eq!(with_measure_refine(Criterion::Circles), given_profile);
}

/// On a rough scan the refinement's skins break up and its criterion may be undefined on
/// the fragment's sections: the refinement then keeps its start, and no bootstrap resample
/// can be refined again. Such an axis has no interval and is never called `ok` (these
/// fragments of a vessel with 0.25 mm of noise were `ok` and 6-24 mm off without
/// intervals before; `docs/calibration.md`).
#[test]
fn an_axis_without_intervals_is_not_called_ok() {
    let vessel = generate_vessel(502, &VesselOptions { fragment_count: 33, cell_size_mm: 0.5, noise_mm: 0.25, random_motion: true, ..Default::default() });
    let options = PipelineOptions { refine: Some(RefineOptions::default()), ..Default::default() };
    let mut unrepeatable = 0;
    for index in [6, 15, 16, 17, 19, 26] {
        let fragment = &vessel.fragments[index];
        let analysis = analyse(fragment.mesh.clone(), &options).unwrap();
        let record = SherdRecord::from_analysis(format!("fragment {index}"), &analysis);
        let measurements = analysis.measurements.as_ref();
        let intervals = measurements.is_some_and(|m| m.axis_angle_interval_deg.is_some() && m.axis_distance_interval_mm.is_some());
        let context = format!("fragment {index}: {} {:?}", record.status, record.reason);
        assert!(record.status != RecordStatus::Ok || intervals, "{context}");
        unrepeatable += analysis.axis_doubts().iter().any(|d| d.contains("precision is unknown")) as usize;
    }
    assert!(unrepeatable >= 1, "no fragment met the case the test is about");
}
