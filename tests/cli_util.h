// Running the strata binary from tests: exit status and combined output, and
// a scratch directory removed afterwards.
#pragma once
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "gltf_util.h"

namespace strata::test {

struct Run {
    int status = -1;
    std::string output;  // stdout and stderr together
};

// Runs a shell command line and waits for it, stderr merged into the output.
inline Run runShell(const std::string& command) {
    Run r;
    FILE* p = popen((command + " 2>&1").c_str(), "r");
    REQUIRE(p != nullptr);
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
    const int raw = pclose(p);
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    return r;
}

// Runs `strata ARGS` (a shell command line); `env` (NAME=value ...) is set
// for that run only.
inline Run run(const std::string& args, const std::string& env = "") {
    return runShell((env.empty() ? "" : "env " + env + " ") + std::string(STRATA_EXE) + " " + args);
}

inline std::size_t lines(const std::string& s) {
    std::size_t n = 0;
    for (char c : s) n += c == '\n';
    return n + (!s.empty() && s.back() != '\n');
}

// Starts `strata ARGS` (without --quiet) in the background, waits until it
// has opened its device (its first line on stderr, at most 30 s) and
// `settle` seconds more, sends it
// `signals` (kill arguments, e.g. "-INT"), `gap` seconds apart, and waits for
// it. The output ends with "status=N".
inline Run signalled(const std::string& args, const std::vector<std::string>& signals, double settle, double gap,
              const std::string& log) {
    std::string script = std::string(STRATA_EXE) + " " + args + " 2>" + log + " & p=$!; n=0; " +
                         "while ! grep -q \"strata: device\" " + log + " && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; " +
                         "sleep " + std::to_string(settle) + "; ";
    for (std::size_t i = 0; i < signals.size(); ++i)
        script += (i ? "sleep " + std::to_string(gap) + "; " : "") + "kill " + signals[i] + " $p; ";
    script += "wait $p; echo status=$?";
    return runShell("sh -c '" + script + "'");
}

inline int statusOf(const Run& r) {
    const std::size_t at = r.output.rfind("status=");
    return at == std::string::npos ? -1 : std::stoi(r.output.substr(at + 7));
}

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        static std::atomic<int> counter{0};
        path = std::filesystem::temp_directory_path() /
               ("strata-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~TempDir() { std::filesystem::remove_all(path); }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    std::string operator/(const std::string& name) const { return (path / name).string(); }
    bool empty() const { return std::filesystem::is_empty(path); }
};

// `strata render FILE` (8 x 8, 1 spp, an EXR and a PNG asked for) fails as
// bad input: exit status 2, one line starting "FILE: error: ", no file written.
// Runs `args` (a render-like command) with an EXR and a PNG output in a
// fresh directory and checks the error contract: exit 2, one line starting
// with `prefix`, nothing written.
inline void expectError(const std::string& args, const std::string& prefix) {
    TempDir out;
    const Run r = run(args + " -o " + out / "a.exr" + " -o " + out / "a.png" + " --spp 1 --width 8 --height 8 --quiet");
    CAPTURE(args);
    CAPTURE(r.output);
    CHECK(r.status == 2);
    CHECK(lines(r.output) == 1);
    CHECK(r.output.rfind(prefix, 0) == 0);
    CHECK(out.empty());
}

inline void checkRenderRefuses(const std::string& file) { expectError("render " + file, file + ": error: "); }

// A folder of broken files under tests/data (`folder`, e.g.
// "materials/broken"), each with the one error line it must give after
// "FILE: error: " (`cases`: file name, message): every .gltf there has its
// case, loading gives exactly that one line, and render refuses it.
inline void checkBrokenFolder(const std::string& folder,
                              const std::vector<std::pair<std::string, std::string>>& cases) {
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dataPath(folder)))
        files += entry.path().extension() == ".gltf";
    CHECK(files == cases.size());  // every file in the folder has its case
    for (const auto& [file, expected] : cases) {
        const std::string path = dataPath(folder + "/" + file);
        CAPTURE(path);
        const std::string message = loadError(path);
        REQUIRE_MESSAGE(!message.empty(), "loaded without an error");
        CHECK(isOneLine(message));
        CHECK(message == path + ": error: " + expected);
        checkRenderRefuses(path);
    }
}

}  // namespace strata::test
