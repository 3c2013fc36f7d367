//! The sandbox overlay (`s`): a copy of the run's settings being edited, and the
//! highlighted field. Enter retrains with the copy; nothing changes before that.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget};

use super::{Component, Ctx, Reply, centered, clear, panel};
use crate::env::EnvId;
use crate::i18n::t;
use crate::lesson::{Environment, RunConfig};
use crate::ppo::{Algorithm, PpoConfig, PpoContinuousConfig};
use crate::tui::keys::Action;
use crate::tui::theme::Theme;

/// One editable setting of the sandbox.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Field {
    /// The clip range ε.
    #[default]
    Eps,
    /// The discount γ.
    Gamma,
    /// GAE's λ.
    Lmbda,
    /// The actor's learning rate.
    ActorLr,
    /// The critic's learning rate.
    CriticLr,
    /// The seed of the agent and the environment.
    Seed,
    /// Whether the TD target bootstraps `V(s')` on a time-limit truncation.
    BootstrapOnTruncation,
    /// Whether the advantage is normalised per batch.
    NormalizeAdvantage,
    /// CartPole-v1, CartPole-v0 or Pendulum-v1 (with the book's continuous defaults).
    Env,
    /// The entropy bonus: off (the seed) or CleanRL's 0.01.
    EntropyCoef,
    /// Gradient-norm clipping: off (the seed) or CleanRL's 0.5.
    MaxGradNorm,
    /// Early stop at a target KL: off (the seed) or 0.01 (Spinning Up's default).
    TargetKl,
    /// Passes over each batch: 1, 2, 3, 5, 10 (the seed), 20 or 40.
    Epochs,
    /// The clip on (the seed) or off.
    NoClip,
    /// PPO (the seed) or REINFORCE with a baseline.
    Algorithm,
}

impl Field {
    /// Every field, in display order.
    pub const ALL: [Self; 15] = [
        Self::Eps,
        Self::Gamma,
        Self::Lmbda,
        Self::ActorLr,
        Self::CriticLr,
        Self::Seed,
        Self::BootstrapOnTruncation,
        Self::NormalizeAdvantage,
        Self::Env,
        Self::EntropyCoef,
        Self::MaxGradNorm,
        Self::TargetKl,
        Self::Epochs,
        Self::NoClip,
        Self::Algorithm,
    ];

    /// The setting's name, as in [`PpoConfig`] (and the `--flag` of `ppo-tutor train`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Eps => "eps",
            Self::Gamma => "gamma",
            Self::Lmbda => "lmbda",
            Self::ActorLr => "actor_lr",
            Self::CriticLr => "critic_lr",
            Self::Seed => "seed",
            Self::BootstrapOnTruncation => "bootstrap_on_truncation",
            Self::NormalizeAdvantage => "normalize_advantage",
            Self::Env => "env",
            Self::EntropyCoef => "entropy_coef",
            Self::MaxGradNorm => "max_grad_norm",
            Self::TargetKl => "target_kl",
            Self::Epochs => "epochs",
            Self::NoClip => "no_clip",
            Self::Algorithm => "algorithm",
        }
    }

    /// The position in [`Field::ALL`].
    #[must_use]
    pub fn index(self) -> usize {
        Self::ALL.iter().position(|&f| f == self).unwrap_or(0)
    }

    fn at(index: usize) -> Self {
        Self::ALL[index.min(Self::ALL.len() - 1)]
    }
}

/// The settings being edited and the highlighted field.
#[derive(Debug, Clone, Default)]
pub struct Sandbox {
    /// The hyper-parameters of the next CartPole run.
    pub config: PpoConfig,
    /// The hyper-parameters of the next Pendulum run.
    pub pendulum: PpoContinuousConfig,
    /// The environment of the next run.
    pub env: Environment,
    /// The seed of the next run.
    pub seed: u64,
    /// The highlighted field.
    pub selected: Field,
}

/// What the sandbox shows for a CartPole-only switch while Pendulum is chosen (English;
/// [`cartpole_only`] is the current language's).
pub const CARTPOLE_ONLY: &str = "(CartPole only)";

/// [`CARTPOLE_ONLY`] in the current language.
#[must_use]
pub fn cartpole_only() -> &'static str {
    t(CARTPOLE_ONLY, "（仅 CartPole）")
}

/// What the sandbox shows for a switch that is off.
fn off() -> String {
    t("off", "关").into()
}

impl Sandbox {
    /// A sandbox starting from the current CartPole run's settings, first field highlighted.
    #[must_use]
    pub fn new(config: PpoConfig, seed: u64) -> Self {
        Self {
            config,
            seed,
            ..Self::default()
        }
    }

