//! Exit codes: 2 for bad input or settings (the library's input errors and the
//! CLI's own [`BadArgs`]), 1 for everything else, 0 for success.

/// A settings error found by the CLI itself (exit code 2), among them outputs that
/// would overwrite an input or each other.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadArgs(pub String);

/// 2 for bad input or settings (the library's and its files' errors say which they
/// are), 1 else.
pub fn code(e: &anyhow::Error) -> i32 {
    if let Some(fe) = e.downcast_ref::<primdecomp_files::Error>() {
        return fe.exit_code();
    }
    match e.downcast_ref::<primdecomp::Error>() {
        Some(pe) => pe.exit_code(),
        None if e.downcast_ref::<BadArgs>().is_some() => 2,
        None => 1,
    }
}

/// Prints `e` and gives the process's exit code for it (the library's messages make
/// names visible themselves; a path's line and paragraph separators are escaped here).
pub fn report(e: &anyhow::Error) -> i32 {
    eprintln!("{}", one_line(&format!("error: {e:#}")));
    code(e)
}

/// Text as the terminal is shown it: control characters (ESC, BEL, a carriage
/// return…) in file and object names, or in a file's bytes quoted by a message, are
/// written as visible escapes (`\u{1b}`, `primdecomp_files::visible`) instead of
/// acting on the terminal, and so are U+2028 and U+2029 ([`one_line`]); line ends
/// between lines stay.
pub fn terminal(text: &str) -> String {
    text.split('\n')
        .map(|line| one_line(&primdecomp_files::visible(line)))
        .collect::<Vec<_>>()
        .join("\n")
}

/// `text` with the line and paragraph separators U+2028 and U+2029 written as
/// `\u{2028}` and `\u{2029}`. A terminal does not break a line there, but what reads a
/// captured log by lines does (Python's `str.splitlines`, editors): a file name
/// holding one would cut a message in two. (In the exports they stay: every format's
/// reader takes them inside a string or name, `primdecomp_export::names`.)
fn one_line(text: &str) -> String {
    if !text.contains(['\u{2028}', '\u{2029}']) {
        return text.to_string();
    }
    text.replace('\u{2028}', "\\u{2028}")
        .replace('\u{2029}', "\\u{2029}")
}

/// Set once standard output carries a result (`decompose -o -`): from then on what
/// the CLI says goes to standard error, so the output stays the result alone.
static STDOUT_CARRIES_RESULT: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Keeps standard output for a result: [`println`] and [`print`] write to standard
/// error from now on.
pub fn keep_stdout_for_result() {
    STDOUT_CARRIES_RESULT.store(true, std::sync::atomic::Ordering::Relaxed);
}

/// Whether standard output carries a result ([`keep_stdout_for_result`]).
pub fn stdout_carries_result() -> bool {
    STDOUT_CARRIES_RESULT.load(std::sync::atomic::Ordering::Relaxed)
}

/// Set by `export`, `view`, `eval` and `demo-scene` under `--quiet`: from then on
/// [`println`] and [`print`] print nothing, since all they say there is what was
/// written (errors go to standard error through [`report`] as ever). `decompose` and
/// `sim` decide line by line instead: `decompose --timings` prints even when quiet.
static QUIET: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Prints nothing more through [`println`] and [`print`] ([`QUIET`]).
pub fn quiet_from_now() {
    QUIET.store(true, std::sync::atomic::Ordering::Relaxed);
}

/// What [`println`] and [`print`] print: `text` through [`terminal`], then `end`, on
/// standard output, or on standard error where standard output carries a result;
/// nothing after [`quiet_from_now`].
pub fn say(text: &str, end: &str) {
    if QUIET.load(std::sync::atomic::Ordering::Relaxed) {
        return;
    }
    let text = terminal(text);
    match stdout_carries_result() {
        true => std::eprint!("{text}{end}"),
        false => std::print!("{text}{end}"),
    }
}

// `println!`, `print!` and `eprintln!` through [`terminal`]: a module that prints
// names or paths imports these (`use crate::exit::{eprintln, print, println};`),
// which shadow the standard ones, so every line it prints is escaped. `println!` and
// `print!` go through [`say`].
macro_rules! println {
    () => { $crate::exit::say("", "\n") };
    ($($t:tt)*) => { $crate::exit::say(&format!($($t)*), "\n") };
}
macro_rules! print {
    ($($t:tt)*) => { $crate::exit::say(&format!($($t)*), "") };
}
macro_rules! eprintln {
    () => { std::eprintln!() };
    ($($t:tt)*) => { std::eprintln!("{}", $crate::exit::terminal(&format!($($t)*))) };
}
pub(crate) use {eprintln, print, println};

#[cfg(test)]
mod tests {
    #[test]
    fn control_characters_reach_the_terminal_escaped() {
        let text = "error: a\u{1b}[31mb\u{7}.obj: bad\nsecond line\r";
        assert_eq!(
            super::terminal(text),
            "error: a\\u{1b}[31mb\\u{7}.obj: bad\nsecond line\\u{d}"
        );
    }

    #[test]
    fn line_and_paragraph_separators_stay_on_their_line() {
        let text = "input     a\u{2028}b\u{2029}c.obj: 12 faces\nwrote     d\u{2028}.json";
        let shown = super::terminal(text);
        assert_eq!(
            shown,
            "input     a\\u{2028}b\\u{2029}c.obj: 12 faces\nwrote     d\\u{2028}.json"
        );
        assert_eq!(super::one_line("plain 日本"), "plain 日本");
    }
}
