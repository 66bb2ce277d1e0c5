#pragma once
// The one parallel loop of the tracer: work items handed out to threads from an atomic counter,
// with a worker's exception stopping the others and reaching the caller. The helper threads are
// the process's own pool, started once and reused.

#include <functional>

namespace tracer {

/// Calls body(worker, item) once for every item in [0, count), on `threads` threads (worker 0 is
/// the calling thread, workers are numbered 0 .. threads-1); items go out in increasing order
/// from one atomic counter, so a worker's calls see increasing items. When a call throws, the
/// workers take no new item, and the first exception is rethrown here after every worker has
/// returned. `threads` is clamped to [1, count]; nothing runs when count <= 0.
void parallel_items(int threads, int count, const std::function<void(int worker, int item)>& body);

/// Starts, ahead of time, the helper threads that parallel_items(threads, ...) will use, so that
/// a timed call does not pay for starting them. Optional: parallel_items starts what it lacks.
void prepare_threads(int threads);

/// The number of worker threads `threads` resolves to (0 = hardware threads, at least 1).
int resolve_threads(int threads);

}  // namespace tracer
