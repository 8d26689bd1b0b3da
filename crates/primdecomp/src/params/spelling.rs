//! How a user spells each setting's value ("1%", "4K", "exact", "auto", "box"): one
//! [`FromStr`] and one [`Display`] per value type (a byte count, a plain number, is
//! read by [`Goal::parse_bytes`]), used by the command line and the
//! Python keywords alike, so that each reads the same words and says the same thing
//! when a word is wrong. A parse error is [`Error::InvalidParams`] with what was
//! expected and what was given; the caller names the flag or keyword.

use super::{Dedup, Fit, Goal, Partitions, Reprice, Target, Tolerance};
use crate::error::Error;
use crate::primitive::Kind;
use std::fmt::{self, Display, Formatter};
use std::str::FromStr;

fn invalid(message: String) -> Error {
    Error::InvalidParams(message)
}

/// A number written as briefly as it reads back (`0.5`, `2`), rounded to 12
/// significant digits so that 0.07 × 100 shows as 7.
fn brief(x: f64) -> String {
    let digits = 12 - x.abs().log10().ceil().clamp(-300.0, 300.0) as i32;
    let scale = 10f64.powi(digits.clamp(0, 300));
    let rounded = (x * scale).round() / scale;
    match rounded.is_finite() {
        true => format!("{rounded}"),
        false => format!("{x}"),
    }
}

/// A distance in the input's units (`0.5`) or a percentage of its diagonal (`1%`).
///
/// ```
/// use primdecomp::Tolerance;
///
/// assert_eq!("1%".parse::<Tolerance>()?, Tolerance::Diagonal(0.01));
/// assert_eq!("0.5".parse::<Tolerance>()?, Tolerance::Units(0.5));
/// assert_eq!(Tolerance::Diagonal(0.02).to_string(), "2%");
/// assert!("-1%".parse::<Tolerance>().is_err());
/// # Ok::<(), primdecomp::Error>(())
/// ```
impl FromStr for Tolerance {
    type Err = Error;

    fn from_str(t: &str) -> Result<Tolerance, Error> {
        let t = t.trim();
        let (num, percent) = match t.strip_suffix('%') {
            Some(p) => (p.trim(), true),
            None => (t, false),
        };
        if num.parse::<f64>().is_ok_and(|v| v <= 0.0) {
            return Err(invalid(format!(
                "'{t}' is not positive: a tolerance is how far every primitive may stand from \
                 the mesh, a distance (input units) or a percentage of the diagonal like 1%, \
                 greater than 0"
            )));
        }
        match num.parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 && (!percent || v < 100.0) => Ok(match percent {
                true => Tolerance::Diagonal(v / 100.0),
                false => Tolerance::Units(v),
            }),
            _ => Err(invalid(format!(
                "expected a positive distance (input units) or a percentage of the diagonal \
                 like 1%, got '{t}'"
            ))),
        }
    }
}

impl Display for Tolerance {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match *self {
            Tolerance::Units(d) => write!(f, "{}", brief(d)),
            Tolerance::Diagonal(x) => write!(f, "{}%", brief(x * 100.0)),
        }
    }
}

impl Goal {
    /// A byte count as the user writes it, optionally with K, M, G or T (powers of
    /// 1024; `KB`, `KiB` read the same): a byte budget ([`Goal::max_bytes`],
    /// `--max-bytes`) or a memory limit (`--max-memory`). Zero reads as zero; a goal
    /// refuses it ([`crate::Params::validate`]).
    ///
    /// ```
    /// use primdecomp::Goal;
    ///
    /// assert_eq!(Goal::parse_bytes("4K")?, 4096);
    /// assert_eq!(Goal::parse_bytes("1.5GiB")?, 3 << 29);
    /// assert!(Goal::parse_bytes("lots").is_err());
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn parse_bytes(s: &str) -> Result<u64, Error> {
        let bad = || {
            invalid(format!(
                "expected a byte count such as 4096 or 4K, got '{s}'"
            ))
        };
        let t = s.trim().to_ascii_uppercase();
        let t = t.trim_end_matches("IB").trim_end_matches('B');
        let (num, shift) = match t.chars().last().ok_or_else(bad)? {
            'K' => (&t[..t.len() - 1], 10),
            'M' => (&t[..t.len() - 1], 20),
            'G' => (&t[..t.len() - 1], 30),
            'T' => (&t[..t.len() - 1], 40),
            _ => (t, 0),
        };
        let v: f64 = num.trim().parse().map_err(|_| bad())?;
        let bytes = v * (1u64 << shift) as f64;
        match v.is_finite() && v >= 0.0 && bytes < u64::MAX as f64 {
            true => Ok(bytes as u64),
            false => Err(bad()),
        }
    }
}

