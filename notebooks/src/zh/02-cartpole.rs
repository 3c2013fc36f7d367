//! notebooks/zh/02-cartpole.ipynb 的生成脚本，是 ../02-cartpole.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::env::{CartPole, EnvId};
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::{cartpole_svg, snapshot};
use ppo_engine::ppo::PpoConfig;
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 30)?;

// %% step: The state: four numbers
// 逐位重现 Gymnasium 的 env.reset(seed=0)：
let mut env = CartPole::new(EnvId::CartPoleV1);
let obs: [f32; 4] = env.reset(Some(0));
println!("[x, x_dot, theta, theta_dot] = {obs:?}");

// %%
cartpole_svg(&obs.map(f64::from))

// %% step: Two actions and the physics step
// 向右推（动作 1）五次，看小车越来越快，杆向后倒去。
for _ in 0..5 {
    let step = env.step(1)?;
    println!("{:?} 奖励 {}", step.obs, step.reward);
}

// %% step: Reset and seeding
// 相同的随机种子给出相同的起点；不给随机种子则沿用原来的随机数生成器，与 Gymnasium 一致。
let a = env.reset(Some(42));
let b = env.reset(None);
let c = env.reset(Some(42));
println!("随机种子 42：{a:?}\n不传种子：   {b:?}\n随机种子 42：{c:?}");
assert_eq!(a, c);

// %% step: One reward per step, the last one too
let mut env = CartPole::new(EnvId::CartPoleV1);
env.reset(Some(0));
let mut total = 0.0;
loop {
    let step = env.step(0)?; // 一直向左推：杆很快就会倒下
    total += step.reward;
    if step.terminated || step.truncated {
        println!("terminated = {}，回报 = {total}", step.terminated);
        break;
    }
}

// %% step: Termination and truncation
use ppo_engine::env::cartpole::{THETA_THRESHOLD_RADIANS, X_THRESHOLD};
println!("终止（terminated）：|x| > {X_THRESHOLD} 或 |θ| > {THETA_THRESHOLD_RADIANS:.4} rad（12°）");
println!("时限中断（truncated）：达到时间上限，CartPole-v1 上为 {} 步", EnvId::CartPoleV1.max_episode_steps());

// %%
// 相反的陷阱：只用 `done = terminated`。这个手写策略把小车推向杆正在倒下的一侧，
// 从而让杆一直立着；只等待 `terminated` 的循环会越过时间上限继续跑下去
// （这里在 2000 步时停下）。
fn balance(obs: [f32; 4]) -> usize {
    usize::from(0.05 * obs[0] + 0.1 * obs[1] + obs[2] + 0.5 * obs[3] > 0.0)
}
let mut env = CartPole::new(EnvId::CartPoleV1);
let mut obs = env.reset(Some(0));
let mut episode_return = 0.0;
let mut truncated_at: Option<usize> = None;
for t in 1..=2000 {
    let step = env.step(balance(obs))?;
    episode_return += step.reward;
    obs = step.obs;
    if step.truncated && truncated_at.is_none() {
        truncated_at = Some(t);
    }
    if step.terminated {
        break;
    }
}
println!("第一次因时限中断发生在第 {truncated_at:?} 步；循环继续跑下去，回报一直累积到 {episode_return}");
assert!(episode_return > 500.0);

// %% step: CartPole-v0 and CartPole-v1
for id in EnvId::ALL {
    println!("{}：在 {} 步时因时限中断", id.as_str(), id.max_episode_steps());
}
