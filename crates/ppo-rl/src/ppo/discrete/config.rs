//! The hyper-parameters: [`PpoConfig::default`] is the seed's `__main__` block.
//!
//! The seed has no tricks beyond the clipped surrogate and GAE. CleanRL-style extras
//! (bootstrapping on truncation, advantage normalisation, an entropy bonus, gradient
//! clipping, early stopping at a target KL) are opt-in switches, all off by default, so the default run is the seed's.
//! So are the two switches the lessons compare PPO against: no clip at all, and plain
//! REINFORCE with a baseline.

use serde::{Deserialize, Serialize};

use crate::env::EnvId;
use crate::i18n::t;
use crate::ppo::PpoError;
use crate::ppo::ranges::{invalid, positive};

/// Everything that sets one PPO run apart from another.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PpoConfig {
    /// Adam learning rate of the actor (policy network); seed: `1e-3`.
    pub actor_lr: f64,
    /// Adam learning rate of the critic (value network); seed: `1e-2`.
    pub critic_lr: f64,
    /// Width of the hidden layer of both networks; seed: 128.
    pub hidden_dim: usize,
    /// Discount factor γ in the TD target; seed: 0.98.
    pub gamma: f64,
    /// GAE's λ (the seed spells it `lmbda`); seed: 0.95.
    pub lmbda: f64,
    /// Passes over each episode's batch per update; seed: 10.
    pub epochs: usize,
    /// The critic's Adam steps per update, when they differ from the actor's; `None` (the
    /// seed) steps the critic as often as the actor (`epochs`, or once for REINFORCE). The
    /// clip lab's epochs experiment sets it to change one network's epochs and not the
    /// other's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub critic_epochs: Option<usize>,
    /// Clip range ε of the surrogate: the ratio is clamped to `[1-ε, 1+ε]`; seed: 0.2.
    pub eps: f64,
    /// Episodes to train for (one update per episode); seed: 500.
    pub num_episodes: usize,
    /// The environment; seed: `CartPole-v1`.
    #[serde(with = "env_id_serde")]
    pub env_id: EnvId,
    /// Use `terminated` (not `terminated or truncated`) in the TD target, so a time-limit
    /// cut bootstraps from `V(s')`; the seed folds both into `done` (off).
    pub bootstrap_on_truncation: bool,
    /// Normalise the advantage to mean 0, std 1 before the epochs (off in the seed).
    pub normalize_advantage: bool,
    /// Weight of the policy-entropy bonus subtracted from the actor loss; 0 is off (the seed).
    pub entropy_coef: f64,
    /// Clip each network's gradient to this global L2 norm before Adam; `None` is off (the seed).
    pub max_grad_norm: Option<f64>,
    /// Stop an update's epochs early once the policy has moved too far, as Spinning Up does:
    /// before each epoch's step, if `approx_kl > 1.5 · target_kl` the update ends there (both
    /// networks; Spinning Up keeps training its value function). `None` is off (the seed).
    #[serde(default)]
    pub target_kl: Option<f64>,
    /// Drop the clip: the actor loss is `−mean(ratio · Â)`, the unclipped surrogate, for
    /// every epoch (off in the seed). `eps` is then unused.
    #[serde(default)]
    pub no_clip: bool,
    /// The update rule: the seed's PPO, or REINFORCE with a baseline for comparison.
    #[serde(default)]
    pub algorithm: Algorithm,
    /// PPO's objective for the actor: the seed's clipped surrogate (`clip`, PPO-Clip, the
    /// book's PPO-截断), a KL penalty with an adaptive β (`penalty`, PPO-惩罚; see
    /// [`penalty`](super::penalty)) or a KL-constrained line search on the surrogate's
    /// gradient (`line-search`, see [`line_search`](super::line_search)). REINFORCE has no
    /// ratio and ignores it.
    #[serde(default, skip_serializing_if = "Objective::is_clip")]
    pub objective: Objective,
    /// PPO-Penalty's β₀, the KL coefficient of the first update (β then adapts from update
    /// to update); 1, the PPO paper's. Unused with `clip`.
    #[serde(
        default = "default_beta_init",
        skip_serializing_if = "is_default_beta_init"
    )]
    pub beta_init: f64,
    /// PPO-Penalty's δ, the mean KL per update that β steers towards (β halves below
    /// δ / 1.5, doubles above 1.5 · δ); 0.01. Also the KL line search's bound: a step is
    /// accepted only if the mean KL after it is at most δ. Not `target_kl`, which stops
    /// epochs early. Unused with `clip`.
    #[serde(
        default = "default_kl_delta",
        skip_serializing_if = "is_default_kl_delta"
    )]
    pub kl_delta: f64,
    /// The KL line search's first step length α along `g/‖g‖` (the unit direction of the
    /// surrogate's gradient at θ_old), halved until the step is accepted; 0.25, chosen by
    /// measurement so that the first try usually overshoots δ = 0.01: searching from α = 1
    /// with 20 halvings on seeds 0–2, no update of episodes 0–39 (120) nor 100–199 (300)
    /// accepted α ≥ 0.5, and 0.25 was accepted in 8 and 4 of them (most took 0.0625), so
    /// starting at 0.25 accepts the same steps with two tries fewer
    /// ([`line_search`](super::line_search)). Unused unless `objective = line-search`.
    #[serde(
        default = "default_ls_max_step",
        skip_serializing_if = "is_default_ls_max_step"
    )]
    pub ls_max_step: f64,
    /// The KL line search's largest number of halvings of α; 10. After `ls_backtracks`
    /// halvings without an accepted step the actor keeps θ_old. Unused unless
    /// `objective = line-search`.
    #[serde(
        default = "default_ls_backtracks",
        skip_serializing_if = "is_default_ls_backtracks"
    )]
    pub ls_backtracks: usize,
}

