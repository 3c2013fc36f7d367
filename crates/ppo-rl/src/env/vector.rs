//! `CartPoleVec`: N CartPoles stepped together, for throughput.
//!
//! The states are kept as a struct of arrays (`x[i]`, `x_dot[i]`, ...), every
//! environment has its own numpy-compatible generator, and an environment whose
//! episode ends is reset in the same call (its terminal observation is kept in
//! [`VecStep::final_obs`]). Environment `i` of `CartPoleVec::new(config, n, seed)`
//! produces exactly the numbers of a single [`CartPole`](super::CartPole) reset
//! with `Some(seed + i)` and then with `None` after every episode.
//!
//! ```
//! use ppo_rl::env::{CartPoleConfig, CartPoleVec, EnvId};
//! let mut envs = CartPoleVec::new(CartPoleConfig::new(EnvId::CartPoleV1), 8, 0);
//! let out = envs.step(&[1; 8])?;
//! assert_eq!(out.rewards, vec![1.0; 8]);
//! # Ok::<(), ppo_rl::env::EnvError>(())
//! ```
//!
//! [`PendulumVec`] does the same for `Pendulum-v1`: environment `i` equals a single
//! [`Pendulum`](super::Pendulum) reset with `Some(seed + i)`, then `None` after every
//! 200-step episode.

use super::EnvError;
use super::cartpole::{CartPoleConfig, Integrator, accelerations, integrate, is_terminated};
use super::pendulum::{
    MAX_EPISODE_STEPS, PendulumConfig, clip_torque, cost, draw_state, dynamics, observe_trig,
};
use super::seeding::NumpyRng;
use super::sincos::{self, Math, WithMath};

/// What one vector step returns, one entry per environment; `O` is one observation
/// (CartPole's `[f32; 4]` by default, Pendulum's `[f32; 3]`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VecStep<O = [f32; 4]> {
    /// Observations after the step; for an environment that just ended, the first
    /// observation of its next episode.
    pub obs: Vec<O>,
    /// Rewards of this step.
    pub rewards: Vec<f64>,
    /// Whether each environment terminated on this step.
    pub terminated: Vec<bool>,
    /// Whether each environment was truncated by the time limit on this step.
    pub truncated: Vec<bool>,
    /// The terminal observation of each environment that ended on this step (same-step
    /// autoreset; under next-step it is in `obs`).
    pub final_obs: Vec<Option<O>>,
    /// Next-step autoreset: this step reset the environment; its action was ignored, its
    /// reward is 0 and both flags are false. Always false under same-step autoreset.
    pub reset: Vec<bool>,
}

impl<O: Clone> VecStep<O> {
    /// The outputs of `n` environments before their first reset: no observations yet, no
    /// rewards, no ends.
    pub(crate) fn before_reset(n: usize) -> Self {
        Self {
            obs: Vec::new(),
            rewards: vec![0.0; n],
            terminated: vec![false; n],
            truncated: vec![false; n],
            final_obs: vec![None; n],
            reset: vec![false; n],
        }
    }

    /// Forgets the last step's rewards, flags and final observations, as a reset does.
    pub(crate) fn clear_step(&mut self) {
        self.rewards.fill(0.0);
        self.terminated.fill(false);
        self.truncated.fill(false);
        self.final_obs.fill(None);
        self.reset.fill(false);
    }
}

/// The generators of `n` environments as Gymnasium seeds a vector env: environment `i`
/// with `seed + i` (wrapping).
fn seeded_rngs(n: usize, seed: u64) -> Vec<NumpyRng> {
    (0..n as u64)
        .map(|i| NumpyRng::from_seed(seed.wrapping_add(i)))
        .collect()
}

/// N CartPoles with automatic reset, stored as a struct of arrays.
#[derive(Debug, Clone)]
pub struct CartPoleVec {
    config: CartPoleConfig,
    x: Vec<f64>,
    x_dot: Vec<f64>,
    theta: Vec<f64>,
    theta_dot: Vec<f64>,
    elapsed: Vec<u32>,
    rngs: Vec<NumpyRng>,
    sin: Vec<f64>,
    cos: Vec<f64>,
    out: VecStep,
}

impl CartPoleVec {
    /// `n` environments, environment `i` reset with seed `seed + i` (wrapping).
    #[must_use]
    pub fn new(config: CartPoleConfig, n: usize, seed: u64) -> Self {
        let mut envs = Self {
            config,
            x: vec![0.0; n],
            x_dot: vec![0.0; n],
            theta: vec![0.0; n],
            theta_dot: vec![0.0; n],
            elapsed: vec![0; n],
            rngs: seeded_rngs(n, seed),
            sin: vec![0.0; n],
            cos: vec![0.0; n],
            out: VecStep {
                obs: vec![[0.0; 4]; n],
                ..VecStep::before_reset(n)
            },
        };
        for i in 0..n {
            envs.reset_one(i);
        }
        envs
    }

