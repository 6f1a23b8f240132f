#include "util/error.h"

#include <iostream>

namespace strata {

void warn(const std::string& file, const std::string& what) {
    // One line: line breaks inside `what` become spaces.
    std::string line = file + ": warning: " + what;
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    line += '\n';
    std::cerr << line << std::flush;
}

}  // namespace strata
