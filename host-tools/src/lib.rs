//! Host-side helpers shared by the host tools, benches and examples.

pub mod accuracy;
pub mod console;
pub mod convert;
pub mod figures;
pub mod obj;
pub mod output;
pub mod reference3d;
pub mod scenefile;
pub mod scenes;
pub mod scenes3d;
mod vec64;
