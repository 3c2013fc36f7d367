//! The values exercises take and return: typed, encoded as text for the harness, compared
//! with a tolerance, and shown to the learner in short form.

use std::fmt::Write as _;

use crate::i18n::{Lang, Text};
use crate::text;

/// The type of one parameter of an exercise function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// `f32`.
    F32,
    /// `usize`.
    Usize,
    /// `&[f32]`.
    F32s,
    /// `&[f64]`.
    F64s,
    /// `&[bool]`.
    Bools,
    /// `&[usize]`.
    Usizes,
    /// `&[[f32; 2]]`.
    Pairs,
}

impl Kind {
    /// The Rust parameter type, as in the exercise's signature.
    #[must_use]
    pub fn rust_param(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::Usize => "usize",
            Self::F32s => "&[f32]",
            Self::F64s => "&[f64]",
            Self::Bools => "&[bool]",
            Self::Usizes => "&[usize]",
            Self::Pairs => "&[[f32; 2]]",
        }
    }

    /// The owned type the harness parses the parameter into.
    #[must_use]
    pub fn rust_owned(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::Usize => "usize",
            Self::F32s => "Vec<f32>",
            Self::F64s => "Vec<f64>",
            Self::Bools => "Vec<bool>",
            Self::Usizes => "Vec<usize>",
            Self::Pairs => "Vec<[f32; 2]>",
        }
    }

    /// Whether the function takes it by reference (a slice).
    #[must_use]
    pub fn is_slice(self) -> bool {
        !matches!(self, Self::F32 | Self::Usize)
    }
}

/// One argument of one test case.
#[derive(Debug, Clone, PartialEq)]
pub enum Arg {
    /// `f32`.
    F32(f32),
    /// `usize`.
    Usize(usize),
    /// `&[f32]`.
    F32s(Vec<f32>),
    /// `&[f64]`.
    F64s(Vec<f64>),
    /// `&[bool]`.
    Bools(Vec<bool>),
    /// `&[usize]`.
    Usizes(Vec<usize>),
    /// `&[[f32; 2]]`.
    Pairs(Vec<[f32; 2]>),
}

impl Arg {
    /// The text the harness reads: scalars as one token, slices as `len v1 v2 ...`.
    #[must_use]
    pub fn encode(&self) -> String {
        fn list<T>(out: &mut String, xs: &[T], f: impl Fn(&T) -> String) {
            let _ = write!(out, "{}", xs.len());
            for x in xs {
                out.push(' ');
                out.push_str(&f(x));
            }
        }
        let mut out = String::new();
        match self {
            Self::F32(x) => out = format!("{x:?}"),
            Self::Usize(x) => out = x.to_string(),
            Self::F32s(xs) => list(&mut out, xs, |x| format!("{x:?}")),
            Self::F64s(xs) => list(&mut out, xs, |x| format!("{x:?}")),
            Self::Bools(xs) => list(&mut out, xs, |x| u8::from(*x).to_string()),
            Self::Usizes(xs) => list(&mut out, xs, ToString::to_string),
            Self::Pairs(xs) => list(&mut out, xs, |p| format!("{:?} {:?}", p[0], p[1])),
        }
        out
    }

    /// A short rendering for reports (long slices are cut, with their length in words).
    #[must_use]
    pub fn show(&self) -> Text {
        match self {
            Self::F32(x) => Text::same(format!("{x:?}")),
            Self::Usize(x) => Text::same(x.to_string()),
            Self::F32s(xs) => show_list(xs, |x| format!("{x:?}")),
            Self::F64s(xs) => show_list(xs, |x| format!("{x:?}")),
            Self::Bools(xs) => show_list(xs, ToString::to_string),
            Self::Usizes(xs) => show_list(xs, ToString::to_string),
            Self::Pairs(xs) => show_list(xs, |p| format!("[{:?}, {:?}]", p[0], p[1])),
        }
    }
}

/// What an exercise function returns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutKind {
    /// `f32`.
    F32,
    /// `usize`.
    Usize,
    /// `Vec<f32>`.
    F32s,
    /// `Vec<f64>`.
    F64s,
    /// `Vec<bool>`.
    Bools,
    /// `(Vec<f32>, Vec<f32>)`.
    F32sPair,
}

