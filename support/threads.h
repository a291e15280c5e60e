// Whether this build may start threads. Natively it may: the pipeline's stages, the output
// writer, the certificate and its reader each have one. WebAssembly without shared memory
// (the browser page, web/, served by a plain static file server) has none: there every stage
// runs on the caller's thread, in turn. The tests turn threads off to run that way natively.
#pragma once

namespace clpc {

bool threads_available();
// Tests only: run as the browser build does (false), or as usual (true).
void set_threads_available(bool on);

// Names the calling thread for debuggers and perf (where the platform can).
void name_this_thread(const char* name);

}  // namespace clpc