    /// A sandbox starting from the settings of `run` (the other environment's from its
    /// defaults, or from `cartpole` when `run` is a Pendulum run).
    #[must_use]
    pub fn for_run(run: &RunConfig, cartpole: &PpoConfig, seed: u64) -> Self {
        match run {
            RunConfig::CartPole(c) => Self::new(c.clone(), seed),
            RunConfig::Pendulum(p) => Self {
                pendulum: p.clone(),
                env: Environment::Pendulum,
                ..Self::new(cartpole.clone(), seed)
            },
        }
    }

    /// The run the sandbox's settings describe.
    #[must_use]
    pub fn run_config(&self) -> RunConfig {
        match self.env {
            Environment::CartPole => RunConfig::CartPole(self.config.clone()),
            Environment::Pendulum => RunConfig::Pendulum(self.pendulum.clone()),
        }
    }

    /// Whether `field` applies to the chosen environment (the discrete PPO's switches do
    /// not apply to Pendulum's).
    #[must_use]
    pub fn applies(&self, field: Field) -> bool {
        self.env == Environment::CartPole
            || matches!(
                field,
                Field::Eps
                    | Field::Gamma
                    | Field::Lmbda
                    | Field::ActorLr
                    | Field::CriticLr
                    | Field::Seed
                    | Field::Env
                    | Field::Epochs
            )
    }

    /// Applies one key's action: move the highlight, change the highlighted value, or ask
    /// the app to close, retrain or quit.
    pub fn update(&mut self, action: Action) -> Reply {
        match action {
            Action::Quit => return Reply::Quit,
            Action::Up | Action::ScrollUp => {
                self.selected = Field::at(self.selected.index().saturating_sub(1));
            }
            Action::Down | Action::ScrollDown => {
                self.selected = Field::at(self.selected.index() + 1);
            }
            Action::Increase => self.nudge(self.selected, true),
            Action::Decrease => self.nudge(self.selected, false),
            Action::Enter => return Reply::Retrain,
            Action::Sandbox | Action::Back => return Reply::Close,
            _ => {}
        }
        Reply::Stay
    }

    /// The value of `field` as the sandbox shows it.
    #[must_use]
    pub fn value(&self, field: Field) -> String {
        if self.env == Environment::Pendulum {
            return self.pendulum_value(field);
        }
        let c = &self.config;
        match field {
            Field::Eps => c.eps.to_string(),
            Field::Gamma => c.gamma.to_string(),
            Field::Lmbda => c.lmbda.to_string(),
            Field::ActorLr => format!("{:.2e}", c.actor_lr),
            Field::CriticLr => format!("{:.2e}", c.critic_lr),
            Field::Seed => self.seed.to_string(),
            Field::BootstrapOnTruncation => c.bootstrap_on_truncation.to_string(),
            Field::NormalizeAdvantage => c.normalize_advantage.to_string(),
            Field::Env => c.env_id.to_string(),
            Field::EntropyCoef => c.entropy_coef.to_string(),
            Field::MaxGradNorm => c.max_grad_norm.map_or_else(off, |v| v.to_string()),
            Field::TargetKl => c.target_kl.map_or_else(off, |v| v.to_string()),
            Field::Epochs => c.epochs.to_string(),
            Field::NoClip => c.no_clip.to_string(),
            Field::Algorithm => c.algorithm.as_str().into(),
        }
    }

    fn pendulum_value(&self, field: Field) -> String {
        let p = &self.pendulum;
        match field {
            Field::Eps => p.eps.to_string(),
            Field::Gamma => p.gamma.to_string(),
            Field::Lmbda => p.lmbda.to_string(),
            Field::ActorLr => format!("{:.2e}", p.actor_lr),
            Field::CriticLr => format!("{:.2e}", p.critic_lr),
            Field::Seed => self.seed.to_string(),
            Field::Env => Environment::Pendulum.as_str().into(),
            Field::Epochs => p.epochs.to_string(),
            _ => cartpole_only().into(),
        }
    }

    /// The environment after `self.env`/`env_id` in the cycle CartPole-v1 → CartPole-v0 →
    /// Pendulum-v1 → CartPole-v1 (or back, for `up == false`). Choosing Pendulum starts
    /// from the book's continuous defaults.
    fn cycle_env(&mut self, up: bool) {
        const CYCLE: [(Environment, EnvId); 3] = [
            (Environment::CartPole, EnvId::CartPoleV1),
            (Environment::CartPole, EnvId::CartPoleV0),
            (Environment::Pendulum, EnvId::CartPoleV1),
        ];
        let at = match self.env {
            Environment::Pendulum => 2,
            Environment::CartPole if self.config.env_id == EnvId::CartPoleV0 => 1,
            Environment::CartPole => 0,
        };
        let to = if up { (at + 1) % 3 } else { (at + 2) % 3 };
        let (env, id) = CYCLE[to];
        if env == Environment::Pendulum && self.env != Environment::Pendulum {
            self.pendulum = PpoContinuousConfig::default();
        }
        self.env = env;
        if env == Environment::CartPole {
            self.config.env_id = id;
        }
    }

