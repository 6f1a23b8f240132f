// The commands of strata and their flag tables (cli/flags.h): parsing into
// the command structs of render/ and measure/, and each command's help.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "measure/bench.h"
#include "denoise/command.h"
#include "measure/converge.h"
#include "measure/edges.h"
#include "render/command.h"
#include "render/merge.h"
#include "render/shaders_command.h"

namespace strata::cli {

struct CommandInfo {
    std::string name;
    std::string summary;                           // one line
    std::function<std::string()> help;             // `strata NAME --help`
    std::function<std::string()> tuningHelp;       // `strata NAME --help-tuning`; empty: no tuning flags
    std::function<std::vector<std::string>()> flags;  // every name its table accepts (aliases, old names)
    std::function<std::vector<std::string>()> tuningFlags;  // those --help-tuning lists instead of --help
    // Prints the help and returns 0 when the arguments ask for it; parses and
    // runs the command otherwise.
    std::function<int(const std::vector<std::string>& args)> run;
};

// render, reference, view, compare, converge, edges, bench, denoise, merge, devices, shaders.
const std::vector<CommandInfo>& commands();
const CommandInfo* findCommand(const std::string& name);
// `strata --help`: the commands with their summaries.
std::string overview();

// The parsers: `args` are the words after the command's name. They check
// every value and every combination the flags alone decide (cli/checks.h),
// throwing strata::Error, one line, before anything is read, and fill in
// what the flags leave to a default (render's outputs). Help flags are not
// theirs to handle.
struct CompareArgs {
    std::string image, reference, json;
};

RenderCommand parseRender(const std::vector<std::string>& args);
RenderCommand parseReference(const std::vector<std::string>& args);
CompareArgs parseCompare(const std::vector<std::string>& args);
ConvergeCommand parseConverge(const std::vector<std::string>& args);
EdgesCommand parseEdges(const std::vector<std::string>& args);
BenchCommand parseBench(const std::vector<std::string>& args);
DenoiseCommand parseDenoise(const std::vector<std::string>& args);
MergeCommand parseMerge(const std::vector<std::string>& args);
ShadersCommand parseShaders(const std::vector<std::string>& args);
// `strata view` (cli/view_command.cpp).
CommandInfo viewCommand();

}  // namespace strata::cli
