//! shadowlab: learn real-time shadows — shadow mapping, bias, PCF and PCSS — with a CPU twin
//! of every shader function and a ground truth to compare against.

pub mod app;
pub mod browser;
pub mod built_in;
#[cfg(not(target_arch = "wasm32"))]
pub mod cli;
pub mod diagrams;
pub mod export;
pub mod files;
pub mod homework;
pub mod i18n;
pub mod lessons;
pub mod probe;
pub mod reference;
pub mod render;
pub mod scene;
pub mod shadow;
pub mod shipped;
pub mod ui;
pub mod views;
#[cfg(target_arch = "wasm32")]
mod web;

pub use shipped::shipped_path;