/// The most halvings [`PpoConfig::ls_backtracks`] allows.
pub const MAX_BACKTRACKS: usize = 50;

/// PPO-Penalty's β₀ and δ when a saved configuration has none: the defaults.
fn default_beta_init() -> f64 {
    PpoConfig::default().beta_init
}

fn default_kl_delta() -> f64 {
    PpoConfig::default().kl_delta
}

fn default_ls_max_step() -> f64 {
    PpoConfig::default().ls_max_step
}

fn default_ls_backtracks() -> usize {
    PpoConfig::default().ls_backtracks
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_default_ls_max_step(v: &f64) -> bool {
    *v == default_ls_max_step()
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_default_ls_backtracks(v: &usize) -> bool {
    *v == default_ls_backtracks()
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_default_beta_init(v: &f64) -> bool {
    *v == default_beta_init()
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
fn is_default_kl_delta(v: &f64) -> bool {
    *v == default_kl_delta()
}

/// What PPO's actor minimises ([`PpoConfig::objective`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Objective {
    /// PPO-Clip, the seed's: `mean(-min(ratio · Â, clamp(ratio, 1-ε, 1+ε) · Â))`.
    #[default]
    Clip,
    /// PPO-Penalty: `−mean(ratio · Â) + β · mean(KL(π_old ‖ π_θ))`, β adapted after each
    /// update towards `kl_delta` ([`penalty`](super::penalty)). `eps` and `no_clip` are unused.
    Penalty,
    /// A KL-constrained line search on the surrogate's gradient, the runnable stand-in for
    /// TRPO's hard KL constraint (not TRPO: no natural gradient, no conjugate gradient): one
    /// actor step per update along `∇θ mean(ratio · Â)` at θ_old, its length halved until
    /// the mean exact KL is at most `kl_delta` and the surrogate improves
    /// ([`line_search`](super::line_search)). No Adam for the actor; the critic's update is
    /// the seed's. `eps`, `no_clip` and `actor_lr` are unused.
    LineSearch,
}

impl Objective {
    /// Every objective, in the order the sandbox cycles through them.
    pub const ALL: [Self; 3] = [Self::Clip, Self::Penalty, Self::LineSearch];

    /// The name used on the command line and in JSON (`clip`, `penalty`, `line-search`).
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Clip => "clip",
            Self::Penalty => "penalty",
            Self::LineSearch => "line-search",
        }
    }

    /// The next objective in [`Self::ALL`], after the last the first (the sandbox's toggle).
    #[must_use]
    pub fn next(self) -> Self {
        match self {
            Self::Clip => Self::Penalty,
            Self::Penalty => Self::LineSearch,
            Self::LineSearch => Self::Clip,
        }
    }

    /// Whether this is the seed's clip (the default, left out of JSON).
    #[allow(clippy::trivially_copy_pass_by_ref)] // serde passes a reference
    #[must_use]
    pub fn is_clip(&self) -> bool {
        *self == Self::Clip
    }
}

/// Which update rule [`crate::ppo::Agent::update`] applies to each episode.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Algorithm {
    /// The seed's PPO: `epochs` clipped-surrogate steps on each episode.
    #[default]
    Ppo,
    /// REINFORCE with the critic as baseline: one step per episode on
    /// `−mean(log π(a|s) · (G_t − V(s_t)))`, the critic fitted to the Monte-Carlo return
    /// `G_t`. No ratio, no clip; `epochs`, `eps`, `lmbda` and `target_kl` are unused.
    Reinforce,
}

