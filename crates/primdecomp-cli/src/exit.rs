//! Exit codes: 2 for bad input or settings (the library's input errors and the
//! CLI's own [`BadArgs`]), 1 for everything else, 0 for success.

/// A settings error found by the CLI itself (exit code 2), among them outputs that
/// would overwrite an input or each other.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadArgs(pub String);

/// 2 for bad input or settings (the library's errors say which they are), 1 else.
pub fn code(e: &anyhow::Error) -> i32 {
    match e.downcast_ref::<primdecomp::Error>() {
        Some(pe) => pe.exit_code(),
        None if e.downcast_ref::<BadArgs>().is_some() => 2,
        None => 1,
    }
}

/// Prints `e` and gives the process's exit code for it.
pub fn report(e: &anyhow::Error) -> i32 {
    eprintln!("error: {e:#}");
    code(e)
}
