// The CLI's commands, one file each; each takes the arguments after its name and returns the exit code.
// run() is the whole command line (the arguments after the program's name): usage, dispatch, one-line errors.
#pragma once

#include <string>
#include <vector>

namespace probelights::cli {

int run(const std::vector<std::string>& args);            // command_line.cpp
int bakeCommand(const std::vector<std::string>& argv);    // bake_command.cpp
int shCommand(const std::vector<std::string>& argv);      // sh_commands.cpp
int sampleCommand(const std::vector<std::string>& argv);  // sh_commands.cpp
std::string shOptionsUsage();                             // their options, from sh_request.h's tables
std::string sampleOptionsUsage();
int tradeoffCommand(const std::vector<std::string>& argv);  // tradeoff_command.cpp
std::string tradeoffOptionsUsage();                         // its options, from tradeoff.h's table
int evaluateCommand(const std::vector<std::string>& argv);  // evaluate_command.cpp
std::string evaluateOptionsUsage();                         // its options, from request.h's evaluate table
int sequenceCommand(const std::vector<std::string>& argv);  // sequence_command.cpp
std::string sequenceOptionsUsage();                         // its options, from sequence_request.h's table

}  // namespace probelights::cli