impl Algorithm {
    /// The name used on the command line and in JSON (`ppo`, `reinforce`).
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Ppo => "ppo",
            Self::Reinforce => "reinforce",
        }
    }
}

// ANCHOR: hyper
impl Default for PpoConfig {
    /// The seed's hyper-parameters, as `task_PPO.py` sets them.
    fn default() -> Self {
        Self {
            actor_lr: 1e-3,
            critic_lr: 1e-2,
            hidden_dim: 128,
            gamma: 0.98,
            lmbda: 0.95,
            epochs: 10,
            critic_epochs: None,
            eps: 0.2,
            num_episodes: 500,
            env_id: EnvId::CartPoleV1,
            bootstrap_on_truncation: false,
            normalize_advantage: false,
            entropy_coef: 0.0,
            max_grad_norm: None,
            target_kl: None,
            no_clip: false,
            algorithm: Algorithm::Ppo,
            objective: Objective::Clip,
            beta_init: 1.0,
            kl_delta: 0.01,
            ls_max_step: 0.25,
            ls_backtracks: 10,
        }
    }
}
// ANCHOR_END: hyper

impl PpoConfig {
    /// How many steps each update gives the actor and the critic: `epochs` Adam steps each
    /// (the seed), one each for REINFORCE, one line-search step for the actor with the KL
    /// line search (the critic keeps `epochs`), and `critic_epochs` for the critic when it
    /// is set.
    #[must_use]
    pub fn epochs_of_each(&self) -> (usize, usize) {
        let shared = match self.algorithm {
            Algorithm::Ppo => self.epochs,
            Algorithm::Reinforce => 1,
        };
        let actor = match (self.algorithm, self.objective) {
            (Algorithm::Ppo, Objective::LineSearch) => 1, // one line-search step, no Adam
            _ => shared,
        };
        (actor, self.critic_epochs.unwrap_or(shared))
    }

    /// Checks every field's range.
    ///
    /// # Errors
    /// [`PpoError::InvalidConfig`] naming the first field out of range and its valid range.
    pub fn validate(&self) -> Result<(), PpoError> {
        crate::ppo::ranges::check_shared!(self)?;
        if let Err(clash) = self.rule() {
            return Err(PpoError::InvalidConfig {
                field: clash.with.field(),
                value: clash.with.value().into(),
                expected: clash.expected(),
            });
        }
        if !(self.entropy_coef.is_finite() && self.entropy_coef >= 0.0) {
            return Err(invalid(
                "entropy_coef",
                self.entropy_coef,
                crate::i18n::t(
                    "a finite number >= 0 (0 turns the bonus off)",
                    "大于等于 0 的有限数（0 表示关闭熵奖励）",
                ),
            ));
        }
        if self.critic_epochs == Some(0) {
            return Err(invalid(
                "critic_epochs",
                0,
                crate::i18n::t(
                    "at least 1 (leave it unset to follow epochs)",
                    "至少为 1（不设置则与 epochs 相同）",
                ),
            ));
        }
        if let Some(norm) = self.max_grad_norm {
            positive("max_grad_norm", norm)?;
        }
        if let Some(kl) = self.target_kl {
            positive("target_kl", kl)?;
        }
        positive("beta_init", self.beta_init)?;
        positive("kl_delta", self.kl_delta)?;
        positive("ls_max_step", self.ls_max_step)?;
        if self.ls_backtracks > MAX_BACKTRACKS {
            return Err(invalid(
                "ls_backtracks",
                self.ls_backtracks,
                crate::i18n::t(
                    "0 to 50 halvings (2^-50 of the first step is already below f32's precision)",
                    "0 到 50 次减半（首步的 2^-50 已小于 f32 的精度）",
                ),
            ));
        }
        if self.objective == Objective::LineSearch && self.entropy_coef != 0.0 {
            return Err(invalid(
                "entropy_coef",
                self.entropy_coef,
                crate::i18n::t(
                    "0 with objective = line-search (the line search steps on the surrogate \
                     alone; drop the entropy bonus or choose another objective)",
                    "使用 objective = line-search 时须为 0（线搜索只沿替代目标走一步；\
                     请去掉熵奖励，或换一个目标）",
                ),
            ));
        }
        Ok(())
    }
}

