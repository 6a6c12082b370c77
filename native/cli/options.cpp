#include "options.h"

#ifndef _WIN32
#include <unistd.h>
#endif

#include <cmath>
#include <cstdio>
#include <sstream>

#include "probelights/names.h"
#include "write_whole.h"

namespace probelights::cli {

namespace {
std::FILE* userStderr = nullptr;
}

std::string spelled(const Remedy& remedy) {
  const std::string option =
      remedy.option == "projection" ? "--projection" : requestOption(remedy.option).cliName();
  return option + " " + listOf(remedy.values);
}

std::FILE* messages() { return userStderr ? userStderr : stderr; }

void quietLibraries() {
#ifdef _WIN32
  // The Python package's module there reads images through Python, whose libraries print nothing.
#else
  const int fd = dup(STDERR_FILENO);
  std::FILE* user = fd >= 0 ? fdopen(fd, "w") : nullptr;
  std::FILE* nowhere = std::fopen("/dev/null", "w");
  if (!user || !nowhere) return;  // keep things as they are
  std::setvbuf(user, nullptr, _IONBF, 0);
  userStderr = user;
  stderr = nowhere;  // glibc's stderr is a variable: libpng's fprintf(stderr, ...) reads it at each call
#endif
}

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
      if (inlineValue && !option->switchValue) throw UsageError(name + " takes no value");
      option->apply(inlineValue ? a.substr(eq + 1) : "");
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

std::string nonEmpty(const std::string& flag, const std::string& value) {
  if (value.empty()) throw UsageError(flag + " needs a name, got an empty one");
  return value;
}

void refuseOverwritingProbe(const std::string& probe, const std::vector<std::string>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].empty() || outputs[i] == "-") continue;
    if (outputs[i] == probe || sameFile(outputs[i], probe))
      throw UsageError("'" + outputs[i] + "' is the probe itself: write the output elsewhere");
    for (std::size_t k = 0; k < i; ++k)
      if (outputs[k] == outputs[i]) throw UsageError("two outputs name the same file '" + outputs[i] + "'");
  }
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  return items;
}

std::string usageLines(std::string head, const std::string& text) {
  std::string out;
  if (head.size() >= 36) out += head + "\n", head.clear();
  head.resize(36, ' ');
  std::string line = head;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t take = std::min<std::size_t>(110 - 36, text.size() - at);
    if (at + take < text.size()) {
      const std::size_t space = text.rfind(' ', at + take);
      if (space != std::string::npos && space > at) take = space - at;
    }
    line += text.substr(at, take);
    out += line + "\n";
    at += take;
    while (at < text.size() && text[at] == ' ') ++at;
    line.assign(36, ' ');
  }
  return out;
}

std::string dumpJson(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void writeJson(const nlohmann::json& j, const std::string& output, int indent) {
  if (indent == -2) indent = output == "-" ? -1 : 1;
  const std::string text = dumpJson(j, indent);
  if (output == "-")
    writeStdout(text);
  else
    writeWhole(output, text);
}

}  // namespace probelights::cli
