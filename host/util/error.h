// One exception type for user-facing errors. The message is the whole line
// the user sees ("scene.gltf: error: accessor 7 ..."); main prints it once
// and exits with status 2.
#pragma once
#include <stdexcept>
#include <string>

namespace strata {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// "<file>: error: <what>"
[[noreturn]] inline void fail(const std::string& file, const std::string& what) {
    throw Error(file + ": error: " + what);
}

// Warnings go to stderr as one line each: "<file>: warning: <what>".
void warn(const std::string& file, const std::string& what);

}  // namespace strata