    /// How many environments there are.
    #[must_use]
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True when there are no environments.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// The current observations (after the last step or the initial reset).
    #[must_use]
    pub fn obs(&self) -> &[[f32; 4]] {
        &self.out.obs
    }

    /// The f64 state of environment `i`.
    #[must_use]
    pub fn state(&self, i: usize) -> Option<[f64; 4]> {
        Some([
            *self.x.get(i)?,
            self.x_dot[i],
            self.theta[i],
            self.theta_dot[i],
        ])
    }

    /// Resets every environment, as Gymnasium's `envs.reset(seed=...)`: `Some(s)` reseeds
    /// environment `i` with `s + i` (wrapping), `None` continues each generator.
    pub fn reset_all(&mut self, seed: Option<u64>) {
        if let Some(s) = seed {
            self.rngs = seeded_rngs(self.len(), s);
        }
        for i in 0..self.len() {
            self.reset_one(i);
        }
        self.out.clear_step();
    }

    fn reset_one(&mut self, i: usize) {
        let (low, high) = self.config.reset_bounds;
        let rng = &mut self.rngs[i];
        self.x[i] = rng.uniform(low, high);
        self.x_dot[i] = rng.uniform(low, high);
        self.theta[i] = rng.uniform(low, high);
        self.theta_dot[i] = rng.uniform(low, high);
        self.elapsed[i] = 0;
        self.out.obs[i] = self.obs_of(i);
    }

    fn obs_of(&self, i: usize) -> [f32; 4] {
        [
            self.x[i] as f32,
            self.x_dot[i] as f32,
            self.theta[i] as f32,
            self.theta_dot[i] as f32,
        ]
    }

    /// Steps every environment with its action, resetting those whose episode ends.
    ///
    /// # Errors
    /// [`EnvError::ActionCount`] if `actions.len() != self.len()`;
    /// [`EnvError::InvalidAction`] for an action other than 0 or 1 (nothing is stepped then).
    pub fn step(&mut self, actions: &[usize]) -> Result<&VecStep, EnvError> {
        if actions.len() != self.len() {
            return Err(EnvError::ActionCount {
                expected: self.len(),
                got: actions.len(),
            });
        }
        if let Some(&bad) = actions.iter().find(|&&a| a > 1) {
            return Err(EnvError::InvalidAction(bad));
        }
        let integrator = self.config.integrator;
        let limit = self.config.env_id.max_episode_steps();
        let reward = if self.config.sutton_barto_reward {
            0.0
        } else {
            1.0
        };
        // Three passes so the CPU can overlap independent environments: the sines and
        // cosines, the arithmetic (both vectorised where the inline sin/cos runs), then
        // flags and resets.
        sincos::dispatch(Advance {
            envs: self,
            actions,
            integrator,
        });
        for i in 0..actions.len() {
            let s = [self.x[i], self.x_dot[i], self.theta[i], self.theta_dot[i]];
            let terminated = is_terminated(&s);
            self.elapsed[i] += 1;
            let truncated = self.elapsed[i] >= limit;
            self.out.terminated[i] = terminated;
            self.out.truncated[i] = truncated;
            self.out.rewards[i] = match (terminated, self.config.sutton_barto_reward) {
                (true, true) => -1.0,
                _ => reward,
            };
            if terminated || truncated {
                self.out.final_obs[i] = Some(self.obs_of(i));
                self.reset_one(i);
            } else {
                self.out.final_obs[i] = None;
                self.out.obs[i] = self.obs_of(i);
            }
        }
        Ok(&self.out)
    }
}

/// The physics of one vector step, compiled once per [`Math`].
struct Advance<'a> {
    envs: &'a mut CartPoleVec,
    actions: &'a [usize],
    integrator: Integrator,
}

impl WithMath for Advance<'_> {
    type Output = ();

    #[inline(always)]
    fn run<M: Math>(self, math: M) {
        let e = self.envs;
        math.sin_cos_slice(&e.theta, &mut e.sin, &mut e.cos);
        advance(
            self.actions,
            self.integrator,
            [&mut e.x, &mut e.x_dot, &mut e.theta, &mut e.theta_dot],
            &e.sin,
            &e.cos,
        );
    }
}

/// The arithmetic of a vector step, with the slices as arguments so that the compiler
/// knows they do not overlap (it vectorises the loop only then).
#[inline(always)]
fn advance(
    actions: &[usize],
    integrator: Integrator,
    [x, x_dot, theta, theta_dot]: [&mut [f64]; 4],
    sin: &[f64],
    cos: &[f64],
) {
    let n = actions.len().min(x.len()).min(x_dot.len()).min(theta.len());
    let n = n.min(theta_dot.len()).min(sin.len()).min(cos.len());
    for i in 0..n {
        // Hardware division: it divides four lanes at once here, where the proven guess
        // of `Inline::divide` would branch per lane and stop the vectorising.
        let (xacc, thetaacc) = accelerations(actions[i], theta_dot[i], sin[i], cos[i]);
        let s = [x[i], x_dot[i], theta[i], theta_dot[i]];
        [x[i], x_dot[i], theta[i], theta_dot[i]] = integrate(s, xacc, thetaacc, integrator);
    }
}

