//! Property tests of the native CartPole's invariants.

use ppo_rl::env::cartpole::{THETA_THRESHOLD_RADIANS, X_THRESHOLD};
use ppo_rl::env::{CartPole, CartPoleConfig, CartPoleVec, EnvId, Integrator};
use proptest::prelude::*;

fn env_ids() -> impl Strategy<Value = EnvId> {
    prop_oneof![Just(EnvId::CartPoleV1), Just(EnvId::CartPoleV0)]
}

fn integrators() -> impl Strategy<Value = Integrator> {
    prop_oneof![Just(Integrator::Euler), Just(Integrator::SemiImplicitEuler)]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Within an episode every observation is finite and `terminated` is set exactly
    /// when a threshold is crossed; truncation comes exactly at the time limit.
    #[test]
    fn episodes_obey_thresholds(
        seed in any::<u64>(),
        actions in prop::collection::vec(0_usize..2, 1..600),
        env_id in env_ids(),
        integrator in integrators(),
    ) {
        let mut config = CartPoleConfig::new(env_id);
        config.integrator = integrator;
        let mut env = CartPole::with_config(config);
        let obs = env.reset(Some(seed));
        prop_assert!(obs.iter().all(|v| v.is_finite() && v.abs() <= 0.05));
        for (i, &a) in actions.iter().enumerate() {
            let step = env.step(a).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let s = env.state().ok_or_else(|| TestCaseError::fail("no state"))?;
            prop_assert!(step.obs.iter().all(|v| v.is_finite()));
            let crossed = s[0].abs() > X_THRESHOLD || s[2].abs() > THETA_THRESHOLD_RADIANS;
            prop_assert_eq!(step.terminated, crossed);
            prop_assert_eq!(step.truncated, i + 1 >= env_id.max_episode_steps() as usize);
            prop_assert_eq!(step.obs, s.map(|v| v as f32));
            if step.terminated || step.truncated {
                break;
            }
        }
    }

    /// Environment i of a vector env equals a single CartPole reset with seed + i and
    /// then unseeded after every episode.
    #[test]
    fn vector_env_equals_single_envs(
        seed in any::<u64>(),
        n in 1_usize..9,
        steps in 1_usize..400,
        action_seed in any::<u64>(),
    ) {
        let config = CartPoleConfig::new(EnvId::CartPoleV1);
        let mut vec_env = CartPoleVec::new(config, n, seed);
        let mut singles: Vec<CartPole> = (0..n as u64).map(|i| {
            let mut e = CartPole::with_config(config);
            e.reset(Some(seed.wrapping_add(i)));
            e
        }).collect();
        for (i, e) in singles.iter().enumerate() {
            prop_assert_eq!(vec_env.state(i), e.state());
        }
        let mut rng = ppo_rl::env::seeding::NumpyRng::from_seed(action_seed);
        for _ in 0..steps {
            let actions: Vec<usize> = (0..n).map(|_| (rng.next_u64() & 1) as usize).collect();
            let out = vec_env.step(&actions).map_err(|e| TestCaseError::fail(e.to_string()))?.clone();
            for (i, env) in singles.iter_mut().enumerate() {
                let s = env.step(actions[i]).map_err(|e| TestCaseError::fail(e.to_string()))?;
                prop_assert_eq!(out.rewards[i], s.reward);
                prop_assert_eq!(out.terminated[i], s.terminated);
                prop_assert_eq!(out.truncated[i], s.truncated);
                if s.terminated || s.truncated {
                    prop_assert_eq!(out.final_obs[i], Some(s.obs));
                    let obs = env.reset(None);
                    prop_assert_eq!(out.obs[i], obs);
                } else {
                    prop_assert_eq!(out.obs[i], s.obs);
                }
                prop_assert_eq!(vec_env.state(i), env.state());
            }
        }
    }
}
