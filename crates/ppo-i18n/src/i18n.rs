//! The course's two languages: English and Simplified Chinese (简体中文).
//!
//! One language is current for the whole process. It is chosen once at start
//! ([`Lang::detect`]: `--lang`, then `PPO_TUTOR_LANG`, then the locale) and may be switched
//! live (the app's `L` key). Everything a learner reads asks for it:
//!
//! - lesson prose comes from `lesson.md` or its twin `lesson.zh.md` (and likewise
//!   `quiz.zh.toml`, `exercise.zh.toml`, `exercise.zh.rs`): structure is shared, only the
//!   prose is per language (the course's `lesson::Course::embedded_in`);
//! - interface text is written at its call site in both languages, `t("quit", "退出")`, or
//!   with arguments, `tr!("{n} episodes", "{n} 个回合")`, so no string can exist in one
//!   language only.
//!
//! ```
//! use ppo_i18n::i18n::{Lang, t};
//!
//! assert_eq!(Lang::from_code("zh_CN.UTF-8"), Some(Lang::Zh));
//! assert_eq!(Lang::from_code("C"), None);
//! let _guard = Lang::Zh.scoped();
//! assert_eq!(t("quit", "退出"), "退出");
//! ```

use std::sync::atomic::{AtomicU8, Ordering};

/// A language the course is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, PartialOrd, Ord)]
pub enum Lang {
    /// English, the default.
    #[default]
    En,
    /// Simplified Chinese.
    Zh,
}

static CURRENT: AtomicU8 = AtomicU8::new(0);

thread_local! {
    /// This thread's own language while a [`LangGuard`] lives (tests render both languages
    /// side by side on parallel threads).
    static SCOPED: std::cell::Cell<Option<Lang>> = const { std::cell::Cell::new(None) };
}

impl Lang {
    /// Both languages, English first.
    pub const ALL: [Lang; 2] = [Lang::En, Lang::Zh];

    /// The language a code names: `en`, `zh`, and locale names such as `zh_CN.UTF-8`,
    /// `zh-Hans`, `en_US`; `None` for anything else (`C`, `POSIX`, `fr_FR`).
    #[must_use]
    pub fn from_code(code: &str) -> Option<Lang> {
        let c = code.trim().to_ascii_lowercase();
        if c.starts_with("zh") {
            Some(Lang::Zh)
        } else if c.starts_with("en") {
            Some(Lang::En)
        } else {
            None
        }
    }

