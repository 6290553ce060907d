#![no_main]
//! Fuzz target `pipeline`: see `sherd_fuzz::pipeline`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::pipeline(data));