/// N Pendulums with automatic reset, stored as a struct of arrays.
///
/// ```
/// use ppo_rl::env::{PendulumConfig, PendulumVec};
/// let mut envs = PendulumVec::new(PendulumConfig::default(), 4, 0);
/// let out = envs.step(&[0.5, -0.5, 2.0, 9.0])?;
/// assert!(out.rewards.iter().all(|&r| r <= 0.0));
/// # Ok::<(), ppo_rl::env::EnvError>(())
/// ```
#[derive(Debug, Clone)]
pub struct PendulumVec {
    config: PendulumConfig,
    theta: Vec<f64>,
    theta_dot: Vec<f64>,
    elapsed: Vec<u32>,
    rngs: Vec<NumpyRng>,
    /// `sin θ` and `cos θ` of the current states (the observations', reused by the step).
    sin: Vec<f64>,
    cos: Vec<f64>,
    out: VecStep<[f32; 3]>,
}

impl PendulumVec {
    /// `n` environments, environment `i` reset with seed `seed + i` (wrapping).
    #[must_use]
    pub fn new(config: PendulumConfig, n: usize, seed: u64) -> Self {
        let mut envs = Self {
            config,
            theta: vec![0.0; n],
            theta_dot: vec![0.0; n],
            elapsed: vec![0; n],
            rngs: seeded_rngs(n, seed),
            sin: vec![0.0; n],
            cos: vec![1.0; n],
            out: VecStep {
                obs: vec![[0.0; 3]; n],
                ..VecStep::before_reset(n)
            },
        };
        for i in 0..n {
            envs.reset_one(i);
        }
        envs
    }

    /// How many environments there are.
    #[must_use]
    pub fn len(&self) -> usize {
        self.theta.len()
    }

    /// True when there are no environments.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.theta.is_empty()
    }

    /// The current observations `[cos θ, sin θ, θ̇]` (after the last step or the initial reset).
    #[must_use]
    pub fn obs(&self) -> &[[f32; 3]] {
        &self.out.obs
    }

    /// The f64 state `[θ, θ̇]` of environment `i`.
    #[must_use]
    pub fn state(&self, i: usize) -> Option<[f64; 2]> {
        Some([*self.theta.get(i)?, self.theta_dot[i]])
    }

    /// Resets every environment, as Gymnasium's `envs.reset(seed=...)`: `Some(s)` reseeds
    /// environment `i` with `s + i` (wrapping), `None` continues each generator.
    pub fn reset_all(&mut self, seed: Option<u64>) {
        if let Some(s) = seed {
            self.rngs = seeded_rngs(self.len(), s);
        }
        for i in 0..self.len() {
            self.reset_one(i);
        }
        self.out.clear_step();
    }

    fn reset_one(&mut self, i: usize) {
        let [theta, theta_dot] = draw_state(&mut self.rngs[i], self.config.reset_high);
        self.theta[i] = theta;
        self.theta_dot[i] = theta_dot;
        (self.sin[i], self.cos[i]) = sincos::sin_cos(theta);
        self.elapsed[i] = 0;
        self.out.obs[i] = self.obs_of(i);
    }

    fn obs_of(&self, i: usize) -> [f32; 3] {
        observe_trig((self.sin[i], self.cos[i]), self.theta_dot[i])
    }

    /// Steps every environment with its torque (clipped to `[-2, 2]`), resetting those
    /// whose episode is truncated (Pendulum never terminates).
    ///
    /// # Errors
    /// [`EnvError::ActionCount`] if `torques.len() != self.len()` (nothing is stepped then).
    pub fn step(&mut self, torques: &[f64]) -> Result<&VecStep<[f32; 3]>, EnvError> {
        if torques.len() != self.len() {
            return Err(EnvError::ActionCount {
                expected: self.len(),
                got: torques.len(),
            });
        }
        let g = self.config.g;
        for (i, &torque) in torques.iter().enumerate() {
            let u = clip_torque(torque);
            let state = [self.theta[i], self.theta_dot[i]];
            self.out.rewards[i] = -cost(state[0], state[1], u);
            [self.theta[i], self.theta_dot[i]] = dynamics(state, u, self.sin[i], g);
        }
        sincos::sin_cos_slice(&self.theta, &mut self.sin, &mut self.cos);
        for i in 0..torques.len() {
            self.elapsed[i] += 1;
            let truncated = self.elapsed[i] >= MAX_EPISODE_STEPS;
            self.out.terminated[i] = false;
            self.out.truncated[i] = truncated;
            if truncated {
                self.out.final_obs[i] = Some(self.obs_of(i));
                self.reset_one(i);
            } else {
                self.out.final_obs[i] = None;
                self.out.obs[i] = self.obs_of(i);
            }
        }
        Ok(&self.out)
    }
}
