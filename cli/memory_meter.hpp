#pragma once
/// Heap high-water mark of a stretch of code on one thread, measured by counting every allocation of the
/// `coverbench` process (the global operator new/delete are replaced in memory_meter.cpp, in this
/// binary only, so tests and benchmarks are untouched).

#include <cstddef>

namespace coverbench::cli {

/// Starts a measurement on this thread: the current heap use becomes the baseline.
void resetPeakMemory();
/// Same, and allocations that would grow this thread's heap use more than `limit_bytes` above
/// the baseline throw std::bad_alloc (0: no limit) until peakMemorySinceReset is called.
void limitMemory(std::size_t limit_bytes);
/// Bytes by which this thread's heap use grew at most since the last reset; ends the limit.
std::size_t peakMemorySinceReset();
/// Whether the limit made an allocation fail since the last reset.
bool memoryLimitHit();

}  // namespace coverbench::cli
