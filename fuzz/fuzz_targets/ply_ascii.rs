#![no_main]
//! Fuzz target `ply_ascii`: see `sherd_fuzz::ply_ascii`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::ply_ascii(data));
