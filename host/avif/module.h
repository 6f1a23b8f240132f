// Loading libstrata_avif.so (api.h) on first use.
#pragma once
#include <string>

#include "avif/api.h"

namespace strata::avif {

// The module: $STRATA_AVIF_MODULE when set (only there), else where CMake
// built it, else beside the running executable; loaded once. Null, with
// `error` saying why, when strata was built without it or it cannot be
// loaded.
const Api* module(std::string& error);

}  // namespace strata::avif
