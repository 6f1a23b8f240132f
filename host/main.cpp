// strata command line. Errors: one line on stderr; exit 2 for bad input
// (scene, flags, files), 3 for device failures, 1 for anything else. The
// commands and their flags are tables in cli/commands.cpp.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "cli/commands.h"
#include "cli/flags.h"
#include "strata_version.h"  // generated at build time (cmake/GitVersion.cmake)
#include "util/error.h"
#include "vk/check.h"

namespace {

using strata::cli::badFlag;

// "strata 0.21.0 (git 1abe589)" and the Vulkan loader's version; no
// instance is created.
int printVersion() {
    const std::string git = STRATA_GIT_DESCRIBE;
    const std::string line = std::string("strata ") + STRATA_VERSION + (git.empty() ? "" : " (git " + git + ")");
    std::printf("%s\n", line.c_str());
    std::uint32_t v = 0;
    if (vkEnumerateInstanceVersion(&v) == VK_SUCCESS)
        std::printf("Vulkan loader %u.%u.%u\n", VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                    VK_API_VERSION_PATCH(v));
    else
        std::printf("Vulkan loader: version unknown\n");
    return 0;
}

const strata::cli::CommandInfo& command(const std::string& name) {
    if (const strata::cli::CommandInfo* c = strata::cli::findCommand(name)) return *c;
    std::vector<std::string> names;
    for (const auto& c : strata::cli::commands()) names.push_back(c.name);
    badFlag("unknown command '" + name + "' (commands: " + strata::cli::joined(names, ", ") + ")");
}

int run(const std::vector<std::string>& args) {
    if (args.empty()) {
        std::fputs(strata::cli::overview().c_str(), stderr);
        return 2;
    }
    const std::string& first = args[0];
    if (first == "help" && args.size() > 1) {  // strata help COMMAND
        std::fputs(command(args[1]).help().c_str(), stdout);
        return 0;
    }
    if (first == "-h" || first == "--help" || first == "help") {
        std::fputs(strata::cli::overview().c_str(), stdout);
        return 0;
    }
    if (first == "--version") return printVersion();
    return command(first).run(std::vector<std::string>(args.begin() + 1, args.end()));
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const strata::Error& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const strata::vk::DeviceError& e) {
        std::fprintf(stderr, "strata: error: %s\n", e.what());
        return 3;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "strata: error: %s\n", e.what());
        return 1;
    }
}
