//! Library and ABI versions, so a host can check at run time that the library it loaded
//! matches the header it was compiled against.

use std::ffi::c_char;

/// The version of the C ABI described by `sherd.h` (its `SHERD_ABI_VERSION` macro,
/// written by `cbindgen.toml`; tests/c/test_mesh.c checks that both agree). It changes only when a function's
/// signature or a struct's existing fields change; adding functions, constants or
/// trailing struct fields (behind the `size` field) keeps it.
pub const SHERD_ABI_VERSION: u32 = 1;

/// The library's version (`"major.minor.patch"`), a static NUL-terminated string that
/// must not be freed.
#[unsafe(no_mangle)]
pub extern "C" fn sherd_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// The `SHERD_ABI_VERSION` the library was built with; a host compares it with the
/// macro of the header it was compiled against.
#[unsafe(no_mangle)]
pub extern "C" fn sherd_abi_version() -> u32 {
    SHERD_ABI_VERSION
}
