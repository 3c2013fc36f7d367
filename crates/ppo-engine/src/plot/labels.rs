//! Every word a plot shows, in both languages (the current one: [`Lang::current`]).
//!
//! The figures ([`file`](super::file)) and the character plots ([`terminal`](super::terminal))
//! take their labels from here, and so do the titles the commands give them, so that one
//! list, [`all`], holds every Chinese label a figure can show: `tests/plot_zh.rs` checks
//! that the bundled Chinese font (`assets/fonts/`) has a glyph for each of its characters.
//!
//! ```
//! use ppo_engine::i18n::Lang;
//! use ppo_engine::plot::labels;
//!
//! let _zh = Lang::Zh.scoped();
//! assert_eq!(labels::episodes(), "回合");
//! assert_eq!(labels::moving_average(9), "移动平均（9 回合）");
//! ```

use crate::i18n::{Lang, t};
use crate::ppo::{Algorithm, PpoConfig, RuleSetting, UpdateRule};
use crate::run::RunConfig;
use crate::tr;

/// The x axis: `Episodes`, `回合`.
#[must_use]
pub fn episodes() -> &'static str {
    t("Episodes", "回合")
}

/// The x axis over environment steps: `Environment steps`, `环境时间步`.
#[must_use]
pub fn env_steps() -> &'static str {
    t("Environment steps", "环境时间步")
}

/// The y axis: `Returns`, `回报`.
#[must_use]
pub fn returns_axis() -> &'static str {
    t("Returns", "回报")
}

/// The legend of the raw returns: `returns`, `回报`.
#[must_use]
pub fn returns() -> &'static str {
    t("returns", "回报")
}

/// The legend of the smoothed curve over `window` episodes ([`super::window`]):
/// `moving average (9 episodes)`, `移动平均（9 回合）`.
#[must_use]
pub fn moving_average(window: usize) -> String {
    tr!(
        "moving average ({window} episodes)",
        "移动平均（{window} 回合）"
    )
}

/// The legend of the band of several seeds.
#[must_use]
pub fn band(seeds: usize) -> String {
    tr!(
        "lowest to highest of {seeds} seeds",
        "{seeds} 个随机种子的最低到最高"
    )
}

/// The legend of the seeds' mean curve.
#[must_use]
pub fn mean_over_seeds() -> &'static str {
    t("mean over seeds", "各随机种子的均值")
}

/// The legend of one arm of a lab experiment (`label` is the arm's own label).
#[must_use]
pub fn arm(label: &str, seeds: usize) -> String {
    tr!(
        "{label} (mean of {seeds} seeds, band min–max)",
        "{label}：{seeds} 个随机种子的均值与最低到最高"
    )
}

/// The clip chart's caption: `ε` (shown with 6 decimals at most: it usually comes from an
/// f32) and how many rows of the batch are drawn.
#[must_use]
pub fn clip_caption(eps: f64, rows: usize) -> String {
    let eps = (eps * 1e6).round() / 1e6;
    tr!(
        "L^CLIP for a unit advantage, ε = {eps}; {rows} rows of the batch",
        "单位优势值下的 L^CLIP，ε = {eps}；本批次的 {rows} 行"
    )
}

/// The clip chart's x axis.
#[must_use]
pub fn ratio_axis() -> &'static str {
    t(
        "ratio r = π_θ(a|s) / π_θ_old(a|s)",
        "比率 r = π_θ(a|s) / π_θ_old(a|s)",
    )
}

/// The clip chart's y axis (a formula: the same in both languages).
#[must_use]
pub fn clip_axis() -> &'static str {
    "min(surr1, surr2) / |A|"
}

