// A bake's JSON document, as the CLI writes it: the core's result layout (probelights/result_layout.h) in
// nlohmann::json; format in README.md.
#pragma once

#include <nlohmann/json.hpp>

#include "probelights/result_layout.h"

namespace probelights::cli {

nlohmann::json bakeToJson(const BakeReport& report);
nlohmann::json tradeoffToJson(const TradeoffReport& report);
nlohmann::json sequenceFrameToJson(const SequenceFrameReport& report);
nlohmann::json sourceToJson(const std::string& path, const Probe& probe);

}  // namespace probelights::cli
