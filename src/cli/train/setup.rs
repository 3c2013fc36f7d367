//! Which environment `ppo-tutor train` trains on, and the configuration its flags give:
//! the seed's PPO on CartPole (the default) or the book's `PPOContinuous` on Pendulum-v1.
//!
//! Every hyper-parameter flag (`--actor-lr`, `--critic-lr`, `--gamma`, `--lmbda`, `--eps`,
//! `--epochs`, `--hidden-dim`, `--episodes`) works for both and defaults to the chosen
//! environment's reference (the seed's on CartPole, the book's on Pendulum-v1). The
//! CartPole agent's opt-in switches are refused on Pendulum-v1, each with its reason: the
//! book's continuous update has none of them (no advantage normalisation, entropy bonus,
//! gradient clipping, KL stop, unclipped, PPO-Penalty or REINFORCE variant, nor a bootstrap
//! at the time limit: its `done` is `terminated or truncated`). PPO-Penalty's own flag
//! `--beta-init` needs `--objective penalty`, the KL line search's (`--ls-max-step`,
//! `--ls-backtracks`) need `--objective line-search`, `--kl-delta` needs one of the two, and
//! both objectives need PPO with its clip left alone.

use super::{AlgorithmArg, ObjectiveArg, TrainArgs};
use crate::env::EnvId;
use crate::i18n::t;
use crate::lesson::RunConfig;
use crate::ppo::{PpoConfig, PpoContinuousConfig, PpoError, RuleSetting};
use crate::run::{AgentKind, Choice};
use crate::tr;

/// Parses a Gymnasium id in any case (`CartPole-v1`, `pendulum-v1`): one of the registry's
/// environments ([`RunConfig::choices`]), so a new agent's ids are accepted here by itself.
///
/// # Errors
/// A message listing the supported ids.
pub fn parse_train_env(s: &str) -> Result<Choice, String> {
    let wanted = s.trim();
    let choices = RunConfig::choices();
    choices
        .iter()
        .copied()
        .find(|c| c.id.eq_ignore_ascii_case(wanted))
        .ok_or_else(|| {
            let ids: Vec<_> = choices.iter().map(|c| c.id).collect();
            let ids = ids.join(", ");
            tr!(
                "unknown environment '{s}': expected one of {ids} (any case)",
                "未知的环境 '{s}'：应为 {ids} 之一（不分大小写）"
            )
        })
}

/// The configuration `ppo-tutor train`'s flags give: the environment's reference settings
/// with every flag given applied, checked.
///
/// # Errors
/// A message naming the flag (`invalid --gamma 2: expected ...`), or a CartPole-only
/// switch given with Pendulum-v1, with its reason.
pub fn run_config(args: &TrainArgs) -> Result<RunConfig, String> {
    let choice = args.env_id;
    let setup = match choice.agent {
        AgentKind::CartPole => {
            refuse_lone_penalty_flags(args)?;
            refuse_lone_line_search_flags(args)?;
            let env_id: EnvId = choice
                .id
                .parse()
                .map_err(|e: crate::env::EnvError| e.to_string())?;
            let config = args.config_for(env_id);
            refuse_rule_clash(&config)?;
            RunConfig::CartPole(config)
        }
        AgentKind::Pendulum => {
            refuse_cartpole_switches(args)?;
            let book = PpoContinuousConfig::default();
            RunConfig::Pendulum(PpoContinuousConfig {
                actor_lr: args.actor_lr.unwrap_or(book.actor_lr),
                critic_lr: args.critic_lr.unwrap_or(book.critic_lr),
                hidden_dim: args.hidden_dim.unwrap_or(book.hidden_dim),
                gamma: args.gamma.unwrap_or(book.gamma),
                lmbda: args.lmbda.unwrap_or(book.lmbda),
                epochs: args.epochs.unwrap_or(book.epochs),
                eps: args.eps.unwrap_or(book.eps),
                num_episodes: args.episodes.unwrap_or(book.num_episodes),
            })
        }
    };
    match setup.validate() {
        Ok(()) => Ok(setup),
        Err(PpoError::InvalidConfig {
            field,
            value,
            expected,
        }) => {
            let flag = flag_of(field);
            Err(tr!(
                "invalid --{flag} {value}: expected {expected}",
                "--{flag} {value} 无效：应为 {expected}"
            ))
        }
        Err(other) => Err(other.to_string()),
    }
}