impl FromStr for Partitions {
    type Err = Error;

    fn from_str(k: &str) -> Result<Partitions, Error> {
        match k.trim() {
            "auto" => Ok(Partitions::Auto),
            n => n
                .parse()
                .map(Partitions::Fixed)
                .map_err(|_| invalid(format!("expected auto or a count, got '{k}'"))),
        }
    }
}

impl Display for Partitions {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Partitions::Auto => f.write_str("auto"),
            Partitions::Fixed(k) => write!(f, "{k}"),
        }
    }
}

/// A positive count (`200`) or a percentage of the faces above 0 and at most 100 (`1%`).
impl FromStr for Target {
    type Err = Error;

    fn from_str(t: &str) -> Result<Target, Error> {
        let t = t.trim();
        let bad = || {
            invalid(format!(
                "expected a positive count or a percentage like 1%, got '{t}'"
            ))
        };
        match t.strip_suffix('%') {
            Some(p) => match p.trim().parse::<f64>() {
                Ok(v) if v > 0.0 && v <= 100.0 => Ok(Target::Percent(v)),
                _ => Err(bad()),
            },
            None => match t.parse::<usize>() {
                Ok(v) if v > 0 => Ok(Target::Count(v)),
                _ => Err(bad()),
            },
        }
    }
}

impl Display for Target {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Target::Count(n) => write!(f, "{n}"),
            Target::Percent(p) => write!(f, "{}%", brief(*p)),
        }
    }
}

/// `exact`, `deferred` (every merge's re-pricing deferred) or the neighbour count from
/// which it is.
///
/// ```
/// use primdecomp::Reprice;
///
/// assert_eq!("64".parse::<Reprice>()?, Reprice::Deferred { min_degree: 64 });
/// assert_eq!(Reprice::Exact.to_string(), "exact");
/// # Ok::<(), primdecomp::Error>(())
/// ```
impl FromStr for Reprice {
    type Err = Error;

    fn from_str(r: &str) -> Result<Reprice, Error> {
        Ok(match r.trim() {
            "exact" => Reprice::Exact,
            "deferred" => Reprice::Deferred { min_degree: 0 },
            t => Reprice::Deferred {
                min_degree: t.parse().map_err(|_| {
                    invalid(format!(
                        "expected exact, deferred or a neighbour count, got '{r}'"
                    ))
                })?,
            },
        })
    }
}

impl Display for Reprice {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Reprice::Exact => f.write_str("exact"),
            Reprice::Deferred { min_degree: 0 } => f.write_str("deferred"),
            Reprice::Deferred { min_degree } => write!(f, "{min_degree}"),
        }
    }
}

/// `exact`, `off` or a welding distance in the input's units.
///
/// ```
/// use primdecomp::Dedup;
///
/// assert_eq!("0.25".parse::<Dedup>()?, Dedup::Tolerance(0.25));
/// assert_eq!(Dedup::Off.to_string(), "off");
/// # Ok::<(), primdecomp::Error>(())
/// ```
impl FromStr for Dedup {
    type Err = Error;

    fn from_str(d: &str) -> Result<Dedup, Error> {
        Ok(match d.trim() {
            "exact" => Dedup::Exact,
            "off" => Dedup::Off,
            t => {
                Dedup::Tolerance(t.parse().map_err(|_| {
                    invalid(format!("expected exact, off or a distance, got '{d}'"))
                })?)
            }
        })
    }
}

impl Display for Dedup {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        match self {
            Dedup::Exact => f.write_str("exact"),
            Dedup::Off => f.write_str("off"),
            Dedup::Tolerance(t) => write!(f, "{}", brief(*t)),
        }
    }
}