    /// `en` or `zh`, as `--lang` and `PPO_TUTOR_LANG` take it.
    #[must_use]
    pub fn code(self) -> &'static str {
        match self {
            Lang::En => "en",
            Lang::Zh => "zh",
        }
    }

    /// The language's own name: `English`, `中文`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Lang::En => "English",
            Lang::Zh => "中文",
        }
    }

    /// The other language (the app's `L` key).
    #[must_use]
    pub fn other(self) -> Lang {
        match self {
            Lang::En => Lang::Zh,
            Lang::Zh => Lang::En,
        }
    }

    /// The language to use when no `--lang` is given: `PPO_TUTOR_LANG` (`en` or `zh`) if
    /// set, otherwise the locale (the first of `LC_ALL`, `LC_MESSAGES`, `LANG` that is set
    /// and not empty), Chinese when it starts with `zh`; English otherwise.
    ///
    /// # Errors
    /// `PPO_TUTOR_LANG` set to something other than `en` or `zh`, with the fix.
    pub fn detect() -> Result<Lang, LangError> {
        Self::detect_from(|key| std::env::var(key).ok())
    }

    /// [`Lang::detect`] with the environment given as a function (for tests).
    ///
    /// # Errors
    /// As [`Lang::detect`].
    pub fn detect_from(var: impl Fn(&str) -> Option<String>) -> Result<Lang, LangError> {
        if let Some(v) = var("PPO_TUTOR_LANG").filter(|v| !v.trim().is_empty()) {
            return match v.trim() {
                "en" | "EN" | "En" => Ok(Lang::En),
                "zh" | "ZH" | "Zh" => Ok(Lang::Zh),
                _ => Lang::from_code(&v).ok_or(LangError::Env(v)),
            };
        }
        let locale = ["LC_ALL", "LC_MESSAGES", "LANG"]
            .iter()
            .find_map(|k| var(k).filter(|v| !v.trim().is_empty()));
        Ok(match locale {
            Some(l) if l.trim().to_ascii_lowercase().starts_with("zh") => Lang::Zh,
            _ => Lang::En,
        })
    }

    /// The current language: this thread's [`Lang::scoped`] one if any, otherwise the
    /// process's ([`Lang::set_current`]), otherwise `PPO_TUTOR_LANG` when it names one,
    /// otherwise English.
    ///
    /// The variable is how a notebook kernel gets its language: evcxr links this crate
    /// into every cell anew, so a language set in one cell would be gone in the next, but
    /// the Chinese notebooks' first cell sets the kernel's variable (`:env`).
    #[must_use]
    pub fn current() -> Lang {
        if let Some(lang) = SCOPED.with(std::cell::Cell::get) {
            return lang;
        }
        match CURRENT.load(Ordering::Relaxed) {
            1 => Lang::En,
            2 => Lang::Zh,
            _ => std::env::var("PPO_TUTOR_LANG")
                .ok()
                .and_then(|v| Lang::from_code(&v))
                .unwrap_or_default(),
        }
    }

    /// Makes `self` the language of the whole process (every thread without a scoped one).
    pub fn set_current(self) {
        CURRENT.store(self as u8 + 1, Ordering::Relaxed);
    }

    /// Makes `self` this thread's language until the guard drops, then restores the
    /// previous one (for tests and one-off renders).
    #[must_use]
    pub fn scoped(self) -> LangGuard {
        let previous = SCOPED.with(|s| s.replace(Some(self)));
        LangGuard { previous }
    }

    /// `en` or `zh` of this language.
    #[must_use]
    pub fn pick<T>(self, en: T, zh: T) -> T {
        match self {
            Lang::En => en,
            Lang::Zh => zh,
        }
    }
}

impl std::fmt::Display for Lang {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.code())
    }
}

impl std::str::FromStr for Lang {
    type Err = LangError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim() {
            "en" => Ok(Lang::En),
            "zh" => Ok(Lang::Zh),
            other => Err(LangError::Flag(other.to_string())),
        }
    }
}

/// Restores the previous language when dropped ([`Lang::scoped`]).
#[derive(Debug)]
pub struct LangGuard {
    previous: Option<Lang>,
}

impl Drop for LangGuard {
    fn drop(&mut self) {
        SCOPED.with(|s| s.set(self.previous));
    }
}

/// A language that cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LangError {
    /// `--lang` names no language.
    #[error("--lang '{0}': expected en or zh / 应为 en 或 zh")]
    Flag(String),
    /// `PPO_TUTOR_LANG` names no language.
    #[error(
        "PPO_TUTOR_LANG='{0}': expected en or zh (unset it to follow the locale) / 应为 en 或 zh（不设置则跟随系统语言）"
    )]
    Env(String),
}

/// How many terminal columns `text` takes: a CJK character takes two.
#[must_use]
pub fn width(text: &str) -> usize {
    unicode_width::UnicodeWidthStr::width(text)
}

/// `text` followed by spaces up to `columns` terminal columns (`{:<n}` by display width;
/// unchanged if wider).
#[must_use]
pub fn pad_right(text: &str, columns: usize) -> String {
    format!("{text}{}", " ".repeat(columns.saturating_sub(width(text))))
}

/// `text` after spaces up to `columns` terminal columns (`{:>n}` by display width;
/// unchanged if wider).
#[must_use]
pub fn pad_left(text: &str, columns: usize) -> String {
    format!("{}{text}", " ".repeat(columns.saturating_sub(width(text))))
}

/// Interface text kept in both languages until it is shown: a grader's check name, the
/// reason a check did not run, a quiz measure's description. Written where the thing is
/// defined, as a pair (`Text::new("a single row", "只有一行")`, or [`text!`](crate::text!) with
/// arguments), and resolved when rendered ([`Text::get`], `Display`), so a report made
/// in one language reads in the other after the app's `L` key, and no string is ever
/// looked up by its English.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct Text {
    en: std::borrow::Cow<'static, str>,
    zh: std::borrow::Cow<'static, str>,
}

