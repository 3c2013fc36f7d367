//! Gymnasium 1.4.0's `Pendulum-v1`, bit for bit.
//!
//! State `s = (θ, θ̇)` in f64, `θ = 0` upright and never wrapped; the action is one
//! torque `u`, clipped to `[−2, 2]` and used as f64. One step of `dt = 0.05` s, with
//! the reward computed from the state *before* the step:
//!
//! ```text
//! reward = −(angle_normalize(θ)² + 0.1·θ̇² + 0.001·u²)
//! θ̇'     = clip(θ̇ + (3g/(2l)·sin θ + 3/(m·l²)·u)·dt, −8, 8)
//! θ'     = θ + θ̇'·dt
//! obs    = f32 [cos θ', sin θ', θ̇']
//! ```
//!
//! with `angle_normalize(x) = ((x + π) mod 2π) − π` and Python's floored `mod`. The
//! episode never terminates; Gymnasium's `TimeLimit` truncates it after 200 steps. A
//! reset draws `θ ~ U(−π, π)` then `θ̇ ~ U(−1, 1)` from the same numpy generator as
//! CartPole ([`super::seeding`]).
//!
//! Three details make the numbers Gymnasium's, bit for bit:
//! - `np.sin`/`np.cos` of a float64 are libm's `sin`/`cos`: numpy 2.4's float64 loops
//!   call them on x86-64-v3 CPUs (the fixture's), and [`super::sincos::sin_cos`] gives
//!   those bits for every angle, far outside `[−π, π]` too. (On x86-64-v4, AVX-512,
//!   numpy switches to Intel's SVML, which the fixture does not cover.)
//! - `x**2` of a numpy float64 is libm's `pow(x, 2.0)`, which is not always `x * x`
//!   (glibc's `pow` is not correctly rounded): [`numpy_square`] calls `pow`.
//! - `%` is Python's floored modulo: [`floored_mod`].
//!
//! ```
//! use ppo_rl::env::Pendulum;
//! let mut env = Pendulum::new();
//! let obs = env.reset(Some(0));
//! assert!((obs[0] * obs[0] + obs[1] * obs[1] - 1.0).abs() < 1e-6);
//! let step = env.step(0.5)?;
//! assert!(step.reward <= 0.0 && !step.terminated);
//! # Ok::<(), ppo_rl::env::EnvError>(())
//! ```

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use super::EnvError;
use super::seeding::NumpyRng;
use super::sincos::sin_cos;

/// The Gymnasium id this environment reproduces.
pub const ENV_ID: &str = "Pendulum-v1";
/// Gymnasium's default gravity `g`, m/s².
pub const DEFAULT_GRAVITY: f64 = 10.0;
/// Mass of the pendulum `m`, kg.
pub const MASS: f64 = 1.0;
/// Length of the pendulum `l`, m.
pub const LENGTH: f64 = 1.0;
/// Seconds per step `dt`.
pub const DT: f64 = 0.05;
/// The angular velocity is clipped to `±MAX_SPEED`, rad/s.
pub const MAX_SPEED: f64 = 8.0;
/// The torque is clipped to `±MAX_TORQUE`, N·m.
pub const MAX_TORQUE: f64 = 2.0;
/// The `TimeLimit` wrapper's `max_episode_steps`.
pub const MAX_EPISODE_STEPS: u32 = 200;
/// Gymnasium's default reset bounds `[x_init, y_init]`: `θ ~ U(−π, π)`, `θ̇ ~ U(−1, 1)`.
pub const DEFAULT_RESET_HIGH: [f64; 2] = [PI, 1.0];

/// Everything that makes one Pendulum differ from another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumConfig {
    /// Gravity, as `gymnasium.make("Pendulum-v1", g=...)`.
    pub g: f64,
    /// Reset bounds `[x_init, y_init]` (`options={"x_init": .., "y_init": ..}`): `θ` is drawn
    /// from `U(−x_init, x_init)` and `θ̇` from `U(−y_init, y_init)`.
    pub reset_high: [f64; 2],
}

