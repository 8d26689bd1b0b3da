//! Numbers as messages show them.

/// Short form of a number for messages, three significant digits: `1e60`,
/// `2.5e-35`, `inf`.
///
/// ```
/// use primdecomp_math::short;
///
/// assert_eq!(short(1e60), "1e60");
/// assert_eq!(short(2.5e-35), "2.5e-35");
/// assert_eq!(short(123456.0), "1.23e5");
/// assert_eq!(short(f64::INFINITY), "inf");
/// assert_eq!(short(0.0), "0");
/// ```
pub fn short(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{x:.2e}");
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s,
    }
}
