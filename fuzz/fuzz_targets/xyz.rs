#![no_main]
//! Fuzz target `xyz`: see `sherd_fuzz::xyz`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::xyz(data));
