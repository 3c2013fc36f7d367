//! Givens in a question's text: `{{name}}` shows this run's value of the measure `name`,
//! `{{name:.N}}` with `N` decimals.
//!
//! A number is shown as an integer when it is one, otherwise rounded to 4 decimals (or
//! `N`), and in scientific notation below 0.01 when no `N` is given, so that no digit the
//! learner needs is lost; trailing zeros are dropped. The loader checks every `{{…}}` ([`check`]); a value the run has not
//! computed yet shows as `…`.
//!
//! ```
//! use ppo_engine::lesson::Snapshot;
//! use ppo_engine::lesson::quiz::template::{fill, show};
//!
//! let snap = Snapshot { returns: vec![21.0, 14.0], ..Snapshot::default() };
//! assert_eq!(fill("first {{return_first}}, third {{return_third}}", &snap), "first 21, third …");
//! assert_eq!(show(0.93125, None), "0.9313");
//! assert_eq!(show(-0.004231, None), "-4.231e-3");
//! assert_eq!((show(0.98, None), show(0.001, None), show(0.5, Some(5))), ("0.98".into(), "1e-3".into(), "0.5".into()));
//! ```

use super::super::Snapshot;
use super::measure;

/// One `{{…}}` of a text: where it is and what it names.
struct Slot<'a> {
    /// Byte range of the whole `{{…}}`.
    start: usize,
    end: usize,
    /// What is between the braces.
    inner: &'a str,
    /// Whether the `}}` is there.
    closed: bool,
}

fn slots(text: &str) -> Vec<Slot<'_>> {
    let mut out = Vec::new();
    let mut from = 0;
    while let Some(open) = text[from..].find("{{").map(|i| from + i) {
        let Some(close) = text[open + 2..].find("}}").map(|i| open + 2 + i) else {
            out.push(Slot {
                start: open,
                end: text.len(),
                inner: &text[open + 2..],
                closed: false,
            });
            break;
        };
        out.push(Slot {
            start: open,
            end: close + 2,
            inner: &text[open + 2..close],
            closed: true,
        });
        from = close + 2;
    }
    out
}

/// `name` and its decimals from the inside of `{{…}}`, `None` if it is not of that form.
fn parse(inner: &str) -> Option<(&str, Option<usize>)> {
    let (name, decimals) = match inner.split_once(":.") {
        Some((name, n)) => (name, Some(n.parse().ok().filter(|&n| n <= 12)?)),
        None => (inner, None),
    };
    let ok = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_');
    ok.then_some((name, decimals))
}

/// The measures `text` shows, in order, with their decimals (a malformed `{{…}}` is left
/// out; [`check`] reports it).
#[must_use]
pub fn names(text: &str) -> Vec<(String, Option<usize>)> {
    slots(text)
        .iter()
        .filter(|s| s.closed)
        .filter_map(|s| parse(s.inner))
        .map(|(name, decimals)| (name.to_string(), decimals))
        .collect()
}

/// The measures `text` shows.
///
/// # Errors
/// What is wrong with the first `{{…}}` that is not `{{name}}` or `{{name:.N}}` with `name`
/// a measure, and what to write instead.
pub fn check(text: &str) -> Result<Vec<&'static str>, String> {
    slots(text)
        .iter()
        .map(|s| {
            let (name, _) = parse(s.inner).filter(|_| s.closed).ok_or_else(|| {
                format!(
                    "'{{{{{}}}}}' is not a given: write {{{{name}}}} or {{{{name:.N}}}}, with the \
                     measure's name and N decimals",
                    s.inner
                )
            })?;
            measure(name).map(|m| m.name).ok_or_else(|| {
                format!(
                    "{{{{{name}}}}} is not a measure; use one of: {}",
                    super::measures::all()
                        .map(|m| m.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })
        })
        .collect()
}

/// `text` with every `{{name}}` replaced by the run's value in `snapshot` ([`show`]), or `…`
/// where it has none yet.
#[must_use]
pub fn fill(text: &str, snapshot: &Snapshot) -> String {
    let mut out = String::with_capacity(text.len());
    let mut from = 0;
    for slot in slots(text) {
        out.push_str(&text[from..slot.start]);
        let value = parse(slot.inner)
            .filter(|_| slot.closed)
            .and_then(|(name, decimals)| {
                let v = (measure(name)?.value)(snapshot)?;
                Some(show(v, decimals))
            });
        out.push_str(value.as_deref().unwrap_or("…"));
        from = slot.end;
    }
    out.push_str(&text[from..]);
    out
}

/// A number as a given shows it: an integer as one; else rounded to `decimals` decimals,
/// or to 4, or below 0.01 to 4 significant digits in scientific notation; trailing zeros
/// dropped (0.98, not 0.9800; 1e-3, not 1.000e-3).
#[must_use]
pub fn show(x: f64, decimals: Option<usize>) -> String {
    if x.fract() == 0.0 && x.abs() < 1e9 {
        return format!("{x:.0}");
    }
    let trim = |digits: &str| -> String {
        if digits.contains('.') {
            digits
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string()
        } else {
            digits.to_string()
        }
    };
    match decimals {
        Some(n) => trim(&format!("{x:.n$}")),
        None if x.abs() < 0.01 => {
            let sci = format!("{x:.3e}");
            let (mantissa, exponent) = sci.split_once('e').unwrap_or((&sci, "0"));
            format!("{}e{exponent}", trim(mantissa))
        }
        None => trim(&format!("{x:.4}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn givens_are_checked_and_filled() {
        assert_eq!(
            check("δ = {{td_delta_last}}, γλ = {{gamma_lambda:.3}}"),
            Ok(vec!["td_delta_last", "gamma_lambda"])
        );
        for (bad, want) in [
            ("{{td_delta_lst}}", "not a measure"),
            ("{{td_delta_last", "not a given"),
            ("{{Td}}", "not a given"),
            ("{{gamma:.x}}", "not a given"),
        ] {
            let e = check(bad).err().unwrap_or_default();
            assert!(e.contains(want), "{bad}: {e}");
        }
        assert!(check("e^{z_i + 3}").is_ok(), "single braces are text");
        let snap = Snapshot {
            returns: vec![21.0, 14.0, 30.0],
            ..Snapshot::default()
        };
        assert_eq!(
            fill(
                "{{return_second}} then {{mean_return:.2}}; {{td_delta_last}}",
                &snap
            ),
            "14 then 21.67; …"
        );
        assert_eq!(show(1.5e-5, None), "1.5e-5");
        assert_eq!(show(-0.25, None), "-0.25");
        assert_eq!(show(12.00004, None), "12");
    }
}
