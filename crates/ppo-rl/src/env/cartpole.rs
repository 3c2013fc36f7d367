//! Gymnasium 1.4.0's `CartPole-v1` (and `-v0`), bit for bit.
//!
//! State `s = (x, ẋ, θ, θ̇)` in f64; action 0 pushes left, 1 pushes right with
//! `F = ±10 N`. One step of 0.02 s:
//!
//! ```text
//! temp = (F + m_p·l·θ̇²·sin θ) / (m_c + m_p)
//! θ̈    = (g·sin θ − cos θ·temp) / (l·(4/3 − m_p·cos²θ / (m_c + m_p)))
//! ẍ    = temp − m_p·l·θ̈·cos θ / (m_c + m_p)
//! ```
//!
//! then explicit Euler (`x += τ·ẋ; ẋ += τ·ẍ; θ += τ·θ̇; θ̇ += τ·θ̈`) or, as an
//! option, semi-implicit Euler. Every expression keeps Gymnasium's left-to-right
//! order and no multiply-add is fused, so the f64 states equal Gymnasium's exactly.
//! `sin θ` and `cos θ` are libm's, bit for bit (computed inline where that is proven
//! equal: see [`super::sincos`]).
//! The episode terminates when `|x| > 2.4` or `|θ| > 12°` (decided on the f64
//! state) and is truncated by the time limit (500 steps for v1, 200 for v0).
//!
//! ```
//! use ppo_rl::env::{CartPole, EnvId};
//! let mut env = CartPole::new(EnvId::CartPoleV1);
//! let obs = env.reset(Some(0));
//! assert!(obs.iter().all(|v| v.abs() < 0.05));
//! let step = env.step(1)?;
//! assert_eq!(step.reward, 1.0);
//! # Ok::<(), ppo_rl::env::EnvError>(())
//! ```

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use super::EnvError;
use super::quotient::Divisor;
use super::seeding::NumpyRng;
use super::sincos::{self, Math, Portable, WithMath, sin_cos};

/// Gravity, m/s².
pub const GRAVITY: f64 = 9.8;
/// Mass of the cart, kg.
pub const MASS_CART: f64 = 1.0;
/// Mass of the pole, kg.
pub const MASS_POLE: f64 = 0.1;
/// Total mass, computed as Gymnasium does (`masspole + masscart`).
pub const TOTAL_MASS: f64 = MASS_POLE + MASS_CART;
/// Half the pole's length, m.
pub const LENGTH: f64 = 0.5;
/// `masspole * length`.
pub const POLEMASS_LENGTH: f64 = MASS_POLE * LENGTH;
/// [`TOTAL_MASS`] as a divisor for [`Math::divide`].
const BY_TOTAL_MASS: Divisor = Divisor::new(TOTAL_MASS);
/// Magnitude of the push, N.
pub const FORCE_MAG: f64 = 10.0;
/// Seconds between state updates.
pub const TAU: f64 = 0.02;
/// The pole angle beyond which the episode terminates: 12° in radians, as `12 * 2 * pi / 360`.
pub const THETA_THRESHOLD_RADIANS: f64 = 12.0 * 2.0 * PI / 360.0;
/// The cart position beyond which the episode terminates, m.
pub const X_THRESHOLD: f64 = 2.4;
/// Gymnasium's default reset bounds: each state variable is drawn from `U(-0.05, 0.05)`.
pub const DEFAULT_RESET_BOUNDS: (f64, f64) = (-0.05, 0.05);

/// The Gymnasium environment ids this CartPole reproduces.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum EnvId {
    /// `CartPole-v1`: 500-step time limit (reward threshold 475).
    #[default]
    CartPoleV1,
    /// `CartPole-v0`: 200-step time limit (reward threshold 195).
    CartPoleV0,
}

impl EnvId {
    /// Every supported id, in the order help text lists them.
    pub const ALL: [EnvId; 2] = [EnvId::CartPoleV1, EnvId::CartPoleV0];

