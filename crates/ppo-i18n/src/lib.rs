//! # ppo-i18n
//!
//! The language of what ppo-tutor prints for people, English or Simplified Chinese, and the
//! wording of the errors other libraries raise. A leaf of the workspace: the RL core
//! (`ppo-rl`) and the course (`ppo-engine`) both build on it.
//!
//! - [`i18n`](mod@i18n): the current [`Lang`](i18n::Lang), [`t`](i18n::t), [`tr!`], [`text!`]
//!   and display widths.
//! - [`causes`]: an error's cause (I/O, JSON, TOML, safetensors, candle) in the current
//!   language.

pub mod causes;
pub mod i18n;