/// Refuses each switch of the CartPole agent that the book's continuous update lacks.
fn refuse_cartpole_switches(args: &TrainArgs) -> Result<(), String> {
    let given: [(bool, &str, &str); 9] = [
        (
            args.bootstrap_truncation,
            "--bootstrap-truncation",
            t(
                "the book's PPOContinuous ends every episode at Pendulum-v1's 200-step time limit \
                 (done = terminated or truncated) and its update has no bootstrap from V(s')",
                "书中的 PPOContinuous 让每个回合都在 Pendulum-v1 的 200 步时限处结束\
                 （`done = terminated or truncated`），更新时也不从 V(s') 自举",
            ),
        ),
        (
            args.normalize_advantage,
            "--normalize-advantage",
            t(
                "the book's PPOContinuous update uses the GAE advantage as it is",
                "书中的 PPOContinuous 更新直接使用 GAE 优势值",
            ),
        ),
        (
            args.entropy_coef != 0.0,
            "--entropy-coef",
            t(
                "the book's PPOContinuous update has no entropy bonus",
                "书中的 PPOContinuous 更新没有熵奖励",
            ),
        ),
        (
            args.max_grad_norm.is_some(),
            "--max-grad-norm",
            t(
                "the book's PPOContinuous update does not clip gradients",
                "书中的 PPOContinuous 更新不做梯度裁剪",
            ),
        ),
        (
            args.target_kl.is_some(),
            "--target-kl",
            t(
                "the book's PPOContinuous update always runs all its epochs",
                "书中的 PPOContinuous 更新总是跑完所有轮",
            ),
        ),
        (
            args.critic_epochs.is_some(),
            "--critic-epochs",
            t(
                "the book's PPOContinuous update steps both networks once per epoch",
                "书中的 PPOContinuous 更新每一轮都让两个网络各走一步",
            ),
        ),
        (
            args.no_clip,
            "--no-clip",
            t(
                "the book's PPOContinuous update always clips the ratio",
                "书中的 PPOContinuous 更新总是截断比率",
            ),
        ),
        (
            args.algorithm != AlgorithmArg::Ppo,
            "--algorithm",
            t(
                "REINFORCE is implemented for CartPole's softmax policy only",
                "REINFORCE 只为 CartPole 的 softmax 策略实现了",
            ),
        ),
        (
            args.objective != ObjectiveArg::Clip,
            "--objective",
            t(
                "the book's PPOContinuous is PPO-Clip; the exact KL of PPO-Penalty and of the \
                 KL line search is written for CartPole's two actions",
                "书中的 PPOContinuous 是 PPO-截断；PPO-惩罚和 KL 线搜索的精确 KL 是为 CartPole 的两个动作写的",
            ),
        ),
    ];
    match given.into_iter().find(|(on, _, _)| *on) {
        Some((_, flag, why)) => {
            let env = args.env_id;
            Err(tr!(
                "{flag} works only with CartPole: {why}; drop {flag} to train {env}",
                "{flag} 只适用于 CartPole：{why}。要训练 {env}，请去掉 {flag}"
            ))
        }
        None => Ok(()),
    }
}

/// Refuses PPO-Penalty's flags where they would change nothing: `--beta-init` and
/// `--kl-delta` without `--objective penalty`.
fn refuse_lone_penalty_flags(args: &TrainArgs) -> Result<(), String> {
    let penalty = args.objective == ObjectiveArg::Penalty;
    // δ is also the line search's bound (refused there by its own check)
    let search = args.objective == ObjectiveArg::LineSearch;
    let unused = [
        (!penalty && args.beta_init.is_some(), "--beta-init"),
        (!penalty && !search && args.kl_delta.is_some(), "--kl-delta"),
    ];
    if let Some((_, flag)) = unused.into_iter().find(|(on, _)| *on) {
        return Err(tr!(
            "{flag} is a setting of PPO-Penalty: add --objective penalty, or drop {flag}",
            "{flag} 是 PPO-惩罚的设置：请加上 --objective penalty，或去掉 {flag}"
        ));
    }
    Ok(())
}

/// Refuses the KL line search's flags where they would change nothing: `--ls-max-step` and
/// `--ls-backtracks` without `--objective line-search`.
fn refuse_lone_line_search_flags(args: &TrainArgs) -> Result<(), String> {
    let search = args.objective == ObjectiveArg::LineSearch;
    let unused = [
        (!search && args.ls_max_step.is_some(), "--ls-max-step"),
        (!search && args.ls_backtracks.is_some(), "--ls-backtracks"),
    ];
    if let Some((_, flag)) = unused.into_iter().find(|(on, _)| *on) {
        return Err(tr!(
            "{flag} is a setting of the KL line search: add --objective line-search, or drop {flag}",
            "{flag} 是 KL 线搜索的设置：请加上 --objective line-search，或去掉 {flag}"
        ));
    }
    Ok(())
}

/// Refuses settings that name no update rule together ([`PpoConfig::rule`]): REINFORCE with
/// `--objective penalty`, `--objective line-search` or `--no-clip`, and `--no-clip` with
/// PPO-Penalty or the KL line search, each with why.
fn refuse_rule_clash(config: &PpoConfig) -> Result<(), String> {
    let Err(clash) = config.rule() else {
        return Ok(());
    };
    let flag = |setting: RuleSetting| match setting {
        RuleSetting::Reinforce => "--algorithm reinforce",
        RuleSetting::NoClip => "--no-clip",
        RuleSetting::Penalty => "--objective penalty",
        RuleSetting::LineSearch => "--objective line-search",
    };
    let (chosen, with, why) = (flag(clash.chosen), flag(clash.with), clash.why());
    Err(tr!(
        "{chosen} and {with} do not go together: {why}",
        "{chosen} 不能与 {with} 同用：{why}"
    ))
}

/// The `--flag` spelling of a config field.
fn flag_of(field: &str) -> String {
    match field {
        "num_episodes" => "episodes".into(),
        "bootstrap_on_truncation" => "bootstrap-truncation".into(),
        other => other.replace('_', "-"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_parse_in_any_case_and_unknown_ones_list_the_choices() {
        let pendulum = parse_train_env("pendulum-V1");
        assert_eq!(
            pendulum.map(|c| (c.agent, c.id)),
            Ok((AgentKind::Pendulum, "Pendulum-v1"))
        );
        let v0 = parse_train_env("CARTPOLE-v0");
        assert_eq!(
            v0.map(|c| (c.agent, c.id)),
            Ok((AgentKind::CartPole, "CartPole-v0"))
        );
        let err = parse_train_env("Acrobot-v1").err().unwrap_or_default();
        assert!(
            err.contains("'Acrobot-v1'")
                && err.contains("CartPole-v1")
                && err.contains("Pendulum-v1"),
            "{err}"
        );
    }
}
