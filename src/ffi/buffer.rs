//! `SherdBuffer`: bytes the library hands to the host (a drawing in memory, a report as
//! JSON), owned by the library until `sherd_buffer_free`.

use std::ffi::CString;

use super::error::FfiResult;
use super::panic::guard;
use super::pointers::{borrow, require, write_out};
use super::status::SherdStatus;

/// An immutable byte buffer owned by the library. Read it with `sherd_buffer_contents`;
/// release it with `sherd_buffer_free`.
pub struct SherdBuffer {
    /// The content, followed by a NUL byte for text.
    bytes: Vec<u8>,
    /// The content's length (without the NUL of text).
    size: usize,
}

/// Hands binary `bytes` (a PNG, a PDF...) to the host through `out_buffer`.
pub(crate) unsafe fn hand_out_bytes(out_buffer: *mut *mut SherdBuffer, bytes: Vec<u8>) -> FfiResult {
    let size = bytes.len();
    unsafe { hand_out(out_buffer, SherdBuffer { bytes, size }) }
}

unsafe fn hand_out(out_buffer: *mut *mut SherdBuffer, buffer: SherdBuffer) -> FfiResult {
    require(out_buffer.cast_const(), "out_buffer")?;
    unsafe { write_out(out_buffer, Box::into_raw(Box::new(buffer)), "out_buffer") }
}

/// Hands UTF-8 `text` to the host, NUL-terminated (the NUL not counted in the size) so
/// that C can use it as a string directly.
pub(crate) unsafe fn hand_out_text(out_buffer: *mut *mut SherdBuffer, text: String) -> FfiResult {
    let bytes = CString::new(text.replace('\0', "\u{2400}")).unwrap_or_default().into_bytes_with_nul();
    let size = bytes.len() - 1;
    unsafe { hand_out(out_buffer, SherdBuffer { bytes, size }) }
}

/// Writes a pointer to the buffer's first byte to `*out_data` and its length in bytes
/// to `*out_size`. The pointer stays valid until `sherd_buffer_free`. Text buffers (JSON
/// reports) are followed by a NUL byte not counted in the size.
///
/// # Safety
/// `buffer` must be a live handle; `out_data` and `out_size` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_buffer_contents(
    buffer: *const SherdBuffer,
    out_data: *mut *const u8,
    out_size: *mut usize,
) -> SherdStatus {
    guard("sherd_buffer_contents", || {
        let buffer = unsafe { borrow(buffer, "buffer") }?;
        require(out_data.cast_const(), "out_data")?;
        require(out_size.cast_const(), "out_size")?;
        unsafe { write_out(out_data, buffer.bytes.as_ptr(), "out_data") }?;
        unsafe { write_out(out_size, buffer.size, "out_size") }
    })
}

/// Releases a buffer. NULL is accepted and ignored; freeing twice is undefined behaviour.
///
/// # Safety
/// `buffer` must be NULL or a handle from this library not freed before.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_buffer_free(buffer: *mut SherdBuffer) {
    if !buffer.is_null() {
        drop(unsafe { Box::from_raw(buffer) });
    }
}

/// Hands `report` to the host as JSON when it asked for it (`out_report_json` not NULL).
pub(crate) unsafe fn hand_out_report(out_report_json: *mut *mut SherdBuffer, report: &impl serde::Serialize) -> FfiResult {
    if out_report_json.is_null() {
        return Ok(());
    }
    let json = serde_json::to_string(report)
        .map_err(|e| super::error::Failure::new(SherdStatus::Panic, format!("the report could not be serialised: {e}")))?;
    unsafe { hand_out_text(out_report_json, json) }
}
