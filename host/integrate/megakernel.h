// The megakernel integrator: shaders/pathtrace.comp, one path per
// invocation with both traversals inlined (integrate/integrator.h).
#pragma once
#include <memory>

#include "integrate/integrator.h"

namespace strata {

std::unique_ptr<Integrator> makeMegakernel(const vk::Context& ctx, const DeviceScene& dev, const RenderSettings& s,
                                           const RenderTuning& t, const FilmBuffers& film);

}  // namespace strata
