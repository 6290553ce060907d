//! The panic boundary. A panic unwinding out of an `extern "C"` function aborts the host
//! (Blender, MeshLab, a museum database) and loses the user's work, so every entry point
//! runs its body through [`guard`], which turns a panic into `SherdStatus::Panic`.

use std::panic::{AssertUnwindSafe, catch_unwind};

use super::error::{FfiResult, set_last_error};
use super::status::SherdStatus;

/// Runs `body` for the entry point `function`, records a failure's message as the
/// thread's last error and returns its status.
///
/// `AssertUnwindSafe` is sound here: after a panic, the only state a caller can observe
/// is what the body already wrote through its out-pointers (each written whole, at the
/// end) and its handles, which stay valid to free.
pub(crate) fn guard(function: &str, body: impl FnOnce() -> FfiResult) -> SherdStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => SherdStatus::Ok,
        Ok(Err(failure)) => {
            set_last_error(&format!("{function}: {}", failure.message));
            failure.status
        }
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic payload".to_string());
            set_last_error(&format!("{function}: internal error (panic): {what}"));
            SherdStatus::Panic
        }
    }
}

#[cfg(test)]
mod tests {
    use std::ffi::CStr;

    use super::*;
    use crate::ffi::error::{Failure, sherd_last_error_message};
    
    fn last_message() -> String {
        unsafe { CStr::from_ptr(sherd_last_error_message()) }.to_string_lossy().into_owned()
    }

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let status = guard("sherd_test_entry", || {
            let values: Vec<u32> = Vec::new();
            let index = values.len() + 3;
            std::hint::black_box(values[index]);
            Ok(())
        });
        assert_eq!(status, SherdStatus::Panic);
        let message = last_message();
        assert!(message.starts_with("sherd_test_entry: internal error (panic): index out of bounds"), "{message}");
    }

    #[test]
    fn a_failure_keeps_its_status_and_names_the_function() {
        let status = guard("sherd_read", || Err(Failure::new(SherdStatus::Io, "scan.ply: no such file")));
        assert_eq!(status, SherdStatus::Io);
        assert_eq!(last_message(), "sherd_read: scan.ply: no such file");
        assert_eq!(guard("sherd_ok", || Ok(())), SherdStatus::Ok);
        assert_eq!(last_message(), "sherd_read: scan.ply: no such file", "success must not clear the message");
    }

    #[test]
    fn messages_are_per_thread() {
        guard("sherd_main_thread", || Err(Failure::invalid("here")));
        std::thread::spawn(|| {
            assert_eq!(last_message(), "");
            guard("sherd_other_thread", || Err(Failure::invalid("there")));
            assert_eq!(last_message(), "sherd_other_thread: there");
        })
        .join()
        .unwrap();
        assert_eq!(last_message(), "sherd_main_thread: here");
    }
}
