// One layout of a bake's result for every shell: the CLI's JSON (native/cli/json_output.cpp) and the Python
// module's dict (native/python/shell.cpp) are both written by writeBake() through a ResultWriter, so they
// have the same keys, nested the same way (tests/python/test_module.py checks it). The layout (README,
// "JSON"):
//   source {path, width, height, projection, negative_samples, non_finite_samples}
//   method, sh {bands, epsilon, depth} | null, centroid, requested_lights, horizon_split,
//   working_resolution {setting, cell_size},
//   lights: a table, one row per light: direction (3), rgb (3), solid_angle, angular_radius, angle, rect (4),
//           energy_share
//   total_rgb (3), timings_ms {load, tables, partition, lights}, notes,
//   evaluation {effects, refit, error, diffuse | shadow | glossy, energy_shift, sun_angles, sun_profile,
//               sun_cones, auto_count {met, lights, tried: a table of lights, worst_error}} | null
// and of the tradeoff grid (writeTradeoff, below).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "probelights/placement.h"
#include "probelights/probe.h"
#include "probelights/sequence.h"
#include "probelights/tradeoff.h"

namespace probelights {

// A column of a table: `width` numbers per row (1: a scalar), filled row by row; or one word per row (text).
struct ResultColumn {
  enum class Kind { Number, Integer, Boolean, Text };
  const char* key;
  int width = 1;
  Kind kind = Kind::Number;
  std::function<void(std::size_t row, double* out)> fill;  // Number, Integer, Boolean (0 or 1)
  std::function<std::string(std::size_t row)> text = {};   // Text
};

// What a shell implements to receive the layout: keyed values inside nested objects.
class ResultWriter {
 public:
  virtual ~ResultWriter() = default;
  virtual void begin(const char* key) = 0;  // a nested object, until end()
  virtual void end() = 0;
  virtual void null(const char* key) = 0;
  virtual void number(const char* key, double value) = 0;
  virtual void integer(const char* key, long long value) = 0;
  virtual void boolean(const char* key, bool value) = 0;
  virtual void text(const char* key, const std::string& value) = 0;
  // Notes (note.h): a list of {kind, text, detail}.
  virtual void notes(const char* key, const std::vector<Note>& values) = 0;
  virtual void numbers(const char* key, std::span<const double> values) = 0;
  virtual void table(const char* key, std::size_t rows, const std::vector<ResultColumn>& columns) = 0;
};

struct BakeReport {
  std::string path;  // the probe's file; "" for a caller's pixels (written as null)
  const Probe& probe;
  const BakeOptions& options;
  const EvaluatedBake& bake;
  double loadMs = 0;
};

void writeBake(ResultWriter& writer, const BakeReport& report);

// A table of lights (a bake's "lights"); `ids`: each row's index first, as "id" (a sequence's lights).
void writeLights(ResultWriter& writer, const char* key, const std::vector<Light>& lights, bool ids = false);

// One frame of a sequence (sequence.h): frame, source, recut, motion, spread, fresh_spread, lights (with
// id), total_rgb, timings_ms {load, tables, partition, lights}, notes, evaluation {diffuse, shadow} | null.
struct SequenceFrameReport {
  int frame = 0;
  std::string path;
  const Probe& probe;
  const SequenceFrame& lights;
  const FrameResponse* judged = nullptr;  // when evaluated
  double loadMs = 0;
};
void writeSequenceFrame(ResultWriter& writer, const SequenceFrameReport& report);

// The "source" object alone (every document about a probe starts with it).
void writeSource(ResultWriter& writer, const std::string& path, const Probe& probe);

// The tradeoff grid (tradeoff.h): source, effects, error, and rows: a table of method, lights, made,
// resolution ("-" for the SH method), refit, bake_ms and each evaluated effect's error.
struct TradeoffReport {
  std::string path;
  const Probe& probe;
  Effects effects;
  const std::vector<TradeoffRow>& rows;
};

void writeTradeoff(ResultWriter& writer, const TradeoffReport& report);

}  // namespace probelights