impl Default for PendulumConfig {
    fn default() -> Self {
        Self {
            g: DEFAULT_GRAVITY,
            reset_high: DEFAULT_RESET_HIGH,
        }
    }
}

/// What one `step` returns: Gymnasium's `(obs, reward, terminated, truncated)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendulumStep {
    /// `[cos θ, sin θ, θ̇]` of the new state, each computed in f64 and cast to f32.
    pub obs: [f32; 3],
    /// `−cost` of the state before the step and the clipped torque (at most 0).
    pub reward: f64,
    /// Always false: the pendulum has no terminal state.
    pub terminated: bool,
    /// The time limit (200 steps) was reached.
    pub truncated: bool,
}

/// numpy's `x ** 2` for a float64 scalar: libm's `pow(x, 2.0)`, which differs from `x * x`
/// in the last bit for about one `x` in 1,300 (glibc's `pow` is accurate to 0.52 ulp, not
/// correctly rounded).
#[must_use]
#[inline]
pub fn numpy_square(x: f64) -> f64 {
    // The opaque exponent keeps LLVM from rewriting `pow(x, 2.0)` as `x * x`.
    x.powf(std::hint::black_box(2.0))
}

/// Python's (and numpy's) floored `a % b`: the result has the sign of `b`.
///
/// `fmod` (Rust's `%`, exact), then `b` added when the signs differ; a zero result
/// takes the sign of `b`. The same steps as CPython's `float_rem` and numpy's `npy_divmod`.
#[must_use]
#[inline]
pub fn floored_mod(a: f64, b: f64) -> f64 {
    let m = a % b;
    if m != 0.0 {
        if (b < 0.0) != (m < 0.0) { m + b } else { m }
    } else {
        0.0_f64.copysign(b)
    }
}

/// Gymnasium's `angle_normalize`: `((x + π) % (2π)) − π`, in `[−π, π)`.
#[must_use]
#[inline]
pub fn angle_normalize(x: f64) -> f64 {
    floored_mod(x + PI, 2.0 * PI) - PI
}

/// The torque Gymnasium applies: `np.clip(u, −2, 2)` (NaN stays NaN).
#[must_use]
#[inline]
pub fn clip_torque(torque: f64) -> f64 {
    torque.clamp(-MAX_TORQUE, MAX_TORQUE)
}

// ANCHOR: cost
/// The cost of being in `(θ, θ̇)` and applying the (clipped) torque `u`; the reward is
/// its negation. Same order of operations as Gymnasium, with numpy's squares.
#[must_use]
#[inline]
pub fn cost(theta: f64, theta_dot: f64, u: f64) -> f64 {
    numpy_square(angle_normalize(theta)) + 0.1 * numpy_square(theta_dot) + 0.001 * numpy_square(u)
}
// ANCHOR_END: cost

// ANCHOR: dynamics
/// One step of the dynamics from `state` under the clipped torque `u`, given `sin θ`
/// (as [`sin_cos`] computes it) and gravity `g`.
#[must_use]
#[inline]
pub fn dynamics(state: [f64; 2], u: f64, sin_theta: f64, g: f64) -> [f64; 2] {
    let [th, thdot] = state;
    let newthdot =
        thdot + (3.0 * g / (2.0 * LENGTH) * sin_theta + 3.0 / (MASS * (LENGTH * LENGTH)) * u) * DT;
    let newthdot = newthdot.clamp(-MAX_SPEED, MAX_SPEED);
    let newth = th + newthdot * DT;
    [newth, newthdot]
}
// ANCHOR_END: dynamics

/// [`dynamics`] with the raw torque, computing `sin θ` itself: `(next state, reward)`.
#[must_use]
pub fn physics(state: [f64; 2], torque: f64, g: f64) -> ([f64; 2], f64) {
    let u = clip_torque(torque);
    let reward = -cost(state[0], state[1], u);
    let (sin_theta, _) = sin_cos(state[0]);
    (dynamics(state, u, sin_theta, g), reward)
}