impl Text {
    /// A fixed pair.
    #[must_use]
    pub const fn new(en: &'static str, zh: &'static str) -> Self {
        Self {
            en: std::borrow::Cow::Borrowed(en),
            zh: std::borrow::Cow::Borrowed(zh),
        }
    }

    /// A pair made at run time (what [`text!`](crate::text!) builds).
    #[must_use]
    pub fn owned(en: String, zh: String) -> Self {
        Self {
            en: std::borrow::Cow::Owned(en),
            zh: std::borrow::Cow::Owned(zh),
        }
    }

    /// `render` run once in each language (its `t`/`tr!` and `Display`s answer in that
    /// language): an error's message kept for later, say.
    #[must_use]
    pub fn in_each(render: impl Fn() -> String) -> Self {
        let en = {
            let _en = Lang::En.scoped();
            render()
        };
        let _zh = Lang::Zh.scoped();
        Self::owned(en, render())
    }

    /// The same text in both languages: numbers, values, code, a learner's own message.
    #[must_use]
    pub fn same(text: impl Into<String>) -> Self {
        let text = text.into();
        Self::owned(text.clone(), text)
    }

    /// The text in the current language.
    #[must_use]
    pub fn get(&self) -> &str {
        self.in_lang(Lang::current())
    }

    /// The text in `lang`.
    #[must_use]
    pub fn in_lang(&self, lang: Lang) -> &str {
        lang.pick(&self.en, &self.zh)
    }

    /// Whether both languages are empty.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.en.is_empty() && self.zh.is_empty()
    }

    /// Each language's text passed through `f` (a prefix, a wrapper), in that language.
    #[must_use]
    pub fn map(&self, f: impl Fn(Lang, &str) -> String) -> Self {
        Self::owned(f(Lang::En, &self.en), f(Lang::Zh, &self.zh))
    }
}

impl std::fmt::Display for Text {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.get())
    }
}

/// A [`Text`] formatted in both languages now, shown later in the current one:
/// `text!("{n} seeded random inputs", "{n} 组由随机种子生成的输入")`.
#[macro_export]
macro_rules! text {
    ($en:literal, $zh:literal $(,)?) => {
        $crate::i18n::Text::owned(format!($en), format!($zh))
    };
    ($en:literal, $zh:literal, $($args:tt)+) => {
        $crate::i18n::Text::owned(format!($en, $($args)+), format!($zh, $($args)+))
    };
}

/// Names a Chinese screen may show in Latin letters besides code spans, flags, file
/// names, formulas and all-caps abbreviations (reviewed: program, library, algorithm and
/// environment names, units, the language codes). The tests that look for English on
/// Chinese screens ([`english_words`]) allow these and nothing else by default.
pub const ALLOWED_WORDS: &[&str] = &[
    // Programs, libraries and file formats.
    "ppo-tutor",
    "ppo-engine",
    "ppo-rl",
    "Gymnasium",
    "PyTorch",
    "Python",
    "numpy",
    "CleanRL",
    "candle",
    "safetensors",
    "evcxr",
    "cargo",
    "rustc",
    "Rust",
    "markdown",
    "Spinning",
    "Up",
    // Environments, algorithms and classes, by their names.
    "CartPole",
    "Pendulum",
    "PPOContinuous",
    "Actor-Critic",
    "Adam",
    "Categorical",
    "Normal",
    "bang-bang",
    // Cited authors (Williams 1992, Kakade and Langford 2002, Schulman) and Kaiming He's
    // initialisation.
    "Williams",
    "Kakade",
    "Langford",
    "Schulman",
    "Kaiming",
    // Mathematical functions and values, written as in the formulas.
    "ln",
    "log",
    "exp",
    "sin",
    "cos",
    "min",
    "max",
    "argmax",
    "softmax",
    "log-softmax",
    "sigmoid",
    "ReLU",
    "logit",
    "logits",
    "NaN",
    // Units.
    "N·m",
    "rad",
    "kg",
    "fps",
    // The language codes.
    "en",
    "zh",
];

