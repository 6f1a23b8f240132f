// A scene's size against what can hold it, checked once the placements are
// decided and before any triangle is placed (gltf_internal.h,
// checkSceneSize): the instances strata can index, the host memory the
// flattened triangles and instances take to load and build, and the device
// memory the flattened triangles' arrays take at least.
#include <cstdint>
#include <string>

#include "scene/gltf_internal.h"
#include "scene/scene.h"
#include "util/error.h"
#include "util/memory.h"

namespace strata::gltf {

namespace {

std::string count(std::size_t n) { return n == SIZE_MAX ? std::string("more than 2^64") : std::to_string(n); }

std::uint64_t times(std::size_t n, std::uint64_t bytes) {
    std::uint64_t out = 0;
    return __builtin_mul_overflow(std::uint64_t(n), bytes, &out) ? UINT64_MAX : out;
}

void checkHostMemory(const std::string& path, const SceneSize& size, std::uint64_t hostMemory) {
    const std::uint64_t budget = hostMemory != 0 ? hostMemory : hostMemoryBudget();
    const std::uint64_t triangles = times(size.triangles, kHostBytesPerTriangle);
    const std::uint64_t emitters = times(size.emitters, kHostBytesPerEmitter);
    const std::uint64_t needed = triangles > UINT64_MAX - emitters ? UINT64_MAX : triangles + emitters;
    const std::uint64_t forInstances = std::uint64_t(size.instances) * kHostBytesPerInstance;
    if (budget == 0 || (needed <= budget && forInstances <= budget - needed)) return;
    if (forInstances == 0 || needed > budget)
        fail(path, "the scene's " + std::to_string(size.placements) + " placed nodes flatten into " +
                       count(size.triangles) + " triangles" +
                       (size.emitters > 0 ? " (" + count(size.emitters) + " of them emitters)" : std::string()) +
                       ", which need about " + bytesText(needed) +
                       " of host memory to load and build; " + bytesText(budget) +
                       " are available (--instancing on stores a mesh placed many times once)");
    fail(path, "the scene's " + std::to_string(size.instances) + " instances" +
                   (size.triangles > 0 ? " and " + std::to_string(size.triangles) + " flattened triangles" : std::string()) +
                   " need about " + bytesText(needed + forInstances) + " of host memory to load and build; " +
                   bytesText(budget) + " are available");
}

// The flattened triangles' TriVerts, TriShading and Emitters alone: a lower
// bound of what the upload will need, so a scene refused here would be
// refused there, after it was built.
void checkDeviceMemory(const std::string& path, const SceneSize& size, const SizeBudget& budget) {
    if (!budget.deviceMemory) return;
    const std::uint64_t triangles = times(size.triangles, kDeviceBytesPerTriangle);
    const std::uint64_t emitters = times(size.emitters, kDeviceBytesPerEmitter);
    const std::uint64_t needed = triangles > UINT64_MAX - emitters ? UINT64_MAX : triangles + emitters;
    const DeviceBudget device = budget.deviceMemory(needed);
    if (device.bytes == 0 || needed <= device.bytes) return;
    fail(path, "the scene's " + std::to_string(size.placements) + " placed nodes flatten into " +
                   count(size.triangles) + " triangles (" + count(size.emitters) +
                   " of them emitters, which are always flattened), whose arrays need at least " + sizeText(needed) +
                   " of device memory, more than the " + sizeText(device.bytes) + " of " + device.device);
}

}  // namespace

void checkSceneSize(const std::string& path, const SceneSize& size, const SizeBudget& budget) {
    if (size.instances > kMaxInstances)
        fail(path, "the scene places its instanced meshes " + std::to_string(size.instances) +
                       " times, more than the " + std::to_string(kMaxInstances) + " instances strata can index");
    checkHostMemory(path, size, budget.hostMemory);
    checkDeviceMemory(path, size, budget);
}

}  // namespace strata::gltf
