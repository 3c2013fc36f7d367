//! The sandbox overlay (`s`): a copy of the run's settings being edited, and the
//! highlighted field. Enter retrains with the copy; nothing changes before that.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget};

use super::{Component, Ctx, Reply, centered, clear, panel};
use crate::i18n::t;
use crate::lesson::{AgentKind, RunConfig};
use crate::ppo::knobs::KnobValue;
use crate::tr;
use crate::tui::keys::Action;
use crate::tui::theme::Theme;

/// The settings being edited and the highlighted row.
#[derive(Debug, Clone)]
pub struct Sandbox {
    /// The environment and hyper-parameters of the next run.
    pub config: RunConfig,
    /// The main run's settings (the app's CartPole run), kept while another environment is
    /// chosen: choosing its environment again restores them, where any other environment
    /// starts from its agent's defaults (the book's, for Pendulum).
    pub main: RunConfig,
    /// The seed of the next run.
    pub seed: u64,
    /// The highlighted row: a knob's id ([`Sandbox::rows`]).
    pub selected: &'static str,
}

impl Default for Sandbox {
    /// The defaults of the first environment (CartPole-v1, the seed's PPO), seed 0, first
    /// row highlighted.
    fn default() -> Self {
        Self::new(RunConfig::default(), 0)
    }
}

/// What the sandbox shows for a setting that the chosen environment's agent does not have:
/// which environments have it, "(CartPole only)".
fn only(id: &str) -> String {
    let names: Vec<&str> = RunConfig::environments_with(id)
        .into_iter()
        .map(|env| env.spec().name)
        .collect();
    let names = names.join(" / ");
    tr!("({names} only)", "（仅 {names}）")
}

