//! An error as the command line prints it, in the current language.
//!
//! `main` prints an [`anyhow::Error`]: the context the commands add (`reading FILE`,
//! `loading the agent`), then each cause below it. The contexts and the engine's
//! errors are already pairs; the causes from lower layers (the file system, JSON, TOML,
//! number parsing, safetensors, candle) speak English. In Chinese, [`render`] gives each of
//! those its Chinese sentence ([`ppo_engine::causes`]) and joins the chain with `：`; an
//! error of another kind keeps its own text. In English the chain is printed as anyhow
//! prints it (`{err:#}`).

use crate::i18n::Lang;

/// `err` and its causes as one line, in the current language.
#[must_use]
pub fn render(err: &anyhow::Error) -> String {
    match Lang::current() {
        Lang::En => format!("{err:#}"),
        Lang::Zh => {
            let mut parts: Vec<String> = Vec::new();
            for cause in err.chain() {
                let text = ppo_engine::causes::message(cause);
                // A wrapper whose own text already ends with its cause's (thiserror's
                // `"...: {0}"` with `#[from]`) would say it twice.
                if parts.last().is_some_and(|last| last.ends_with(&text)) {
                    continue;
                }
                parts.push(text);
            }
            parts.join("：")
        }
    }
}

/// The Chinese reason a value parser of the standard library gives (`'x' 无效：不是整数`),
/// for a usage error whose cause is a [`std::num::ParseIntError`] or
/// [`std::num::ParseFloatError`]; `None` for any other cause.
#[must_use]
pub fn parse_reason(cause: &(dyn std::error::Error + 'static)) -> Option<String> {
    let number = cause.downcast_ref::<std::num::ParseIntError>().is_some()
        || cause.downcast_ref::<std::num::ParseFloatError>().is_some();
    number.then(|| ppo_engine::causes::chinese(cause)).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;
    use anyhow::Context as _;

    fn chain(result: anyhow::Result<()>) -> String {
        let _zh = Lang::Zh.scoped();
        result.err().map(|e| render(&e)).unwrap_or_default()
    }

    /// Each kind of lower-layer cause reads in Chinese after the context a command adds.
    #[test]
    fn lower_layer_causes_read_in_chinese() {
        let io = std::fs::read_to_string("/no/such/file.json")
            .map(drop)
            .context("读取 /no/such/file.json");
        assert_eq!(
            chain(io),
            "读取 /no/such/file.json：找不到该文件或文件夹（系统错误码 2）"
        );
        let json = serde_json::from_str::<serde_json::Value>("{")
            .map(drop)
            .context("读取 a.json");
        assert_eq!(
            chain(json),
            "读取 a.json：不是有效的 JSON：在第 1 行第 1 列意外结束"
        );
        let toml = "a = ="
            .parse::<toml::Table>()
            .map(drop)
            .context("读取 a.toml");
        assert_eq!(
            chain(toml),
            "读取 a.toml：不是有效的 TOML：第 1 行第 5 列有错误"
        );
        let int = "x".parse::<u64>().map(drop).context("--seed");
        assert_eq!(chain(int), "--seed：不是整数");
        let float = "x".parse::<f64>().map(drop).context("--eps");
        assert_eq!(chain(float), "--eps：不是数");
        // An engine error is a pair already, and its candle cause is not said twice.
        let candle = crate::candle_core::Tensor::zeros(
            2,
            crate::candle_core::DType::F32,
            &crate::candle_core::Device::Cpu,
        )
        .and_then(|a| a.matmul(&a))
        .map(drop)
        .map_err(ppo_engine::ppo::PpoError::from)
        .context("训练中止");
        let text = chain(candle);
        assert!(
            text.starts_with("训练中止：张量运算失败（candle：`"),
            "{text}"
        );
        assert_eq!(text.matches("candle：").count(), 1, "{text}");
        // Another kind keeps its text.
        let other: anyhow::Result<()> = Err(anyhow::anyhow!("自己的话"));
        assert_eq!(chain(other), "自己的话");
    }

    /// In English the chain is what anyhow prints.
    #[test]
    fn english_is_anyhow_s_chain() {
        let _en = Lang::En.scoped();
        let Err(err) = std::fs::read_to_string("/no/such/file").context("reading /no/such/file")
        else {
            panic!("/no/such/file was read");
        };
        let text = render(&err);
        assert_eq!(text, format!("{err:#}"));
        assert!(
            text.starts_with("reading /no/such/file: No such file"),
            "{text}"
        );
    }

    #[test]
    fn std_parse_errors_give_a_chinese_reason() {
        let _zh = Lang::Zh.scoped();
        let int = "x".parse::<usize>().err();
        assert_eq!(
            int.as_ref().and_then(|e| parse_reason(e)),
            Some("不是整数".to_string())
        );
        let float = "x".parse::<f32>().err();
        assert_eq!(
            float.as_ref().and_then(|e| parse_reason(e)),
            Some("不是数".to_string())
        );
        assert_eq!(parse_reason(&std::fmt::Error), None);
    }
}