    /// Changes a Pendulum setting one notch up or down (the CartPole-only ones stay).
    fn nudge_pendulum(&mut self, field: Field, up: bool) {
        let p = &mut self.pendulum;
        let step = |v: f64, by: f64, lo: f64, hi: f64| {
            round3((v + if up { by } else { -by }).clamp(lo, hi))
        };
        let scale = |v: f64| (if up { v * 2.0 } else { v / 2.0 }).clamp(1e-6, 1.0);
        match field {
            Field::Eps => p.eps = step(p.eps, 0.05, 0.05, 0.95),
            Field::Gamma => p.gamma = step(p.gamma, 0.01, 0.5, 1.0),
            Field::Lmbda => p.lmbda = step(p.lmbda, 0.05, 0.0, 1.0),
            Field::ActorLr => p.actor_lr = scale(p.actor_lr),
            Field::CriticLr => p.critic_lr = scale(p.critic_lr),
            Field::Epochs => {
                const LADDER: [usize; 7] = [1, 2, 3, 5, 10, 20, 40];
                let at = LADDER.iter().position(|&e| e >= p.epochs).unwrap_or(4);
                let to = if up {
                    (at + 1).min(LADDER.len() - 1)
                } else {
                    at.saturating_sub(1)
                };
                p.epochs = LADDER[to];
            }
            _ => {}
        }
    }

    /// Changes `field` one notch up or down, within its valid range.
    fn nudge(&mut self, field: Field, up: bool) {
        if field == Field::Env {
            self.cycle_env(up);
            return;
        }
        if field == Field::Seed {
            self.seed = if up {
                self.seed.saturating_add(1)
            } else {
                self.seed.saturating_sub(1)
            };
            return;
        }
        if self.env == Environment::Pendulum {
            self.nudge_pendulum(field, up);
            return;
        }
        let c = &mut self.config;
        let step = |v: f64, by: f64, lo: f64, hi: f64| {
            round3((v + if up { by } else { -by }).clamp(lo, hi))
        };
        let scale = |v: f64| (if up { v * 2.0 } else { v / 2.0 }).clamp(1e-6, 1.0);
        match field {
            Field::Eps => c.eps = step(c.eps, 0.05, 0.05, 0.95),
            Field::Gamma => c.gamma = step(c.gamma, 0.01, 0.5, 1.0),
            Field::Lmbda => c.lmbda = step(c.lmbda, 0.05, 0.0, 1.0),
            Field::ActorLr => c.actor_lr = scale(c.actor_lr),
            Field::CriticLr => c.critic_lr = scale(c.critic_lr),
            Field::Seed | Field::Env => {}
            Field::BootstrapOnTruncation => {
                c.bootstrap_on_truncation = !c.bootstrap_on_truncation;
            }
            Field::NormalizeAdvantage => c.normalize_advantage = !c.normalize_advantage,
            // The three switches toggle between off and the value their source uses.
            Field::EntropyCoef => {
                c.entropy_coef = if c.entropy_coef > 0.0 { 0.0 } else { 0.01 };
            }
            Field::MaxGradNorm => {
                c.max_grad_norm = if c.max_grad_norm.is_some() {
                    None
                } else {
                    Some(0.5)
                };
            }
            Field::TargetKl => {
                c.target_kl = if c.target_kl.is_some() {
                    None
                } else {
                    Some(0.01)
                };
            }
            Field::Epochs => {
                const LADDER: [usize; 7] = [1, 2, 3, 5, 10, 20, 40];
                let at = LADDER.iter().position(|&e| e >= c.epochs).unwrap_or(4);
                let to = if up {
                    (at + 1).min(LADDER.len() - 1)
                } else {
                    at.saturating_sub(1)
                };
                c.epochs = LADDER[to];
            }
            Field::NoClip => c.no_clip = !c.no_clip,
            Field::Algorithm => {
                c.algorithm = match c.algorithm {
                    Algorithm::Ppo => Algorithm::Reinforce,
                    Algorithm::Reinforce => Algorithm::Ppo,
                };
            }
        }
    }
}

fn round3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

impl Component for Sandbox {
    fn handle(&mut self, action: Action, _: &Ctx<'_>) -> Reply {
        self.update(action)
    }

