// The fuzz targets' bodies (docs/security.md): each takes one input and
// returns when strata handled it, loaded or refused with strata::Error (the
// one-line error of exit status 2). Any other exception escapes and any
// memory error aborts: both are findings. fuzz/fuzz_main.cpp makes them
// libFuzzer targets; tests/test_fuzz_regressions.cpp runs every regression
// input of tests/data/fuzz through them in the normal build.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace strata::fuzz {

// glTF or GLB bytes, as `<root>/input.gltf` (uris resolve against root):
// loaded with the limits and path rules on, then the BVH, the packing and
// the camera, all that happens before a device is opened.
void gltfInput(const std::uint8_t* data, std::size_t size, const std::string& root);

// A state file's bytes, read by readState.
void stateInput(const std::uint8_t* data, std::size_t size);

// Words separated by NUL bytes: a command's name, then its arguments, given
// to that command's parser (nothing runs).
void cliInput(const std::uint8_t* data, std::size_t size);

// The first byte picks: even, the rest is an image file (PNG, JPEG, WebP,
// ...) that a one-triangle GLB uses as its base colour and emissive texture,
// loaded and packed as gltfInput does; odd, the next two bytes size an
// environment map whose texels are the rest's floats, checked and turned
// into its sampling tables.
void imageInput(const std::uint8_t* data, std::size_t size, const std::string& root);

}  // namespace strata::fuzz
