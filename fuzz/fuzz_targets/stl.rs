#![no_main]
//! Fuzz target `stl`: see `sherd_fuzz::stl`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::stl(data));
