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
// While a HeldWarnings lives they are held instead.
void warn(const std::string& file, const std::string& what);

// Holds warn()'s lines (from every thread) while it lives: loading a scene
// holds them, so that bad input prints its one error line alone. release()
// marks the load done; when the outermost holder ends, its lines are
// printed in order if it was released and dropped if not (an Error is on
// its way out).
class HeldWarnings {
public:
    HeldWarnings();
    ~HeldWarnings();
    HeldWarnings(const HeldWarnings&) = delete;
    HeldWarnings& operator=(const HeldWarnings&) = delete;
    void release() { released_ = true; }

private:
    bool released_ = false;
};

}  // namespace strata
