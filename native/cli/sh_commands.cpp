// probelights sh and probelights sample: the probe's SH coefficients, and samples of its SH importance
// sampler (Jarosz et al. 2009 warping, Berger 2011 epsilon clamping). Usage in main.cpp.
#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/image_file.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"

namespace probelights::cli {

namespace {

constexpr const char* kConvention =
    "real SH, index l(l+1)+m, orthonormal, Condon-Shortley phase (Sloan 2008); theta from +Z, phi = atan2(y, "
    "x)";

// What the sh and sample commands take.
struct ShArgs {
  std::string probe, output = "-";
  ProbeOptions probeOptions;
  int bands = 0, samples = 0, depth = 8;
  double epsilon = -1;
  std::uint64_t seed = 1;
  bool irradiance = false;
  ShWindow window = ShWindow::None;
};

ShArgs parseShArgs(const std::vector<std::string>& argv, bool sampling) {
  ShArgs a;
  std::vector<Option> table{
      {{"--bands"}, [&](const std::string& v) { a.bands = parseCount("--bands", v); }},
      {{"-o", "--output"}, [&](const std::string& v) { a.output = nonEmpty("-o", v); }},
  };
  if (sampling) {
    table.push_back({{"--samples"}, [&](const std::string& v) { a.samples = parseCount("--samples", v); }});
    table.push_back({{"--depth"}, [&](const std::string& v) { a.depth = parseCount("--depth", v); }});
    table.push_back({{"--seed"}, [&](const std::string& v) {
                       a.seed = static_cast<std::uint64_t>(parseCount("--seed", v));
                     }});
    table.push_back({{"--epsilon"}, [&](const std::string& v) { a.epsilon = parseReal("--epsilon", v); }});
  } else {
    table.push_back(flag({"--irradiance"}, [&] { a.irradiance = true; }));
    table.push_back({{"--window"}, [&](const std::string& v) { a.window = parseShWindow(v); }});
  }
  addProbeOptions(table, a.probeOptions);
  a.probe = oneProbe(parseOptions(argv, table), sampling ? "sample" : "sh");
  refuseOverwritingProbe(a.probe, {a.output});
  if (a.bands < 1) throw UsageError("--bands B (at least 1) is required");
  if (sampling && a.samples < 1) throw UsageError("--samples N (at least 1) is required");
  if (sampling && a.epsilon < 0) throw UsageError("--epsilon E (in [0, 0.5]) is required");
  return a;
}

}  // namespace

int shCommand(const std::vector<std::string>& argv) {
  ShArgs a = parseShArgs(argv, false);
  Probe probe = loadProbe(a.probe, a.probeOptions);
  ShCoefficients sh = projectProbe(probe, a.bands);
  applyWindow(sh, a.window);
  if (a.irradiance) sh = irradianceCoefficients(sh);
  nlohmann::json c = nlohmann::json::array();
  for (const Rgb& v : sh.c) c.push_back(v);
  writeJson({{"source", sourceToJson(a.probe, probe)},
             {"bands", a.bands},
             {"convention", kConvention},
             {"quantity", a.irradiance ? "irradiance" : "radiance"},
             {"window", toString(a.window)},
             {"coefficients", c}},
            a.output);
  return 0;
}

int sampleCommand(const std::vector<std::string>& argv) {
  ShArgs a = parseShArgs(argv, true);
  Probe probe = loadProbe(a.probe, a.probeOptions);
  ShSampler sampler(a.bands, projectProbe(probe, a.bands).luminance(), a.epsilon, a.depth);
  nlohmann::json dirs = nlohmann::json::array(), pdfs = nlohmann::json::array();
  for (const auto& s : sampler.sampleSeeded(a.samples, a.seed)) {
    dirs.push_back({s.direction.x, s.direction.y, s.direction.z});
    pdfs.push_back(s.pdf);
  }
  writeJson({{"source", sourceToJson(a.probe, probe)},
             {"bands", a.bands},
             {"epsilon", a.epsilon},
             {"depth", a.depth},
             {"seed", a.seed},
             {"convention", kConvention},
             {"directions", dirs},
             {"pdf", pdfs}},
            a.output);
  return 0;
}

}  // namespace probelights::cli