/// The f32 observation Gymnasium returns for an f64 state: `[cos θ, sin θ, θ̇]`.
#[must_use]
pub fn observe(state: &[f64; 2]) -> [f32; 3] {
    observe_trig(sin_cos(state[0]), state[1])
}

/// The observation from `(sin θ, cos θ)` and `θ̇`, each rounded to f32 once.
#[must_use]
#[inline]
pub fn observe_trig((sin_theta, cos_theta): (f64, f64), theta_dot: f64) -> [f32; 3] {
    [cos_theta as f32, sin_theta as f32, theta_dot as f32]
}

/// A native Pendulum, equal to `gymnasium.make("Pendulum-v1")` (with its `TimeLimit`).
#[derive(Debug, Clone)]
pub struct Pendulum {
    config: PendulumConfig,
    state: Option<[f64; 2]>,
    /// `(sin θ, cos θ)` of the current state: the observation's, reused by the next step.
    trig: (f64, f64),
    rng: Option<NumpyRng>,
    elapsed_steps: u32,
}

impl Default for Pendulum {
    fn default() -> Self {
        Self::new()
    }
}

impl Pendulum {
    /// A Pendulum with Gymnasium's defaults. Call [`Pendulum::reset`] before stepping.
    #[must_use]
    pub fn new() -> Self {
        Self::with_config(PendulumConfig::default())
    }

    /// A Pendulum with explicit options.
    #[must_use]
    pub fn with_config(config: PendulumConfig) -> Self {
        Self {
            config,
            state: None,
            trig: (0.0, 1.0),
            rng: None,
            elapsed_steps: 0,
        }
    }

    /// The options this environment was built with.
    #[must_use]
    pub fn config(&self) -> &PendulumConfig {
        &self.config
    }

    /// Gymnasium's `reset(seed=seed)`: a seed re-creates the generator; `None` continues it
    /// (or, on the very first reset, seeds it from OS entropy as Gymnasium does).
    pub fn reset(&mut self, seed: Option<u64>) -> [f32; 3] {
        let rng = match (seed, self.rng.take()) {
            (Some(s), _) => NumpyRng::from_seed(s),
            (None, Some(rng)) => rng,
            (None, None) => NumpyRng::from_seed(rand::random()),
        };
        let rng = self.rng.insert(rng);
        let state = draw_state(rng, self.config.reset_high);
        self.state = Some(state);
        self.trig = sin_cos(state[0]);
        self.elapsed_steps = 0;
        observe_trig(self.trig, state[1])
    }

    /// Gymnasium's `step([torque])` through the `TimeLimit` wrapper. The torque is clipped
    /// to `[−2, 2]`; like Gymnasium, a NaN torque is not refused (the state becomes NaN).
    ///
    /// # Errors
    /// [`EnvError::NotReset`] before the first reset.
    pub fn step(&mut self, torque: f64) -> Result<PendulumStep, EnvError> {
        let state = self.state.ok_or(EnvError::NotReset)?;
        let u = clip_torque(torque);
        let reward = -cost(state[0], state[1], u);
        let next = dynamics(state, u, self.trig.0, self.config.g);
        self.trig = sin_cos(next[0]);
        self.state = Some(next);
        self.elapsed_steps = self.elapsed_steps.saturating_add(1);
        Ok(PendulumStep {
            obs: observe_trig(self.trig, next[1]),
            reward,
            terminated: false,
            truncated: self.elapsed_steps >= MAX_EPISODE_STEPS,
        })
    }

    /// The f64 internal state `[θ, θ̇]` (`env.unwrapped.state`), `None` before the first reset.
    #[must_use]
    pub fn state(&self) -> Option<[f64; 2]> {
        self.state
    }

    /// Steps taken since the last reset (the `TimeLimit`'s `_elapsed_steps`).
    #[must_use]
    pub fn elapsed_steps(&self) -> u32 {
        self.elapsed_steps
    }
}

