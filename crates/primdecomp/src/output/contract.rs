//! The result contract's identity: every result says it is one (`"format":
//! "primdecomp"`) and which version of the contract it follows (`"version": 1`), and
//! whatever reads a result back (`export`, `view`, `eval`, `sim`, `--config`) checks
//! both strictly before trusting anything else in it.

/// The `format` every result declares.
pub(crate) const FORMAT: &str = "primdecomp";

/// The one `version` of the result contract this build reads and writes.
pub(crate) const VERSION: u64 = 1;

/// A JSON value for a message: compact, control characters made visible, cut to 40
/// characters.
fn show_value(v: &serde_json::Value) -> String {
    let s = primdecomp_files::visible(&v.to_string());
    if s.chars().count() > 40 {
        format!("{}…", s.chars().take(40).collect::<String>())
    } else {
        s
    }
}

/// Refuses a document that does not say it is a result of this contract: `format`
/// must be the string `"primdecomp"` and `version` the integer 1 (not `"1"`, `1.0` or
/// 2). Used wherever a result is read back (`export`, `view`, `eval`, `sim`,
/// `--config`).
pub(crate) fn check_header(
    format: Option<&serde_json::Value>,
    version: Option<&serde_json::Value>,
) -> Result<(), String> {
    let start = r#"(a result starts {"format": "primdecomp", "version": 1, …})"#;
    match format {
        None => {
            return Err(format!(
                "not a primdecomp result: it has no \"format\" {start}"
            ))
        }
        Some(serde_json::Value::String(f)) if f == FORMAT => {}
        Some(f) => {
            return Err(format!(
                "not a primdecomp result: its \"format\" is {}, not \"{FORMAT}\"",
                show_value(f)
            ))
        }
    }
    match version {
        None => Err(format!("the result has no \"version\" {start}")),
        Some(v) if v.as_u64() == Some(VERSION) => Ok(()),
        Some(v @ serde_json::Value::Number(n)) if n.as_u64().is_some() => Err(format!(
            "the result's \"version\" is {}; this primdecomp reads version {VERSION} (a newer \
             primdecomp wrote it?)",
            show_value(v)
        )),
        Some(v) => Err(format!(
            "the result's \"version\" is {}, not the integer {VERSION}",
            show_value(v)
        )),
    }
}
