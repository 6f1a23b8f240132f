// Image formats beyond PNG and JPEG: EXT_texture_webp through libwebp and
// EXT_texture_avif through libavif on files tests/data/make_webp.cpp and
// make_avif.cpp encode at build time (a lossless image decodes to its
// source pixels exactly; without the decoder the fallback image and the
// required-extension error), and KHR_texture_basisu, which strata
// cannot decode: the texture's fallback source, or an error only where a
// material uses the texture. Other formats (GIF, PNM) never reach stb_image.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "cli_util.h"
#include "gltf_util.h"
#include "scene/scene.h"

TEST_SUITE_BEGIN("unit");

namespace {

using namespace strata;
using namespace strata::test;

const LoadOptions kNoRequirements{false, false};

}  // namespace

TEST_CASE("KHR_texture_basisu: the texture shows its fallback source, one without is refused only where used") {
    const std::string path = dataPath("geometry/basisu-fallback.gltf");
    CerrCapture capture;
    const Scene scene = loadGltf(path, kNoRequirements);
    CHECK(capture.text() == path + ": warning: 1 texture(s) that materials read are KHR_texture_basisu, which "
                                   "strata cannot decode (Debian has no Basis Universal decoder): showing their "
                                   "fallback images\n");
    REQUIRE(scene.textures.size() == 1);
    CHECK(scene.textures[0].image == 1);  // the PNG, not the KTX2 image 0
    REQUIRE(scene.materials.at(1).emissiveTexture.texture == 0);
    const TextureImage& png = scene.images.at(1);
    CHECK(png.width == 2);
    CHECK(png.data == std::vector<std::uint8_t>{255, 32, 0, 255, 0, 128, 255, 255});
    // No fallback, no material reading it: loads, the texture unusable.
    const Scene unused = loadGltf(dataPath("geometry/basisu-unused.gltf"), kNoRequirements);
    CHECK(unused.textures.at(0).image == -1);
}

namespace {

// format_files.h's checker: 4 x 4 RGBA rows top to bottom.
std::vector<std::uint8_t> checker() {
    std::vector<std::uint8_t> out;
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            const bool odd = (x + y) % 2 != 0;
            out.insert(out.end(), {static_cast<std::uint8_t>(odd ? 255 : 16 * x), static_cast<std::uint8_t>(64 * y),
                                   static_cast<std::uint8_t>(odd ? 32 : 200), 255});
        }
    }
    return out;
}

// The files format_files.h's writeSet made in `dir` for `extension`
// (`name`.gltf and its -required and -corrupt copies), read by a strata
// built with the decoder (`built`) or without it (`decoder` names it).
void checkFormatFiles(const std::string& dir, const std::string& name, const std::string& extension, bool built,
                      const std::string& decoder, const std::string& corruptWhat) {
    const std::string path = dir + "/" + name + ".gltf";
    CerrCapture capture;
    const Scene scene = loadGltf(path, kNoRequirements);
    REQUIRE(scene.textures.size() == 1);
    const std::string required = dir + "/" + name + "-required.gltf";
    if (built) {
        CHECK(capture.text().empty());
        REQUIRE(scene.textures[0].image == 1);
        const TextureImage& image = scene.images[1];
        CHECK(image.width == 4);
        CHECK(image.height == 4);
        CHECK(image.bits == 8);
        CHECK(image.data == checker());  // lossless: the source pixels exactly
        // Required and without a fallback: the image through the extension.
        const Scene only = loadGltf(required, kNoRequirements);
        REQUIRE(only.textures.at(0).image == 0);
        CHECK(only.images[0].data == checker());
        const std::string corrupt = dir + "/" + name + "-corrupt.gltf";
        CHECK(loadError(corrupt) == corrupt + ": error: material 0 (\"Checker\") emissiveTexture: texture 0: image 1 "
                                              "(\"corrupt." + name + "\"): cannot decode 40 bytes: " + corruptWhat);
        checkRenderRefuses(corrupt);
    } else {
        CHECK(capture.text() == path + ": warning: extension " + extension + " is used but strata was built without " +
                                    decoder + "; reading the textures' fallback images\n");
        CHECK(scene.textures[0].image == 0);  // the 1 x 1 black PNG
        CHECK(loadError(required) == required + ": error: required extension " + extension +
                                         " cannot be read: strata was built without " + decoder);
        checkRenderRefuses(required);
    }
}

}  // namespace

TEST_CASE("images other than PNG and JPEG (and WebP, AVIF) are refused where used, not handed to stb_image") {
    // A valid 1 x 1 GIF and PPM, which stb_image would decode, and the image
    // fuzzer's PNM that tinygltf copied out of bounds: glTF 2.0's images
    // are PNG and JPEG, so each is one line where a material reads it.
    const std::string gif("GIF89a\x01\x00\x01\x00\x80\x00\x00\xff\xff\xff\x00\x00\x00,\x00\x00\x00\x00\x01\x00"
                          "\x01\x00\x00\x02\x02"
                          "D\x01\x00;",
                          35);
    const std::string ppm = "P6\n1 1\n255\n\x10\x20\x30";
    const std::string fuzzed("P61 \n\n1 \n\n967 967 25\xff\x10\x10\x10", 24);
    std::ifstream in(dataPath("textures/broken/corrupt-image.gltf"));
    std::string gltf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string uri = "corrupt.png";
    REQUIRE(gltf.find(uri) != std::string::npos);
    gltf.replace(gltf.find(uri), uri.size(), "image.bin");
    for (const std::string& bytes : {gif, ppm, fuzzed}) {
        TempDir dir;
        std::ofstream(dir.path / "image.bin", std::ios::binary) << bytes;
        const std::string path = (dir.path / "scene.gltf").string();
        std::ofstream(path) << gltf;
        CHECK(loadError(path) == path + ": error: material 0 (\"Emitter\") emissiveTexture: texture 0: image 0 "
                                        "(\"image.bin\"): cannot decode " + std::to_string(bytes.size()) +
                                        " bytes: not a PNG or JPEG (the image formats of glTF 2.0), nor a WebP or AVIF "
                                        "image");
    }
}

#ifdef STRATA_WEBP_DIR
TEST_CASE("EXT_texture_webp: the WebP source through libwebp, else the fallback image") {
    checkFormatFiles(STRATA_WEBP_DIR, "webp", "EXT_texture_webp", STRATA_WEBP, "the WebP decoder (libwebp)",
                     "a corrupt WebP image (libwebp)");
}
#endif

#ifdef STRATA_AVIF_DIR
TEST_CASE("EXT_texture_avif: the AVIF source through libavif, else the fallback image") {
    checkFormatFiles(STRATA_AVIF_DIR, "avif", "EXT_texture_avif", STRATA_AVIF, "the AVIF decoder (libavif)",
                     "a corrupt AVIF image (libavif)");
}
#endif

TEST_SUITE_END();
