//! The RL core's tests in one binary (each links candle once; `cargo test -p ppo-rl` runs
//! them alone): the native CartPole-v1 and
//! Pendulum-v1 against Gymnasium (bit for bit), the vector CartPole against Gymnasium's
//! `SyncVectorEnv` in both autoreset modes, their invariants, the inline sin/cos and
//! the fast division against libm and IEEE, the PPO updates (PPO-Clip and PPO-Penalty on
//! CartPole, PPOContinuous on Pendulum) against PyTorch, and learning. The recorded
//! references are the project's, in `tests/fixtures/` at the workspace root.

mod parity_cartpole;
mod parity_pendulum;
mod parity_ppo;
mod parity_ppo_continuous;
mod parity_ppo_penalty;
mod parity_rliable;
mod parity_vector;
mod props_cartpole;
mod quotient;
mod sincos;
mod train_ppo;