    /// The id as Gymnasium spells it.
    #[must_use]
    pub fn as_str(self) -> &'static str {
        match self {
            EnvId::CartPoleV1 => "CartPole-v1",
            EnvId::CartPoleV0 => "CartPole-v0",
        }
    }

    /// The `TimeLimit` wrapper's `max_episode_steps`.
    #[must_use]
    pub fn max_episode_steps(self) -> u32 {
        match self {
            EnvId::CartPoleV1 => 500,
            EnvId::CartPoleV0 => 200,
        }
    }
}

impl fmt::Display for EnvId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for EnvId {
    type Err = EnvError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        EnvId::ALL
            .into_iter()
            .find(|id| id.as_str() == s)
            .ok_or_else(|| EnvError::UnknownEnv(s.to_string()))
    }
}

/// How positions and velocities are advanced each step (Gymnasium's `kinematics_integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// Explicit Euler: positions move with the old velocities (Gymnasium's default).
    #[default]
    Euler,
    /// Semi-implicit Euler: velocities first, then positions with the new velocities.
    SemiImplicitEuler,
}

/// Everything that makes one CartPole differ from another.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CartPoleConfig {
    /// Which Gymnasium id (sets the time limit).
    pub env_id: EnvId,
    /// The integration scheme.
    pub integrator: Integrator,
    /// Gymnasium's `sutton_barto_reward`: 0 per surviving step, -1 on failure.
    pub sutton_barto_reward: bool,
    /// Reset bounds `(low, high)`, as Gymnasium's `options={"low": .., "high": ..}`.
    pub reset_bounds: (f64, f64),
}

impl Default for CartPoleConfig {
    fn default() -> Self {
        Self::new(EnvId::default())
    }
}

impl CartPoleConfig {
    /// Gymnasium's defaults for `env_id`.
    #[must_use]
    pub fn new(env_id: EnvId) -> Self {
        Self {
            env_id,
            integrator: Integrator::Euler,
            sutton_barto_reward: false,
            reset_bounds: DEFAULT_RESET_BOUNDS,
        }
    }
}

/// What one `step` returns: Gymnasium's `(obs, reward, terminated, truncated)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The f32 cast of the new internal state.
    pub obs: [f32; 4],
    /// 1.0 for every step, including the one that terminates (see `sutton_barto_reward`).
    pub reward: f64,
    /// The pole fell or the cart left the track.
    pub terminated: bool,
    /// The time limit was reached (may be true together with `terminated`).
    pub truncated: bool,
    /// Set on the first step taken after termination, as Gymnasium warns once.
    pub warning: Option<&'static str>,
}

/// The warning Gymnasium logs when `step` is called after `terminated = True`.
pub const STEP_AFTER_TERMINATED: &str = "You are calling 'step()' even though this environment has already returned terminated = True. You should always call 'reset()' once you receive 'terminated = True' -- any further steps are undefined behavior.";

// ANCHOR: physics
/// One physics step from `state` under `action` (0 = left, 1 = right), in Gymnasium's
/// exact operation order.
#[must_use]
#[inline]
pub fn physics(state: [f64; 4], action: usize, integrator: Integrator) -> [f64; 4] {
    // Python's math.sin and math.cos, bit for bit (see env::sincos).
    let (sintheta, costheta) = sin_cos(state[2]);
    let (xacc, thetaacc) = accelerations(action, state[3], sintheta, costheta);
    integrate(state, xacc, thetaacc, integrator)
}

/// The cart's and the pole's accelerations `(ẍ, θ̈)`, given `sin θ` and `cos θ`.
#[must_use]
#[inline]
pub fn accelerations(action: usize, theta_dot: f64, sintheta: f64, costheta: f64) -> (f64, f64) {
    accelerations_with(Portable, action, theta_dot, sintheta, costheta)
}

