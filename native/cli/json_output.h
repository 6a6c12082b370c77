// The bake's JSON document, as the CLI writes it (format in README.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "probelights/bake.h"
#include "probelights/probe.h"

namespace probelights::cli {

nlohmann::json bakeToJson(const std::string& sourcePath, const Probe& probe, const BakeOptions& options,
                          const BakeResult& result, double loadMs);

}  // namespace probelights::cli
