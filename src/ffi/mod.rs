//! The stable C ABI (see `include/sherd.h`). Handles, status codes, the thread's last
//! error and the panic boundary live here; no algorithm does.