/// `np_random.uniform(low=-high, high=high)` for `[θ, θ̇]`, in that order.
pub(crate) fn draw_state(rng: &mut NumpyRng, [x_init, y_init]: [f64; 2]) -> [f64; 2] {
    let theta = rng.uniform(-x_init, x_init);
    let theta_dot = rng.uniform(-y_init, y_init);
    [theta, theta_dot]
}

/// One Pendulum episode, in the schema of the Gymnasium fixture traces
/// (`tests/fixtures/pendulum_gymnasium.json`) and of `ppo-tutor pendulum --json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PendulumTrajectory {
    /// The seed given to `reset`.
    pub seed: u64,
    /// The f64 state `[θ, θ̇]` after `reset(seed)`.
    pub reset_state: [f64; 2],
    /// The f32 observation after `reset(seed)`, widened to f64.
    pub reset_obs: [f64; 3],
    /// The torques applied, as given (before clipping).
    pub actions: Vec<f64>,
    /// The f64 state after each step.
    pub states: Vec<[f64; 2]>,
    /// The f32 observation after each step, widened to f64.
    pub obs: Vec<[f64; 3]>,
    /// The reward of each step.
    pub rewards: Vec<f64>,
    /// `terminated` of each step (always false).
    pub terminated: Vec<bool>,
    /// `truncated` of each step.
    pub truncated: Vec<bool>,
    /// States of further unseeded resets, when asked for.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub next_resets: Vec<[f64; 2]>,
}

impl PendulumTrajectory {
    /// Resets a Pendulum with `seed`, applies `torques` in order until they run out or the
    /// time limit truncates the episode, then performs `extra_resets` unseeded resets and
    /// records their states.
    ///
    /// # Errors
    /// [`EnvError::NotReset`] only if the environment lost its state (never expected).
    pub fn record(
        config: PendulumConfig,
        seed: u64,
        torques: &[f64],
        extra_resets: usize,
    ) -> Result<Self, EnvError> {
        let mut env = Pendulum::with_config(config);
        let reset_obs = env.reset(Some(seed));
        let mut t = PendulumTrajectory {
            seed,
            reset_state: env.state().ok_or(EnvError::NotReset)?,
            reset_obs: reset_obs.map(f64::from),
            actions: Vec::new(),
            states: Vec::new(),
            obs: Vec::new(),
            rewards: Vec::new(),
            terminated: Vec::new(),
            truncated: Vec::new(),
            next_resets: Vec::new(),
        };
        for &torque in torques {
            let step = env.step(torque)?;
            t.actions.push(torque);
            t.states.push(env.state().ok_or(EnvError::NotReset)?);
            t.obs.push(step.obs.map(f64::from));
            t.rewards.push(step.reward);
            t.terminated.push(step.terminated);
            t.truncated.push(step.truncated);
            if step.terminated || step.truncated {
                break;
            }
        }
        for _ in 0..extra_resets {
            env.reset(None);
            t.next_resets.push(env.state().ok_or(EnvError::NotReset)?);
        }
        Ok(t)
    }

