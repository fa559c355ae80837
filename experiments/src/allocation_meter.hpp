#pragma once
/// A run's own peak memory in a worker process: the highest sum of live C++ allocations (operator
/// new, usable sizes) between start and stop. allocation_meter.cpp says what it counts and what not.

namespace coverbench {

/// False in a build whose allocator is not ours (AddressSanitizer's): then nothing is measured.
bool allocationMeterAvailable();
/// Starts metering from zero (allocations made before do not count; their release is subtracted).
void startAllocationMeter();
/// Stops metering; returns the peak of live bytes since the start.
double stopAllocationMeter();

}  // namespace coverbench
