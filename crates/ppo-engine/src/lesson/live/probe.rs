//! The trust-region probe of a live CartPole run: [`probe_snapshot`] reads θ_old, the
//! surrogate's gradient and the critic from a [`Snapshot`] and runs the RL core's
//! [`probe`].

use crate::i18n::t;
use crate::lesson::live::Snapshot;
use crate::ppo::trust_region::{ProbeSettings, TrustRegionProbe, probe};
use crate::ppo::{PpoConfig, PpoError};

/// [`crate::ppo::trust_region::probe`] from a live CartPole snapshot: `θ_old` is the actor that played the latest
/// batch ([`Snapshot::played_with`]), the direction that batch's surrogate gradient
/// ([`Snapshot::gradients`]), the critic the snapshot's weights after the update.
/// `config` must be the run's: its γ, λ, environment and done switch are checked against
/// the snapshot's hyper-parameter table.
///
/// # Errors
/// [`PpoError::InvalidBatch`] when the snapshot holds no update yet (train at least one
/// episode first) or comes from a Pendulum run; [`PpoError::InvalidConfig`] naming a
/// setting where `config` is not the run's; and [`probe`]'s errors.
pub fn probe_snapshot(
    snapshot: &Snapshot,
    config: &PpoConfig,
    settings: &ProbeSettings,
) -> Result<TrustRegionProbe, PpoError> {
    let Some(latest) = snapshot.cartpole_update() else {
        return Err(PpoError::InvalidBatch(
            t(
                "the snapshot holds no CartPole update yet: train at least one episode before probing the trust region",
                "快照里还没有 CartPole 的更新：先训练至少一个回合，再探测信任区域",
            )
            .into(),
        ));
    };
    for (field, value) in [
        ("gamma", config.gamma.to_string()),
        ("lmbda", config.lmbda.to_string()),
        ("env_name", config.env_id.as_str().to_string()),
        (
            "bootstrap_on_truncation",
            config.bootstrap_on_truncation.to_string(),
        ),
    ] {
        let run = snapshot.hyper.iter().find(|(name, _)| name == field);
        if run.is_some_and(|(_, v)| *v != value) {
            return Err(PpoError::InvalidConfig {
                field,
                value,
                expected: "the value of the run the snapshot comes from",
            });
        }
    }
    probe(
        &latest.played_with,
        &snapshot.weights,
        &latest.gradients.surrogate,
        config,
        settings,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lesson::Session;

    type TestResult = Result<(), Box<dyn std::error::Error>>;

    fn trained(episodes: usize) -> Result<Snapshot, PpoError> {
        Session::run(PpoConfig::default(), 0, episodes)
    }

    fn small(steps: &[f32]) -> ProbeSettings {
        ProbeSettings {
            steps: steps.to_vec(),
            episodes: 12,
            seed: 3,
        }
    }

    /// At α = 0 nothing moves: the KL, the prediction and the paired truth are exactly 0;
    /// further out the KL grows with every step.
    #[test]
    fn zero_step_changes_nothing_and_the_kl_grows_with_the_step() -> TestResult {
        let snapshot = trained(5)?;
        let steps = [0.0, 0.05, 0.2, 0.8, 3.2];
        let p = probe_snapshot(&snapshot, &PpoConfig::default(), &small(&steps))?;
        assert_eq!(p.points.len(), steps.len());
        let zero = p.points[0];
        assert_eq!(
            (zero.kl, zero.kl_max, zero.predicted, zero.truth),
            (0.0, 0.0, 0.0, 0.0)
        );
        assert_eq!(
            (zero.return_change, zero.truth_se, zero.predicted_se),
            (0.0, 0.0, 0.0)
        );
        for pair in p.points.windows(2) {
            assert!(pair[1].kl > pair[0].kl, "{pair:?}");
            assert!(pair[1].kl_max >= pair[1].kl);
        }
        assert!(p.points[1].kl < 1e-2 && p.points[4].kl > 1e-2, "{p:?}");
        assert_eq!((p.episodes, p.states > 12), (12, true));
        assert!(p.old_score >= 8.0 && p.old_return <= p.old_score);
        assert!(p.gradient_norm > 0.0);
        Ok(())
    }

    #[test]
    fn bad_input_is_refused_by_name() -> TestResult {
        let config = PpoConfig::default();
        let empty = Snapshot::new(config.clone(), 0);
        let err = probe_snapshot(&empty, &config, &ProbeSettings::default())
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.contains("train at least one episode"), "{err}");
        let snapshot = trained(2)?;
        for (settings, field) in [
            (small(&[]), "steps"),
            (small(&[0.0, f32::NAN]), "steps"),
            (
                ProbeSettings {
                    episodes: 1,
                    ..small(&[0.1])
                },
                "episodes",
            ),
        ] {
            let err = probe_snapshot(&snapshot, &config, &settings)
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(field), "{field}: {err}");
        }
        let other = PpoConfig {
            gamma: 0.9,
            ..PpoConfig::default()
        };
        let err = probe_snapshot(&snapshot, &other, &small(&[0.1]))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.contains("gamma"), "{err}");
        let old = snapshot
            .cartpole_update()
            .map(|c| c.played_with.clone())
            .ok_or("no θ_old")?;
        let n = old.parameters().len();
        for (direction, want) in [
            (vec![1.0; n - 1], "direction has"),
            (vec![0.0; n], "norm is 0"),
            (vec![f32::NAN; n], "norm is NaN"),
        ] {
            let err = probe(&old, &snapshot.weights, &direction, &config, &small(&[0.1]))
                .err()
                .map(|e| e.to_string())
                .unwrap_or_default();
            assert!(err.contains(want), "{want}: {err}");
        }
        let mut no_critic = snapshot.weights.clone();
        no_critic.remove("critic.fc2.bias");
        let err = probe(&old, &no_critic, &vec![1.0; n], &config, &small(&[0.1]))
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.contains("critic.fc2.bias"), "{err}");
        Ok(())
    }
}
