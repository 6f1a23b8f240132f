#include "util/error.h"

#include <iostream>
#include <mutex>
#include <vector>

namespace strata {
namespace {

// The held lines, and how many HeldWarnings live.
std::mutex heldMutex;
std::vector<std::string> heldLines;
int holders = 0;

}  // namespace

void warn(const std::string& file, const std::string& what) {
    // One line: line breaks inside `what` become spaces.
    std::string line = file + ": warning: " + what;
    for (char& c : line) {
        if (c == '\n' || c == '\r') c = ' ';
    }
    line += '\n';
    const std::lock_guard<std::mutex> lock(heldMutex);
    if (holders > 0) {
        heldLines.push_back(std::move(line));
        return;
    }
    std::cerr << line << std::flush;
}

HeldWarnings::HeldWarnings() {
    const std::lock_guard<std::mutex> lock(heldMutex);
    ++holders;
}

HeldWarnings::~HeldWarnings() {
    const std::lock_guard<std::mutex> lock(heldMutex);
    if (--holders > 0) return;
    if (released_)
        for (const std::string& line : heldLines) std::cerr << line;
    std::cerr << std::flush;
    heldLines.clear();
}

}  // namespace strata