/// [`accelerations`], dividing with `math` (the same bits, faster with FMA).
#[must_use]
#[inline(always)]
fn accelerations_with<M: Math>(
    math: M,
    action: usize,
    theta_dot: f64,
    sintheta: f64,
    costheta: f64,
) -> (f64, f64) {
    let force = if action == 1 { FORCE_MAG } else { -FORCE_MAG };
    // `/ TOTAL_MASS`, rounded as Python rounds it; with FMA, faster (see env::quotient).
    let temp = math.divide(
        force + POLEMASS_LENGTH * (theta_dot * theta_dot) * sintheta,
        BY_TOTAL_MASS,
    );
    let thetaacc = (GRAVITY * sintheta - costheta * temp)
        / (LENGTH * (4.0 / 3.0 - MASS_POLE * (costheta * costheta) / TOTAL_MASS));
    let xacc = temp - POLEMASS_LENGTH * thetaacc * costheta / TOTAL_MASS;
    (xacc, thetaacc)
}

/// Advances `state` by one time step `τ` with the given accelerations.
#[must_use]
#[inline]
pub fn integrate(state: [f64; 4], xacc: f64, thetaacc: f64, integrator: Integrator) -> [f64; 4] {
    let [mut x, mut x_dot, mut theta, mut theta_dot] = state;
    match integrator {
        Integrator::Euler => {
            x += TAU * x_dot;
            x_dot += TAU * xacc;
            theta += TAU * theta_dot;
            theta_dot += TAU * thetaacc;
        }
        Integrator::SemiImplicitEuler => {
            x_dot += TAU * xacc;
            x += TAU * x_dot;
            theta_dot += TAU * thetaacc;
            theta += TAU * theta_dot;
        }
    }
    [x, x_dot, theta, theta_dot]
}
// ANCHOR_END: physics

// ANCHOR: termination
/// Gymnasium's termination test, on the f64 state.
#[must_use]
#[inline]
#[allow(clippy::manual_range_contains)] // Gymnasium's exact comparisons (NaN included)
pub fn is_terminated(state: &[f64; 4]) -> bool {
    let [x, _, theta, _] = *state;
    x < -X_THRESHOLD
        || x > X_THRESHOLD
        || theta < -THETA_THRESHOLD_RADIANS
        || theta > THETA_THRESHOLD_RADIANS
}
// ANCHOR_END: termination

/// The f32 observation Gymnasium returns for an f64 state.
#[must_use]
#[inline]
pub fn observe(state: &[f64; 4]) -> [f32; 4] {
    state.map(|v| v as f32)
}

/// Gymnasium's reward for a step, given how many steps the episode has gone past termination.
#[inline]
fn reward(terminated: bool, steps_beyond: Option<u32>, sutton_barto: bool) -> f64 {
    match (terminated, steps_beyond, sutton_barto) {
        (false, _, false) => 1.0,
        (false, _, true) => 0.0,
        (true, None, false) => 1.0,
        (true, _, true) => -1.0,
        (true, Some(_), false) => 0.0,
    }
}

/// A native CartPole, equal to `gymnasium.make("CartPole-v1")` (with its `TimeLimit`).
#[derive(Debug, Clone)]
pub struct CartPole {
    config: CartPoleConfig,
    state: Option<[f64; 4]>,
    /// `(sin θ, cos θ)` of the current state, computed one step ahead (see `step`).
    trig: (f64, f64),
    rng: Option<NumpyRng>,
    elapsed_steps: u32,
    steps_beyond_terminated: Option<u32>,
}

impl CartPole {
    /// A CartPole with Gymnasium's defaults for `env_id`. Call [`CartPole::reset`] before stepping.
    #[must_use]
    pub fn new(env_id: EnvId) -> Self {
        Self::with_config(CartPoleConfig::new(env_id))
    }

    /// A CartPole with explicit options.
    #[must_use]
    pub fn with_config(config: CartPoleConfig) -> Self {
        Self {
            config,
            state: None,
            trig: (0.0, 1.0),
            rng: None,
            elapsed_steps: 0,
            steps_beyond_terminated: None,
        }
    }

    /// The options this environment was built with.
    #[must_use]
    pub fn config(&self) -> &CartPoleConfig {
        &self.config
    }

