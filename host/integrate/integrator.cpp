#include "integrate/integrator.h"

#include "integrate/megakernel.h"
#include "integrate/wavefront.h"
#include "util/error.h"

namespace strata {

std::unique_ptr<Integrator> makeIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, std::uint32_t maxTilePixels,
                                           const FilmBuffers& film) {
    // The wavefront's hit lists carry no instance (lib/bvh.glsl, gHitInstance).
    if (s.integrator == IntegratorKind::Wavefront && (dev.features.bits & gpu::kFeatureInstancing) != 0u)
        fail("strata", "--integrator wavefront does not render instanced meshes yet; --instancing off flattens them, "
             "or use the megakernel");
    if (s.integrator == IntegratorKind::Wavefront)
        return std::make_unique<WavefrontIntegrator>(ctx, dev, s, t, maxTilePixels, film);
    return makeMegakernel(ctx, dev, s, t, film);
}

}  // namespace strata
