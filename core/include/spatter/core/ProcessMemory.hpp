#pragma once

#include <cstddef>

// SPATTER_ASAN: defined in a build with AddressSanitizer (GCC or clang).
#if defined(__SANITIZE_ADDRESS__)
#define SPATTER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SPATTER_ASAN 1
#endif
#endif

namespace spatter {

// Memory of the running process, for benchmarks and soak tests.

// Resident set size now (/proc/self/statm), in bytes; 0 where it cannot be read.
size_t residentBytes();

// Largest resident set size the process has had (getrusage), in bytes.
size_t peakResidentBytes();

// Heap bytes handed out and not taken back: glibc's mallinfo2 (arena and mmapped blocks), or the
// allocator's own statistics under AddressSanitizer, which replaces malloc.
size_t heapBytes();

} // namespace spatter
