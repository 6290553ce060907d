//! The names of the C ABI's named values, listed by the library, so that a host offers
//! the library's names (in its menus, its parameters, its bindings) instead of writing
//! them out a second time.

use std::ffi::c_char;

use super::enums::SherdVocabulary;
use super::error::Failure;
use super::panic::guard;
use super::pointers::{SizedStruct, text_from, write_out, write_sized};
use super::status::SherdStatus;

/// One named value of a vocabulary. Set `size` to `sizeof(SherdVocabularyEntry)` first.
/// The strings are static, NUL-terminated UTF-8: never free them.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SherdVocabularyEntry {
    /// `sizeof(SherdVocabularyEntry)`, set by the caller.
    pub size: usize,
    /// The name users type and hosts show, e.g. `"circles"` (lower case, words joined by
    /// underscores): the name `sherd orient --refine`, Python and the add-ons take.
    pub name: *const c_char,
    /// The value of the named constant, e.g. `SHERD_CRITERION_CIRCLES`.
    pub value: u32,
    /// What the value does, in one line: for a tooltip or a help text.
    pub description: *const c_char,
}

impl Default for SherdVocabularyEntry {
    fn default() -> Self {
        SherdVocabularyEntry { size: 0, name: std::ptr::null(), value: 0, description: std::ptr::null() }
    }
}

unsafe impl SizedStruct for SherdVocabularyEntry {
    const NAME: &'static str = "SherdVocabularyEntry";
    const MIN_SIZE: usize = size_of::<SherdVocabularyEntry>();
}

/// Writes the number of named values of `vocabulary` (a `SHERD_VOCABULARY_*` value) to
/// `*out_count`; `SHERD_STATUS_INVALID_ARGUMENT` for another value.
///
/// # Safety
/// `out_count` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_vocabulary_count(vocabulary: u32, out_count: *mut usize) -> SherdStatus {
    guard("sherd_vocabulary_count", || {
        let vocabulary = SherdVocabulary::parse(vocabulary, "vocabulary")?;
        unsafe { write_out(out_count, vocabulary.entries().len(), "out_count") }
    })
}

/// Writes the named value number `index` (from 0 to the count less one, in the order the
/// library lists them to users, which is not always the values' order) of `vocabulary` (a `SHERD_VOCABULARY_*` value) to `*out_entry` (`size` set):
/// its name, its value and its description. `SHERD_STATUS_INVALID_ARGUMENT` for another
/// vocabulary or an index past the count, with `*out_entry` left unchanged.
///
/// # Safety
/// `out_entry` must be writable with its `size` set.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_vocabulary_entry(vocabulary: u32, index: usize, out_entry: *mut SherdVocabularyEntry) -> SherdStatus {
    guard("sherd_vocabulary_entry", || {
        let kind = SherdVocabulary::parse(vocabulary, "vocabulary")?;
        let entries = kind.entries();
        let entry = entries.get(index).ok_or_else(|| {
            Failure::invalid(format!("`index` {index} is past the {} values of vocabulary {vocabulary} ({kind:?})", entries.len()))
        })?;
        let out = SherdVocabularyEntry {
            size: size_of::<SherdVocabularyEntry>(),
            name: entry.name.as_ptr(),
            value: entry.value,
            description: entry.description.as_ptr(),
        };
        unsafe { write_sized(out_entry, out, "out_entry") }
    })
}

/// Writes the value of `vocabulary` (a `SHERD_VOCABULARY_*` value) named `name` (a
/// NUL-terminated UTF-8 string; case and hyphens for underscores do not matter, and a
/// few aliases such as `"color"` are accepted) to `*out_value`.
/// `SHERD_STATUS_INVALID_ARGUMENT`, with a message listing the names, for an unknown name.
///
/// # Safety
/// `name` must be a NUL-terminated string; `out_value` writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn sherd_vocabulary_value(vocabulary: u32, name: *const c_char, out_value: *mut u32) -> SherdStatus {
    guard("sherd_vocabulary_value", || {
        let vocabulary = SherdVocabulary::parse(vocabulary, "vocabulary")?;
        let name = unsafe { text_from(name, "name") }?;
        let value = vocabulary.value_named(name)?;
        unsafe { write_out(out_value, value, "out_value") }
    })
}
