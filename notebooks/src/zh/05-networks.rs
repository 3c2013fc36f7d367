//! notebooks/zh/05-networks.ipynb 的生成脚本，是 ../05-networks.rs 的中文版（代码相同，注释和打印的文字为中文）。

// %%
use ppo_engine::lesson::Snapshot;
use ppo_engine::notebook::snapshot;
use ppo_engine::ppo::{Agent, NamedWeights, PpoConfig};
// 只训练一个回合：网络（几乎）还是初始化时的样子。
let config: PpoConfig = PpoConfig::default();
let snap: Snapshot = snapshot(config.clone(), 0, 1)?;
let agent: Agent = Agent::new(&config, 0)?;
let weights: NamedWeights = agent.weights()?;

// %% step: Two networks with the same body
for (name, w) in &weights {
    println!("{name:20} {:?}", w.shape);
}

// %% step: PolicyNet ends in a softmax
// 用纯 Rust 手算策略网络：softmax(fc2(relu(fc1(s))))。
fn layer(w: &ppo_engine::ppo::WeightTensor, b: &ppo_engine::ppo::WeightTensor, x: &[f32]) -> Vec<f32> {
    let (out, inp) = (w.shape[0], w.shape[1]);
    (0..out)
        .map(|o| (0..inp).map(|i| w.data[o * inp + i] * x[i]).sum::<f32>() + b.data[o])
        .collect()
}
let s: [f32; 4] = [0.01, -0.02, 0.03, 0.04];
let hidden: Vec<f32> = layer(&weights["actor.fc1.weight"], &weights["actor.fc1.bias"], &s)
    .into_iter()
    .map(|v| v.max(0.0))
    .collect();
let logits = layer(&weights["actor.fc2.weight"], &weights["actor.fc2.bias"], &hidden);
let z: f32 = logits.iter().map(|l| l.exp()).sum();
let by_hand: Vec<f32> = logits.iter().map(|l| l.exp() / z).collect();
let from_agent = agent.probs(&s);
println!("手算：  {by_hand:?}\n智能体：{from_agent:?}");
assert!(by_hand.iter().zip(&from_agent).all(|(a, b)| (a - b).abs() < 1e-6));

// %% step: ValueNet ends in a plain number
let v = agent.value(&s)?;
println!("V(s) = {v:.6}：只有一个数，没有 softmax，正负皆可");

// %% step: How the weights start
// PyTorch 的 nn.Linear 从 U(-1/sqrt(fan_in), 1/sqrt(fan_in)) 中抽取初始权重：检查上下界。
for (name, w) in &weights {
    let fan_in = if name.contains("fc1") { 4.0_f32 } else { config.hidden_dim as f32 };
    let bound = 1.0 / fan_in.sqrt();
    let max = w.data.iter().map(|x| x.abs()).fold(0.0_f32, f32::max);
    println!("{name:20} max |w| = {max:.4} <= {bound:.4}");
    assert!(max <= bound);
}

// %% step: What the untrained networks say