    /// The episode's return (sum of rewards).
    #[must_use]
    pub fn episode_return(&self) -> f64 {
        self.rewards.iter().sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_before_reset_is_an_error() {
        assert!(matches!(Pendulum::new().step(0.0), Err(EnvError::NotReset)));
    }

    #[test]
    fn floored_mod_follows_python() {
        // Values from CPython: -1.0 % 3.0 == 2.0, 1.0 % -3.0 == -2.0, -3.0 % 3.0 == 0.0,
        // 3.0 % -3.0 == -0.0, 5.5 % 2.0 == 1.5.
        assert_eq!(floored_mod(-1.0, 3.0), 2.0);
        assert_eq!(floored_mod(1.0, -3.0), -2.0);
        assert_eq!(floored_mod(-3.0, 3.0).to_bits(), 0.0_f64.to_bits());
        assert_eq!(floored_mod(3.0, -3.0).to_bits(), (-0.0_f64).to_bits());
        assert_eq!(floored_mod(5.5, 2.0), 1.5);
        assert!(floored_mod(f64::NAN, 2.0).is_nan());
    }

    #[test]
    fn angles_normalize_into_minus_pi_to_pi() {
        for k in -50..50 {
            let x = f64::from(k) * 0.37;
            let a = angle_normalize(x);
            assert!((-PI..PI).contains(&a), "{x} -> {a}");
            assert!((((x - a) / (2.0 * PI)).round() * 2.0 * PI - (x - a)).abs() < 1e-9);
        }
        assert_eq!(angle_normalize(PI), -PI);
    }

    #[test]
    fn numpy_square_is_libm_pow() {
        // 0x1.03bbb9088a7p-3 ** 2 in numpy 2.4.6 (glibc 2.36) is 0x1.0785620f20564p-6,
        // one ulp above the correctly rounded x * x.
        let x = f64::from_bits(0x3fc0_3bbb_9088_a700);
        assert_eq!(numpy_square(x).to_bits(), 0x3f90_7856_20f2_0564);
        assert_eq!((x * x).to_bits(), 0x3f90_7856_20f2_0563);
    }

    #[test]
    fn rewards_use_numpy_squares() {
        // Recorded with Gymnasium 1.4.0 (numpy 2.4.6, glibc 2.36): `env.unwrapped.state =
        // np.array([th, thd])`, then `env.step([u])[1]`. With `x * x` for the squares each
        // reward comes out one ulp off.
        for (th, thd, u, want) in [
            (
                1.77878149736088,
                -7.528624350774189,
                0.9000266308969094,
                -8.832892124796746,
            ),
            (
                -1.3885674974018327,
                -4.338834189050683,
                -0.15685606762210957,
                -3.8106925106742486,
            ),
            (
                -2.5473586437770184,
                1.275474665620136,
                0.7776074604408634,
                -6.652324295651903,
            ),
        ] {
            assert_eq!(
                (-cost(th, thd, u)).to_bits(),
                f64::to_bits(want),
                "{th} {thd} {u}"
            );
            let a = angle_normalize(th);
            let naive = -(a * a + 0.1 * (thd * thd) + 0.001 * (u * u));
            assert_ne!(naive.to_bits(), f64::to_bits(want));
        }
    }

    #[test]
    fn torque_is_clipped_and_speed_is_limited() -> Result<(), EnvError> {
        let mut a = Pendulum::new();
        let mut b = Pendulum::new();
        a.reset(Some(4));
        b.reset(Some(4));
        for _ in 0..60 {
            let sa = a.step(7.5)?;
            let sb = b.step(2.0)?;
            assert_eq!(sa.obs, sb.obs);
            assert_eq!(sa.reward.to_bits(), sb.reward.to_bits());
            let [_, thdot] = a.state().ok_or(EnvError::NotReset)?;
            assert!(thdot.abs() <= MAX_SPEED);
        }
        Ok(())
    }

    #[test]
    fn truncates_at_200_and_never_terminates() -> Result<(), EnvError> {
        let mut env = Pendulum::new();
        env.reset(Some(0));
        for i in 1..=MAX_EPISODE_STEPS {
            let step = env.step(-1.0)?;
            assert!(!step.terminated);
            assert_eq!(step.truncated, i == MAX_EPISODE_STEPS, "step {i}");
        }
        Ok(())
    }

    #[test]
    fn step_equals_physics() -> Result<(), EnvError> {
        let mut env = Pendulum::new();
        env.reset(Some(11));
        let mut rng = NumpyRng::from_seed(3);
        for _ in 0..1000 {
            let before = env.state().ok_or(EnvError::NotReset)?;
            let torque = rng.uniform(-3.0, 3.0);
            let step = env.step(torque)?;
            let (want, reward) = physics(before, torque, DEFAULT_GRAVITY);
            let got = env.state().ok_or(EnvError::NotReset)?;
            assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
            assert_eq!(step.reward.to_bits(), reward.to_bits());
            assert_eq!(step.obs, observe(&got));
            if step.truncated {
                env.reset(None);
            }
        }
        Ok(())
    }
}