/// Whether `c` is a CJK character or a full-width punctuation mark (it ends a word).
#[must_use]
pub fn is_cjk(c: char) -> bool {
    // (U+3000 to U+303F, the ideographic punctuation, are in the first range.)
    matches!(c, '\u{2e80}'..='\u{9fff}' | '\u{ff00}'..='\u{ffef}')
}

/// The English words in `text`: Latin words outside `code spans` and formulas (a stretch
/// between Chinese characters with an operator `= * + < > ≤ ≥ Σ √ −` in it), flags (`--seed`),
/// file names and identifiers (anything with `. _ / = ( [ · ^ \` or a digit in it),
/// all-caps names (`PPO`, `GAE`), single letters (symbols: `u`, `x`), [`ALLOWED_WORDS`] and `allowed` (a test's own reviewed
/// names). On a Chinese screen the list should be empty.
///
/// ```
/// use std::collections::BTreeSet;
/// use ppo_i18n::i18n::english_words;
///
/// let none = BTreeSet::new();
/// assert!(english_words("用 `torch.clamp` 截断比率（PPO，--eps 0.2）", &none).is_empty());
/// assert!(english_words("从后往前：adv = gamma * lmbda * adv + δ，再取 ln 2", &none).is_empty());
/// assert_eq!(english_words("第 3 次 Iteration：done", &none), ["Iteration", "done"]);
/// ```
#[must_use]
pub fn english_words(text: &str, allowed: &std::collections::BTreeSet<String>) -> Vec<String> {
    // Drop code spans.
    let mut plain = String::new();
    for (i, part) in text.split('`').enumerate() {
        if i % 2 == 0 {
            plain.push_str(part);
        }
        plain.push(' ');
    }
    // Drop formulas: a stretch between Chinese characters that holds an operator
    // (`adv = gamma * lmbda * adv + δ`, `k < n`, `Σ_a p·(ln p − ln q)`) is code or maths.
    let mut prose = String::new();
    for (i, run) in plain.split(is_cjk).enumerate() {
        if i > 0 {
            prose.push(' ');
        }
        if !run.contains(|c: char| "=*+<>≤≥Σ∑√−".contains(c)) {
            prose.push_str(run);
        }
    }
    let mut found = Vec::new();
    for token in prose.split(char::is_whitespace) {
        let word = token
            .trim_start_matches(|c: char| "([{<'\"".contains(c))
            .trim_end_matches(|c: char| ")]}>,;:'\".!?|-…".contains(c));
        let code_like = word.starts_with('-')
            || word.contains(|c: char| "._/=([&|·^²ˣ\\".contains(c) || c.is_ascii_digit());
        let caps = word
            .chars()
            .all(|c| c.is_ascii_uppercase() || c == '_' || !c.is_ascii_alphabetic());
        // A single letter is a symbol (`u`, `x`, `s_t`'s `s`), not a word.
        let symbol = word.chars().count() == 1;
        if word.chars().any(|c| c.is_ascii_alphabetic())
            && !symbol
            && !code_like
            && !caps
            && !ALLOWED_WORDS.contains(&word)
            && !allowed.contains(word)
        {
            found.push(word.to_string());
        }
    }
    found
}

/// `en` or `zh`, whichever is the current language.
#[must_use]
pub fn t(en: &'static str, zh: &'static str) -> &'static str {
    Lang::current().pick(en, zh)
}

