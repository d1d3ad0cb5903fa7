//! A live view as a command runs it: the station's tap and the server it feeds, started from
//! `--view [ADDR:]PORT` and stopped after the station. Without the `view` feature, asking for
//! one is an error naming the rebuild.

use super::ViewAddress;

/// A running live view and the tap the station feeds it through.
#[derive(Debug)]
#[cfg_attr(not(feature = "view"), allow(dead_code))] // never started without the feature
pub struct LiveView {
    /// Give this to the station's hooks.
    pub tap: crate::station_node::tap::Tap,
    #[cfg(feature = "view")]
    server: super::ViewServer,
}

/// The live view could not start.
#[derive(Debug, thiserror::Error)]
pub enum LiveViewError {
    /// The server could not start.
    #[cfg(feature = "view")]
    #[error(transparent)]
    Start(#[from] super::ViewError),
    /// This build has no live view.
    #[error(
        "--view {address}: this pomdar was built without the live view; rebuild with `cargo build --release -p teleop --features view`"
    )]
    NotBuilt {
        /// The address asked for.
        address: ViewAddress,
    },
}

#[cfg(feature = "view")]
/// Messages the tap holds for a live view that falls behind, before the oldest are dropped
/// (several seconds of every topic at the station's rates).
const TAP_CAPACITY: usize = 4096;

/// Start the live view if an address is given.
pub async fn start_live_view(
    address: Option<ViewAddress>,
) -> Result<Option<LiveView>, LiveViewError> {
    let Some(address) = address else {
        return Ok(None);
    };
    start_view(address).await.map(Some)
}

#[cfg(feature = "view")]
async fn start_view(address: ViewAddress) -> Result<LiveView, LiveViewError> {
    let tap = crate::station_node::tap::Tap::new(TAP_CAPACITY);
    let server = super::ViewServer::start(address, tap.subscribe()).await?;
    Ok(LiveView { tap, server })
}

#[cfg(not(feature = "view"))]
async fn start_view(address: ViewAddress) -> Result<LiveView, LiveViewError> {
    Err(LiveViewError::NotBuilt { address })
}

#[cfg_attr(not(feature = "view"), allow(dead_code))]
impl LiveView {
    /// The line to show on start: where to point the Foxglove app.
    pub fn announcement(&self) -> String {
        #[cfg(feature = "view")]
        return self.server.announcement();
        #[cfg(not(feature = "view"))]
        String::new()
    }

    /// Stop the view after the station (a no-op without the `view` feature, which never
    /// starts one).
    pub async fn stop(self) {
        #[cfg(feature = "view")]
        {
            let report = self.server.stop().await;
            if report.counts.lagged > 0 {
                eprintln!(
                    "live view: fell behind and dropped {} of {} messages",
                    report.counts.lagged,
                    report.counts.lagged + report.counts.forwarded
                );
            }
        }
    }
}
