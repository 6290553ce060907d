//! The thread's last error message, and the failure type entry points return inside Rust.

use std::cell::RefCell;
use std::ffi::{CString, c_char};

use super::status::SherdStatus;
use crate::Error;

/// Why an entry point did not return `SHERD_STATUS_OK`: the status and its message.
#[derive(Debug)]
pub(crate) struct Failure {
    pub(crate) status: SherdStatus,
    pub(crate) message: String,
}

impl Failure {
    /// A failure with `status` and `message`.
    pub(crate) fn new(status: SherdStatus, message: impl Into<String>) -> Self {
        Failure { status, message: message.into() }
    }

    /// `SHERD_STATUS_INVALID_ARGUMENT` with `message`.
    pub(crate) fn invalid(message: impl Into<String>) -> Self {
        Failure::new(SherdStatus::InvalidArgument, message)
    }
}

impl From<Error> for Failure {
    fn from(error: Error) -> Self {
        let status = match &error {
            Error::Io { .. } => SherdStatus::Io,
            Error::Parse { .. } => SherdStatus::Parse,
            Error::InvalidArgument(_) => SherdStatus::InvalidArgument,
            Error::DegenerateGeometry(_) => SherdStatus::DegenerateGeometry,
            Error::NotConverged(_) => SherdStatus::NotConverged,
            Error::NeedsManualOrientation(_) => SherdStatus::NeedsManualOrientation,
        };
        Failure::new(status, error.to_string())
    }
}

/// What entry points return inside Rust before the boundary turns it into a status.
pub(crate) type FfiResult<T = ()> = Result<T, Failure>;

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Records `message` as this thread's last error. Interior NUL bytes (which a C string
/// cannot hold) are replaced so that the message is never lost.
pub(crate) fn set_last_error(message: &str) {
    let text = CString::new(message.replace('\0', "\u{2400}")).unwrap_or_default();
    LAST_ERROR.with(|last| *last.borrow_mut() = text);
}

/// The message of the most recent call on this thread that did not return
/// `SHERD_STATUS_OK`, as a NUL-terminated UTF-8 string; the empty string if there was
/// none. Successful calls leave it unchanged.
///
/// Never NULL. The string belongs to the library: do not free it. It stays valid until
/// the next call on this thread that fails; copy it to keep it longer. Each thread has
/// its own message, so concurrent calls on other threads do not disturb it.
#[unsafe(no_mangle)]
pub extern "C" fn sherd_last_error_message() -> *const c_char {
    LAST_ERROR.with(|last| last.borrow().as_ptr())
}
