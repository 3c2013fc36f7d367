//! Errors of the layers below the course (the file system, JSON, TOML, number parsing,
//! safetensors, candle) in the current language.
//!
//! Their `Display` is English, and a Chinese screen printed it as it was (`No such file or
//! directory (os error 2)`, `expected value at line 1 column 1`). [`message`] gives one
//! sentence per kind instead: in English the error's own text, unchanged; in Chinese a
//! sentence built from the kind and what the error carries (the line and column of a JSON or
//! TOML error, the OS error code). An error of another kind keeps its own text.
//!
//! ```
//! use ppo_i18n::causes::message;
//! use ppo_i18n::i18n::Lang;
//!
//! let err = std::io::Error::from(std::io::ErrorKind::NotFound);
//! let _zh = Lang::Zh.scoped();
//! assert_eq!(message(&err), "找不到该文件或文件夹");
//! ```

use std::error::Error;
use std::io::ErrorKind;
use std::num::{IntErrorKind, ParseFloatError, ParseIntError};

use crate::i18n::Lang;

/// `err`'s message in the current language: in English its `Display`; in Chinese the
/// sentence of its kind ([`chinese`]), or its `Display` for a kind this module does not know.
#[must_use]
pub fn message(err: &(dyn Error + 'static)) -> String {
    match Lang::current() {
        Lang::En => err.to_string(),
        Lang::Zh => chinese(err).unwrap_or_else(|| err.to_string()),
    }
}

/// The Chinese sentence for a lower-layer error: [`std::io::Error`] by its kind,
/// [`serde_json::Error`] by its category with the line and column, a TOML error with its
/// line and column, [`ParseIntError`] and [`ParseFloatError`], safetensors' and candle's
/// errors. `None` for any other error.
#[must_use]
pub fn chinese(err: &(dyn Error + 'static)) -> Option<String> {
    if let Some(e) = err.downcast_ref::<std::io::Error>() {
        return Some(io(e));
    }
    if let Some(e) = err.downcast_ref::<serde_json::Error>() {
        return Some(json(e));
    }
    if let Some(e) = err.downcast_ref::<toml::de::Error>() {
        return Some(toml_error(&e.to_string()));
    }
    if let Some(e) = err.downcast_ref::<ParseIntError>() {
        return Some(integer(e).to_string());
    }
    if err.downcast_ref::<ParseFloatError>().is_some() {
        return Some("不是数".to_string());
    }
    if let Some(e) = err.downcast_ref::<safetensors::SafeTensorError>() {
        return Some(safetensors_error(e));
    }
    if let Some(e) = err.downcast_ref::<candle_core::Error>() {
        return Some(candle(e));
    }
    None
}

/// An I/O error by its kind, with the OS error code when there is one.
fn io(e: &std::io::Error) -> String {
    let what = match e.kind() {
        ErrorKind::NotFound => "找不到该文件或文件夹",
        ErrorKind::PermissionDenied => "没有访问权限",
        ErrorKind::AlreadyExists => "已经存在",
        ErrorKind::IsADirectory => "这是一个文件夹，不是文件",
        ErrorKind::NotADirectory => "路径中有一项不是文件夹",
        ErrorKind::DirectoryNotEmpty => "文件夹不是空的",
        ErrorKind::InvalidData if e.to_string().contains("UTF-8") => "内容不是有效的 UTF-8 文本",
        ErrorKind::InvalidData => "数据无效",
        ErrorKind::InvalidInput => "参数无效",
        ErrorKind::UnexpectedEof => "文件意外结束",
        ErrorKind::StorageFull => "磁盘已满",
        ErrorKind::ReadOnlyFilesystem => "文件系统是只读的",
        ErrorKind::FileTooLarge => "文件太大",
        ErrorKind::BrokenPipe => "管道的另一端已关闭",
        ErrorKind::TimedOut => "操作超时",
        ErrorKind::Interrupted => "操作被中断",
        ErrorKind::OutOfMemory => "内存不足",
        ErrorKind::Unsupported => "本系统不支持此操作",
        _ => "输入输出出错",
    };
    match e.raw_os_error() {
        Some(code) => format!("{what}（系统错误码 {code}）"),
        None => what.to_string(),
    }
}

/// A JSON error by its category, with where it happened.
fn json(e: &serde_json::Error) -> String {
    use serde_json::error::Category;
    let (line, column) = (e.line(), e.column());
    match e.classify() {
        Category::Syntax => format!("不是有效的 JSON：第 {line} 行第 {column} 列有语法错误"),
        Category::Eof => format!("不是有效的 JSON：在第 {line} 行第 {column} 列意外结束"),
        Category::Data => format!("JSON 的内容不符合要求：第 {line} 行第 {column} 列"),
        Category::Io => "读取 JSON 时出错".to_string(),
    }
}

/// A TOML error from its text (`TOML parse error at line 3, column 7 ...`): the line and
/// column when the text gives them.
fn toml_error(text: &str) -> String {
    let number_after = |word: &str| -> Option<usize> {
        let at = text.find(word)? + word.len();
        let digits: String = text[at..]
            .chars()
            .take_while(char::is_ascii_digit)
            .collect();
        digits.parse().ok()
    };
    match (number_after("line "), number_after("column ")) {
        (Some(line), Some(column)) => {
            format!("不是有效的 TOML：第 {line} 行第 {column} 列有错误")
        }
        _ => "不是有效的 TOML".to_string(),
    }
}

/// Why a text is not the integer asked for.
fn integer(e: &ParseIntError) -> &'static str {
    match e.kind() {
        IntErrorKind::Empty => "是空的，应为整数",
        IntErrorKind::PosOverflow => "整数太大，超出了允许的范围",
        IntErrorKind::NegOverflow => "整数太小，超出了允许的范围",
        IntErrorKind::Zero => "不能为 0",
        _ => "不是整数",
    }
}

/// A safetensors error: a file that is not safetensors, or its tensors do not fit.
fn safetensors_error(e: &safetensors::SafeTensorError) -> String {
    use safetensors::SafeTensorError as E;
    match e {
        E::IoError(io_err) => io(io_err),
        E::JsonError(json_err) | E::InvalidHeaderDeserialization(json_err) => {
            format!("文件头无效，这不是 safetensors 文件（{}）", json(json_err))
        }
        E::InvalidHeader(_) | E::HeaderTooLarge | E::HeaderTooSmall | E::InvalidHeaderLength => {
            "文件头无效，这不是 safetensors 文件".to_string()
        }
        E::TensorNotFound(name) => format!("文件中没有张量 '{name}'"),
        E::InvalidOffset(name) => format!("张量 '{name}' 的偏移量无效"),
        _ => "张量数据与文件头声明的形状或类型不符".to_string(),
    }
}

/// A candle error: its safetensors or I/O cause in Chinese; otherwise candle's own words
/// quoted as code after a Chinese sentence (they name shapes, dtypes and operations).
fn candle(e: &candle_core::Error) -> String {
    match e {
        candle_core::Error::SafeTensor(inner) => safetensors_error(inner),
        candle_core::Error::Io(inner) => io(inner),
        candle_core::Error::WithBacktrace { inner, .. }
        | candle_core::Error::WithPath { inner, .. } => candle(inner),
        other => {
            let said = other.to_string().replace('`', "'");
            format!("张量运算失败（candle：`{said}`）")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zh(err: &(dyn Error + 'static)) -> String {
        let _zh = Lang::Zh.scoped();
        message(err)
    }

    #[test]
    fn io_errors_by_kind_with_the_os_code() {
        assert_eq!(
            zh(&std::io::Error::from_raw_os_error(2)),
            "找不到该文件或文件夹（系统错误码 2）"
        );
        assert_eq!(
            zh(&std::io::Error::from(ErrorKind::PermissionDenied)),
            "没有访问权限"
        );
        let utf8 = std::fs::read_to_string("/proc/self/exe")
            .err()
            .map_or_else(String::new, |e| zh(&e));
        if !utf8.is_empty() {
            assert_eq!(utf8, "内容不是有效的 UTF-8 文本");
        }
        let _en = Lang::En.scoped();
        let e = std::io::Error::from_raw_os_error(2);
        assert_eq!(
            message(&e),
            e.to_string(),
            "English is the error's own text"
        );
    }

    #[test]
    fn json_errors_by_category_with_line_and_column() {
        let cases = [
            ("{\n  x", "第 2 行第 3 列有语法错误"),
            ("{", "在第 1 行第 1 列意外结束"),
            ("", "在第 1 行第 0 列意外结束"),
        ];
        for (text, says) in cases {
            let e = serde_json::from_str::<serde_json::Value>(text)
                .err()
                .map(|e| zh(&e))
                .unwrap_or_default();
            assert!(e.contains(says), "{text:?}: {e}");
        }
        let data = serde_json::from_str::<Vec<u8>>("[1, -3]")
            .err()
            .map(|e| zh(&e))
            .unwrap_or_default();
        assert_eq!(data, "JSON 的内容不符合要求：第 1 行第 6 列");
    }

    #[test]
    fn toml_errors_with_line_and_column() {
        let e = "a = 1\nb = =\n"
            .parse::<toml::Table>()
            .err()
            .map(|e| zh(&e))
            .unwrap_or_default();
        assert_eq!(e, "不是有效的 TOML：第 2 行第 5 列有错误");
        assert_eq!(toml_error("something else"), "不是有效的 TOML");
    }

    #[test]
    fn number_parse_errors_say_what_was_expected() {
        let int = |s: &str| s.parse::<u8>().err().map(|e| zh(&e)).unwrap_or_default();
        assert_eq!(int("x"), "不是整数");
        assert_eq!(int(""), "是空的，应为整数");
        assert_eq!(int("300"), "整数太大，超出了允许的范围");
        let small = "-300"
            .parse::<i8>()
            .err()
            .map(|e| zh(&e))
            .unwrap_or_default();
        assert_eq!(small, "整数太小，超出了允许的范围");
        let float = "x".parse::<f64>().err().map(|e| zh(&e)).unwrap_or_default();
        assert_eq!(float, "不是数");
    }

    #[test]
    fn safetensors_and_candle_errors() {
        let not_a_file = safetensors::SafeTensors::read_metadata(b"not a checkpoint")
            .err()
            .map(|e| zh(&e))
            .unwrap_or_default();
        assert_eq!(not_a_file, "文件头无效，这不是 safetensors 文件");
        let candle_err = candle_core::safetensors::load_buffer(b"tiny", &candle_core::Device::Cpu)
            .err()
            .map(|e| zh(&e))
            .unwrap_or_default();
        assert_eq!(candle_err, "文件头无效，这不是 safetensors 文件");
        let shapes =
            candle_core::Tensor::zeros(2, candle_core::DType::F32, &candle_core::Device::Cpu)
                .and_then(|a| a.matmul(&a))
                .err()
                .map(|e| zh(&e))
                .unwrap_or_default();
        assert!(shapes.starts_with("张量运算失败（candle：`"), "{shapes}");
    }

    #[test]
    fn other_errors_keep_their_text() {
        let e = std::fmt::Error;
        assert_eq!(zh(&e), e.to_string());
    }
}
