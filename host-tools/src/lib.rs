//! Host-side helpers shared by the host tools, benches and examples.

pub mod obj;
pub mod scenes;
