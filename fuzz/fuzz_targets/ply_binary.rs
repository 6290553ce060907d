#![no_main]
//! Fuzz target `ply_binary`: see `sherd_fuzz::ply_binary`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::ply_binary(data));
