//! Reading the C caller's arguments: NULL checks, strings, arrays and out-pointers,
//! each refused with a message naming the argument.

use crate::status::Failure;
use std::ffi::{c_char, CStr};

/// A NUL-terminated UTF-8 string argument.
pub(crate) fn text<'a>(p: *const c_char, name: &str) -> Result<&'a str, Failure> {
    if p.is_null() {
        return Err(Failure::argument(format!("{name} is NULL")));
    }
    // SAFETY: the caller passes a NUL-terminated string that lives for the call.
    unsafe { CStr::from_ptr(p) }
        .to_str()
        .map_err(|e| Failure::argument(format!("{name} is not UTF-8: {e}")))
}

/// An optional string argument: NULL or empty is `None`.
pub(crate) fn optional_text<'a>(p: *const c_char, name: &str) -> Result<Option<&'a str>, Failure> {
    if p.is_null() {
        return Ok(None);
    }
    text(p, name).map(|s| (!s.is_empty()).then_some(s))
}

/// An array of `len` elements; NULL is allowed only when `len` is 0.
pub(crate) fn array<'a, T>(p: *const T, len: usize, name: &str) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Failure::argument(format!(
            "{name} is NULL but its length is {len}"
        )));
    }
    if len
        .checked_mul(std::mem::size_of::<T>())
        .is_none_or(|b| b > isize::MAX as usize)
    {
        return Err(Failure::argument(format!(
            "{name}: length {len} is too large"
        )));
    }
    if (p as usize) % std::mem::align_of::<T>() != 0 {
        return Err(Failure::argument(format!(
            "{name} is not aligned for its type"
        )));
    }
    // SAFETY: non-null, aligned, and the caller promises `len` readable elements that
    // outlive the call.
    Ok(unsafe { std::slice::from_raw_parts(p, len) })
}

/// Writes `value` through the out-pointer `p`.
pub(crate) fn put<T>(p: *mut T, value: T, name: &str) -> Result<(), Failure> {
    if p.is_null() {
        return Err(Failure::argument(format!("{name} is NULL")));
    }
    // SAFETY: non-null; the caller passes a writable `T`.
    unsafe { p.write(value) };
    Ok(())
}

/// Checks that the out-pointer `p` can be written before any work is done.
pub(crate) fn writable<T>(p: *mut T, name: &str) -> Result<(), Failure> {
    if p.is_null() {
        return Err(Failure::argument(format!("{name} is NULL")));
    }
    Ok(())
}

/// The object behind a handle argument.
pub(crate) fn handle<'a, T>(p: *const T, name: &str) -> Result<&'a T, Failure> {
    // SAFETY: the caller passes a handle this library returned and has not freed.
    unsafe { p.as_ref() }.ok_or_else(|| Failure::argument(format!("{name} is NULL")))
}