impl OutKind {
    /// The Rust return type.
    #[must_use]
    pub fn rust(self) -> &'static str {
        match self {
            Self::F32 => "f32",
            Self::Usize => "usize",
            Self::F32s => "Vec<f32>",
            Self::F64s => "Vec<f64>",
            Self::Bools => "Vec<bool>",
            Self::F32sPair => "(Vec<f32>, Vec<f32>)",
        }
    }

    /// Parses the harness's `ok ...` payload.
    #[must_use]
    pub fn parse(self, text: &str) -> Option<Output> {
        fn list<'a, T: std::str::FromStr>(
            tokens: &mut impl Iterator<Item = &'a str>,
        ) -> Option<Vec<T>> {
            let n: usize = tokens.next()?.parse().ok()?;
            (0..n).map(|_| tokens.next()?.parse().ok()).collect()
        }
        let mut tokens = text.split_whitespace();
        let out = match self {
            Self::F32 => Output::F32(tokens.next()?.parse().ok()?),
            Self::Usize => Output::Usize(tokens.next()?.parse().ok()?),
            Self::F32s => Output::F32s(list(&mut tokens)?),
            Self::F64s => Output::F64s(list(&mut tokens)?),
            Self::Bools => {
                let flags: Vec<u8> = list(&mut tokens)?;
                Output::Bools(flags.into_iter().map(|f| f != 0).collect())
            }
            Self::F32sPair => {
                let first = list(&mut tokens)?;
                Output::F32sPair(first, list(&mut tokens)?)
            }
        };
        tokens.next().is_none().then_some(out)
    }
}

/// One result of an exercise function.
#[derive(Debug, Clone, PartialEq)]
pub enum Output {
    /// `f32`.
    F32(f32),
    /// `usize`.
    Usize(usize),
    /// `Vec<f32>`.
    F32s(Vec<f32>),
    /// `Vec<f64>`.
    F64s(Vec<f64>),
    /// `Vec<bool>`.
    Bools(Vec<bool>),
    /// `(Vec<f32>, Vec<f32>)`: two vectors, compared one after the other.
    F32sPair(Vec<f32>, Vec<f32>),
}

/// How close a result must be to the reference: `|got - want| <= abs + rel * |want|`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerance {
    /// Absolute part.
    pub abs: f64,
    /// Relative part.
    pub rel: f64,
}

impl Tolerance {
    fn close(self, got: f64, want: f64) -> bool {
        if want.is_nan() || got.is_nan() {
            return want.is_nan() && got.is_nan();
        }
        if want.is_infinite() || got.is_infinite() {
            return want == got;
        }
        (got - want).abs() <= self.abs + self.rel * want.abs()
    }
}

impl Output {
    /// `None` when `self` (got) is within `tol` of `want`; else where they first differ
    /// (empty for a single number: the values say it).
    #[must_use]
    pub fn differs(&self, want: &Self, tol: Tolerance) -> Option<Text> {
        let lengths = |want: usize, got: usize| {
            text!(
                "expected {want} values, got {got}",
                "应有 {want} 个值，实际 {got} 个"
            )
        };
        let at = |i: usize, want: String, got: String| {
            text!(
                "first difference at [{i}]: expected {want}, got {got}",
                "第一处不同在 [{i}]：应为 {want}，实际为 {got}"
            )
        };
        let list = |got: &[f64], want: &[f64]| {
            if got.len() != want.len() {
                return Some(lengths(want.len(), got.len()));
            }
            got.iter()
                .zip(want)
                .position(|(&g, &w)| !tol.close(g, w))
                .map(|i| at(i, format!("{:?}", want[i]), format!("{:?}", got[i])))
        };
        match (self, want) {
            (Self::F32(g), Self::F32(w)) => {
                (!tol.close(f64::from(*g), f64::from(*w))).then(Text::default)
            }
            (Self::Usize(g), Self::Usize(w)) => (g != w).then(Text::default),
            (Self::F32s(g), Self::F32s(w)) => list(&widen(g), &widen(w)),
            (Self::F64s(g), Self::F64s(w)) => list(g, w),
            (Self::Bools(g), Self::Bools(w)) => {
                if g.len() != w.len() {
                    return Some(lengths(w.len(), g.len()));
                }
                g.iter()
                    .zip(w)
                    .position(|(g, w)| g != w)
                    .map(|i| at(i, w[i].to_string(), g[i].to_string()))
            }
            (Self::F32sPair(g0, g1), Self::F32sPair(w0, w1)) => list(&widen(g0), &widen(w0))
                .map(|d| {
                    d.map(|lang, d| {
                        lang.pick(
                            format!("in the first vector, {d}"),
                            format!("第一个向量中，{d}"),
                        )
                    })
                })
                .or_else(|| {
                    list(&widen(g1), &widen(w1)).map(|d| {
                        d.map(|lang, d| {
                            lang.pick(
                                format!("in the second vector, {d}"),
                                format!("第二个向量中，{d}"),
                            )
                        })
                    })
                }),
            _ => Some(Text::new("a result of another type", "结果的类型不同")),
        }
    }

