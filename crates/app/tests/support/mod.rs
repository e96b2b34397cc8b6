//! What several of the app's tests share: a virtual display and xdotool
//! for the window tests, the ray-parity inside test for exports, the kill
//! harness for atomic writes, and where the Sintel data lives.

pub mod display;
pub mod inside;
pub mod kill;
pub mod sintel;
pub mod xdo;
