//! Status codes, the per-thread last-error message, and the guard every exported
//! function runs its body in: a panic (a bug) is caught there and becomes
//! [`PrimdecompStatus::Panic`], so no unwinding ever reaches the C caller.

use primdecomp::Error;
use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// What a call returns: `PRIMDECOMP_STATUS_OK` (0) or why it failed;
/// `primdecomp_last_error()` then says more, in one sentence.
#[repr(i32)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrimdecompStatus {
    /// Success.
    Ok = 0,
    /// A pointer that must not be NULL was, a string is not UTF-8, or sizes do not add up.
    InvalidArgument = 1,
    /// The settings JSON does not parse or a setting is out of range.
    InvalidSettings = 2,
    /// The mesh is malformed, empty, or too large (the message names the file and the
    /// line or byte offset).
    InvalidInput = 3,
    /// Reading or writing a file failed for a reason that is not the input's fault.
    Io = 4,
    /// The run was cancelled (the cancel flag or the progress callback).
    Cancelled = 5,
    /// The level asked for does not exist.
    OutOfRange = 6,
    /// An internal error (a bug in primdecomp; please report the message).
    Panic = 7,
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// A failed call: its status and message.
pub(crate) struct Failure {
    pub status: PrimdecompStatus,
    pub message: String,
}

impl Failure {
    pub(crate) fn new(status: PrimdecompStatus, message: impl Into<String>) -> Failure {
        Failure {
            status,
            message: message.into(),
        }
    }

    pub(crate) fn argument(message: impl Into<String>) -> Failure {
        Failure::new(PrimdecompStatus::InvalidArgument, message)
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Failure {
        let status = match e {
            Error::InvalidParams(_) => PrimdecompStatus::InvalidSettings,
            Error::Cancelled => PrimdecompStatus::Cancelled,
            Error::Io { .. } | Error::Write { .. } => PrimdecompStatus::Io,
            _ => PrimdecompStatus::InvalidInput,
        };
        Failure::new(status, e.to_string())
    }
}

fn set_last_error(message: &str) {
    // A message holding NUL is cut there (C strings end at the first NUL).
    let cut = message.split('\0').next().unwrap_or_default();
    let text = CString::new(cut).unwrap_or_default();
    LAST_ERROR.with(|l| *l.borrow_mut() = text);
}

/// The message of a caught panic.
pub(crate) fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    p.downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| p.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Runs `body`, returning its status and setting this thread's last error: the
/// failure's message, or empty on success. A panic is caught and reported as
/// [`PrimdecompStatus::Panic`].
pub(crate) fn guard(body: impl FnOnce() -> Result<(), Failure>) -> PrimdecompStatus {
    let outcome = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|p| {
        Err(Failure::new(
            PrimdecompStatus::Panic,
            format!(
                "internal error in primdecomp (a bug, please report it): {}",
                panic_message(p.as_ref())
            ),
        ))
    });
    match outcome {
        Ok(()) => {
            set_last_error("");
            PrimdecompStatus::Ok
        }
        Err(f) => {
            set_last_error(&f.message);
            f.status
        }
    }
}

/// The message of the last call on this thread that failed, or an empty string when
/// the last call succeeded. Never NULL; valid until the next primdecomp call on this
/// thread.
#[no_mangle]
pub extern "C" fn primdecomp_last_error() -> *const c_char {
    LAST_ERROR.with(|l| l.borrow().as_ptr())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    fn last() -> String {
        // SAFETY: never NULL, valid until the next call on this thread.
        unsafe { CStr::from_ptr(primdecomp_last_error()) }
            .to_string_lossy()
            .into_owned()
    }

    #[test]
    fn a_panic_becomes_a_status_and_a_message() {
        let s = guard(|| panic!("a bug with \"quotes\" and a\nnewline"));
        assert_eq!(s, PrimdecompStatus::Panic);
        assert!(
            last().starts_with("internal error in primdecomp"),
            "{}",
            last()
        );
        assert!(last().contains("a bug with"), "{}", last());
        // The next call that succeeds clears the message; the library goes on working.
        assert_eq!(guard(|| Ok(())), PrimdecompStatus::Ok);
        assert_eq!(last(), "");
    }

    #[test]
    fn a_message_holding_nul_is_still_a_c_string() {
        let s = guard(|| Err(Failure::argument("before\0after")));
        assert_eq!(s, PrimdecompStatus::InvalidArgument);
        assert!(last().starts_with("before"), "{}", last());
    }
}
