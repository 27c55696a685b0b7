//! `libillume`: the RenderMan Interface C binding.
//!
//! The C half (`csrc/`) owns the varargs forms, tokens, filter functions and the error-handler
//! pointer; each `Ri…` call becomes a short sequence of `illume_*` calls into [`ffi`], which
//! builds an [`illume_session::Call`] and sends it to the open [`illume_session::Session`].
//! All `unsafe` lives in `ffi`.
#![deny(unsafe_code)]

mod ffi;
mod state;
