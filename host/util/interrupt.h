// SIGINT and SIGTERM during a render. The first signal asks the render loop
// to stop after the submission in progress (render/renderer.cpp), so the
// command writes every output with the samples reached and exits 128 +
// the signal (130, 143). A second signal ends the process at once, with the
// same status, after removing the temporary files of any write in progress:
// outputs appear whole or not at all.
#pragma once
#include <string>

namespace strata {

// Installs the handlers (strata render and reference). Until then, and in
// the tests that render in their own process, interruptSignal() stays 0.
void installInterruptHandlers();

// 0, or the first SIGINT or SIGTERM received since installInterruptHandlers.
int interruptSignal();

// "SIGINT", "SIGTERM", or "signal N".
std::string signalName(int signal);

// A temporary file being written (a file's content before its rename into
// place): a second signal removes it before the process ends. At most 16 are
// held at once; more are not guarded.
class TempFileGuard {
public:
    explicit TempFileGuard(const std::string& path);
    ~TempFileGuard();
    TempFileGuard(const TempFileGuard&) = delete;
    TempFileGuard& operator=(const TempFileGuard&) = delete;

private:
    int slot_ = -1;
};

}  // namespace strata
