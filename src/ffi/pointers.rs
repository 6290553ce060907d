//! Checked conversions from the host's raw pointers: NULL and misalignment become
//! `SHERD_STATUS_NULL_POINTER` naming the argument, lengths that overflow become
//! `SHERD_STATUS_INVALID_ARGUMENT`, never undefined behaviour inside Rust.

use super::error::{Failure, FfiResult};
use super::status::SherdStatus;

fn check_pointer<T>(pointer: *const T, name: &str) -> FfiResult {
    if pointer.is_null() {
        return Err(Failure::new(SherdStatus::NullPointer, format!("`{name}` is NULL")));
    }
    if !pointer.is_aligned() {
        return Err(Failure::new(
            SherdStatus::NullPointer,
            format!("`{name}` ({pointer:p}) is not aligned to {} bytes", align_of::<T>()),
        ));
    }
    Ok(())
}

/// A shared reference to the object `pointer` points at.
///
/// # Safety
/// A non-NULL `pointer` must point to a live, initialised `T` for `'a`.
pub(crate) unsafe fn borrow<'a, T>(pointer: *const T, name: &str) -> FfiResult<&'a T> {
    check_pointer(pointer, name)?;
    Ok(unsafe { &*pointer })
}

/// A mutable reference to the object `pointer` points at.
///
/// # Safety
/// A non-NULL `pointer` must point to a live, initialised `T` for `'a`, not aliased.
pub(crate) unsafe fn borrow_mut<'a, T>(pointer: *mut T, name: &str) -> FfiResult<&'a mut T> {
    check_pointer(pointer, name)?;
    Ok(unsafe { &mut *pointer })
}

/// Number of scalars in `count` groups of `per_item` (3 per vertex, 16 per matrix...),
/// refusing counts whose byte size does not fit the address space.
pub(crate) fn scalar_count<T>(count: usize, per_item: usize, name: &str) -> FfiResult<usize> {
    count
        .checked_mul(per_item)
        .filter(|&n| n.checked_mul(size_of::<T>()).is_some_and(|bytes| bytes <= isize::MAX as usize))
        .ok_or_else(|| Failure::invalid(format!("`{name}`: {count} items of {per_item} values is too large")))
}

/// The host array of `count * per_item` values at `pointer`. NULL is accepted when the
/// array is empty.
///
/// # Safety
/// A non-NULL `pointer` must point to at least `count * per_item` initialised `T` that
/// stay alive and unmodified for `'a`.
pub(crate) unsafe fn host_slice<'a, T>(pointer: *const T, count: usize, per_item: usize, name: &str) -> FfiResult<&'a [T]> {
    let len = scalar_count::<T>(count, per_item, name)?;
    if len == 0 {
        return Ok(&[]);
    }
    check_pointer(pointer, name)?;
    Ok(unsafe { std::slice::from_raw_parts(pointer, len) })
}

/// The host's output array of `count * per_item` values at `pointer`. NULL is accepted
/// when there is nothing to write.
///
/// # Safety
/// A non-NULL `pointer` must point to at least `count * per_item` writable `T`, not
/// aliased by anything else during `'a`.
pub(crate) unsafe fn host_slice_mut<'a, T>(pointer: *mut T, count: usize, per_item: usize, name: &str) -> FfiResult<&'a mut [T]> {
    let len = scalar_count::<T>(count, per_item, name)?;
    if len == 0 {
        return Ok(&mut []);
    }
    check_pointer(pointer, name)?;
    Ok(unsafe { std::slice::from_raw_parts_mut(pointer, len) })
}

/// Writes `value` through the out-pointer `pointer`.
///
/// # Safety
/// A non-NULL `pointer` must be valid for writing a `T`.
pub(crate) unsafe fn write_out<T>(pointer: *mut T, value: T, name: &str) -> FfiResult {
    check_pointer(pointer, name)?;
    unsafe { pointer.write(value) };
    Ok(())
}