/// A primitive kind by name (`box`, `sphere`, `capsule`, `cylinder`, `frustum`,
/// `prism`).
///
/// ```
/// use primdecomp::Kind;
///
/// assert_eq!("prism".parse::<Kind>()?, Kind::Prism);
/// assert_eq!(Kind::Frustum.to_string(), "frustum");
/// # Ok::<(), primdecomp::Error>(())
/// ```
impl Fit {
    /// Sets the weights of the kinds `spelled` names, as a user writes them:
    /// `kind=w` pairs separated by commas (`frustum=3,box=1.2`); the kinds it does not
    /// name keep theirs. A word that is not `kind=w`, a kind that does not exist or a
    /// weight that is not a number is refused with what was expected and what was
    /// given, and nothing is changed; [`crate::Params::validate`] refuses weights that
    /// are not positive.
    ///
    /// ```
    /// use primdecomp::{Fit, Kind};
    ///
    /// let mut fit = Fit::default();
    /// fit.set_weights("frustum=3, box=1.5")?;
    /// assert_eq!(fit.weights[Kind::Frustum as usize], 3.0);
    /// assert_eq!(fit.weights[Kind::Box as usize], 1.5);
    /// assert!(fit.set_weights("cone=2").is_err());
    /// assert!(fit.set_weights("box").is_err());
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn set_weights(&mut self, spelled: &str) -> Result<(), Error> {
        let mut weights = self.weights;
        for pair in spelled.split(',') {
            let (k, v) = pair
                .split_once('=')
                .ok_or_else(|| invalid(format!("expected kind=value, got '{pair}'")))?;
            let kind: Kind = k.parse()?;
            weights[kind as usize] =
                (v.trim().parse()).map_err(|_| invalid(format!("'{v}' is not a number")))?;
        }
        self.weights = weights;
        Ok(())
    }

    /// Every kind's weight as [`Fit::set_weights`] reads it back, in [`Kind::ALL`]'s
    /// order.
    ///
    /// ```
    /// use primdecomp::Fit;
    ///
    /// let spelled = Fit::default().weights_spelled();
    /// assert_eq!(spelled, "box=1,sphere=1,capsule=1,cylinder=1.05,frustum=2.1,prism=1.4");
    /// let mut fit = Fit { weights: [2.0; 6], ..Fit::default() };
    /// fit.set_weights(&spelled)?;
    /// assert_eq!(fit, Fit::default());
    /// # Ok::<(), primdecomp::Error>(())
    /// ```
    pub fn weights_spelled(&self) -> String {
        let pairs = Kind::ALL.map(|k| format!("{k}={}", brief(self.weights[k as usize])));
        pairs.join(",")
    }
}

impl FromStr for Kind {
    type Err = Error;

    fn from_str(k: &str) -> Result<Kind, Error> {
        Kind::from_name(k.trim()).ok_or_else(|| {
            invalid(format!(
                "unknown primitive kind '{k}': expected box, sphere, capsule, cylinder, \
                 frustum or prism"
            ))
        })
    }
}

impl Display for Kind {
    fn fmt(&self, f: &mut Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every value reads back from what it displays.
    #[test]
    fn spellings_read_back() {
        for t in [
            Tolerance::Diagonal(0.02),
            Tolerance::Diagonal(0.005),
            Tolerance::Units(0.5),
            Tolerance::Units(3.0),
        ] {
            assert_eq!(t.to_string().parse::<Tolerance>().unwrap(), t, "{t}");
        }
        assert_eq!(Tolerance::Diagonal(0.07).to_string(), "7%");
        for p in [Partitions::Auto, Partitions::Fixed(16)] {
            assert_eq!(p.to_string().parse::<Partitions>().unwrap(), p);
        }
        for r in [
            Reprice::Exact,
            Reprice::Deferred { min_degree: 0 },
            Reprice::Deferred { min_degree: 64 },
        ] {
            assert_eq!(r.to_string().parse::<Reprice>().unwrap(), r);
        }
        for d in [Dedup::Exact, Dedup::Off, Dedup::Tolerance(0.25)] {
            assert_eq!(d.to_string().parse::<Dedup>().unwrap(), d);
        }
        for k in Kind::ALL {
            assert_eq!(k.to_string().parse::<Kind>().unwrap(), k);
        }
    }

    /// A wrong word says what was expected and what was given.
    #[test]
    fn wrong_words_are_named() {
        let msg = |e: Error| e.to_string();
        assert!(msg("1mm".parse::<Tolerance>().unwrap_err()).contains("got '1mm'"));
        assert!(msg("-1%".parse::<Tolerance>().unwrap_err()).contains("'-1%' is not positive"));
        assert!(msg("100%".parse::<Tolerance>().unwrap_err()).contains("percentage"));
        assert!(msg(Goal::parse_bytes("lots").unwrap_err()).contains("got 'lots'"));
        assert!(Goal::parse_bytes("-1G").is_err());
        for (s, b) in [
            ("1048576", 1 << 20),
            ("512M", 512 << 20),
            ("8g", 8 << 30),
            ("2KB", 2048),
            ("0", 0),
        ] {
            assert_eq!(Goal::parse_bytes(s).unwrap(), b, "{s}");
        }
        assert!(msg("some".parse::<Partitions>().unwrap_err()).contains("auto or a count"));
        assert!(msg("cone".parse::<Kind>().unwrap_err()).contains("unknown primitive kind 'cone'"));
    }
}
