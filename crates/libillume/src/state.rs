//! The process-wide RI state behind the C calls: the open session and the call being built.
//!
//! RI is a global-state API; the session belongs to the thread that called `RiBegin` (the
//! renderer's state is not `Send`), as RI programs are written. The state is borrowed only
//! inside one `illume_*` call and released before the error handler runs (it may call Ri).
use illume_session::{Call, RiError, Session};
use std::cell::RefCell;

#[derive(Default)]
pub struct State {
    pub session: Option<Session>,
    pub call: Option<Call>,
    /// Problems with no session to hold them (calls before `RiBegin`).
    pub orphan: Vec<RiError>,
}

thread_local! {
    static STATE: RefCell<State> = RefCell::new(State::default());
}

/// Runs `f` on this thread's state (a panic inside releases the borrow as it unwinds).
pub fn with<R>(f: impl FnOnce(&mut State) -> R) -> R {
    STATE.with(|s| f(&mut s.borrow_mut()))
}

impl State {
    /// Queues an error for the handler.
    pub fn report(&mut self, e: RiError) {
        match &mut self.session {
            Some(s) => s.report(e),
            None => self.orphan.push(e),
        }
    }

    /// Everything the handler should see now.
    pub fn take_errors(&mut self) -> Vec<RiError> {
        let mut out = std::mem::take(&mut self.orphan);
        if let Some(s) = &mut self.session {
            out.extend(s.take_errors());
        }
        out
    }
}
