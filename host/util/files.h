// Small file helpers shared by the commands.
#pragma once
#include <string>

namespace strata {

// The extension of `path`, lower-cased, with its dot (".csv"), or "".
std::string lowerExtension(const std::string& path);

// Writes `text` to `path` whole or not at all: a temporary file in the same
// directory, then a rename. Throws strata::Error naming `path` on failure.
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace strata
