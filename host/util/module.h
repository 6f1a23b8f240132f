// Loading one of strata's modules (libstrata_oiio.so, libstrata_avif.so,
// libstrata_view.so): libraries that only some commands need, kept out of
// the executable so that the others neither load nor initialise them.
#pragma once
#include <string>

namespace strata {

struct ModuleSpec {
    const char* env;       // $ENV names the module to load (only that one) when set
    const char* built;     // where CMake built it; "" when this build has none
    const char* fileName;  // else this file beside the running executable
    const char* symbol;    // its one exported function, returning its Api as const void* (the
                           // type it is called through: calling through another type is
                           // undefined, and clang's -fsanitize=function reports it)
    int version;           // the Api's first member (an int) must be this
    const char* missing;   // the error when the build has none
    const char* what;      // "image module", ...: the error when a file is another build's
};

// The module's Api, loaded once per call site's static (the caller keeps
// it); null with `error` saying why when it cannot be loaded.
const void* loadModuleApi(const ModuleSpec& spec, std::string& error);

}  // namespace strata