    // ANCHOR: reset_seed
    /// Gymnasium's `reset(seed=seed)`: a seed re-creates the generator; `None` continues it
    /// (or, on the very first reset, seeds it from OS entropy as Gymnasium does).
    pub fn reset(&mut self, seed: Option<u64>) -> [f32; 4] {
        let rng = match (seed, self.rng.take()) {
            (Some(s), _) => NumpyRng::from_seed(s),
            (None, Some(rng)) => rng,
            (None, None) => NumpyRng::from_seed(rand::random()),
        };
        let rng = self.rng.insert(rng);
        let (low, high) = self.config.reset_bounds;
        let state = [0; 4].map(|_| rng.uniform(low, high));
        self.state = Some(state);
        self.trig = sin_cos(state[2]);
        self.elapsed_steps = 0;
        self.steps_beyond_terminated = None;
        observe(&state)
    }
    // ANCHOR_END: reset_seed

    /// [`CartPole::reset`] with custom bounds, as Gymnasium's `options={"low": low, "high": high}`.
    ///
    /// # Errors
    /// [`EnvError::InvalidBounds`] unless `low <= high` and both are finite.
    pub fn reset_with_bounds(
        &mut self,
        seed: Option<u64>,
        low: f64,
        high: f64,
    ) -> Result<[f32; 4], EnvError> {
        if !(low.is_finite() && high.is_finite() && low <= high) {
            return Err(EnvError::InvalidBounds { low, high });
        }
        self.config.reset_bounds = (low, high);
        Ok(self.reset(seed))
    }

