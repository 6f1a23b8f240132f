#include "integrate/integrator.h"

#include "integrate/megakernel.h"
#include "integrate/wavefront.h"

namespace strata {

std::unique_ptr<Integrator> makeIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, std::uint32_t maxTilePixels,
                                           const FilmBuffers& film) {
    if (s.integrator == IntegratorKind::Wavefront)
        return std::make_unique<WavefrontIntegrator>(ctx, dev, s, t, maxTilePixels, film);
    return makeMegakernel(ctx, dev, s, t, film);
}

}  // namespace strata
