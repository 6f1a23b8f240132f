#include "integrate/integrator.h"

#include "integrate/megakernel.h"
#include "integrate/wavefront.h"
#include "util/error.h"

namespace strata {

std::unique_ptr<Integrator> makeIntegrator(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, std::uint32_t maxTilePixels,
                                           const FilmBuffers& film) {
    if (s.integrator == IntegratorKind::Wavefront) {
        if (s.aov)
            throw Error("strata: error: --aov and --denoise need the megakernel integrator (--integrator megakernel); "
                        "the wavefront integrator keeps no AOVs");
        if (s.cameraEffects())
            throw Error("strata: error: --lens-radius and a --shutter interval need the megakernel integrator "
                        "(--integrator megakernel); the wavefront integrator has no lens and no time");
        if (dev.features.indexMatchedMedia)
            throw Error("strata: error: a scattering medium behind an index-matched boundary (ior 1, "
                        "KHR_materials_volume_scatter) needs the megakernel integrator (--integrator megakernel); "
                        "the wavefront integrator's shadow rays stop at the boundary");
        return std::make_unique<WavefrontIntegrator>(ctx, dev, s, t, maxTilePixels, film);
    }
    return makeMegakernel(ctx, dev, s, t, film);
}

}  // namespace strata
