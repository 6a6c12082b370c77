#include "probelights/result_layout.h"

namespace probelights {

namespace {

void writeEvaluation(ResultWriter& w, const EvaluatedBake& e) {
  if (!e.evaluated) return w.null("evaluation");
  w.begin("evaluation");
  w.text("effects", effectsToString(e.effects));
  w.boolean("refit", e.refit);
  w.text("error", "relative RMS of luminance vs the probe");
  if (e.effects & kDiffuse) w.number("diffuse", e.errors.diffuse);
  if (e.effects & kShadow) w.number("shadow", e.errors.shadow);
  if (e.effects & kGlossy) w.number("glossy", e.errors.glossy);
  if (e.refit && !e.autoCount) w.number("energy_shift", e.energyShift);
  w.text("sun_angles", toString(e.sunAngles));
  w.text("sun_profile", toString(e.sunProfile));
  w.text("sun_cones", toString(e.sunCones));
  if (e.autoCount) {
    w.begin("auto_count");
    w.boolean("met", e.met);
    w.integer("lights", e.count);
    w.table("tried", e.tried.size(),
            {{"lights", 1, ResultColumn::Kind::Integer,
              [&](std::size_t i, double* out) { out[0] = e.tried[i].first; }},
             {"worst_error", 1, ResultColumn::Kind::Number,
              [&](std::size_t i, double* out) { out[0] = e.tried[i].second; }}});
    w.end();
  }
  w.end();
}

}  // namespace

void writeSource(ResultWriter& w, const std::string& path, const Probe& probe) {
  w.begin("source");
  if (path.empty())
    w.null("path");
  else
    w.text("path", path);
  w.integer("width", probe.width());
  w.integer("height", probe.height());
  w.text("projection", toString(probe.projection().kind()));
  w.integer("negative_samples", probe.report().negativeSamples);
  w.integer("non_finite_samples", probe.report().nonFiniteSamples);
  w.end();
}

namespace {

// A bake's (or a frame's) timings_ms {load, tables, partition, lights} and its notes: the probe's reading
// notes, then the bake's own.
void writeTimingsAndNotes(ResultWriter& w, double loadMs, const BakeTimings& t, const Probe& probe,
                          const std::vector<Note>& bakeNotes) {
  w.begin("timings_ms");
  w.number("load", loadMs);
  w.number("tables", t.tablesMs);
  w.number("partition", t.partitionMs);
  w.number("lights", t.lightsMs);
  w.end();
  std::vector<Note> notes = probe.report().notes;
  notes.insert(notes.end(), bakeNotes.begin(), bakeNotes.end());
  w.notes("notes", notes);
}

}  // namespace

void writeLights(ResultWriter& w, const char* key, const std::vector<Light>& L, bool ids) {
  std::vector<ResultColumn> columns{
      {"direction", 3, ResultColumn::Kind::Number,
       [&](std::size_t i, double* out) {
         out[0] = L[i].direction.x, out[1] = L[i].direction.y, out[2] = L[i].direction.z;
       }},
      {"rgb", 3, ResultColumn::Kind::Number,
       [&](std::size_t i, double* out) { out[0] = L[i].rgb[0], out[1] = L[i].rgb[1], out[2] = L[i].rgb[2]; }},
      {"solid_angle", 1, ResultColumn::Kind::Number,
       [&](std::size_t i, double* out) { out[0] = L[i].solidAngle; }},
      {"angular_radius", 1, ResultColumn::Kind::Number,
       [&](std::size_t i, double* out) { out[0] = L[i].angularRadius; }},
      {"angle", 1, ResultColumn::Kind::Number, [&](std::size_t i, double* out) { out[0] = L[i].angle; }},
      {"rect", 4, ResultColumn::Kind::Integer,
       [&](std::size_t i, double* out) {
         out[0] = L[i].rect.x0, out[1] = L[i].rect.y0, out[2] = L[i].rect.x1, out[3] = L[i].rect.y1;
       }},
      {"energy_share", 1, ResultColumn::Kind::Number,
       [&](std::size_t i, double* out) { out[0] = L[i].energyShare; }}};
  if (ids)
    columns.insert(columns.begin(), {"id", 1, ResultColumn::Kind::Integer,
                                     [](std::size_t i, double* out) { out[0] = static_cast<double>(i); }});
  w.table(key, L.size(), columns);
}

void writeSequenceFrame(ResultWriter& w, const SequenceFrameReport& report) {
  const SequenceFrame& f = report.lights;
  w.integer("frame", report.frame);
  writeSource(w, report.path, report.probe);
  w.boolean("recut", f.recut);
  w.number("motion", f.motion);
  w.number("spread", f.spread);
  w.number("fresh_spread", f.freshSpread);
  w.number("energy_shift", f.energyShift);
  writeLights(w, "lights", f.lights, true);
  w.numbers("total_rgb", f.totalRgb);
  writeTimingsAndNotes(w, report.loadMs, f.timings, report.probe, f.notes);
  if (report.judged) {
    w.begin("evaluation");
    w.number("diffuse", report.judged->errors.diffuse);
    w.number("shadow", report.judged->errors.shadow);
    w.end();
  } else {
    w.null("evaluation");
  }
}

void writeBake(ResultWriter& w, const BakeReport& report) {
  const Probe& probe = report.probe;
  const BakeOptions& o = report.options;
  const BakeResult& r = report.bake.bake;
  // Who wrote it: how a library bake knows its own earlier results, which alone it may replace.
  w.text("generator", "probelights " PROBELIGHTS_VERSION);
  writeSource(w, report.path, probe);
  w.text("method", toString(report.bake.cut));  // with both cuts: the one kept
  if (o.method == Method::SphericalHarmonics) {
    w.begin("sh");
    w.integer("bands", o.shBands);
    w.number("epsilon", o.shEpsilon);
    w.integer("depth", o.shDepth);
    w.end();
  } else {
    w.null("sh");
  }
  w.text("centroid", toString(o.centroid));
  w.integer("requested_lights", report.bake.count);
  w.boolean("horizon_split", r.horizonSplit);
  w.begin("working_resolution");
  w.text("setting", o.resolution.toString());
  w.integer("cell_size", r.cellSize);
  w.end();
  writeLights(w, "lights", r.lights);
  w.numbers("total_rgb", r.totalRgb);
  if (report.bake.sources) {
    // The lamps took the sources alone (sources.h): total_rgb and the lights are the sources', and the
    // residual the world keeps gives back the rest of the probe's light.
    const SourceSplit& split = *report.bake.sources;
    w.begin("sources");
    w.number("level", split.level);
    w.number("mean_luminance", split.meanLuminance);
    w.number("share", split.share);
    w.numbers("sources_rgb", split.sourcesRgb);
    w.numbers("residual_rgb", split.residualRgb);
    w.end();
  } else {
    w.null("sources");
  }
  writeTimingsAndNotes(w, report.loadMs, r.timings, probe, r.notes);
  writeEvaluation(w, report.bake);
}

void writeTradeoff(ResultWriter& w, const TradeoffReport& report) {
  using Kind = ResultColumn::Kind;
  const auto& rows = report.rows;
  writeSource(w, report.path, report.probe);
  w.text("effects", effectsToString(report.effects));
  w.text("error", "relative RMS of luminance over the effect's sample points");
  std::vector<ResultColumn> columns{
      {"method", 1, Kind::Text, {}, [&](std::size_t i) { return toString(rows[i].method); }},
      {"lights", 1, Kind::Integer, [&](std::size_t i, double* out) { out[0] = rows[i].lights; }},
      {"made", 1, Kind::Integer, [&](std::size_t i, double* out) { out[0] = rows[i].made; }},
      {"resolution",
       1,
       Kind::Text,
       {},
       [&](std::size_t i) { return rows[i].resolution ? rows[i].resolution->toString() : std::string("-"); }},
      {"refit", 1, Kind::Boolean, [&](std::size_t i, double* out) { out[0] = rows[i].refit; }},
      {"bake_ms", 1, Kind::Number, [&](std::size_t i, double* out) { out[0] = rows[i].bakeMs; }}};
  if (report.effects & kDiffuse)
    columns.push_back(
        {"diffuse", 1, Kind::Number, [&](std::size_t i, double* out) { out[0] = rows[i].errors.diffuse; }});
  if (report.effects & kShadow)
    columns.push_back(
        {"shadow", 1, Kind::Number, [&](std::size_t i, double* out) { out[0] = rows[i].errors.shadow; }});
  if (report.effects & kGlossy)
    columns.push_back(
        {"glossy", 1, Kind::Number, [&](std::size_t i, double* out) { out[0] = rows[i].errors.glossy; }});
  w.table("rows", rows.size(), columns);
}

}  // namespace probelights
