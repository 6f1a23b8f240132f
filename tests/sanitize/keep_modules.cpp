// Linked into strata and strata_tests by STRATA_SANITIZE only (make
// test-sanitize). The Vulkan loader unloads its drivers and layers when an
// instance is destroyed; LeakSanitizer reports at exit, when their frames
// belong to no module any more and no suppression can name the library
// (tests/sanitize/lsan.supp). This dlclose, found before libc's, keeps
// every shared object loaded until the process ends.
extern "C" int dlclose(void*) { return 0; }
