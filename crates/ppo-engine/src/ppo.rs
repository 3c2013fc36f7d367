//! The agents, from the RL core ([`ppo_rl::ppo`], every item re-exported here), and the
//! course's two pieces that change and compare their settings:
//!
//! - [`knobs`]: the settings the sandbox changes, one notch at a time ([`knobs::Knob`]).
//! - [`lab`]: the clip lab's experiments, one knob changed at a time over several seeds.

pub use ppo_rl::ppo::*;

pub mod knobs;
pub mod lab;

/// The RL core's trust-region probe ([`ppo_rl::ppo::trust_region`]), and the probe of a
/// live run's snapshot ([`probe_snapshot`](trust_region::probe_snapshot)).
pub mod trust_region {
    pub use crate::lesson::live::probe::probe_snapshot;
    pub use ppo_rl::ppo::trust_region::*;
}