impl Sandbox {
    /// Every row, in display order: the knobs of every agent ([`RunConfig::all_knob_ids`]),
    /// named as in their configuration (and the `--flag` of `ppo-tutor train`).
    #[must_use]
    pub fn rows() -> Vec<&'static str> {
        RunConfig::all_knob_ids()
    }

    /// A sandbox starting from `run`'s settings, first row highlighted.
    #[must_use]
    pub fn new(run: RunConfig, seed: u64) -> Self {
        Self::for_run(run, RunConfig::default(), seed)
    }

    /// A sandbox starting from the settings of `run`, with `main` the main run's settings
    /// (the app's CartPole run, kept for when its environment is chosen; `run` itself when
    /// it is on that environment), first row highlighted.
    #[must_use]
    pub fn for_run(run: RunConfig, main: RunConfig, seed: u64) -> Self {
        let main = if run.agent() == main.agent() {
            run.clone()
        } else {
            main
        };
        Self {
            config: run,
            main,
            seed,
            selected: Self::rows().first().copied().unwrap_or_default(),
        }
    }

    /// The run the sandbox's settings describe.
    #[must_use]
    pub fn run_config(&self) -> RunConfig {
        self.config.clone()
    }

    /// The environment of the next run.
    #[must_use]
    pub fn env(&self) -> AgentKind {
        self.config.agent()
    }

    /// Whether the knob `id` applies to the chosen environment (the discrete PPO's
    /// switches do not apply to Pendulum's).
    #[must_use]
    pub fn applies(&self, id: &str) -> bool {
        self.config.knob(id).is_some()
    }

    /// Applies one key's action: move the highlight, change the highlighted value, or ask
    /// the app to close, retrain or quit.
    pub fn update(&mut self, action: Action) -> Reply {
        let rows = Self::rows();
        let at = rows.iter().position(|&r| r == self.selected).unwrap_or(0);
        let mut select = |i: usize| {
            if let Some(&row) = rows.get(i.min(rows.len().saturating_sub(1))) {
                self.selected = row;
            }
        };
        match action {
            Action::Quit => return Reply::Quit,
            Action::Up | Action::ScrollUp => select(at.saturating_sub(1)),
            Action::Down | Action::ScrollDown => select(at + 1),
            Action::Increase => self.nudge(self.selected, true),
            Action::Decrease => self.nudge(self.selected, false),
            // settings that name no update rule (REINFORCE with PPO-Penalty, say) are
            // refused here, with why, rather than by a run that fails to start
            Action::Enter => {
                return match self.run_config().validate() {
                    Ok(()) => Reply::Retrain,
                    Err(e) => Reply::Say(crate::tr!("Not retrained: {e}", "没有重新训练：{e}")),
                };
            }
            Action::Sandbox | Action::Back => return Reply::Close,
            _ => {}
        }
        Reply::Stay
    }

    /// The value of the knob `id` as the sandbox shows it.
    #[must_use]
    pub fn value(&self, id: &str) -> String {
        match self.config.knob(id) {
            Some(KnobValue::Value(v)) => v,
            Some(KnobValue::Seed) => self.seed.to_string(),
            Some(KnobValue::Environment) => self.config.env_id().into(),
            None => only(id),
        }
    }

    /// The environment after the chosen one in [`RunConfig::choices`] (CartPole-v1 →
    /// CartPole-v0 → Pendulum-v1 → CartPole-v1), or before it for `up == false`. Another
    /// agent's environment starts from its defaults, the main run's from [`Sandbox::main`].
    fn cycle_env(&mut self, up: bool) {
        let choices = RunConfig::choices();
        let n = choices.len();
        let at = choices
            .iter()
            .position(|&c| c == self.config.choice())
            .unwrap_or(0);
        let Some(&to) = choices.get(if up { at + 1 } else { at + n - 1 } % n.max(1)) else {
            return;
        };
        if to.agent != self.env() {
            let next = if to.agent == self.main.agent() {
                self.main.clone()
            } else {
                RunConfig::default_for(to.agent)
            };
            let left = std::mem::replace(&mut self.config, next);
            if left.agent() == self.main.agent() {
                self.main = left;
            }
        }
        self.config.set_env_id(to.id);
    }

    /// Changes the knob `id` one notch up or down, within its valid range (a setting the
    /// chosen agent does not have stays).
    fn nudge(&mut self, id: &str, up: bool) {
        match self.config.knob(id) {
            Some(KnobValue::Seed) => {
                self.seed = if up {
                    self.seed.saturating_add(1)
                } else {
                    self.seed.saturating_sub(1)
                };
            }
            Some(KnobValue::Environment) => self.cycle_env(up),
            Some(KnobValue::Value(_)) => {
                self.config.nudge(id, up);
            }
            None => {}
        }
    }
}

impl Component for Sandbox {
    fn handle(&mut self, action: Action, _: &Ctx<'_>) -> Reply {
        self.update(action)
    }

