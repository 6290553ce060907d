//! Status codes: every entry point of the C ABI returns one.
//!
//! In the header `SherdStatus` is a `uint32_t` with named constants. The Rust enum only
//! ever travels from the library to the host; values coming from the host (as in
//! `sherd_status_name`) are taken as plain integers and checked, because a Rust enum
//! holding a value the host made up is undefined behaviour.

use std::ffi::c_char;

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

    /// The name of the C constant, NUL-terminated.
    fn c_name(self) -> &'static str {
        match self {
            SherdStatus::Ok => "SHERD_STATUS_OK\0",
            SherdStatus::InvalidArgument => "SHERD_STATUS_INVALID_ARGUMENT\0",
            SherdStatus::NullPointer => "SHERD_STATUS_NULL_POINTER\0",
            SherdStatus::BufferTooSmall => "SHERD_STATUS_BUFFER_TOO_SMALL\0",
            SherdStatus::NotAvailable => "SHERD_STATUS_NOT_AVAILABLE\0",
            SherdStatus::Io => "SHERD_STATUS_IO\0",
            SherdStatus::Parse => "SHERD_STATUS_PARSE\0",
            SherdStatus::DegenerateGeometry => "SHERD_STATUS_DEGENERATE_GEOMETRY\0",
            SherdStatus::NotConverged => "SHERD_STATUS_NOT_CONVERGED\0",
            SherdStatus::NeedsManualOrientation => "SHERD_STATUS_NEEDS_MANUAL_ORIENTATION\0",
            SherdStatus::Panic => "SHERD_STATUS_PANIC\0",
            SherdStatus::SenseUncertain => "SHERD_STATUS_SENSE_UNCERTAIN\0",
        }
    }
}

/// The name of a status constant as a static NUL-terminated string, e.g.
/// `"SHERD_STATUS_PARSE"`; `"SHERD_STATUS_UNKNOWN"` for a value that is not a status.
/// Never NULL; the string must not be freed.
#[unsafe(no_mangle)]
pub extern "C" fn sherd_status_name(status: u32) -> *const c_char {
    SherdStatus::ALL
        .iter()
        .find(|known| **known as u32 == status)
        .map_or("SHERD_STATUS_UNKNOWN\0", |known| known.c_name())
        .as_ptr()
        .cast()
}