    /// Gymnasium's `step(action)` through the `TimeLimit` wrapper.
    ///
    /// # Errors
    /// [`EnvError::NotReset`] before the first reset; [`EnvError::InvalidAction`] for an action
    /// other than 0 or 1.
    #[inline]
    pub fn step(&mut self, action: usize) -> Result<Step, EnvError> {
        /// The step, compiled once per [`Math`].
        struct StepWith<'a>(&'a mut CartPole, usize);
        impl WithMath for StepWith<'_> {
            type Output = Result<Step, EnvError>;
            #[inline(always)]
            fn run<M: Math>(self, math: M) -> Self::Output {
                self.0.step_with(self.1, math)
            }
        }
        sincos::dispatch(StepWith(self, action))
    }

    // ANCHOR: env_step
    /// The body of [`CartPole::step`], compiled once per [`Math`] (`math`: libm and the
    /// hardware division, or the inline versions where they give the same bits).
    #[inline(always)]
    fn step_with<M: Math>(&mut self, action: usize, math: M) -> Result<Step, EnvError> {
        if action > 1 {
            return Err(EnvError::InvalidAction(action));
        }
        let state = self.state.ok_or(EnvError::NotReset)?;
        // physics(state, action, integrator), with one change of order only: under explicit
        // Euler the next angle θ + τ·θ̇ does not depend on this step's accelerations, so
        // its sin and cos (needed by the next step) are computed here. The CPU works on
        // them while this step's divisions are in flight. They come after the
        // accelerations in the code, so that the compiler keeps the accelerations in
        // registers. (docs/measurements.md, "CartPole speed", has what each change gave;
        // the numbers are the same.)
        let (sintheta, costheta) = self.trig;
        let (xacc, thetaacc) = accelerations_with(math, action, state[3], sintheta, costheta);
        let next_trig = match self.config.integrator {
            Integrator::Euler => Some(math.sin_cos(state[2] + TAU * state[3])),
            Integrator::SemiImplicitEuler => None,
        };
        let next = integrate(state, xacc, thetaacc, self.config.integrator);
        self.trig = next_trig.unwrap_or_else(|| math.sin_cos(next[2]));
        self.state = Some(next);
        let terminated = is_terminated(&next);
        let reward = reward(
            terminated,
            self.steps_beyond_terminated,
            self.config.sutton_barto_reward,
        );
        let mut warning = None;
        if terminated {
            self.steps_beyond_terminated = Some(match self.steps_beyond_terminated {
                None => 0,
                Some(n) => {
                    if n == 0 {
                        warning = Some(STEP_AFTER_TERMINATED);
                    }
                    n + 1
                }
            });
        }
        self.elapsed_steps += 1;
        let truncated = self.elapsed_steps >= self.config.env_id.max_episode_steps();
        Ok(Step {
            obs: observe(&next),
            reward,
            terminated,
            truncated,
            warning,
        })
    }
    // ANCHOR_END: env_step

    /// The f64 internal state (`env.unwrapped.state`), `None` before the first reset.
    #[must_use]
    pub fn state(&self) -> Option<[f64; 4]> {
        self.state
    }

    /// Steps taken since the last reset (the `TimeLimit`'s `_elapsed_steps`).
    #[must_use]
    pub fn elapsed_steps(&self) -> u32 {
        self.elapsed_steps
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_before_reset_is_an_error() {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        assert!(matches!(env.step(0), Err(EnvError::NotReset)));
    }

    #[test]
    fn invalid_action_is_an_error() {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        env.reset(Some(0));
        assert!(matches!(env.step(2), Err(EnvError::InvalidAction(2))));
    }

    #[test]
    fn after_termination_reward_is_zero_and_warns_once() -> Result<(), EnvError> {
        let mut env = CartPole::new(EnvId::CartPoleV1);
        env.reset(Some(3));
        let mut n = 0;
        while !env.step(1)?.terminated {
            n += 1;
            assert!(n < 500, "pushing right forever must topple the pole");
        }
        let first = env.step(1)?;
        assert!(first.terminated);
        assert_eq!(first.reward, 0.0);
        assert_eq!(first.warning, Some(STEP_AFTER_TERMINATED));
        let second = env.step(1)?;
        assert!(second.terminated);
        assert_eq!(second.warning, None);
        Ok(())
    }

    #[test]
    fn v0_truncates_at_200() -> Result<(), EnvError> {
        let mut env = CartPole::new(EnvId::CartPoleV0);
        env.reset(Some(0));
        // Alternate pushes keep the pole up for a while; keep stepping until the limit.
        let mut last = env.step(0)?;
        for i in 1..200 {
            last = env.step(i % 2)?;
        }
        assert!(last.truncated);
        assert_eq!(env.elapsed_steps(), 200);
        Ok(())
    }

    #[test]
    fn step_equals_physics_for_both_integrators() -> Result<(), EnvError> {
        // `step` computes the next angle's sin and cos ahead of time; the states must
        // still be exactly those of `physics`.
        for integrator in [Integrator::Euler, Integrator::SemiImplicitEuler] {
            let mut config = CartPoleConfig::new(EnvId::CartPoleV1);
            config.integrator = integrator;
            let mut env = CartPole::with_config(config);
            env.reset(Some(5));
            let mut rng = NumpyRng::from_seed(9);
            for _ in 0..3000 {
                let before = env.state().ok_or(EnvError::NotReset)?;
                let action = (rng.next_u64() & 1) as usize;
                let step = env.step(action)?;
                let want = physics(before, action, integrator);
                let got = env.state().ok_or(EnvError::NotReset)?;
                assert_eq!(
                    got.map(f64::to_bits),
                    want.map(f64::to_bits),
                    "{integrator:?}"
                );
                if step.terminated || step.truncated {
                    env.reset(None);
                }
            }
        }
        Ok(())
    }

    #[test]
    fn env_ids_parse() {
        assert_eq!("CartPole-v0".parse::<EnvId>().ok(), Some(EnvId::CartPoleV0));
        assert!("CartPole-v2".parse::<EnvId>().is_err());
    }

    #[test]
    fn sutton_barto_reward() -> Result<(), EnvError> {
        let mut config = CartPoleConfig::new(EnvId::CartPoleV1);
        config.sutton_barto_reward = true;
        let mut env = CartPole::with_config(config);
        env.reset(Some(1));
        let mut step = env.step(1)?;
        assert_eq!(step.reward, 0.0);
        while !step.terminated {
            step = env.step(1)?;
        }
        assert_eq!(step.reward, -1.0);
        Ok(())
    }
}
