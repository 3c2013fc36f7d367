//! The command line's help and usage errors in Chinese: every subcommand's
//! help, whichever way Chinese is chosen, and one Chinese line for a usage error.

use crate::common::with_env;

type TestResult = Result<(), Box<dyn std::error::Error>>;

/// What clap prints in English and must not be left on a Chinese screen.
const CLAP_ENGLISH: &[&str] = &[
    "Usage:",
    "Options:",
    "Arguments:",
    "Commands:",
    "Print help",
    "Print version",
    "Possible values",
    "[default:",
    "[OPTIONS]",
    "Examples:",
];

/// Every subcommand's help (and the program's, and `dev`'s) is Chinese with `--lang zh`,
/// `PPO_TUTOR_LANG=zh` and a Chinese locale, and exits 0.
#[test]
fn every_help_is_chinese_however_chinese_is_chosen() -> TestResult {
    let commands: [&[&str]; 16] = [
        &[],
        &["cartpole"],
        &["pendulum"],
        &["lessons"],
        &["show"],
        &["train"],
        &["lab"],
        &["trust-region"],
        &["play"],
        &["replay"],
        &["grade"],
        &["watch"],
        &["reset"],
        &["init"],
        &["dev"],
        &["dev", "notebooks"],
    ];
    for path in commands {
        for flag in ["-h", "--help"] {
            for (how, mut cmd, extra) in [
                ("--lang zh", with_env(&[]), Some("--lang=zh")),
                (
                    "PPO_TUTOR_LANG=zh",
                    with_env(&[("PPO_TUTOR_LANG", "zh")]),
                    None,
                ),
                (
                    "LANG=zh_CN.UTF-8",
                    with_env(&[("LANG", "zh_CN.UTF-8")]),
                    None,
                ),
            ] {
                cmd.args(extra).args(path).arg(flag);
                let out = cmd.output()?;
                let text = String::from_utf8(out.stdout)?;
                assert_eq!(out.status.code(), Some(0), "{how} {path:?} {flag}");
                assert!(
                    text.contains("用法：ppo-tutor") && text.contains("选项："),
                    "{how} {path:?} {flag}:\n{text}"
                );
                for english in CLAP_ENGLISH {
                    assert!(
                        !text.contains(english),
                        "{how} {path:?} {flag}: {english}\n{text}"
                    );
                }
            }
        }
    }
    // `help COMMAND` too, and the English help is still English.
    let out = with_env(&[])
        .args(["--lang", "zh", "help", "train"])
        .output()?;
    let text = String::from_utf8(out.stdout)?;
    assert!(
        text.contains("截断范围 ε") && text.contains("[默认：0.2]"),
        "{text}"
    );
    let out = with_env(&[("PPO_TUTOR_LANG", "en")])
        .args(["train", "--help"])
        .output()?;
    let text = String::from_utf8(out.stdout)?;
    assert!(
        text.contains("Usage: ppo-tutor train [OPTIONS]") && text.contains("Clip range ε"),
        "{text}"
    );
    Ok(())
}

/// A usage error in Chinese is one Chinese line quoting the argument, exit code 2.
#[test]
fn usage_errors_are_one_chinese_line() -> TestResult {
    for (args, says) in [
        (&["train", "--foo"][..], "不认识的参数 '--foo'"),
        (
            &["trian"][..],
            "不认识的子命令 'trian'；你是不是想用 'train'？",
        ),
        (&["show"][..], "缺少必需的参数"),
        (&["cartpole", "--policy", "lea"][..], "'lea' 不是 '--policy"),
        (&["cartpole", "--seed", "abc"][..], "的值 'abc' 无效：应为"),
        (&["train", "--seeds", "0-2", "--seed", "3"][..], "不能与"),
    ] {
        let out = with_env(&[("PPO_TUTOR_LANG", "zh")]).args(args).output()?;
        let err = String::from_utf8(out.stderr)?;
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("错误：")
                && err.contains(says)
                && err.trim_end().ends_with("（见 --help）"),
            "{args:?}: {err}"
        );
        for english in ["error", "unexpected", "invalid", "argument", "Usage"] {
            assert!(!err.contains(english), "{args:?}: {err}");
        }
    }
    Ok(())
}
