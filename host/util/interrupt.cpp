#include "util/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <cstring>

namespace strata {
namespace {

std::atomic<int> gSignal{0};

// The guarded temporary files: a path is written before its slot is marked
// used, and the handler reads only used slots (unlink is async-signal-safe).
constexpr int kSlots = 16;
char gPaths[kSlots][PATH_MAX];
std::atomic<bool> gUsed[kSlots];

extern "C" void onSignal(int sig) {
    int none = 0;
    if (gSignal.compare_exchange_strong(none, sig)) return;  // the first: stop after this submission
    for (int i = 0; i < kSlots; ++i)
        if (gUsed[i].load()) ::unlink(gPaths[i]);
    ::_exit(128 + gSignal.load());
}

}  // namespace

void installInterruptHandlers() {
    struct sigaction action {};
    action.sa_handler = onSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

int interruptSignal() { return gSignal.load(); }

std::string signalName(int signal) {
    if (signal == SIGINT) return "SIGINT";
    if (signal == SIGTERM) return "SIGTERM";
    return "signal " + std::to_string(signal);
}

TempFileGuard::TempFileGuard(const std::string& path) {
    if (path.size() >= PATH_MAX) return;
    for (int i = 0; i < kSlots; ++i) {
        if (gUsed[i].load()) continue;
        std::memcpy(gPaths[i], path.c_str(), path.size() + 1);
        gUsed[i].store(true);
        slot_ = i;
        return;
    }
}

TempFileGuard::~TempFileGuard() {
    if (slot_ >= 0) gUsed[slot_].store(false);
}

}  // namespace strata
