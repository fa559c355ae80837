#pragma once
/// Heap high-water mark of a stretch of code, measured by counting every allocation of the
/// `coverbench` process (the global operator new/delete are replaced in memory_meter.cpp, in this
/// binary only, so tests and benchmarks are untouched).

#include <cstddef>

namespace coverbench::cli {

/// Starts a measurement: the current heap use becomes the baseline.
void resetPeakMemory();
/// Bytes by which the heap grew at most since the last reset.
std::size_t peakMemorySinceReset();

}  // namespace coverbench::cli
