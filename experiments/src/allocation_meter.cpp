// A run's own peak memory: C++ allocations counted while a worker meters them (isolation.cpp).
// The process's peak resident set cannot say it: a reused worker's freed pages stay resident, so a
// run that reuses them reads 0 MiB. Here every operator new and delete of the process is replaced
// by one that, while metering is on, adds and subtracts the block's usable size (malloc's, so the
// two always agree) and keeps the highest sum reached. Off, it costs one relaxed load per call.
// Not counted: C allocations (malloc called directly: GMP inside the exact judge, SQLite) and
// memory mapped by other means. Under AddressSanitizer, which brings its own operator new, nothing
// is replaced and the meter reports nothing.
#include "allocation_meter.hpp"

#include <malloc.h>

#include <atomic>
#include <cstdlib>
#include <new>

#if defined(__SANITIZE_ADDRESS__)
#define COVERBENCH_NO_METER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COVERBENCH_NO_METER 1
#endif
#endif

namespace coverbench {
namespace {

std::atomic<bool> g_on{false};
std::atomic<long long> g_live{0};
std::atomic<long long> g_peak{0};

#ifndef COVERBENCH_NO_METER
void added(void* p) {
  if (!g_on.load(std::memory_order_relaxed)) return;
  const auto size = static_cast<long long>(malloc_usable_size(p));
  const long long now = g_live.fetch_add(size, std::memory_order_relaxed) + size;
  long long peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
}

/// `get()` until it returns memory, calling the new-handler (the worker's marks the run and
/// throws) between tries, as operator new must; counted when metering.
template <typename Get>
void* allocate(Get get) {
  for (;;) {
    if (void* p = get()) {
      added(p);
      return p;
    }
    const std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* allocate(std::size_t n) {
  return allocate([n] { return std::malloc(n == 0 ? 1 : n); });
}

void* allocateAligned(std::size_t n, std::align_val_t align) {
  const std::size_t a = static_cast<std::size_t>(align);
  const std::size_t size = ((n == 0 ? 1 : n) + a - 1) / a * a;  // aligned_alloc wants a multiple
  return allocate([a, size] { return std::aligned_alloc(a, size); });
}

/// The nothrow forms: nullptr where the throwing form throws.
template <typename F>
void* orNull(F f) noexcept {
  try {
    return f();
  } catch (...) {
    return nullptr;
  }
}

void release(void* p) noexcept {
  if (p && g_on.load(std::memory_order_relaxed))
    g_live.fetch_sub(static_cast<long long>(malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}
#endif

}  // namespace

bool allocationMeterAvailable() {
#ifdef COVERBENCH_NO_METER
  return false;
#else
  return true;
#endif
}

void startAllocationMeter() {
  g_on.store(false);
  g_live.store(0);
  g_peak.store(0);
  g_on.store(true);
}

double stopAllocationMeter() {
  g_on.store(false);
  return static_cast<double>(g_peak.load());
}

}  // namespace coverbench

#ifndef COVERBENCH_NO_METER
void* operator new(std::size_t n) { return coverbench::allocate(n); }
void* operator new[](std::size_t n) { return coverbench::allocate(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  return coverbench::orNull([n] { return coverbench::allocate(n); });
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  return coverbench::orNull([n] { return coverbench::allocate(n); });
}
void* operator new(std::size_t n, std::align_val_t a) { return coverbench::allocateAligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return coverbench::allocateAligned(n, a); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return coverbench::orNull([n, a] { return coverbench::allocateAligned(n, a); });
}
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept {
  return coverbench::orNull([n, a] { return coverbench::allocateAligned(n, a); });
}
void operator delete(void* p) noexcept { coverbench::release(p); }
void operator delete[](void* p) noexcept { coverbench::release(p); }
void operator delete(void* p, std::size_t) noexcept { coverbench::release(p); }
void operator delete[](void* p, std::size_t) noexcept { coverbench::release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { coverbench::release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { coverbench::release(p); }
void operator delete(void* p, std::align_val_t) noexcept { coverbench::release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { coverbench::release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { coverbench::release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { coverbench::release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { coverbench::release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { coverbench::release(p); }
#endif
