//! The scene: every client's window surfaces with their placement, properties, layers and
//! lighting, the pacing between clients and the compositor, and the life of each surface's
//! frames (`frames`: queued by the client's executor, taken and released by the compositor).
//! It depends on the device layer only: the GLES executor and the compositor both depend on it,
//! and it knows neither.
#![warn(missing_docs)]

mod analyze;
pub mod depth;
mod events;
mod frames;
mod ids;
mod input;
mod layers;
mod mailbox;
mod pacing;
pub mod presets;
mod properties;
pub mod region;
mod state;
pub mod transfer;
mod waiter;

pub use frames::{Producer, Swapped};
pub use ids::IdRefused;
pub use input::Candidate;
pub use layers::{LayerState, Layers};
pub use mailbox::{Buffers, Images, Use, Views};
pub use pacing::Work;
pub use region::Region;
pub use state::{Acquired, Part, Scene, SceneSurface, Shown};
pub use waiter::FrameWaiter;
