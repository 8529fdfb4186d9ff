//! Cancellation of running computations: a process-wide request that the engines poll — the
//! Taylor engine with its deadline ([`super::taylor::TaylorOptions::out_of_time`], so a
//! cancelled run stops as one whose time budget ran out), DOP853 before each step
//! ([`super::dop853::Dop853Error::Cancelled`]) — so that a computation stops within one step
//! of the request.
//!
//! The program never requests it (Ctrl-C ends the process). The Python bindings do, on a
//! KeyboardInterrupt during a call, and withdraw the request once the call's computation has
//! stopped; a call stopped so raises KeyboardInterrupt and returns nothing it computed. The
//! request is process-wide: other bwcl calls running in other Python threads at that moment
//! stop too (their cases "not proved: the time budget ran out", or not integrated) — never a
//! number that was not computed.

use std::sync::atomic::{AtomicUsize, Ordering};

/// The requests outstanding.
static REQUESTS: AtomicUsize = AtomicUsize::new(0);

/// Whether a stop is requested.
#[inline]
pub fn requested() -> bool {
    REQUESTS.load(Ordering::Relaxed) > 0
}

/// A request to stop every running computation, in force while it lives.
#[derive(Debug)]
pub struct Request(());

impl Request {
    pub fn new() -> Self {
        REQUESTS.fetch_add(1, Ordering::SeqCst);
        Request(())
    }
}

impl Default for Request {
    fn default() -> Self {
        Self::new()
    }
}

impl Drop for Request {
    fn drop(&mut self) {
        REQUESTS.fetch_sub(1, Ordering::SeqCst);
    }
}
