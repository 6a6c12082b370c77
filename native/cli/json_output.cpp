#include "json_output.h"

#include <vector>

namespace probelights::cli {

namespace {

// Writes the layout into nested JSON objects; a table becomes an array of objects, one per row.
class JsonWriter : public ResultWriter {
 public:
  explicit JsonWriter(nlohmann::json& root) { stack_.push_back(&root); }
  void begin(const char* key) override { stack_.push_back(&(top()[key] = nlohmann::json::object())); }
  void end() override { stack_.pop_back(); }
  void null(const char* key) override { top()[key] = nullptr; }
  void number(const char* key, double v) override { top()[key] = v; }
  void integer(const char* key, long long v) override { top()[key] = v; }
  void boolean(const char* key, bool v) override { top()[key] = v; }
  void text(const char* key, const std::string& v) override { top()[key] = v; }
  void notes(const char* key, const std::vector<Note>& v) override {
    nlohmann::json list = nlohmann::json::array();
    for (const Note& n : v)
      list.push_back({{"kind", toString(n.kind)}, {"text", n.text}, {"detail", n.detail}});
    top()[key] = list;
  }
  void numbers(const char* key, std::span<const double> v) override {
    top()[key] = std::vector<double>(v.begin(), v.end());
  }
  void table(const char* key, std::size_t rows, const std::vector<ResultColumn>& columns) override {
    nlohmann::json array = nlohmann::json::array();
    double values[16];
    for (std::size_t i = 0; i < rows; ++i) {
      nlohmann::json row = nlohmann::json::object();
      for (const ResultColumn& c : columns) {
        if (c.kind == ResultColumn::Kind::Text) {
          row[c.key] = c.text(i);
          continue;
        }
        c.fill(i, values);
        auto value = [&](int k) {
          switch (c.kind) {
            case ResultColumn::Kind::Integer:
              return nlohmann::json(static_cast<long long>(values[k]));
            case ResultColumn::Kind::Boolean:
              return nlohmann::json(values[k] != 0);
            default:
              return nlohmann::json(values[k]);
          }
        };
        if (c.width == 1) {
          row[c.key] = value(0);
        } else {
          nlohmann::json v = nlohmann::json::array();
          for (int k = 0; k < c.width; ++k) v.push_back(value(k));
          row[c.key] = v;
        }
      }
      array.push_back(row);
    }
    top()[key] = array;
  }

 private:
  nlohmann::json& top() { return *stack_.back(); }
  std::vector<nlohmann::json*> stack_;
};

}  // namespace

nlohmann::json bakeToJson(const BakeReport& report) {
  nlohmann::json root = nlohmann::json::object();
  JsonWriter writer(root);
  writeBake(writer, report);
  return root;
}

nlohmann::json sourceToJson(const std::string& path, const Probe& probe) {
  nlohmann::json root = nlohmann::json::object();
  JsonWriter writer(root);
  writeSource(writer, path, probe);
  return root["source"];
}

nlohmann::json sequenceFrameToJson(const SequenceFrameReport& report) {
  nlohmann::json root = nlohmann::json::object();
  JsonWriter writer(root);
  writeSequenceFrame(writer, report);
  return root;
}

nlohmann::json tradeoffToJson(const TradeoffReport& report) {
  nlohmann::json root = nlohmann::json::object();
  JsonWriter writer(root);
  writeTradeoff(writer, report);
  return root;
}

}  // namespace probelights::cli
