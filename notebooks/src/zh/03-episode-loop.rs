//! notebooks/zh/03-episode-loop.ipynb 的生成脚本，是 ../03-episode-loop.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{PpoConfig, UpdateTrace};
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;
let trace: UpdateTrace = snap.cartpole_update().expect("已训练 30 个回合").trace.clone();

// %% step: Ten iterations of fifty episodes
println!(
    "{} 个回合 = 10 个进度条，每个 {} 个回合；目前已训练：{}",
    config.num_episodes,
    config.num_episodes / 10,
    snap.episodes
);

// %% step: take_action: sampling, not choosing the best
// 智能体有多少次选了它自己给出的概率较小的那个动作？
let against = trace
    .actions
    .iter()
    .zip(&snap.cartpole_update().expect("一次训练过的 CartPole 运行").probs)
    .filter(|(a, p)| p[**a] < 0.5)
    .count();
println!("{against} 个动作（共 {} 个）选的是概率较小的那个：采样带来了探索", trace.actions.len());

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
// next_states 就是 states 错开一步：
assert_eq!(&trace.states[1..], &trace.next_states[..trace.next_states.len() - 1]);

// %% step: One update per episode
// %% exercise
