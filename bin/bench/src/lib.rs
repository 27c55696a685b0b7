//! `bench`: what each quality knob of the renderer costs in time and buys in accuracy
//! (issue 8). Scenes with closed forms plus the `rib/` gallery are rendered by the real
//! `render` binary over sweeps of each knob, measured, compared with a converged render and
//! the closed form, and written as `speed_error.csv`, `speed_error.png` and `speed_error.md`.
#![forbid(unsafe_code)]

pub mod closed_form;
pub mod csv;
pub mod font;
pub mod knob;
pub mod measure;
pub mod metrics;
pub mod motion;
pub mod pareto;
pub mod plot;
pub mod scene;
pub mod sweep;
pub mod table;
pub mod threads;
