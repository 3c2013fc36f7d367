//! The training worker: runs the PPO on its own thread so the UI never waits on it.
//!
//! The worker owns a live [`Session`] (the engine's job of turning episodes into snapshots);
//! the UI sends [`Command`]s and the worker answers with [`WorkerEvent`]s over a channel,
//! among them the session's [`Snapshot`] after each episode.
//!
//! Errors (a diverged run, invalid settings) travel as events too: a panic in a worker
//! thread would restore the terminal under the running UI.
//!
//! Every event of a run carries the number of the [`Command::Reset`] or [`Command::Switch`]
//! that started it (`run`), so that the app can drop what an earlier run sent before the
//! worker read the command (an episode finished while `r` was pressed).

use std::sync::mpsc::{Receiver, Sender, TryRecvError};
use std::thread::JoinHandle;

use crate::lesson::{RunConfig, Session, Snapshot};
use crate::run::PerAgent;

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
        /// The environment and hyper-parameters of the new run.
        config: Box<RunConfig>,
        /// Seeds the agent's weights, its sampling and the environment's first reset.
        seed: u64,
        /// The app's number for the run from here on: the worker's events carry it.
        run: u64,
    },
    /// Go to `config`'s environment (paused): the current session is kept aside, and the
    /// one kept for that environment, if any, continues where it stopped; otherwise a fresh
    /// agent starts from `config` and `seed`. One live session per environment, so browsing
    /// from a CartPole lesson to a Pendulum one and back loses no training.
    Switch {
        /// The environment and hyper-parameters of a fresh run there.
        config: Box<RunConfig>,
        /// The seed of a fresh run there.
        seed: u64,
        /// The app's number for the run from here on: the worker's events carry it.
        run: u64,
    },
    /// End the thread.
    Quit,
}

/// What the worker tells the UI.
#[derive(Debug, Clone)]
pub enum WorkerEvent {
    /// An episode and its update finished: what the tutor shows after it.
    Episode {
        /// The run it belongs to (see the module's documentation).
        run: u64,
        /// The live values after it.
        snapshot: Box<Snapshot>,
    },
    /// The run reached its configured number of episodes.
    Finished {
        /// The run that finished.
        run: u64,
    },
    /// A fresh agent is ready (after [`Command::Reset`]).
    Reset {
        /// The seed used.
        seed: u64,
    },
    /// The session kept for the environment switched to continues (after
    /// [`Command::Switch`]), after this many episodes.
    Resumed {
        /// Its episodes so far.
        episodes: usize,
    },
    /// Training cannot go on; the message names the episode and the fix.
    Error {
        /// The run that stopped.
        run: u64,
        /// What went wrong.
        message: String,
    },
}

/// Starts the worker thread with a fresh agent from `config` and `seed`.
#[must_use]
pub fn spawn(
    config: impl Into<RunConfig>,
    seed: u64,
    commands: Receiver<Command>,
    events: Sender<WorkerEvent>,
) -> JoinHandle<()> {
    let config = config.into();
    std::thread::spawn(move || run(config, seed, &commands, &events))
}

fn run(config: RunConfig, seed: u64, commands: &Receiver<Command>, events: &Sender<WorkerEvent>) {
    // The app's number of the run being trained (0 until its first reset or switch).
    let mut id = 0;
    let mut session = start(config, seed, id, events);
    // Each other agent's session, kept while its lessons are not open: one slot per agent.
    let mut parked: PerAgent<Option<Session>> = PerAgent::from_fn(|_| None);
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
            Some(Command::Reset { config, seed, run }) => {
                running = false;
                one_more = false;
                id = run;
                session = start(*config, seed, id, events);
                if session.is_some() {
                    let _ = events.send(WorkerEvent::Reset { seed });
                }
            }
            Some(Command::Switch { config, seed, run }) => {
                running = false;
                one_more = false;
                id = run;
                let agent = config.agent();
                if let Some(left) = session.take() {
                    let left_agent = left.snapshot().agent();
                    parked[left_agent] = Some(left);
                }
                session = if let Some(s) = parked[agent].take() {
                    let episodes = s.snapshot().episodes;
                    let _ = events.send(WorkerEvent::Resumed { episodes });
                    Some(s)
                } else {
                    let fresh = start(*config, seed, id, events);
                    if fresh.is_some() {
                        let _ = events.send(WorkerEvent::Reset { seed });
                    }
                    fresh
                };
            }
            None => {}
        }
        if !(running || one_more) {
            continue;
        }
        one_more = false;
        let Some(s) = session.as_mut() else {
            running = false;
            continue;
        };
        match s.next_episode() {
            Ok(Some(snapshot)) => {
                let event = WorkerEvent::Episode {
                    run: id,
                    snapshot: Box::new(snapshot.clone()),
                };
                if events.send(event).is_err() {
                    return;
                }
            }
            Ok(None) => {
                running = false;
                let _ = events.send(WorkerEvent::Finished { run: id });
            }
            Err(e) => {
                running = false;
                session = None;
                let _ = events.send(WorkerEvent::Error {
                    run: id,
                    message: e.to_string(),
                });
            }
        }
    }
}

/// A fresh session, or `None` after sending the reason it could not start (as run `run`).
fn start(config: RunConfig, seed: u64, run: u64, events: &Sender<WorkerEvent>) -> Option<Session> {
    match Session::new(config, seed) {
        Ok(session) => Some(session),
        Err(e) => {
            let _ = events.send(WorkerEvent::Error {
                run,
                message: e.to_string(),
            });
            None
        }
    }
}
