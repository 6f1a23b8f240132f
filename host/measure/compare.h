// `strata compare IMAGE REFERENCE [--json FILE]`: error metrics of an image
// against a reference (RGB channels by name; sizes must match).
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "image/metrics.h"

namespace strata {

nlohmann::json metricsJson(const ErrorMetrics& m);

// Reads both images and compares them. Throws strata::Error naming the file
// on unreadable input and on images of different sizes.
ErrorMetrics compareFiles(const std::string& image, const std::string& reference);

// The arguments as the command line parsed and checked them (cli/checks.h).
int runCompare(const std::string& image, const std::string& reference, const std::string& json);

}  // namespace strata
