// Small file helpers shared by the commands.
#pragma once
#include <string>

namespace strata {

// The extension of `path`, lower-cased, with its dot (".csv"), or "".
std::string lowerExtension(const std::string& path);

// Writes `text` to `path` whole or not at all: a temporary file in the same
// directory, then a rename. Throws strata::Error naming `path` on failure.
void writeTextAtomically(const std::string& path, const std::string& text);

// An input no reader can use, named by the callers in their own words (the
// libraries' words for these mislead: "bad_alloc", "RGBE read error").
enum class Unusable { No, Directory, EmptyFile };
Unusable unusableInput(const std::string& path);

// Fails (strata::Error naming `path`) unless `path` can be written as a new
// or replaced file: its directory exists and is writable, and `path` is not
// a directory. The commands check every output before any work, so a long
// run does not end in a failed write.
void checkOutputPath(const std::string& path);

// --restrict-paths: `dir` made canonical (absolute, symlinks resolved),
// the folder every input must resolve into. Fails (strata: error) when
// `dir` is not an existing folder.
std::string restrictRoot(const std::string& dir);

// `path` resolved (absolute, symlinks followed as far as it exists) when
// that lies outside the canonical folder `root`; "" when inside.
std::string outsideRoot(const std::string& path, const std::string& root);

}  // namespace strata
