#include "memory_meter.hpp"

#include <malloc.h>

#include <cstdlib>
#include <new>

namespace {

// Per thread: experiments run one plan per worker thread, so each thread measures (and limits)
// its own plan. Memory freed by another thread than the one that allocated it skews both
// threads' counts; within one plan call that does not happen.
thread_local long long t_current = 0;
thread_local long long t_peak = 0;
thread_local long long t_baseline = 0;
thread_local long long t_limit = 0;  // bytes above the baseline; 0: no limit
thread_local bool t_limit_hit = false;

void note(void* p) {
  const auto n = static_cast<long long>(malloc_usable_size(p));
  t_current += n;
  if (t_limit > 0 && t_current - t_baseline > t_limit) {
    t_current -= n;
    std::free(p);
    t_limit_hit = true;
    throw std::bad_alloc();
  }
  if (t_current > t_peak) t_peak = t_current;
}

void unnote(void* p) {
  if (p) t_current -= static_cast<long long>(malloc_usable_size(p));
}

void* allocate(std::size_t n) {
  void* p = std::malloc(n ? n : 1);
  if (!p) throw std::bad_alloc();
  note(p);
  return p;
}

void* allocateAligned(std::size_t n, std::align_val_t align) {
  const auto a = static_cast<std::size_t>(align);
  void* p = std::aligned_alloc(a, (n + a - 1) / a * a);
  if (!p) throw std::bad_alloc();
  note(p);
  return p;
}

void release(void* p) noexcept {
  unnote(p);
  std::free(p);
}

}  // namespace

void* operator new(std::size_t n) { return allocate(n); }
void* operator new[](std::size_t n) { return allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return allocateAligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return allocateAligned(n, a); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  try {
    return allocate(n);
  } catch (...) {
    return nullptr;
  }
}
void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }

namespace coverbench::cli {

void resetPeakMemory() { limitMemory(0); }

void limitMemory(std::size_t limit_bytes) {
  t_baseline = t_current;
  t_peak = t_current;
  t_limit = static_cast<long long>(limit_bytes);
  t_limit_hit = false;
}

std::size_t peakMemorySinceReset() {
  t_limit = 0;
  const long long grown = t_peak - t_baseline;
  return grown > 0 ? static_cast<std::size_t>(grown) : 0;
}

bool memoryLimitHit() { return t_limit_hit; }

}  // namespace coverbench::cli
