// The validation layers are really on in the tests, and a message is caught.
#include <doctest/doctest.h>

#include "test_util.h"

using namespace strata;

TEST_SUITE_BEGIN("render");

TEST_CASE("validation layers are enabled under ctest and report misuse") {
    REQUIRE(vk::validationRequestedByEnvironment());
    vk::Context& ctx = test::context();
    REQUIRE(ctx.validation);
    const std::uint64_t before = vk::validationMessageCount();
    REQUIRE(before == 0);
    // A zero-sized buffer is invalid usage (VUID-VkBufferCreateInfo-size-00912).
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 0;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(ctx.device, &info, nullptr, &buffer) == VK_SUCCESS && buffer)
        vkDestroyBuffer(ctx.device, buffer, nullptr);
    CHECK(vk::validationMessageCount() > before);
    vk::resetValidationMessageCount();
}

TEST_SUITE_END();
