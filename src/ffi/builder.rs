//! What every option builder shares. A builder is an opaque handle holding the Rust
//! options of one operation, created with their defaults, changed through typed setters
//! that check each value, and passed (or NULL for the defaults) to the operation. Freeing
//! a builder twice is undefined behaviour, as with `free`; set your pointer to NULL after
//! `_free`. Each builder lives beside its operation (`SherdRefineOptions` in `refine.rs`),
//! as rustls-ffi keeps its config builders beside their connections.

use super::error::{Failure, FfiResult};
use super::panic::guard;
use super::pointers::{borrow, borrow_mut, require, write_out};
use super::status::SherdStatus;

/// Creates a builder holding `T::default()`.
pub(crate) unsafe fn new_builder<B>(out: *mut *mut B, builder: B) -> FfiResult {
    require(out.cast_const(), "out_options")?;
    unsafe { write_out(out, Box::into_raw(Box::new(builder)), "out_options") }
}

/// Frees a builder; NULL is ignored.
pub(crate) unsafe fn free_builder<B>(builder: *mut B) {
    if !builder.is_null() {
        drop(unsafe { Box::from_raw(builder) });
    }
}

/// Runs a setter on the builder behind `options`.
pub(crate) fn set<B>(function: &str, options: *mut B, setter: impl FnOnce(&mut B) -> FfiResult) -> SherdStatus {
    guard(function, || setter(unsafe { borrow_mut(options, "options") }?))
}

/// An option builder: a handle around the Rust options of one operation.
pub(crate) trait Builder {
    /// The Rust options it holds.
    type Options;
    /// Those options, to change.
    fn options_mut(&mut self) -> &mut Self::Options;
}

/// The setter of one option: checks the handle, then the value (`value` refuses it with
/// its reason), and stores it in the `field` of the builder's options.
pub(crate) fn assign<B: Builder, V>(
    function: &str,
    options: *mut B,
    field: impl FnOnce(&mut B::Options) -> &mut V,
    value: impl FnOnce() -> FfiResult<V>,
) -> SherdStatus {
    set(function, options, |builder| {
        *field(builder.options_mut()) = value()?;
        Ok(())
    })
}

/// Declares `$builder` the builder of `$options` (its field `options`).
macro_rules! builder {
    ($builder:ident => $options:ty) => {
        impl $crate::ffi::builder::Builder for $builder {
            type Options = $options;
            fn options_mut(&mut self) -> &mut $options {
                &mut self.options
            }
        }
    };
}
pub(crate) use builder;

/// The options behind a nullable builder pointer: the builder's, or the defaults.
pub(crate) unsafe fn options_or_default<B, T: Clone + Default>(options: *const B, get: impl FnOnce(&B) -> &T) -> FfiResult<T> {
    if options.is_null() {
        return Ok(T::default());
    }
    Ok(get(unsafe { borrow(options, "options") }?).clone())
}

pub(crate) fn finite_positive(value: f64, name: &str) -> FfiResult<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be finite and positive, got {value}")))
    }
}

pub(crate) fn fraction(value: f64, name: &str) -> FfiResult<f64> {
    if value > 0.0 && value <= 1.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be in (0, 1], got {value}")))
    }
}

/// `value` when it is at most `maximum`: counts that set iterations or sizes are bounded,
/// so that no option value makes an operation run for ever or exhaust memory.
pub(crate) fn at_most(value: usize, maximum: usize, name: &str) -> FfiResult<usize> {
    if value <= maximum {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be at most {maximum}, got {value}")))
    }
}

pub(crate) fn positive_count(value: usize, name: &str) -> FfiResult<usize> {
    if value > 0 { Ok(value) } else { Err(Failure::invalid(format!("`{name}` must be at least 1"))) }
}

/// A finite positive length, or `None` (the library's default) for 0.
pub(crate) fn positive_or_default(value: f64, name: &str) -> FfiResult<Option<f64>> {
    if value == 0.0 { Ok(None) } else { finite_positive(value, name).map(Some) }
}

/// A confidence level, strictly between 0 and 1.
pub(crate) fn confidence_level(value: f64, name: &str) -> FfiResult<f64> {
    if value > 0.0 && value < 1.0 {
        Ok(value)
    } else {
        Err(Failure::invalid(format!("`{name}` must be in (0, 1), got {value}")))
    }
}
