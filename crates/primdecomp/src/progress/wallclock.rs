//! The clock the stage timings read ([`crate::Timings`]). WebAssembly without a host
//! (`wasm32-unknown-unknown`) has no clock in `std`: `std::time::Instant::now` panics
//! there, so on that target every reading is the same instant and the timings are 0
//! (the embedder times the call itself, as the JavaScript package does). Elsewhere
//! this is `std::time::Instant`, unchanged.

#[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
pub(crate) use std::time::Instant;

#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
pub(crate) use no_clock::Instant;

#[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
mod no_clock {
    use std::time::Duration;

    /// An instant of a clock that never moves.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
    pub(crate) struct Instant;

    impl Instant {
        pub(crate) fn now() -> Instant {
            Instant
        }
        pub(crate) fn elapsed(&self) -> Duration {
            Duration::ZERO
        }
    }

    impl std::ops::Add<Duration> for Instant {
        type Output = Instant;
        fn add(self, _: Duration) -> Instant {
            Instant
        }
    }
}
