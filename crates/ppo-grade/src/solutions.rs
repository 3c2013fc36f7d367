//! The reference solutions, compiled from the very files the tutor shows after a pass
//! (`lessons/NN-slug/solution.rs`), so what is shown is what grades.

#[allow(clippy::needless_range_loop)]
#[path = "../../../lessons/03-episode-loop/solution.rs"]
pub mod episode_loop;

#[path = "../../../lessons/07-td-target/solution.rs"]
pub mod td_target;

#[allow(clippy::needless_range_loop)]
#[path = "../../../lessons/08-gae/solution.rs"]
pub mod gae;

#[path = "../../../lessons/09-ratio/solution.rs"]
pub mod ratio;

#[path = "../../../lessons/10-trust-region/solution.rs"]
pub mod trust_region;

#[path = "../../../lessons/11-clipping/solution.rs"]
pub mod clipping;

#[path = "../../../lessons/12-losses/solution.rs"]
pub mod losses;

#[path = "../../../lessons/12-losses/solution_candle.rs"]
pub mod losses_candle;

#[path = "../../../lessons/13-clip-lab/solution.rs"]
pub mod clip_lab;

#[allow(clippy::needless_range_loop)]
#[path = "../../../lessons/16-beyond-the-seed/solution.rs"]
pub mod beyond;

#[path = "../../../lessons/17-continuous-actions/solution.rs"]
pub mod continuous;