/// `format!` in the current language: `tr!("{n} episodes", "{n} 个回合")`, both strings
/// with the same arguments (inline names or trailing arguments, as in `format!`).
#[macro_export]
macro_rules! tr {
    ($en:literal, $zh:literal $(,)?) => {
        match $crate::i18n::Lang::current() {
            $crate::i18n::Lang::En => format!($en),
            $crate::i18n::Lang::Zh => format!($zh),
        }
    };
    ($en:literal, $zh:literal, $($args:tt)+) => {
        match $crate::i18n::Lang::current() {
            $crate::i18n::Lang::En => format!($en, $($args)+),
            $crate::i18n::Lang::Zh => format!($zh, $($args)+),
        }
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    fn env(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let owned: Vec<(String, String)> = pairs
            .iter()
            .map(|(k, v)| ((*k).to_string(), (*v).to_string()))
            .collect();
        move |k| {
            owned
                .iter()
                .find(|(key, _)| key == k)
                .map(|(_, v)| v.clone())
        }
    }

    #[test]
    fn the_variable_beats_the_locale_and_the_locale_beats_the_default() {
        assert_eq!(Lang::detect_from(env(&[])), Ok(Lang::En));
        assert_eq!(
            Lang::detect_from(env(&[("LANG", "zh_CN.UTF-8")])),
            Ok(Lang::Zh)
        );
        assert_eq!(
            Lang::detect_from(env(&[("LANG", "fr_FR.UTF-8")])),
            Ok(Lang::En)
        );
        // LC_ALL overrides LANG, as in every POSIX program.
        assert_eq!(
            Lang::detect_from(env(&[("LC_ALL", "en_US.UTF-8"), ("LANG", "zh_CN.UTF-8")])),
            Ok(Lang::En)
        );
        assert_eq!(
            Lang::detect_from(env(&[("LC_MESSAGES", "zh_TW"), ("LANG", "C")])),
            Ok(Lang::Zh)
        );
        assert_eq!(
            Lang::detect_from(env(&[("PPO_TUTOR_LANG", "en"), ("LC_ALL", "zh_CN.UTF-8")])),
            Ok(Lang::En)
        );
        assert_eq!(
            Lang::detect_from(env(&[("PPO_TUTOR_LANG", "zh"), ("LANG", "en_US")])),
            Ok(Lang::Zh)
        );
        assert_eq!(
            Lang::detect_from(env(&[("PPO_TUTOR_LANG", "de")])),
            Err(LangError::Env("de".into()))
        );
        // Empty counts as unset.
        assert_eq!(
            Lang::detect_from(env(&[("PPO_TUTOR_LANG", ""), ("LANG", "zh_CN")])),
            Ok(Lang::Zh)
        );
    }

    #[test]
    fn tr_formats_in_the_thread_s_language() {
        let n = 3;
        let _zh = Lang::Zh.scoped();
        assert_eq!(crate::tr!("{n} episodes", "{n} 个回合"), "3 个回合");
        assert_eq!(crate::tr!("{} of {w}", "{} / {w}", 1, w = 2), "1 / 2");
        {
            let _en = Lang::En.scoped();
            assert_eq!(crate::tr!("{} of {w}", "{} / {w}", 1, w = 2), "1 of 2");
        }
        assert_eq!(t("quit", "退出"), "退出");
    }

    #[test]
    fn a_text_is_shown_in_the_language_current_when_it_is_shown() {
        let n = 15;
        let made = {
            let _en = Lang::En.scoped();
            crate::text!("{n} seeded random inputs", "{n} 组由随机种子生成的输入")
        };
        let _zh = Lang::Zh.scoped();
        assert_eq!(made.get(), "15 组由随机种子生成的输入");
        assert_eq!(made.in_lang(Lang::En), "15 seeded random inputs");
        assert_eq!(
            Text::new("a single row", "只有一行").to_string(),
            "只有一行"
        );
        let wrapped = made.map(|lang, s| lang.pick(format!("({s})"), format!("（{s}）")));
        assert_eq!(wrapped.get(), "（15 组由随机种子生成的输入）");
        assert!(Text::default().is_empty() && !Text::same("1.5").is_empty());
        let both = Text::in_each(|| t("quit", "退出").to_string());
        assert_eq!((both.in_lang(Lang::En), both.get()), ("quit", "退出"));
    }

    #[test]
    fn padding_counts_a_chinese_character_as_two_columns() {
        assert_eq!(width("回合 500"), 8);
        assert_eq!(pad_right("回合", 6), "回合  ");
        assert_eq!(pad_left("回合", 6), "  回合");
        assert_eq!(pad_right("episode", 3), "episode");
    }

    #[test]
    fn the_flag_takes_exactly_en_or_zh() {
        assert_eq!("zh".parse::<Lang>(), Ok(Lang::Zh));
        assert_eq!("en".parse::<Lang>(), Ok(Lang::En));
        assert!("chinese".parse::<Lang>().is_err());
    }
}
