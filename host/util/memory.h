// Host memory of this process.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

namespace strata {

// Peak resident set size so far (getrusage; Linux reports KiB).
inline std::uint64_t peakRssBytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;
}

// Asks the kernel for 2 MiB pages in [p, p + bytes) (MADV_HUGEPAGE: in THP's
// "madvise" mode, Debian's default, only memory so advised gets them): a
// large array then takes one page fault per 2 MiB instead of one per 4 KiB
// when first written (on 4 KiB pages the faults cost more than the filling:
// docs/experiments/scale-and-startup.md). Advice only; arrays under 2 MiB
// are left alone.
inline void adviseHugePages(const void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
    constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
    const std::uintptr_t b = (std::uintptr_t(p) + kHuge - 1) & ~(kHuge - 1);
    const std::uintptr_t e = (std::uintptr_t(p) + bytes) & ~(kHuge - 1);
    if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

// Hands the whole pages inside [p, p + bytes) back to the kernel
// (MADV_DONTNEED): the resident set shrinks and the bytes there read as zero
// afterwards. For the consumed front of a large array that is read no more;
// partial pages at either end (and so any allocator header) are kept.
inline void discardPages(const void* p, std::size_t bytes) {
    const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
    const std::uintptr_t b = (std::uintptr_t(p) + page - 1) & ~(page - 1);
    const std::uintptr_t e = (std::uintptr_t(p) + bytes) & ~(page - 1);
    if (e > b) madvise(reinterpret_cast<void*>(b), e - b, MADV_DONTNEED);
}

// v.reserve(n), the new storage advised for huge pages before anything touches it.
template <class T>
void reserveHuge(std::vector<T>& v, std::size_t n) {
    v.reserve(n);
    adviseHugePages(v.data(), v.capacity() * sizeof(T));
}

// The host memory this process may still use: the kernel's MemAvailable
// (/proc/meminfo), lowered by an address-space or data limit (ulimit -v,
// ulimit -d) where one is set; 0 when none of them can be read.
inline std::uint64_t hostMemoryBudget() {
    std::uint64_t budget = 0;
    if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
        char line[256];
        unsigned long long kib = 0;
        while (std::fgets(line, sizeof line, f))
            if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) budget = std::uint64_t(kib) * 1024u;
        std::fclose(f);
    }
    for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
        rlimit limit{};
        if (getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
            budget = budget == 0 ? std::uint64_t(limit.rlim_cur) : std::min(budget, std::uint64_t(limit.rlim_cur));
    }
    return budget;
}

// Bytes as "3.2 GiB" (or MiB under a GiB).
inline std::string bytesText(std::uint64_t bytes) {
    char text[32];
    if (bytes >= (std::uint64_t(1) << 30)) std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1 << 30));
    else std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / double(1 << 20));
    return text;
}

// Bytes exactly below a MiB, else as "3.5 MiB" or "2.00 GiB".
inline std::string sizeText(std::uint64_t bytes) {
    if (bytes < (1u << 20)) return std::to_string(bytes) + " bytes";
    const bool gib = bytes >= (std::uint64_t(1) << 30);
    char buf[32];
    std::snprintf(buf, sizeof buf, gib ? "%.2f GiB" : "%.1f MiB",
                  static_cast<double>(bytes) / static_cast<double>(gib ? 1u << 30 : 1u << 20));
    return buf;
}

}  // namespace strata
