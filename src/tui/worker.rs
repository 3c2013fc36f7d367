//! The training worker: runs the PPO on its own thread so the UI never waits on it.
//!
//! The UI sends [`Command`]s; the worker answers with [`WorkerEvent`]s over a channel.
//! Errors (a diverged run, invalid settings) travel as events too: a panic in a worker
//! thread would restore the terminal under the running UI.

use std::sync::mpsc::{Receiver, Sender, TryRecvError};
use std::thread::JoinHandle;

use crate::ppo::model::ActorSnapshot;
use crate::ppo::{EpisodeReport, PpoConfig, Trainer};

/// What the UI asks of the worker.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    /// Train episode after episode until paused or done.
    Run,
    /// Stop after the current episode.
    Pause,
    /// Train exactly one episode, then pause.
    OneEpisode,
    /// Start over with a fresh agent from `config` and `seed` (paused).
    Reset {
        /// The hyper-parameters of the new run.
        config: Box<PpoConfig>,
        /// Seeds the agent's weights, its sampling and the environment's first reset.
        seed: u64,
    },
    /// End the thread.
    Quit,
}

/// One finished episode, with what the lessons show beside the update's trace.
#[derive(Debug, Clone)]
pub struct EpisodeData {
    /// The trainer's report (return, steps, the update trace).
    pub report: EpisodeReport,
    /// `π(·|s_t)` for every state of the batch, under the updated actor.
    pub probs: Vec<[f32; 2]>,
    /// Every parameter after the update: `(name, shape, values)`.
    pub weights: Vec<(String, Vec<usize>, Vec<f32>)>,
}

/// What the worker tells the UI.
#[derive(Debug, Clone)]
pub enum WorkerEvent {
    /// An episode and its update finished.
    Episode(Box<EpisodeData>),
    /// The run reached its configured number of episodes.
    Finished,
    /// A fresh agent is ready (after [`Command::Reset`]).
    Reset {
        /// The seed used.
        seed: u64,
    },
    /// Training cannot go on; the message names the episode and the fix.
    Error(String),
}

/// Starts the worker thread with a fresh agent from `config` and `seed`.
#[must_use]
pub fn spawn(
    config: PpoConfig,
    seed: u64,
    commands: Receiver<Command>,
    events: Sender<WorkerEvent>,
) -> JoinHandle<()> {
    std::thread::spawn(move || run(config, seed, &commands, &events))
}

fn run(config: PpoConfig, seed: u64, commands: &Receiver<Command>, events: &Sender<WorkerEvent>) {
    let mut trainer = match Trainer::new(config, seed) {
        Ok(t) => Some(t),
        Err(e) => {
            let _ = events.send(WorkerEvent::Error(e.to_string()));
            None
        }
    };
    let mut running = false;
    let mut one_more = false;
    loop {
        let command = if running || one_more {
            match commands.try_recv() {
                Ok(c) => Some(c),
                Err(TryRecvError::Empty) => None,
                Err(TryRecvError::Disconnected) => return,
            }
        } else {
            match commands.recv() {
                Ok(c) => Some(c),
                Err(_) => return,
            }
        };
        match command {
            Some(Command::Quit) => return,
            Some(Command::Run) => running = true,
            Some(Command::Pause) => running = false,
            Some(Command::OneEpisode) => one_more = true,
            Some(Command::Reset { config, seed }) => {
                running = false;
                one_more = false;
                trainer = match Trainer::new(*config, seed) {
                    Ok(t) => {
                        let _ = events.send(WorkerEvent::Reset { seed });
                        Some(t)
                    }
                    Err(e) => {
                        let _ = events.send(WorkerEvent::Error(e.to_string()));
                        None
                    }
                };
            }
            None => {}
        }
        if !(running || one_more) {
            continue;
        }
        one_more = false;
        let Some(t) = trainer.as_mut() else {
            running = false;
            continue;
        };
        // The policy the episode is played with, before the episode's update changes it.
        let played_with = ActorSnapshot::of(t.agent().actor()).unwrap_or_default();
        match t.next_episode() {
            Ok(Some(report)) => {
                let data = episode_data(t, &played_with, report);
                if events.send(WorkerEvent::Episode(Box::new(data))).is_err() {
                    return;
                }
            }
            Ok(None) => {
                running = false;
                let _ = events.send(WorkerEvent::Finished);
            }
            Err(e) => {
                running = false;
                trainer = None;
                let _ = events.send(WorkerEvent::Error(e.to_string()));
            }
        }
    }
}

/// Gathers what the lessons show beside the trace.
fn episode_data(
    trainer: &Trainer,
    played_with: &ActorSnapshot,
    report: EpisodeReport,
) -> EpisodeData {
    let agent = trainer.agent();
    let probs = crate::lesson::live::probs_over(played_with, &report.trace.states);
    let weights = crate::lesson::live::weights_of(agent);
    EpisodeData {
        report,
        probs,
        weights,
    }
}