    fn render(&self, _: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        let rect = centered(
            area,
            64,
            u16::try_from(Field::ALL.len() + 7).unwrap_or(u16::MAX),
        );
        clear(rect, buf);
        let mut lines: Vec<Line> = Field::ALL
            .iter()
            .map(|&field| {
                let text = format!(" {:<26} {}", field.name(), self.value(field));
                if field == self.selected {
                    Line::styled(text, theme.highlight())
                } else if self.applies(field) {
                    Line::raw(text)
                } else {
                    Line::styled(text, theme.dim())
                }
            })
            .collect();
        lines.push(Line::raw(""));
        lines.push(Line::styled(
            t(
                " ↑↓ choose · +/− or ←/→ change · Enter retrains",
                " ↑↓ 选择 · +/− 或 ←/→ 修改 · Enter 重新训练",
            ),
            theme.dim(),
        ));
        lines.push(Line::styled(
            t(
                " (the current curve stays on the plot for comparison)",
                " （当前曲线会留在图上作对比）",
            ),
            theme.dim(),
        ));
        Paragraph::new(lines)
            .block(panel(t("sandbox", "沙盒"), theme))
            .render(rect, buf);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_match_the_config_fields_in_display_order() {
        let names: Vec<&str> = Field::ALL.iter().map(|f| f.name()).collect();
        assert_eq!(
            names,
            [
                "eps",
                "gamma",
                "lmbda",
                "actor_lr",
                "critic_lr",
                "seed",
                "bootstrap_on_truncation",
                "normalize_advantage",
                "env",
                "entropy_coef",
                "max_grad_norm",
                "target_kl",
                "epochs",
                "no_clip",
                "algorithm"
            ]
        );
        assert!(Field::ALL.iter().enumerate().all(|(i, f)| f.index() == i));
    }

    #[test]
    fn the_highlight_stays_within_the_fields() {
        let mut s = Sandbox::default();
        assert_eq!(s.update(Action::Up), Reply::Stay);
        assert_eq!(s.selected, Field::Eps);
        for _ in 0..20 {
            s.update(Action::Down);
        }
        assert_eq!(s.selected, Field::Algorithm);
    }

    #[test]
    fn every_field_changes_within_its_range() {
        let mut s = Sandbox::new(PpoConfig::default(), 0);
        for field in Field::ALL {
            let before = s.value(field);
            s.selected = field;
            s.update(Action::Increase);
            assert_ne!(s.value(field), before, "{} did not change", field.name());
        }
        for _ in 0..100 {
            for field in Field::ALL {
                s.selected = field;
                s.update(Action::Decrease);
            }
        }
        let c = &s.config;
        assert_eq!((c.eps, c.gamma, c.lmbda, s.seed), (0.05, 0.5, 0.0, 0));
        assert_eq!((c.actor_lr, c.critic_lr), (1e-6, 1e-6));
        assert!(
            c.validate().is_ok(),
            "the sandbox's lower ends are valid settings"
        );
    }

    #[test]
    fn the_env_field_switches_to_pendulum_with_the_books_defaults() {
        let mut s = Sandbox::new(PpoConfig::default(), 3);
        s.pendulum.eps = 0.5;
        s.selected = Field::Env;
        let mut seen = Vec::new();
        for _ in 0..3 {
            s.update(Action::Increase);
            seen.push(s.value(Field::Env));
        }
        assert_eq!(seen, ["CartPole-v0", "Pendulum-v1", "CartPole-v1"]);
        s.update(Action::Decrease);
        assert_eq!(s.env, Environment::Pendulum);
        assert_eq!(
            s.pendulum,
            PpoContinuousConfig::default(),
            "the book's defaults"
        );
        assert_eq!(s.value(Field::Gamma), "0.9");
        assert_eq!(s.value(Field::EntropyCoef), CARTPOLE_ONLY);
        assert!(!s.applies(Field::NoClip) && s.applies(Field::Eps));
        s.selected = Field::Eps;
        s.update(Action::Increase);
        assert!((s.pendulum.eps - 0.25).abs() < 1e-12);
        assert_eq!(
            s.config,
            PpoConfig::default(),
            "CartPole's settings are kept"
        );
        assert_eq!(
            s.run_config(),
            RunConfig::Pendulum(PpoContinuousConfig {
                eps: 0.25,
                ..PpoContinuousConfig::default()
            })
        );
    }

    #[test]
    fn enter_retrains_and_escape_closes() {
        let mut s = Sandbox::default();
        assert_eq!(s.update(Action::Enter), Reply::Retrain);
        assert_eq!(s.update(Action::Back), Reply::Close);
        assert_eq!(s.update(Action::Sandbox), Reply::Close);
        assert_eq!(s.update(Action::Quit), Reply::Quit);
    }
}
