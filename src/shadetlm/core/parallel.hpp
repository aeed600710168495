#pragma once
// Work shared out over threads: the golden model's bands, its frame's layers and a
// comparison's layers (the SystemC pipeline stays on one thread, deterministic).
#include <functional>

namespace shadetlm::core {

// `threads`, or one per core when it is 0 or less.
int threads_or_cores(int threads);

// Runs part(0) … part(parts − 1), each on its own thread (the last on this one), and
// returns once all are done. A thread that cannot be had leaves its part to this
// thread, after the others. Every error is kept, by part, and the first rethrown once
// every thread is joined. The helper threads never take SIGINT, SIGTERM or SIGHUP.
void run_parts(int parts, const std::function<void(int part)>& part);

}  // namespace shadetlm::core