/// The discrete agent's update rule: the one of five that the settings `algorithm`,
/// `objective` and `no_clip` name together, built once from them ([`PpoConfig::rule`]) and
/// matched by the tensor update, the fast path and the lab.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum UpdateRule {
    /// PPO-Clip, the seed's: `−mean(min(ratio · Â, clamp(ratio, 1 − ε, 1 + ε) · Â))`.
    Clip,
    /// PPO without the clip: `−mean(ratio · Â)`, every epoch.
    NoClip,
    /// PPO-Penalty: `−mean(ratio · Â) + β · mean(KL(π_old ‖ π_θ))`, β adapted after each
    /// update ([`penalty`](super::penalty)).
    Penalty,
    /// The KL-constrained line search on the surrogate's gradient: one actor step per
    /// update, no Adam for the actor ([`line_search`](super::line_search)).
    LineSearch,
    /// REINFORCE with a baseline: `−mean(log π · Â)`, one step per episode, λ = 1.
    Reinforce,
}

impl UpdateRule {
    /// Every rule, in the order the lessons meet them.
    pub const ALL: [Self; 5] = [
        Self::Clip,
        Self::NoClip,
        Self::Penalty,
        Self::LineSearch,
        Self::Reinforce,
    ];

    /// The settings that name this rule: `(algorithm, objective, no_clip)`.
    #[must_use]
    pub fn settings(self) -> (Algorithm, Objective, bool) {
        match self {
            Self::Clip => (Algorithm::Ppo, Objective::Clip, false),
            Self::NoClip => (Algorithm::Ppo, Objective::Clip, true),
            Self::Penalty => (Algorithm::Ppo, Objective::Penalty, false),
            Self::LineSearch => (Algorithm::Ppo, Objective::LineSearch, false),
            Self::Reinforce => (Algorithm::Reinforce, Objective::Clip, false),
        }
    }

    /// Whether the actor's objective uses the probability ratio (every rule but REINFORCE).
    #[must_use]
    pub fn uses_ratio(self) -> bool {
        self != Self::Reinforce
    }
}

/// One setting that picks an update rule, as a clash names it ([`RuleClash`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RuleSetting {
    /// `algorithm = reinforce`.
    Reinforce,
    /// `no_clip = true`.
    NoClip,
    /// `objective = penalty`.
    Penalty,
    /// `objective = line-search`.
    LineSearch,
}

impl RuleSetting {
    /// The configuration field it sets.
    #[must_use]
    pub fn field(self) -> &'static str {
        match self {
            Self::Reinforce => "algorithm",
            Self::NoClip => "no_clip",
            Self::Penalty | Self::LineSearch => "objective",
        }
    }

    /// The value it gives that field, as the command line and JSON spell it.
    #[must_use]
    pub fn value(self) -> &'static str {
        match self {
            Self::Reinforce => "reinforce",
            Self::NoClip => "true",
            Self::Penalty => "penalty",
            Self::LineSearch => "line-search",
        }
    }
}

/// Two settings that name no update rule together: `chosen` picks a rule that has no use
/// for `with` (REINFORCE has no ratio to penalise, PPO-Penalty no clip to drop, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RuleClash {
    /// The setting that picked the rule.
    pub chosen: RuleSetting,
    /// The setting that rule cannot take.
    pub with: RuleSetting,
}

