//! numpy-compatible seeding: `SeedSequence` -> `PCG64` -> `Generator.uniform`.
//!
//! Gymnasium's `reset(seed=s)` builds `np.random.Generator(np.random.PCG64(np.random.SeedSequence(s)))`
//! and CartPole draws its start state with `uniform(low, high, size=4)`. This module
//! reproduces that chain bit for bit, for every `u64` seed:
//!
//! 1. `SeedSequence(s)`: `s` is split into little-endian `u32` words, hashed into a pool of
//!    four `u32`s, and `generate_state(4, uint64)` expands the pool into 128-bit `state`
//!    and `increment` values.
//! 2. `PCG64`: a 128-bit LCG, `state = state * M + inc`, whose 64-bit output is the
//!    XSL-RR permutation of the state.
//! 3. `uniform(low, high)`: `low + (high - low) * ((next_u64 >> 11) * 2^-53)`.
//!
//! ```
//! use ppo_rl::env::seeding::NumpyRng;
//! let mut rng = NumpyRng::from_seed(0);
//! let x = rng.uniform(-0.05, 0.05);
//! assert!((-0.05..0.05).contains(&x));
//! // The same seed gives the same stream.
//! assert_eq!(NumpyRng::from_seed(0).next_u64(), NumpyRng::from_seed(0).next_u64());
//! ```

const INIT_A: u32 = 0x43b0_d7e5;
const MULT_A: u32 = 0x931e_8875;
const INIT_B: u32 = 0x8b51_f9dd;
const MULT_B: u32 = 0x58f3_8ded;
const MIX_MULT_L: u32 = 0xca01_f9dd;
const MIX_MULT_R: u32 = 0x4973_f715;
const XSHIFT: u32 = 16;
const POOL_SIZE: usize = 4;

/// PCG64's 128-bit LCG multiplier (`PCG_DEFAULT_MULTIPLIER_128`).
const PCG_MULT: u128 = (2_549_297_995_355_413_924_u128 << 64) | 4_865_540_595_714_422_341_u128;

/// numpy's `SeedSequence` hashing of one word: updates the running hash constant.
fn hashmix(value: u32, hash_const: &mut u32) -> u32 {
    let mut value = value ^ *hash_const;
    *hash_const = hash_const.wrapping_mul(MULT_A);
    value = value.wrapping_mul(*hash_const);
    value ^ (value >> XSHIFT)
}

/// numpy's `SeedSequence` mixing of two pool words.
fn mix(x: u32, y: u32) -> u32 {
    let result = MIX_MULT_L
        .wrapping_mul(x)
        .wrapping_sub(MIX_MULT_R.wrapping_mul(y));
    result ^ (result >> XSHIFT)
}

/// The entropy of `SeedSequence(seed)`: the integer as little-endian `u32` words (`[0]` for 0).
fn entropy_words(seed: u64) -> Vec<u32> {
    if seed == 0 {
        return vec![0];
    }
    let mut words = Vec::with_capacity(2);
    let mut n = seed;
    while n > 0 {
        words.push((n & 0xffff_ffff) as u32);
        n >>= 32;
    }
    words
}

/// `SeedSequence(seed).pool`: the four mixed words.
fn seed_pool(seed: u64) -> [u32; POOL_SIZE] {
    let entropy = entropy_words(seed);
    let mut hash_const = INIT_A;
    let mut mixer = [0_u32; POOL_SIZE];
    for (i, slot) in mixer.iter_mut().enumerate() {
        *slot = hashmix(entropy.get(i).copied().unwrap_or(0), &mut hash_const);
    }
    for i_src in 0..POOL_SIZE {
        for i_dst in 0..POOL_SIZE {
            if i_src != i_dst {
                let h = hashmix(mixer[i_src], &mut hash_const);
                mixer[i_dst] = mix(mixer[i_dst], h);
            }
        }
    }
    for &word in entropy.iter().skip(POOL_SIZE) {
        for slot in &mut mixer {
            let h = hashmix(word, &mut hash_const);
            *slot = mix(*slot, h);
        }
    }
    mixer
}

/// `SeedSequence(seed).generate_state(4, np.uint64)`.
fn generate_state_u64(seed: u64) -> [u64; 4] {
    let pool = seed_pool(seed);
    let mut hash_const = INIT_B;
    let mut words = [0_u32; 8];
    for (i, slot) in words.iter_mut().enumerate() {
        let mut data = pool[i % POOL_SIZE] ^ hash_const;
        hash_const = hash_const.wrapping_mul(MULT_B);
        data = data.wrapping_mul(hash_const);
        *slot = data ^ (data >> XSHIFT);
    }
    let mut out = [0_u64; 4];
    for (i, slot) in out.iter_mut().enumerate() {
        *slot = u64::from(words[2 * i]) | (u64::from(words[2 * i + 1]) << 32);
    }
    out
}

/// numpy's `Generator(PCG64(SeedSequence(seed)))`, the part CartPole uses.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NumpyRng {
    state: u128,
    inc: u128,
}

impl NumpyRng {
    /// The generator Gymnasium builds for `reset(seed=seed)`.
    #[must_use]
    pub fn from_seed(seed: u64) -> Self {
        let v = generate_state_u64(seed);
        let initstate = (u128::from(v[0]) << 64) | u128::from(v[1]);
        let initseq = (u128::from(v[2]) << 64) | u128::from(v[3]);
        let mut rng = Self {
            state: 0,
            inc: (initseq << 1) | 1,
        };
        rng.step();
        rng.state = rng.state.wrapping_add(initstate);
        rng.step();
        rng
    }

    fn step(&mut self) {
        self.state = self.state.wrapping_mul(PCG_MULT).wrapping_add(self.inc);
    }

    /// The next 64-bit output (PCG64's XSL-RR of the advanced state).
    pub fn next_u64(&mut self) -> u64 {
        self.step();
        let rot = (self.state >> 122) as u32;
        let xored = ((self.state >> 64) as u64) ^ (self.state as u64);
        xored.rotate_right(rot)
    }

    /// A double in `[0, 1)` with 53 random bits, as numpy's `next_double`.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / 9_007_199_254_740_992.0)
    }

    /// numpy's `Generator.uniform(low, high)`: `low + (high - low) * next_double`.
    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        let range = high - low;
        low + range * self.next_f64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn large_seeds_use_every_word() {
        assert_eq!(entropy_words(0), vec![0]);
        assert_eq!(entropy_words(1 << 32), vec![0, 1]);
        assert_eq!(entropy_words(u64::MAX), vec![u32::MAX, u32::MAX]);
        assert_ne!(NumpyRng::from_seed(1 << 32), NumpyRng::from_seed(0));
    }

    #[test]
    fn doubles_are_in_unit_interval() {
        let mut rng = NumpyRng::from_seed(7);
        for _ in 0..1000 {
            let x = rng.next_f64();
            assert!((0.0..1.0).contains(&x));
        }
    }
}
