// What every CLI command shares: a declarative option table and its parser, number parsing, JSON output.
#pragma once

#include <cstdio>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "probelights/error.h"
#include "probelights/probe.h"
#include "probelights/request.h"

namespace probelights::cli {

// A bad command line: exit code 2 like every other bad input, with the one-line message.
struct UsageError : Error {
  using Error::Error;
};

// Where the CLI's own messages go: the standard error the user sees. Decoders under OpenImageIO (libpng,
// libtiff) print complaints of their own on stderr beside the error OpenImageIO reports ("libpng error:
// ..."); quietLibraries() sends the C library's stderr nowhere, so a bad file gives the user one line, the
// CLI's.
std::FILE* messages();
void quietLibraries();

// A failure's remedy (error.h) as the command line spells it: "--nonfinite zero", "--projection latlong,
// mirror-ball or angular"; and a failure told with it.
std::string spelled(const Remedy& remedy);
inline std::string described(const Error& e) { return describe(e, spelled); }

// One option of a command: its spellings and what it does with its value (a flag takes none; a switch is a
// flag that also takes "=on" or "=off", "--refit=off" turning off what a preset turned on).
struct Option {
  std::vector<std::string> names;                 // e.g. {"--lights", "-n"}
  std::function<void(const std::string&)> apply;  // with the value ("" for a flag, or a switch without one)
  bool flag = false;
  bool switchValue = false;
};

inline Option flag(std::vector<std::string> names, std::function<void()> set) {
  return {std::move(names), [set = std::move(set)](const std::string&) { set(); }, true};
}

inline Option onOffSwitch(std::vector<std::string> names, std::function<void(const std::string&)> set) {
  return {std::move(names), std::move(set), true, true};
}

// Reads "--option value", "--option=value", flags and "--switch=off" against `table`; returns the positional
// arguments. Unknown options are a UsageError.
std::vector<std::string> parseOptions(const std::vector<std::string>& argv, const std::vector<Option>& table);

// One option of a usage text: `head` ("  --name VALUES") in a column of 36, then `text` wrapped at 110
// columns.
std::string usageLines(std::string head, const std::string& text);

// The usage lines of an option table (request.h's TableOption): its name (and `alias`'s extra spelling), its
// values or, for a switch, "[=off]", its help and its default in `defaults`.
template <class Options, class Target>
std::string tableUsage(const Options& options, const Target& defaults,
                       std::string (*alias)(const std::string& name) = nullptr) {
  std::string out;
  for (const auto& o : options)
    out += usageLines(
        "  " + o.cliName() + (alias ? alias(o.name) : "") + (o.isSwitch() ? "[=off]" : " " + o.values),
        o.help + (o.isSwitch() || o.get(defaults).empty() ? "" : " (default " + o.get(defaults) + ")"));
  return out;
}

// A command's options from a table (request.h's TableOption: a bake's, a tradeoff's, an evaluation's), as
// the module takes them: each value kept as it is read, and applied by apply() after the whole line is read,
// in the table's order whatever their order here (a preset first, the options that change it after; the
// same option twice, the last).
template <class Target>
class TableOptions {
 public:
  explicit TableOptions(const std::vector<TableOption<Target>>& options) : options_(options) {}
  // The table's options, for parseOptions's table (a switch also takes =off), with `aliases`' other spellings
  // of some (option name, spelling: "lights", "-n").
  void addTo(std::vector<Option>& table,
             const std::vector<std::pair<std::string, std::string>>& aliases = {}) {
    for (const TableOption<Target>& o : options_) {
      const TableOption<Target>* at = &o;
      std::vector<std::string> names{o.cliName()};
      for (const auto& [name, spelling] : aliases)
        if (name == o.name) names.push_back(spelling);
      if (o.isSwitch())
        table.push_back(onOffSwitch(std::move(names), [this, at](const std::string& v) {
          given_.emplace_back(at, v.empty() ? "true" : v);
        }));
      else
        table.push_back({std::move(names), [this, at](const std::string& v) { given_.emplace_back(at, v); }});
    }
  }
  void give(const std::string& name, const std::string& value) {
    given_.emplace_back(&tableOption(options_, name), value);
  }
  bool has(const std::string& name) const {  // whether the command line gave the option
    const TableOption<Target>* o = &tableOption(options_, name);
    for (const auto& g : given_)
      if (g.first == o) return true;
    return false;
  }
  void apply(Target& target) const {
    for (const TableOption<Target>& o : options_)
      for (const auto& [option, value] : given_)
        if (option == &o) o.set(target, o.cliName(), value);
  }

 private:
  const std::vector<TableOption<Target>>& options_;
  std::vector<std::pair<const TableOption<Target>*, std::string>> given_;
};

// The one probe a command takes, from the positional arguments.
std::string oneProbe(const std::vector<std::string>& positional, const std::string& command);

// The options every command reading a probe has: --projection and --nonfinite.
void addProbeOptions(std::vector<Option>& table, ProbeOptions& options);

// An option's value that must not be empty (a file or folder name).
std::string nonEmpty(const std::string& flag, const std::string& value);

// Refuses outputs that name the probe being read (or each other): a command never writes over its input.
void refuseOverwritingProbe(const std::string& probe, const std::vector<std::string>& outputs);

// Numbers: parseReal, parseCount and parseTolerance of request.h.
std::vector<std::string> splitList(const std::string& text);  // "a,b,c"

// JSON as text: indented by `indent` (-1: compact), ending in a newline; a string that is not UTF-8 (a file
// name's bytes) has U+FFFD in place of its bad bytes.
std::string dumpJson(const nlohmann::json& j, int indent);

// JSON to a file, or standard output for "-"; indented by `indent`, by default compact on standard output and
// by 1 in a file.
void writeJson(const nlohmann::json& j, const std::string& output, int indent = -2);

}  // namespace probelights::cli
