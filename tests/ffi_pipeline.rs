//! The C ABI gives exactly what the Rust API gives: the same synthetic sherd, the same
//! axis bit for bit, the same verdict; and four threads orienting different meshes at
//! once give the results of one thread.

use std::ffi::CStr;
use std::ptr;

use sherd::ffi::*;
use sherd::orient::{OrientOptions, Verdict, orient_automatic};
use sherd::synth::{SherdOptions, SherdPart, synthetic_sherd};

fn empty_axis() -> SherdAxis {
    SherdAxis { size: size_of::<SherdAxis>(), ..Default::default() }
}

/// Synthetic sherd and automatic orientation through the C ABI: (status, axis, message).
fn orient_through_c(seed: u64, kind: SherdSynthKind) -> (SherdStatus, SherdAxis, String) {
    let mut mesh = ptr::null_mut();
    let mut truth = empty_axis();
    let status = unsafe { sherd_synthetic_sherd(seed, kind as u32, 6000, 0.02, &mut mesh, &mut truth, ptr::null_mut()) };
    assert_eq!(status, SherdStatus::Ok);
    let mut axis = empty_axis();
    let status = unsafe { sherd_orient_automatic(mesh, ptr::null(), &mut axis, ptr::null_mut(), ptr::null_mut()) };
    let message = unsafe { CStr::from_ptr(sherd_last_error_message()) }.to_string_lossy().into_owned();
    unsafe { sherd_mesh_free(mesh) };
    (status, axis, message)
}

const CASES: [(u64, SherdSynthKind, SherdPart); 4] = [
    (4, SherdSynthKind::Rim, SherdPart::Rim),
    (10, SherdSynthKind::Rim, SherdPart::Rim),
    (4, SherdSynthKind::Base, SherdPart::Base),
    (10, SherdSynthKind::RimToBase, SherdPart::RimToBase),
];

#[test]
fn the_c_abi_gives_the_rust_api_result_bit_for_bit() {
    for (seed, kind, part) in CASES {
        let mut options = SherdOptions::for_part(part);
        options.target_faces = 6000;
        let sherd = synthetic_sherd(seed, &options);
        let expected = orient_automatic(&sherd.mesh, &OrientOptions::default()).unwrap();
        let (status, axis, message) = orient_through_c(seed, kind);
        assert_eq!(axis.point, <[f64; 3]>::from(expected.axis.point.coords), "seed {seed} {kind:?}");
        assert_eq!(axis.direction, <[f64; 3]>::from(expected.axis.direction.into_inner()), "seed {seed} {kind:?}");
        match expected.verdict {
            Verdict::Oriented => assert_eq!(status, SherdStatus::Ok),
            Verdict::NeedsManualOrientation { reason } => {
                assert_eq!(status, SherdStatus::NeedsManualOrientation);
                assert!(message.ends_with(&reason), "{message} / {reason}");
            }
            Verdict::SenseUncertain { reason } => {
                assert_eq!(status, SherdStatus::SenseUncertain);
                assert!(message.ends_with(&reason), "{message} / {reason}");
            }
        }
    }
}

#[test]
fn four_threads_give_the_results_of_one() {
    let sequential: Vec<_> = CASES.iter().map(|&(seed, kind, _)| orient_through_c(seed, kind)).collect();
    let concurrent: Vec<_> = std::thread::scope(|scope| {
        let handles: Vec<_> = CASES.iter().map(|&(seed, kind, _)| scope.spawn(move || orient_through_c(seed, kind))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for (one, other) in sequential.iter().zip(&concurrent) {
        assert_eq!(one.0, other.0);
        assert_eq!(one.1, other.1);
        if one.0 != SherdStatus::Ok {
            assert_eq!(one.2, other.2, "each thread keeps its own message");
        }
    }
}

#[test]
fn sense_uncertain_is_status_eleven_with_its_name() {
    assert_eq!(SherdStatus::SenseUncertain as u32, 11);
    let name = unsafe { CStr::from_ptr(sherd_status_name(11)) };
    assert_eq!(name.to_str().unwrap(), "SHERD_STATUS_SENSE_UNCERTAIN");
    assert_eq!(SherdStatus::ALL.last(), Some(&SherdStatus::SenseUncertain));
}