impl RuleClash {
    /// What the clashing field may be instead, with why, in the current language (the
    /// `expected` of [`PpoError::InvalidConfig`]).
    #[must_use]
    pub fn expected(self) -> &'static str {
        use RuleSetting as S;
        match (self.chosen, self.with) {
            (S::Penalty, S::Reinforce) => t(
                "ppo with objective = penalty (REINFORCE has no ratio to penalise)",
                "使用 objective = penalty 时须为 ppo（REINFORCE 没有比率可供惩罚）",
            ),
            (S::Penalty, _) => t(
                "false with objective = penalty (PPO-Penalty has no clip to drop)",
                "使用 objective = penalty 时须为 false（PPO-惩罚本来就没有截断）",
            ),
            (S::LineSearch, S::Reinforce) => t(
                "ppo with objective = line-search (REINFORCE has no ratio, so no surrogate to \
                 search along)",
                "使用 objective = line-search 时须为 ppo（REINFORCE 没有比率，也就没有可供搜索的替代目标）",
            ),
            (S::LineSearch, _) => t(
                "false with objective = line-search (the KL line search has no clip to drop)",
                "使用 objective = line-search 时须为 false（KL 线搜索本来就没有截断）",
            ),
            (S::Reinforce | S::NoClip, _) => t(
                "false with algorithm = reinforce (REINFORCE has no ratio, so no clip to drop)",
                "使用 algorithm = reinforce 时须为 false（REINFORCE 没有比率，也就没有截断可去）",
            ),
        }
    }

    /// Why the two do not go together, in the current language.
    #[must_use]
    pub fn why(self) -> &'static str {
        use RuleSetting as S;
        match (self.chosen, self.with) {
            (S::Penalty, S::Reinforce) => t(
                "REINFORCE has no ratio to penalise",
                "REINFORCE 没有比率可供惩罚",
            ),
            (S::Penalty, _) => t("PPO-Penalty has no clip to drop", "PPO-惩罚本来就没有截断"),
            (S::LineSearch, S::Reinforce) => t(
                "REINFORCE has no ratio, so no surrogate to search along",
                "REINFORCE 没有比率，也就没有可供搜索的替代目标",
            ),
            (S::LineSearch, _) => t(
                "the KL line search has no clip to drop",
                "KL 线搜索本来就没有截断",
            ),
            (S::Reinforce | S::NoClip, _) => t(
                "REINFORCE has no ratio, so no clip to drop",
                "REINFORCE 没有比率，也就没有截断可去",
            ),
        }
    }
}

impl PpoConfig {
    /// The update rule `algorithm`, `objective` and `no_clip` name together.
    ///
    /// # Errors
    /// A [`RuleClash`] for settings that name none: REINFORCE with `objective = penalty`
    /// or `line-search`, or with `no_clip`; `no_clip` with `penalty` or `line-search`.
    pub fn rule(&self) -> Result<UpdateRule, RuleClash> {
        use RuleSetting as S;
        let clash = |chosen, with| Err(RuleClash { chosen, with });
        match (self.algorithm, self.objective, self.no_clip) {
            (Algorithm::Ppo, Objective::Clip, false) => Ok(UpdateRule::Clip),
            (Algorithm::Ppo, Objective::Clip, true) => Ok(UpdateRule::NoClip),
            (Algorithm::Ppo, Objective::Penalty, false) => Ok(UpdateRule::Penalty),
            (Algorithm::Ppo, Objective::LineSearch, false) => Ok(UpdateRule::LineSearch),
            (Algorithm::Reinforce, Objective::Clip, false) => Ok(UpdateRule::Reinforce),
            (Algorithm::Reinforce, Objective::Penalty, _) => clash(S::Penalty, S::Reinforce),
            (Algorithm::Reinforce, Objective::LineSearch, _) => clash(S::LineSearch, S::Reinforce),
            (Algorithm::Reinforce, Objective::Clip, true) => clash(S::Reinforce, S::NoClip),
            (Algorithm::Ppo, Objective::Penalty, true) => clash(S::Penalty, S::NoClip),
            (Algorithm::Ppo, Objective::LineSearch, true) => clash(S::LineSearch, S::NoClip),
        }
    }

    /// These settings with `rule`'s `algorithm`, `objective` and `no_clip`.
    #[must_use]
    pub fn with_rule(mut self, rule: UpdateRule) -> Self {
        (self.algorithm, self.objective, self.no_clip) = rule.settings();
        self
    }
}

/// `EnvId` as Gymnasium's id string in JSON.
mod env_id_serde {
    use serde::{Deserialize, Deserializer, Serializer};