/// A result struct of the ABI whose first field is `size_t size`, set by the caller to
/// `sizeof` the struct as its header declares it. Structs only grow at the end, so the
/// library reads and writes the prefix both sides know.
///
/// # Safety
/// Implementors are `#[repr(C)]`, start with a `usize` field, and are valid for any bit
/// pattern of their first `MIN_SIZE` bytes followed by their `Default` values.
pub(crate) unsafe trait SizedStruct: Copy + Default {
    /// The name C sees, for messages.
    const NAME: &'static str;
    /// The size of the first version of the struct; smaller `size` values are refused.
    const MIN_SIZE: usize;
}

/// Checks a sized struct's pointer and `size` field; the number of bytes both sides know.
pub(crate) fn checked_size<T: SizedStruct>(pointer: *const T, name: &str) -> FfiResult<usize> {
    check_pointer(pointer, name)?;
    let size = unsafe { pointer.cast::<usize>().read() };
    if size < T::MIN_SIZE {
        return Err(Failure::invalid(format!(
            "`{name}->size` is {size}, expected sizeof({}) = {} (set it before the call)",
            T::NAME,
            size_of::<T>()
        )));
    }
    Ok(size.min(size_of::<T>()))
}

/// Writes `value` into the caller's struct, keeping its `size` field and writing no byte
/// past it.
///
/// # Safety
/// A non-NULL `pointer` must be valid for writing `(*pointer).size` bytes.
pub(crate) unsafe fn write_sized<T: SizedStruct>(pointer: *mut T, value: T, name: &str) -> FfiResult {
    let size = checked_size(pointer.cast_const(), name)?;
    let bytes = (&raw const value).cast::<u8>();
    let word = size_of::<usize>();
    unsafe { std::ptr::copy_nonoverlapping(bytes.add(word), pointer.cast::<u8>().add(word), size - word) };
    Ok(())
}

/// Reads the caller's struct; fields past its `size` (from a newer library version than
/// the caller's header) take their `Default` values.
///
/// # Safety
/// A non-NULL `pointer` must be valid for reading `(*pointer).size` bytes.
pub(crate) unsafe fn read_sized<T: SizedStruct>(pointer: *const T, name: &str) -> FfiResult<T> {
    let size = checked_size(pointer, name)?;
    let mut value = T::default();
    let word = size_of::<usize>();
    unsafe {
        std::ptr::copy_nonoverlapping(pointer.cast::<u8>().add(word), (&raw mut value).cast::<u8>().add(word), size - word)
    };
    Ok(value)
}

/// Rejects pointer arguments that must be checked before any work starts.
pub(crate) fn require<T>(pointer: *const T, name: &str) -> FfiResult {
    check_pointer(pointer, name)
}

/// The file path in the NUL-terminated string `path` (bytes as the OS takes them on
/// Unix; UTF-8 elsewhere).
///
/// # Safety
/// A non-NULL `path` must point to a NUL-terminated string.
pub(crate) unsafe fn path_from(path: *const std::ffi::c_char, name: &str) -> FfiResult<std::path::PathBuf> {
    check_pointer(path, name)?;
    let bytes = unsafe { std::ffi::CStr::from_ptr(path) }.to_bytes();
    if bytes.is_empty() {
        return Err(Failure::invalid(format!("`{name}` is an empty path")));
    }
    #[cfg(unix)]
    {
        use std::os::unix::ffi::OsStrExt;
        Ok(std::path::PathBuf::from(std::ffi::OsStr::from_bytes(bytes)))
    }
    #[cfg(not(unix))]
    {
        std::str::from_utf8(bytes)
            .map(std::path::PathBuf::from)
            .map_err(|e| Failure::invalid(format!("`{name}` is not UTF-8: {e}")))
    }
}

/// The UTF-8 text of the NUL-terminated string `text`.
///
/// # Safety
/// A non-NULL `text` must point to a NUL-terminated string that lives for `'a`.
pub(crate) unsafe fn text_from<'a>(text: *const std::ffi::c_char, name: &str) -> FfiResult<&'a str> {
    check_pointer(text, name)?;
    let text = unsafe { std::ffi::CStr::from_ptr(text) };
    text.to_str().map_err(|e| Failure::invalid(format!("`{name}` is not UTF-8: {e}")))
}
