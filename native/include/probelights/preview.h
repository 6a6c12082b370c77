// A picture of a bake, like Figure 1 of Viriyothai & Debevec 2009: the tone-mapped probe, region borders and
// lights.
#pragma once

#include <string>

#include "probelights/placement.h"
#include "probelights/probe.h"

namespace probelights {

// The Software tag of every preview, by which a library bake recognises a preview it may replace.
inline constexpr const char* kPreviewSoftware = "probelights preview";

// Writes a PNG (or any format OpenImageIO writes, by extension) at most maxWidth pixels wide. Throws Error.
void writePreview(const Probe& probe, const BakeResult& result, const std::string& path, int maxWidth = 2048);

}  // namespace probelights
