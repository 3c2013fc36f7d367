//! A clap usage error as the command line prints it: help and version as clap does, and
//! every other error as one line in the current language (built from the error's kind and
//! context in Chinese, since what clap renders is English), exit code 2.

use std::process::ExitCode;

use super::{EXIT_USAGE, error_prefix, errors, see_help};
use crate::i18n::Lang;

/// Prints help and version as clap does; usage errors as one line, exit code 2.
pub(super) fn report_clap_error(err: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match err.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = err.print();
            ExitCode::SUCCESS
        }
        _ => {
            let line = match Lang::current() {
                Lang::En => usage_error_line(&err.render().to_string()),
                Lang::Zh => usage_error_zh(err),
            };
            eprintln!("{line}{}", see_help());
            ExitCode::from(EXIT_USAGE)
        }
    }
}

/// A clap usage error as one Chinese line, built from its kind and context (what clap
/// renders is English): `错误：` and one sentence per kind, quoting the argument and value.
pub(super) fn usage_error_zh(err: &clap::Error) -> String {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    let get = |kind: ContextKind| -> Option<String> {
        match err.get(kind)? {
            ContextValue::String(s) => Some(s.clone()),
            ContextValue::Strings(v) => Some(v.join("、")),
            ContextValue::StyledStr(s) => Some(s.to_string()),
            ContextValue::StyledStrs(v) => Some(
                v.iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("、"),
            ),
            ContextValue::Number(n) => Some(n.to_string()),
            ContextValue::Bool(b) => Some(b.to_string()),
            ContextValue::None => None,
            _ => None,
        }
    };
    let quoted = |list: String| -> String {
        list.split('、')
            .map(|item| format!("'{item}'"))
            .collect::<Vec<_>>()
            .join("、")
    };
    let arg = get(ContextKind::InvalidArg).unwrap_or_default();
    let value = get(ContextKind::InvalidValue);
    let suggest = |kind: ContextKind| -> String {
        get(kind)
            .map(|s| format!("；你是不是想用 {}？", quoted(s)))
            .unwrap_or_default()
    };
    let sentence = match err.kind() {
        // A flag clap does not know, or a value no argument takes.
        ErrorKind::UnknownArgument if arg.starts_with('-') => {
            format!("不认识的参数 '{arg}'{}", suggest(ContextKind::SuggestedArg))
        }
        ErrorKind::UnknownArgument => format!("多余的参数 '{arg}'"),
        ErrorKind::InvalidSubcommand => format!(
            "不认识的子命令 '{}'{}",
            get(ContextKind::InvalidSubcommand).unwrap_or_default(),
            suggest(ContextKind::SuggestedSubcommand)
        ),
        ErrorKind::InvalidValue => match value.as_deref() {
            None | Some("") => format!("'{arg}' 需要一个值，但没有给出"),
            Some(value) => {
                let valid = get(ContextKind::ValidValue)
                    .map(|v| format!("；可选值：{}", quoted(v)))
                    .unwrap_or_default();
                format!(
                    "'{value}' 不是 '{arg}' 的有效值{valid}{}",
                    suggest(ContextKind::SuggestedValue)
                )
            }
        },
        ErrorKind::ValueValidation => {
            let value = value.unwrap_or_default();
            // Our own parsers explain in Chinese (or in both languages, then the Chinese
            // half); a number parser of the standard library in English, which
            // `errors::parse_reason` says in Chinese; any other reason in English is left out.
            let source = std::error::Error::source(err);
            let why = source
                .and_then(errors::parse_reason)
                .or_else(|| {
                    source
                        .map(ToString::to_string)
                        .map(|m| match m.split_once(" / ") {
                            Some((_, zh)) if has_chinese(zh) => zh.to_string(),
                            _ => m,
                        })
                        .filter(|m| has_chinese(m))
                })
                .map(|m| format!("：{m}"))
                .unwrap_or_default();
            format!("'{arg}' 的值 '{value}' 无效{why}")
        }
        ErrorKind::MissingRequiredArgument => format!("缺少必需的参数：{}", quoted(arg)),
        ErrorKind::MissingSubcommand => {
            let valid = get(ContextKind::ValidSubcommand)
                .map(|v| format!("：{}", quoted(v)))
                .unwrap_or_default();
            format!(
                "'{}' 需要一个子命令{valid}",
                get(ContextKind::InvalidSubcommand).unwrap_or_default()
            )
        }
        ErrorKind::ArgumentConflict => match get(ContextKind::PriorArg) {
            Some(prior) if prior != arg => {
                format!("'{arg}' 不能与 {} 同时使用", quoted(prior))
            }
            _ => format!("'{arg}' 不能重复使用"),
        },
        ErrorKind::TooManyValues => format!(
            "'{arg}' 不需要更多的值，却多给了 '{}'",
            value.unwrap_or_default()
        ),
        ErrorKind::TooFewValues => format!(
            "'{arg}' 至少需要 {} 个值，只给了 {} 个",
            get(ContextKind::MinValues).unwrap_or_default(),
            get(ContextKind::ActualNumValues).unwrap_or_default()
        ),
        ErrorKind::WrongNumberOfValues => format!(
            "'{arg}' 需要 {} 个值，给了 {} 个",
            get(ContextKind::ExpectedNumValues).unwrap_or_default(),
            get(ContextKind::ActualNumValues).unwrap_or_default()
        ),
        ErrorKind::NoEquals => format!("'{arg}' 的值要用等号连着写，如 '{arg}=…'"),
        ErrorKind::InvalidUtf8 => "参数不是有效的 UTF-8 文本".to_string(),
        _ if arg.is_empty() => "命令行参数有误".to_string(),
        _ => format!("命令行参数 '{arg}' 有误"),
    };
    format!("{}{sentence}", error_prefix())
}

/// Whether `text` holds a Chinese character.
fn has_chinese(text: &str) -> bool {
    text.chars().any(|c| ('\u{4e00}'..='\u{9fff}').contains(&c))
}

/// A clap error as one line: its first line, and for a missing argument the arguments it
/// lists on the lines below (`error: the following required arguments were not provided:
/// <EXERCISE>`), which the first line alone would leave out.
fn usage_error_line(rendered: &str) -> String {
    let mut lines = rendered.lines().skip_while(|l| l.trim().is_empty());
    let Some(first) = lines.next() else {
        return "error: invalid arguments".to_string();
    };
    let listed: Vec<&str> = lines
        .take_while(|l| l.starts_with(' ') && !l.trim().is_empty())
        .map(str::trim)
        .collect();
    if listed.is_empty() {
        first.to_string()
    } else {
        format!("{first} {}", listed.join(", "))
    }
}
