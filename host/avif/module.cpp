#include "avif/module.h"

#include <mutex>

#include "util/module.h"

namespace strata::avif {

const Api* module(std::string& error) {
    static std::once_flag once;
    static const Api* api = nullptr;
    static std::string why;
    std::call_once(once, [] {
        api = static_cast<const Api*>(loadModuleApi({"STRATA_AVIF_MODULE", STRATA_AVIF_MODULE, "libstrata_avif.so",
                                                      "strata_avif_api", kApiVersion,
                                                      "strata was built without the AVIF decoder (libavif)",
                                                      "AVIF module"},
                                                     why));
    });
    if (!api) error = why;
    return api;
}

}  // namespace strata::avif