    /// Whether `self` is within `tol` of `other`.
    #[must_use]
    pub fn matches(&self, other: &Self, tol: Tolerance) -> bool {
        self.differs(other, tol).is_none()
    }

    /// A short rendering for reports.
    #[must_use]
    pub fn show(&self) -> Text {
        match self {
            Self::F32(x) => Text::same(format!("{x:?}")),
            Self::Usize(x) => Text::same(x.to_string()),
            Self::F32s(xs) => show_list(xs, |x| format!("{x:?}")),
            Self::F64s(xs) => show_list(xs, |x| format!("{x:?}")),
            Self::Bools(xs) => show_list(xs, ToString::to_string),
            Self::F32sPair(a, b) => {
                let (a, b) = (
                    show_list(a, |x| format!("{x:?}")),
                    show_list(b, |x| format!("{x:?}")),
                );
                Text::owned(
                    format!("({}, {})", a.in_lang(Lang::En), b.in_lang(Lang::En)),
                    format!("({}, {})", a.in_lang(Lang::Zh), b.in_lang(Lang::Zh)),
                )
            }
        }
    }
}

fn widen(xs: &[f32]) -> Vec<f64> {
    xs.iter().map(|&x| f64::from(x)).collect()
}

/// `[a, b, c]`, or the first eight values and a count for longer lists.
fn show_list<T>(xs: &[T], f: impl Fn(&T) -> String) -> Text {
    const SHOWN: usize = 8;
    let items = xs
        .iter()
        .take(SHOWN)
        .map(f)
        .collect::<Vec<String>>()
        .join(", ");
    let n = xs.len();
    if n > SHOWN {
        text!("[{items}, … ] ({n} values)", "[{items}, … ]（共 {n} 个值）")
    } else {
        Text::same(format!("[{items}]"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn encode_parse_round_trip() {
        let arg = Arg::F32s(vec![0.1, -2.5e-8, f32::NAN]);
        assert_eq!(arg.encode(), "3 0.1 -2.5e-8 NaN");
        let out = OutKind::F32s.parse("2 0.1 -inf");
        assert_eq!(out, Some(Output::F32s(vec![0.1, f32::NEG_INFINITY])));
        assert_eq!(OutKind::F32s.parse("3 0.1"), None);
        assert_eq!(OutKind::Usize.parse("1 2"), None);
        let pair = OutKind::F32sPair.parse("1 0.5 2 1 -1");
        assert_eq!(pair, Some(Output::F32sPair(vec![0.5], vec![1.0, -1.0])));
        assert_eq!(OutKind::F32sPair.parse("1 0.5"), None);
        let flags = OutKind::Bools.parse("3 1 0 1");
        assert_eq!(flags, Some(Output::Bools(vec![true, false, true])));
    }

    #[test]
    fn tolerance_and_differences() {
        let tol = Tolerance {
            abs: 1e-5,
            rel: 1e-5,
        };
        let want = Output::F32s(vec![1.0, 2.0]);
        assert!(Output::F32s(vec![1.000_001, 2.0]).matches(&want, tol));
        let diff = Output::F32s(vec![1.0, 2.1]).differs(&want, tol);
        assert!(diff.is_some_and(|d| d.in_lang(Lang::En).contains("[1]")));
        let diff = Output::F32s(vec![1.0]).differs(&want, tol);
        assert!(diff.is_some_and(|d| d.in_lang(Lang::En).contains("expected 2 values, got 1")));
        assert!(!Output::F32(f32::NAN).matches(&Output::F32(1.0), tol));
        let want = Output::F32sPair(vec![1.0], vec![2.0]);
        let diff = Output::F32sPair(vec![1.0], vec![2.5]).differs(&want, tol);
        assert!(diff.is_some_and(|d| {
            d.in_lang(Lang::En).starts_with("in the second vector")
                && d.in_lang(Lang::Zh)
                    .starts_with("第二个向量中，第一处不同在 [0]")
        }));
        let diff = Output::Bools(vec![true, true]).differs(&Output::Bools(vec![true, false]), tol);
        assert!(diff.is_some_and(|d| d.in_lang(Lang::En).contains("[1]")));
    }

    #[test]
    fn long_lists_are_cut() {
        let s = Arg::Usizes((0..20).collect()).show();
        assert!(s.in_lang(Lang::En).ends_with("… ] (20 values)"), "{s:?}");
        assert!(s.in_lang(Lang::Zh).ends_with("… ]（共 20 个值）"), "{s:?}");
        let short = Arg::Usizes(vec![1, 2]).show();
        assert_eq!(
            (short.in_lang(Lang::En), short.in_lang(Lang::Zh)),
            ("[1, 2]", "[1, 2]")
        );
    }
}
