// The tradeoff plot (`probelights tradeoff --plot`).
#pragma once

#include <string>
#include <vector>

#include "probelights/tradeoff.h"

namespace probelights::cli {

// Writes error (the worst of the evaluated effects, %) against bake time (ms), log axes, one curve per method
// (refit curves lighter), as a PNG.
void writeTradeoffPlot(const std::vector<TradeoffRow>& rows, Effects effects, const std::string& title,
                       const std::string& path);

}  // namespace probelights::cli
