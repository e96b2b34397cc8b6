//! Fuzzes the usdc reader: any bytes, no panic, bounded output.

#![no_main]

#[path = "check.rs"]
mod check;

libfuzzer_sys::fuzz_target!(|data: &[u8]| check::check(data, helixhair_formats::Format::Usdc));
