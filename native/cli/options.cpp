#include "options.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace probelights::cli {

std::vector<std::string> parseOptions(const std::vector<std::string>& argv,
                                      const std::vector<Option>& table) {
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    const auto eq = a.find('=');
    const bool inlineValue = a.rfind("--", 0) == 0 && eq != std::string::npos;
    const std::string name = inlineValue ? a.substr(0, eq) : a;
    const Option* option = nullptr;
    for (const Option& o : table)
      for (const std::string& n : o.names)
        if (n == name) option = &o;
    if (option == nullptr) {
      if (!name.empty() && name[0] == '-' && name != "-")
        throw UsageError("unknown option '" + name + "' (see probelights --help)");
      positional.push_back(a);
      continue;
    }
    if (option->flag) {
      if (inlineValue) throw UsageError(name + " takes no value");
      option->apply("");
    } else if (inlineValue) {
      option->apply(a.substr(eq + 1));
    } else {
      if (i + 1 >= argv.size()) throw UsageError(name + " needs a value");
      option->apply(argv[++i]);
    }
  }
  return positional;
}

std::string oneProbe(const std::vector<std::string>& positional, const std::string& command) {
  if (positional.empty()) throw UsageError("no probe given: probelights " + command + " PROBE");
  if (positional.size() > 1)
    throw UsageError("one probe at a time: got '" + positional[0] + "' and '" + positional[1] + "'");
  return positional[0];
}

void addProbeOptions(std::vector<Option>& table, ProbeOptions& options) {
  table.push_back(
      {{"--projection"}, [&](const std::string& v) { options.projection = parseProjectionChoice(v); }});
  table.push_back(
      {{"--nonfinite"}, [&](const std::string& v) { options.nonFinite = parseNonFinitePolicy(v); }});
}

double parseReal(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a number, got '" + text + "'");
}

int parseCount(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    long long n = std::stoll(text, &used);
    if (used == text.size() && n >= -1000000000LL && n <= 1000000000LL) return static_cast<int>(n);
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a whole number, got '" + text + "'");
}

double parseTolerance(const std::string& flag, const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  double v = parseReal(flag, percent ? text.substr(0, text.size() - 1) : text);
  return percent ? v / 100 : v;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  return items;
}

void writeJson(const nlohmann::json& j, const std::string& output, int indent) {
  if (indent == -2) indent = output == "-" ? -1 : 1;
  std::string text = j.dump(indent) + "\n";
  if (output == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return;
  }
  std::ofstream out(output);
  if (!(out << text)) throw Error("cannot write '" + output + "'");
}

}  // namespace probelights::cli
