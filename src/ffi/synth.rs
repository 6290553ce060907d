//! Synthetic sherds with known axes, for hosts' tests and demonstrations (and the C, C++
//! and Python tests of this ABI): the `synth` layer behind one call.

use super::buffer::{SherdBuffer, hand_out_report};
use super::error::{Failure, FfiResult};
use super::mesh::{SherdMesh, hand_out};
use super::orient::SherdAxis;
use super::panic::guard;
use super::pointers::{checked_size, require, write_sized};
use super::status::SherdStatus;
use crate::synth::{HardCase, SherdOptions, SherdPart};

/// Which kind of synthetic fragment to make.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdSynthKind {
    /// Rim, body, base or complete profile, drawn at random.
    Random = 0,
    /// A piece with part of the rim.
    Rim = 1,
    /// Wall only.
    Body = 2,
    /// A piece with the base's edge.
    Base = 3,
    /// A complete profile, rim to base.
    RimToBase = 4,
    /// A piece of the flat base (its axis position is not determined: orientation must
    /// refuse it).
    FlatBase = 5,
    /// A piece of a spherical body zone (every line through the centre is an axis).
    NearSpherical = 6,
    /// A piece about 15 mm across (too little curvature to measure).
    Tiny = 7,
}

fn options_for(kind: u32) -> FfiResult<SherdOptions> {
    Ok(match kind {
        0 => SherdOptions::default(),
        1 => SherdOptions::for_part(SherdPart::Rim),
        2 => SherdOptions::for_part(SherdPart::Body),
        3 => SherdOptions::for_part(SherdPart::Base),
        4 => SherdOptions::for_part(SherdPart::RimToBase),
        5 => SherdOptions::hard_case(HardCase::FlatBase),
        6 => SherdOptions::hard_case(HardCase::NearSpherical),
        7 => SherdOptions::hard_case(HardCase::Tiny),
        other => return Err(Failure::invalid(format!("`kind` {other} is not a SHERD_SYNTH_KIND_* value (0 to 7)"))),
    })
}

/// Makes a synthetic sherd: a vessel profile revolved with wall thickness, deformed,
/// made noisy, broken and moved by a random rigid motion; the same `seed` gives the same
/// sherd. `kind` is a `SHERD_SYNTH_KIND_*` value; `target_faces` the approximate triangle
/// count (0: 20000); `noise_mm` the standard deviation of the coordinate noise (finite,
/// at least 0; the default is 0.02).
///
/// `*out_mesh` receives the mesh (with vertex normals); `out_true_axis` (its `size` set,
/// or NULL) the true axis, base to rim; `out_truth_json` (or NULL) the whole ground
/// truth (radii, sector angle, height, profile...) as JSON.
///
/// # Safety
/// `out_mesh` must be writable; `out_true_axis` NULL or writable with its `size` set;
/// `out_truth_json` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_synthetic_sherd(
    seed: u64,
    kind: u32,
    target_faces: usize,
    noise_mm: f64,
    out_mesh: *mut *mut SherdMesh,
    out_true_axis: *mut SherdAxis,
    out_truth_json: *mut *mut SherdBuffer,
) -> SherdStatus {
    guard("sherd_synthetic_sherd", || {
        let mut options = options_for(kind)?;
        if !(noise_mm.is_finite() && noise_mm >= 0.0) {
            return Err(Failure::invalid(format!("`noise_mm` must be finite and at least 0, got {noise_mm}")));
        }
        options.noise_mm = noise_mm;
        if target_faces > crate::synth::MAX_TARGET_FACES {
            return Err(Failure::invalid(format!(
                "`target_faces` must be at most {}, got {target_faces}",
                crate::synth::MAX_TARGET_FACES
            )));
        }
        if target_faces > 0 {
            options.target_faces = target_faces;
        }
        require(out_mesh.cast_const(), "out_mesh")?;
        if !out_true_axis.is_null() {
            checked_size(out_true_axis.cast_const(), "out_true_axis")?;
        }
        let sherd = crate::synth::synthetic_sherd(seed, &options);
        if !out_true_axis.is_null() {
            unsafe { write_sized(out_true_axis, SherdAxis::from_axis(&sherd.truth.axis), "out_true_axis") }?;
        }
        unsafe { hand_out_report(out_truth_json, &sherd.truth) }?;
        unsafe { hand_out(out_mesh, sherd.mesh) }
    })
}
