//! The refinement's accuracy corpus and its simulated pre-orientation errors, shared by
//! `examples/refine_accuracy.rs`, `examples/deformation_floor.rs`, the refinement's tests
//! and its benches: the figures of the refinement issue are measured from these.

use crate::orient::Axis;
use crate::synth::SynthSherd;

/// A simulated pre-orientation error: `truth` turned by `tilt_deg` about the horizontal
/// direction at `tilt_azimuth_rad` and its point moved by `shift_mm` along the horizontal
/// direction at `shift_azimuth_rad`, both azimuths in the axis's own frame
/// ([`Axis::rotation_from_z`]). The refinement's accuracy example, tests and benches start
/// from it.
pub fn perturbed_axis(truth: &Axis, tilt_azimuth_rad: f64, tilt_deg: f64, shift_azimuth_rad: f64, shift_mm: f64) -> Axis {
    let frame = truth.rotation_from_z();
    let horizontal = |azimuth: f64| frame * crate::mesh::Vector::new(azimuth.cos(), azimuth.sin(), 0.0);
    let turn = nalgebra::UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(horizontal(tilt_azimuth_rad)), tilt_deg.to_radians());
    Axis::new(truth.point + horizontal(shift_azimuth_rad) * shift_mm, turn * truth.direction.into_inner())
}

/// Fragments per vessel of the refinement corpus (the paper's synthetic vessel broke into 34).
pub const REFINEMENT_CORPUS_FRAGMENTS_PER_VESSEL: usize = 34;

/// Mesh cells of the refinement corpus, mm: the orientation issue's corpus
/// (`examples/orient_accuracy.rs`, `tests/orient.rs`), fragments of a few thousand
/// vertices, as a decimated scan. `REFINE_ACCURACY_CELL_MM=2` gives the synthetic
/// generator's default 2 mm cells instead (a body fragment about 1000 vertices).
pub const REFINEMENT_CORPUS_CELL_MM: f64 = 0.8;

/// The refinement corpus of `examples/refine_accuracy.rs` and `examples/deformation_floor.rs`:
/// vessels `0..vessels`, each broken into 34 fragments moved by random rigid motions, with
/// the deformation scaled by `deformation_scale` (1: the default vessels), scan noise
/// `noise_mm` and mesh cells of `cell_size_mm` ([`REFINEMENT_CORPUS_CELL_MM`] in
/// `refine_accuracy`), the hard cases left out; each fragment with its id
/// `vessel * 1000 + index`.
pub fn refinement_corpus(vessels: u64, deformation_scale: f64, noise_mm: f64, cell_size_mm: f64) -> Vec<(u64, SynthSherd)> {
    let options = crate::synth::VesselOptions {
        fragment_count: REFINEMENT_CORPUS_FRAGMENTS_PER_VESSEL,
        random_motion: true,
        deformation_scale,
        noise_mm,
        cell_size_mm,
        ..Default::default()
    };
    (0..vessels)
        .flat_map(|seed| {
            let vessel = crate::synth::generate_vessel(seed, &options);
            vessel.fragments.into_iter().enumerate().map(move |(i, f)| (seed * 1000 + i as u64, f))
        })
        .filter(|(_, s)| s.truth.hard_case.is_none())
        .collect()
}