    use crate::env::EnvId;

    pub fn serialize<S: Serializer>(id: &EnvId, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(id.as_str())
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<EnvId, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every rule's settings name that rule, and every other combination of `algorithm`,
    /// `objective` and `no_clip` is a clash that `validate` and the agent refuse by name.
    #[test]
    fn the_three_settings_name_five_rules_and_refuse_the_rest() {
        for rule in UpdateRule::ALL {
            let c = PpoConfig::default().with_rule(rule);
            assert_eq!(c.rule(), Ok(rule));
            assert!(c.validate().is_ok(), "{rule:?}");
        }
        let mut clashes = 0;
        for algorithm in [Algorithm::Ppo, Algorithm::Reinforce] {
            for objective in Objective::ALL {
                for no_clip in [false, true] {
                    let c = PpoConfig {
                        algorithm,
                        objective,
                        no_clip,
                        ..PpoConfig::default()
                    };
                    let named = UpdateRule::ALL
                        .into_iter()
                        .find(|r| r.settings() == (algorithm, objective, no_clip));
                    match (c.rule(), named) {
                        (Ok(rule), Some(want)) => assert_eq!(rule, want),
                        (Err(clash), None) => {
                            clashes += 1;
                            let Err(PpoError::InvalidConfig { field, value, .. }) = c.validate()
                            else {
                                panic!("{c:?} validates");
                            };
                            assert_eq!(
                                (field, value.as_str()),
                                (clash.with.field(), clash.with.value())
                            );
                            assert!(crate::ppo::Agent::new(&c, 0).is_err());
                            assert!(!clash.why().is_empty() && !clash.expected().is_empty());
                        }
                        (got, want) => panic!("{c:?}: {got:?}, expected {want:?}"),
                    }
                }
            }
        }
        assert_eq!(clashes, 12 - UpdateRule::ALL.len());
    }

    #[test]
    fn default_is_valid_and_is_the_seed() {
        let c = PpoConfig::default();
        assert!(c.validate().is_ok());
        assert_eq!(
            (c.actor_lr, c.critic_lr, c.gamma, c.lmbda),
            (1e-3, 1e-2, 0.98, 0.95)
        );
        assert_eq!((c.hidden_dim, c.epochs, c.num_episodes), (128, 10, 500));
    }

    #[test]
    fn out_of_range_fields_are_named() {
        type Case = (fn(&mut PpoConfig), &'static str);
        let cases: [Case; 9] = [
            (|c| c.eps = 0.0, "eps"),
            (|c| c.eps = 1.0, "eps"),
            (|c| c.gamma = 0.0, "gamma"),
            (|c| c.gamma = 1.01, "gamma"),
            (|c| c.actor_lr = 0.0, "actor_lr"),
            (|c| c.critic_lr = -1.0, "critic_lr"),
            (|c| c.num_episodes = 0, "num_episodes"),
            (|c| c.gamma = f64::NAN, "gamma"),
            (|c| c.critic_epochs = Some(0), "critic_epochs"),
        ];
        for (set, name) in cases {
            let mut c = PpoConfig::default();
            set(&mut c);
            let err = c
                .validate()
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(name), "{name}: {err}");
        }
        let c = PpoConfig {
            gamma: 1.0,
            ..PpoConfig::default()
        };
        assert!(c.validate().is_ok(), "gamma = 1 is allowed");
    }

    #[test]
    fn the_critic_follows_the_actor_unless_told_otherwise() {
        let seed = PpoConfig::default();
        assert_eq!(seed.epochs_of_each(), (10, 10));
        let apart = PpoConfig {
            epochs: 1,
            critic_epochs: Some(10),
            ..seed.clone()
        };
        assert_eq!(apart.epochs_of_each(), (1, 10));
        let reinforce = PpoConfig {
            algorithm: Algorithm::Reinforce,
            ..seed.clone()
        };
        assert_eq!(reinforce.epochs_of_each(), (1, 1));
        // The seed's configuration serialises as before (no `critic_epochs` key), so saved
        // configurations and their hashes are unchanged.
        let json = serde_json::to_value(&seed).unwrap_or_default();
        assert!(json.get("critic_epochs").is_none(), "{json}");
        let back: PpoConfig = serde_json::from_value(json).unwrap_or_default();
        assert_eq!(back, seed);
    }
}
