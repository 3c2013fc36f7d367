//! Recipe for notebooks/03-episode-loop.ipynb (see 01-what-is-ppo.rs for the format).

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("30 episodes were trained").trace.clone();

// %% step: Ten iterations of fifty episodes
println!(
    "{} episodes = 10 progress bars of {} episodes; trained so far: {}",
    config.num_episodes,
    config.num_episodes / 10,
    snap.episodes
);

// %% step: take_action: sampling, not choosing the best
// How often did the agent take the action it thought less likely?
let against = trace
    .actions
    .iter()
    .zip(&snap.cartpole_update().expect("a trained CartPole run").probs)
    .filter(|(a, p)| p[**a] < 0.5)
    .count();
println!("{against} of {} actions were the less likely one: sampling explores", trace.actions.len());

// %% step: Stepping the environment
// %% step: transition_dict: one episode in five lists
println!(
    "states {}, actions {}, rewards {}, next_states {}, dones {}",
    trace.states.len(),
    trace.actions.len(),
    trace.rewards.len(),
    trace.next_states.len(),
    trace.dones.len()
);
// next_states is states shifted by one step:
assert_eq!(&trace.states[1..], &trace.next_states[..trace.next_states.len() - 1]);

// %% step: One update per episode
// %% exercise
