//! A grading report in a notebook (evcxr): the text of `ppo-tutor grade`, marks coloured.

use std::fmt::Write as _;

use crate::{CheckStatus, Report};
use ppo_engine::notebook::{Html, Rich, emit_rich, escape};

/// A grading report as in `ppo-tutor grade`: the same text, with its marks coloured.
#[must_use]
pub fn report_html(report: &Report) -> Html {
    let text = report.render();
    let colour = |line: &str| {
        let t = line.trim_start();
        if t.starts_with('✓') {
            "#2b8a3e"
        } else if t.starts_with('✗') {
            "#c92a2a"
        } else if t.starts_with("hint:") || t.starts_with("提示") {
            "#1864ab"
        } else {
            ""
        }
    };
    let mut html = String::from("<pre style=\"font-size:12px\">");
    for line in text.lines() {
        let c = colour(line);
        if c.is_empty() {
            let _ = writeln!(html, "{}", escape(line));
        } else {
            let _ = writeln!(html, "<span style=\"color:{c}\">{}</span>", escape(line));
        }
    }
    let passed = report
        .checks
        .iter()
        .all(|c| matches!(c.status, CheckStatus::Passed));
    let verdict = if passed && report.compile_error.is_none() {
        crate::i18n::t(
            "<b style=\"color:#2b8a3e\">All checks pass.</b>",
            "<b style=\"color:#2b8a3e\">全部检查通过。</b>",
        )
    } else {
        crate::i18n::t(
            "<b style=\"color:#c92a2a\">Not yet: fix the first ✗ and run the cell again.</b>",
            "<b style=\"color:#c92a2a\">还没有通过：先修正第一个 ✗，再运行这个单元格。</b>",
        )
    };
    let _ = write!(html, "</pre>{verdict}");
    Html::new(html, text)
}

impl Report {
    /// evcxr's display hook: the report, marks coloured.
    pub fn evcxr_display(&self) {
        emit_rich(self);
    }
}

impl Rich for Report {
    fn rich(&self) -> Vec<(&'static str, String)> {
        report_html(self).rich()
    }
}
