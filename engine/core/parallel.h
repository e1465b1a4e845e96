#pragma once
// One loop over independent items on several threads. The engine's heavy CPU loops are per item
// with nothing shared: synthesising faces, fitting the face model's segments and the pose
// completion's candidates, estimating every face's curvature in `eval realism`, registering
// scans. A plain pool that hands out indices in order is all they need. Each result goes into a
// slot owned by its index and is combined afterwards in index order, which keeps every output
// byte-identical for any number of threads.

#include <functional>

namespace facesketch {

/// Runs body(i) once for every i in [0, count) on up to `threads` threads (0: one per hardware
/// thread; never more than count), the calling thread among them. Indices are handed out in
/// increasing order as threads free up, so body must not depend on which thread runs an index
/// or on the order indices finish. With one thread every index runs on the calling thread, in
/// order.
///
/// After each index it ran, the calling thread runs onCaller(index) (when set): the place for
/// progress reports that must come from one thread.
///
/// An exception thrown by body (or onCaller) stops the handing out of indices; indices already
/// started finish. Once every thread has joined, the exception of the lowest index that failed
/// is rethrown: the one a single thread would have met first, since every index below a failing
/// one has been handed out (in order) before it. So a deterministic body reports the same error
/// for any number of threads. Throws Error for a negative count or threads.
void parallelFor(int count, int threads, const std::function<void(int)>& body, const std::function<void(int)>& onCaller = {});

} // namespace facesketch
