//! Running a console from a program without a tokio runtime (the `semsim` binary): one
//! function for both kinds of console, live ([`crate::Console`]) and replaying
//! ([`crate::RunConsole`]), through the [`Serve`] trait they share.

use crate::config::ConsoleConfig;
use crate::error::{ConsoleError, Result};
use std::future::Future;

/// A console that is bound to its socket, then served until told to stop.
pub trait Serve: Sized {
    /// What it is started with.
    type Setup;
    /// What serving it gives back at the end.
    type Output;
    /// Checks the setup and opens the listening socket.
    fn bind(config: ConsoleConfig, setup: Self::Setup) -> impl Future<Output = Result<Self>>;
    /// The page's URL.
    fn url(&self) -> String;
    /// Serves until `shutdown` completes.
    fn serve<F>(self, shutdown: F) -> impl Future<Output = Result<Self::Output>>
    where
        F: Future<Output = ()> + Send + 'static;
}

/// Runs a console on a runtime of its own until `stop()` answers true (polled every 100 ms;
/// e.g. a Ctrl-C flag), calling `listening` once the socket is open; returns what serving
/// gave (a live console: the run folders saved).
///
/// ```no_run
/// # fn demo(setup: console::SessionSetup) -> console::Result<()> {
/// let saved = console::serve_blocking::<console::Console>(
///     console::ConsoleConfig::default(),
///     setup,
///     |c| println!("console: {}", c.url()),
///     || false,
/// )?;
/// # Ok(()) }
/// ```
pub fn serve_blocking<S: Serve>(
    config: ConsoleConfig,
    setup: S::Setup,
    listening: impl FnOnce(&S),
    stop: impl Fn() -> bool + Send + 'static,
) -> Result<S::Output> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .map_err(ConsoleError::Serve)?;
    runtime.block_on(async move {
        let console = S::bind(config, setup).await?;
        listening(&console);
        console
            .serve(async move {
                while !stop() {
                    tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                }
            })
            .await
    })
}