    fn render(&self, _: &Ctx<'_>, theme: Theme, area: Rect, buf: &mut Buffer) {
        let rows = Self::rows();
        let rect = centered(area, 64, u16::try_from(rows.len() + 7).unwrap_or(u16::MAX));
        clear(rect, buf);
        let mut lines: Vec<Line> = rows
            .iter()
            .map(|&id| {
                let text = format!(" {:<26} {}", id, self.value(id));
                if id == self.selected {
                    Line::styled(text, theme.highlight())
                } else if self.applies(id) {
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
    use crate::ppo::{PpoConfig, PpoContinuousConfig};

    fn cartpole(s: &Sandbox) -> Option<&PpoConfig> {
        s.config.get().or(s.main.get())
    }

    #[test]
    fn rows_are_the_config_fields_in_display_order() {
        assert_eq!(
            Sandbox::rows(),
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
                "objective",
                "algorithm"
            ]
        );
    }

    #[test]
    fn the_highlight_stays_within_the_rows() {
        let mut s = Sandbox::default();
        assert_eq!(s.update(Action::Up), Reply::Stay);
        assert_eq!(s.selected, "eps");
        for _ in 0..20 {
            s.update(Action::Down);
        }
        assert_eq!(s.selected, "algorithm");
    }

    #[test]
    fn every_field_changes_within_its_range() {
        let mut s = Sandbox::new(RunConfig::default(), 0);
        for id in Sandbox::rows() {
            let before = s.value(id);
            s.selected = id;
            s.update(Action::Increase);
            assert_ne!(s.value(id), before, "{id} did not change");
        }
        for _ in 0..100 {
            for id in Sandbox::rows() {
                s.selected = id;
                s.update(Action::Decrease);
            }
        }
        assert_eq!(s.env(), AgentKind::CartPole);
        let c = cartpole(&s).cloned().unwrap_or_default();
        assert_eq!((c.eps, c.gamma, c.lmbda, s.seed), (0.05, 0.5, 0.0, 0));
        assert_eq!((c.actor_lr, c.critic_lr), (1e-6, 1e-6));
        assert!(
            c.validate().is_ok(),
            "the sandbox's lower ends are valid settings"
        );
    }

    #[test]
    fn the_env_field_switches_to_pendulum_with_the_books_defaults() {
        let mut s = Sandbox::new(RunConfig::default(), 3);
        s.selected = "env";
        let mut seen = Vec::new();
        for _ in 0..3 {
            s.update(Action::Increase);
            seen.push(s.value("env"));
            if s.env() == AgentKind::Pendulum {
                // Edited, then left: choosing Pendulum again starts from the book's.
                assert!(s.config.nudge("eps", true));
            }
        }
        assert_eq!(seen, ["CartPole-v0", "Pendulum-v1", "CartPole-v1"]);
        s.update(Action::Decrease);
        assert_eq!(s.env(), AgentKind::Pendulum);
        assert_eq!(
            s.config,
            RunConfig::from(PpoContinuousConfig::default()),
            "the book's defaults"
        );
        assert_eq!(s.value("gamma"), "0.9");
        assert_eq!(s.value("entropy_coef"), "(CartPole only)");
        assert!(!s.applies("no_clip") && s.applies("eps"));
        s.selected = "eps";
        s.update(Action::Increase);
        let eps = s.config.get::<PpoContinuousConfig>().map(|p| p.eps);
        assert!(eps.is_some_and(|eps| (eps - 0.25).abs() < 1e-12), "{eps:?}");
        assert_eq!(s.main, RunConfig::default(), "CartPole's settings are kept");
        assert_eq!(
            s.run_config(),
            RunConfig::from(PpoContinuousConfig {
                eps: 0.25,
                ..PpoContinuousConfig::default()
            })
        );
    }

    #[test]
    fn a_pendulum_run_s_sandbox_keeps_the_cartpole_settings() {
        let main = RunConfig::from(PpoConfig {
            eps: 0.3,
            ..PpoConfig::default()
        });
        let pendulum = RunConfig::from(PpoContinuousConfig {
            gamma: 0.95,
            ..PpoContinuousConfig::default()
        });
        let mut s = Sandbox::for_run(pendulum, main.clone(), 7);
        assert_eq!(
            (s.value("gamma"), s.value("seed")),
            ("0.95".into(), "7".into())
        );
        s.selected = "env";
        s.update(Action::Increase);
        assert_eq!(s.config, main, "CartPole-v1 with the main run's settings");
        s.update(Action::Increase);
        assert_eq!(s.value("env"), "CartPole-v0");
        assert_eq!(s.value("eps"), "0.3");
    }

    #[test]
    fn enter_refuses_settings_that_name_no_update_rule() {
        let mut s = Sandbox::default();
        for id in ["algorithm", "no_clip"] {
            s.selected = id;
            s.update(Action::Increase);
        }
        let Reply::Say(said) = s.update(Action::Enter) else {
            panic!("REINFORCE with no_clip retrained");
        };
        assert!(
            said.contains("no_clip") && said.contains("REINFORCE"),
            "{said}"
        );
        s.update(Action::Increase); // no_clip off again: plain REINFORCE
        assert_eq!(s.update(Action::Enter), Reply::Retrain);
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
