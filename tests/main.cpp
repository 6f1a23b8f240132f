// The test runner: doctest's, with the shader cache (host/spirv/cache.h) in
// the build folder for the tests and every strata they run.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    setenv("XDG_CACHE_HOME", STRATA_TEST_CACHE, 1);
    doctest::Context context(argc, argv);
    return context.run();
}
