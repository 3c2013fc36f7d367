//! The notebooks' generator (`ppo-tutor dev notebooks`): the cells of each lesson's notebook
//! from its lesson and recipe ([`build`]), the `.ipynb` file ([`ipynb`]), the checks both
//! test tiers make on a notebook ([`check`]), every notebook's code as plain Rust for the
//! default tier ([`native`]), and executing cells on the evcxr engine (`kernel`, with the feature
//! `notebook-runner`).
//!
//! None of this is compiled by a notebook: its cells call `ppo_engine::notebook`.

pub mod build;
pub mod check;
pub mod ipynb;
#[cfg(feature = "notebook-runner")]
pub mod kernel;
pub mod native;
