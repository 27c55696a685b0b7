//! Illume: the root package only carries the cross-crate integration tests in `tests/`.
//! The renderer lives in `crates/` and the programs in `bin/`; see `DESIGN.md` in shared/.
