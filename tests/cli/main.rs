//! The command line, run as a user runs it (the built binary), in one test binary: the
//! lessons and exercise commands, training, replay and checkpoints of both agents, and
//! their errors; and the READMEs' pictures `dev screenshots` draws.

mod common;

mod commands;
mod help_zh;
mod parity;
mod pendulum;
mod pendulum_learns;
mod pendulum_train;
mod ppo;
mod screenshots;
mod trust_region;
mod vector;
mod zh_output;
