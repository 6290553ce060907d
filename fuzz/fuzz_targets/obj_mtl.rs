#![no_main]
//! Fuzz target `obj_mtl`: see `sherd_fuzz::obj_mtl`.

libfuzzer_sys::fuzz_target!(|data: &[u8]| sherd_fuzz::obj_mtl(data));
