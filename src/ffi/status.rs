//! Status codes: every entry point of the C ABI returns one.
//!
//! In the header `SherdStatus` is a `uint32_t` with named constants. The Rust enum only
//! ever travels from the library to the host; values coming from the host (as in
//! `sherd_status_name`) are taken as plain integers and checked, because a Rust enum
//! holding a value the host made up is undefined behaviour.

use std::ffi::{CStr, CString, c_char};
use std::sync::OnceLock;

/// The outcome of a call. `SHERD_STATUS_OK` is zero; every other value has a message
/// from `sherd_last_error_message()` on the same thread.
#[repr(u32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SherdStatus {
    /// The call succeeded.
    Ok = 0,
    /// An argument had a value the function does not accept (out-of-range enum value,
    /// NaN coordinate, index past the vertex count, struct `size` too small, ...).
    InvalidArgument = 1,
    /// A pointer argument that must not be NULL was NULL (or was misaligned for its type).
    NullPointer = 2,
    /// An output buffer was smaller than the data to copy into it; nothing was written.
    BufferTooSmall = 3,
    /// The mesh has no such attribute (normals, colours, texture coordinates).
    NotAvailable = 4,
    /// A file could not be opened, read or written.
    Io = 5,
    /// A file's content is malformed; the message names the file and where.
    Parse = 6,
    /// The geometry cannot support the operation (empty, flat, collinear points, ...).
    DegenerateGeometry = 7,
    /// An optimisation stopped at its bound without meeting its tolerance.
    NotConverged = 8,
    /// The data do not determine an axis: a human must give three points. Outputs are
    /// still written (the best guess, flagged by this status); the message gives the
    /// reason.
    NeedsManualOrientation = 9,
    /// A bug inside sherd was caught at the boundary (a Rust panic). The message says
    /// where; please report it. The handles passed to the call remain valid to free.
    Panic = 10,
    /// The axis line is found but not which way it points (base to rim): the sense cues
    /// are weak or disagree. Outputs are still written (the axis, refined and measured
    /// by the pipeline); the message gives the reason. Check the sense, or ask the user.
    SenseUncertain = 11,
}

impl SherdStatus {
    /// Every status, in code order.
    pub const ALL: [SherdStatus; 12] = [
        SherdStatus::Ok,
        SherdStatus::InvalidArgument,
        SherdStatus::NullPointer,
        SherdStatus::BufferTooSmall,
        SherdStatus::NotAvailable,
        SherdStatus::Io,
        SherdStatus::Parse,
        SherdStatus::DegenerateGeometry,
        SherdStatus::NotConverged,
        SherdStatus::NeedsManualOrientation,
        SherdStatus::Panic,
        SherdStatus::SenseUncertain,
    ];

    /// The name of the C constant, e.g. `SHERD_STATUS_PARSE`: made once from the
    /// variant's name, as cbindgen makes the header's, so that the names are written
    /// nowhere else.
    fn c_name(self) -> &'static CStr {
        static NAMES: OnceLock<Vec<CString>> = OnceLock::new();
        let names = NAMES.get_or_init(|| {
            let prefix = screaming_snake_case("SherdStatus");
            SherdStatus::ALL
                .iter()
                .map(|status| {
                    let name = format!("{prefix}_{}", screaming_snake_case(&format!("{status:?}")));
                    CString::new(name).expect("an identifier holds no NUL")
                })
                .collect()
        });
        let index = SherdStatus::ALL.iter().position(|known| *known == self).unwrap_or_default();
        &names[index]
    }
}

/// `SHERD_STATUS` for `SherdStatus`: an identifier in the case of C constants.
pub(crate) fn screaming_snake_case(camel_case: &str) -> String {
    let mut name = String::new();
    for (i, letter) in camel_case.chars().enumerate() {
        if letter.is_ascii_uppercase() && i > 0 {
            name.push('_');
        }
        name.push(letter.to_ascii_uppercase());
    }
    name
}

/// The name of a status constant as a static NUL-terminated string, e.g.
/// `"SHERD_STATUS_PARSE"`; `"SHERD_STATUS_UNKNOWN"` for a value that is not a status.
/// Never NULL; the string must not be freed.
#[unsafe(no_mangle)]
pub extern "C" fn sherd_status_name(status: u32) -> *const c_char {
    SherdStatus::ALL
        .iter()
        .find(|known| **known as u32 == status)
        .map_or(c"SHERD_STATUS_UNKNOWN", |known| known.c_name())
        .as_ptr()
}