/// What trained a run, as titles name it: `PPO` (the seed's PPO-Clip, and the book's
/// `PPOContinuous`, PPO-Clip too), `PPO without the clip` (`--no-clip`), `PPO-Penalty`,
/// `KL line search`, `REINFORCE`.
#[must_use]
pub fn algorithm(run: &RunConfig) -> &'static str {
    let Some(c) = run.get::<PpoConfig>() else {
        return "PPO";
    };
    match c.rule() {
        Ok(UpdateRule::Reinforce) => "REINFORCE",
        Ok(UpdateRule::Penalty) => t("PPO-Penalty", "PPO-惩罚"),
        Ok(UpdateRule::LineSearch) => t("KL line search", "KL 线搜索"),
        Ok(UpdateRule::NoClip) => t("PPO without the clip", "不截断的 PPO"),
        Ok(UpdateRule::Clip) => "PPO",
        // settings that name no rule (refused before any training): the algorithm first
        Err(_) if c.algorithm == Algorithm::Reinforce => "REINFORCE",
        Err(clash) => match clash.chosen {
            RuleSetting::Penalty => t("PPO-Penalty", "PPO-惩罚"),
            RuleSetting::LineSearch => t("KL line search", "KL 线搜索"),
            RuleSetting::Reinforce | RuleSetting::NoClip => "PPO",
        },
    }
}

/// The title of one run's figure (`ppo-tutor train --plot`) and of its summary:
/// `PPO on CartPole-v1`, `REINFORCE on CartPole-v1`.
#[must_use]
pub fn return_title(algorithm: &str, env: &str) -> String {
    tr!("{algorithm} on {env}", "{env} 上的 {algorithm}")
}

/// The title of several seeds' figure (`ppo-tutor train --seeds … --plot`).
#[must_use]
pub fn band_title(algorithm: &str, env: &str, seeds: usize) -> String {
    tr!(
        "{algorithm} on {env}, {seeds} seeds",
        "{env} 上的 {algorithm}，{seeds} 个随机种子"
    )
}

/// The title of a lab experiment's figure (`ppo-tutor lab NAME --plot`, the notebooks).
#[must_use]
pub fn lab_title(experiment: &str, seeds: usize) -> String {
    tr!(
        "lab {experiment}: {seeds} seeds",
        "实验 {experiment}：{seeds} 个随机种子"
    )
}

/// The character plot's legend of one run, whose moving average is over `window` episodes.
#[must_use]
pub fn ascii_returns(window: usize) -> String {
    tr!(
        "Returns  (. per episode, * moving average of {window})",
        "回报（. 为每回合的值，* 为 {window} 回合移动平均）"
    )
}

/// The character plot's legend of several seeds' moving averages over `window` episodes.
#[must_use]
pub fn ascii_band(seeds: usize, window: usize) -> String {
    tr!(
        "Moving average ({window} episodes) of the returns over {seeds} seeds  (* mean, : lowest to highest seed)",
        "{seeds} 个随机种子的回报移动平均（{window} 回合；* 为均值，: 为最低到最高）"
    )
}

/// The character plot's legend of one arm against the base arm.
#[must_use]
pub fn ascii_versus(arm: &str, base: &str, seeds: usize) -> String {
    tr!(
        "{arm} (* mean, : lowest to highest of {seeds} seeds) against {base} (o mean)",
        "{arm}：* 为均值，: 为 {seeds} 个随机种子的最低到最高；对比 {base}：o 为均值"
    )
}

/// Every label above in `lang`, with sample arguments (environment names, seed counts,
/// arm labels and numbers stand for those a run gives): the text a figure can show.
#[must_use]
pub fn all(lang: Lang) -> Vec<String> {
    let _lang = lang.scoped();
    let mut labels: Vec<String> = [
        episodes(),
        env_steps(),
        returns_axis(),
        returns(),
        mean_over_seeds(),
        ratio_axis(),
        clip_axis(),
    ]
    .into_iter()
    .map(String::from)
    .collect();
    // Every algorithm's title (the flags that change what trains).
    let cartpole = PpoConfig::default();
    let runs = UpdateRule::ALL.map(|rule| RunConfig::CartPole(cartpole.clone().with_rule(rule)));
    for run in &runs {
        labels.push(return_title(algorithm(run), "CartPole-v1"));
    }
    labels.extend([
        moving_average(41),
        ascii_returns(9),
        band(5),
        arm("ε = 0.2", 5),
        clip_caption(f64::from(0.2_f32), 64),
        clip_caption(-0.05, 1234),
        return_title("PPO", "Pendulum-v1"),
        band_title("REINFORCE", "CartPole-v1", 10),
        lab_title("target-kl", 3),
        ascii_band(5, 39),
        ascii_versus("ε = 0.05", "ε = 0.2", 5),
        "A > 0".into(),
        "A < 0".into(),
        // Tick labels.
        "-0.123456789 1e-4 1e5".into(),
    ]);
    labels
}
