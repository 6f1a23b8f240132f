// Host memory of this process.
#pragma once
#include <cstdint>

#include <sys/resource.h>

namespace strata {

// Peak resident set size so far (getrusage; Linux reports KiB).
inline std::uint64_t peakRssBytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;
}

}  // namespace strata
