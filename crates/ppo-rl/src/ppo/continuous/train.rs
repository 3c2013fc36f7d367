//! The shared [`Training`](crate::ppo::train::Training) on Pendulum-v1: the book's
//! episode loop for `PPOContinuous`, checked step by step.

use std::ops::ControlFlow;

use crate::env::Pendulum;
use crate::ppo::Trainer;
use crate::ppo::config::PpoConfig;
use crate::ppo::train::{iteration_of, train};
use crate::ppo::{ContinuousEpisodeReport, ContinuousTrainer, PpoContinuousConfig, PpoError};

fn short(num_episodes: usize) -> PpoContinuousConfig {
    PpoContinuousConfig {
        num_episodes,
        ..PpoContinuousConfig::default()
    }
}

#[test]
fn trainer_is_send() {
    fn assert_send<T: Send + 'static>() {}
    assert_send::<ContinuousTrainer>();
    assert_send::<ContinuousEpisodeReport>();
}

/// The same split as the discrete trainer's, for a few lengths.
#[test]
fn iterations_split_like_the_discrete_trainer() -> Result<(), PpoError> {
    for n in [1, 3, 12, 500, 2000] {
        let discrete = Trainer::new(
            PpoConfig {
                num_episodes: n,
                ..PpoConfig::default()
            },
            0,
        )?;
        for episode in 0..n {
            assert_eq!(
                iteration_of(n, episode),
                discrete.iteration_of(episode),
                "{episode} of {n}"
            );
        }
    }
    assert_eq!(iteration_of(2000, 1999), (9, 199, 200));
    Ok(())
}

/// The first episode starts from `reset(seed)`, later ones from unseeded resets; every
/// episode is 200 steps whose last one alone is `done`; the return is the sum of the
/// environment's rewards, each in Pendulum's range.
#[test]
fn episodes_follow_the_books_loop() -> Result<(), PpoError> {
    let mut trainer = ContinuousTrainer::new(short(3), 4)?;
    let mut env = Pendulum::new();
    let first = env.reset(Some(4));
    let reports: Vec<_> = trainer.by_ref().collect::<Result<_, _>>()?;
    assert_eq!(reports.len(), 3);
    assert_eq!(reports[0].trace.states[0], first);
    let second = env.reset(None);
    assert_eq!(
        reports[1].trace.states[0], second,
        "unseeded: the same generator"
    );
    for (i, r) in reports.iter().enumerate() {
        assert_eq!(
            (r.episode, r.steps, r.total_steps),
            (i, 200, 200 * (i as u64 + 1))
        );
        let dones = &r.trace.dones;
        assert!(dones[199] && dones[..199].iter().all(|d| !d));
        let sum: f64 = r.trace.rewards.iter().map(|&x| f64::from(x)).sum();
        assert!(
            (sum - r.episode_return).abs() < 1e-3,
            "{sum} {}",
            r.episode_return
        );
        assert!(r.trace.rewards.iter().all(|&x| (-16.3..=0.0).contains(&x)));
    }
    assert_eq!(trainer.summary().env_steps, 600);
    assert!(trainer.next_episode()?.is_none());
    Ok(())
}

#[test]
fn same_seed_same_run() -> Result<(), PpoError> {
    let (a, agent_a) = train(short(3), 7, |_| ControlFlow::Continue(()))?;
    let (b, agent_b) = train(short(3), 7, |_| ControlFlow::Continue(()))?;
    assert_eq!(a.returns, b.returns);
    assert_eq!(agent_a.weights()?, agent_b.weights()?);
    let (c, _) = train(short(3), 8, |_| ControlFlow::Continue(()))?;
    assert_ne!(a.returns, c.returns);
    Ok(())
}

#[test]
fn a_break_stops_training() -> Result<(), PpoError> {
    let (summary, _) = train(short(5), 0, |r| {
        if r.episode == 1 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })?;
    assert_eq!(summary.returns.len(), 2);
    Ok(())
}

#[test]
fn divergence_names_the_episode() {
    let config = PpoContinuousConfig {
        actor_lr: 1e30,
        critic_lr: 1e30,
        ..short(20)
    };
    match train(config, 0, |_| ControlFlow::Continue(())).err() {
        Some(PpoError::Diverged { episode, what }) => {
            assert!(episode < 20, "{episode} {what}");
        }
        other => panic!("expected divergence, got {other:?}"),
    }
}
