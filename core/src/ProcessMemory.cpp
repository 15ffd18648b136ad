#include "spatter/core/ProcessMemory.hpp"

#include <fstream>
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#ifdef SPATTER_ASAN
// From sanitizer/allocator_interface.h, which GCC does not install.
extern "C" size_t __sanitizer_get_current_allocated_bytes();
#endif

namespace spatter {

size_t residentBytes() {
    std::ifstream statm("/proc/self/statm");
    size_t pages = 0, resident = 0;
    if (!(statm >> pages >> resident)) return 0;
    return resident * size_t(sysconf(_SC_PAGESIZE));
}

size_t peakResidentBytes() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return size_t(u.ru_maxrss) * 1024;
}

size_t heapBytes() {
#ifdef SPATTER_ASAN
    return __sanitizer_get_current_allocated_bytes();
#else
    const struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
#endif
}

} // namespace spatter
