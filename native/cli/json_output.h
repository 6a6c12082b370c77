// The bake's JSON document, as the CLI writes it (format in README.md).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "probelights/bake.h"
#include "probelights/evaluate.h"
#include "probelights/probe.h"

namespace probelights::cli {

// What evaluating a bake found (the --evaluate, --refit and --max-error options).
struct Evaluation {
  bool done = false, refit = false, autoCount = false, met = false;
  unsigned effects = 0;
  EffectErrors errors;
  double energyShift = 0;
  std::vector<std::pair<int, double>> tried;
};

nlohmann::json bakeToJson(const std::string& sourcePath, const Probe& probe, const BakeOptions& options,
                          const BakeResult& result, double loadMs, const Evaluation& evaluation);

}  // namespace probelights::cli
