//! Host-side helpers shared by the host tools, benches and examples.

pub mod accuracy;
pub mod console;
pub mod convert;
pub mod figures;
pub mod output;
pub mod progress;
pub mod scenefile;
pub mod sprite;
#[cfg(feature = "view")]
pub mod view;
