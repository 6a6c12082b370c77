// The CLI's commands, one file each; each takes the arguments after its name and returns the exit code.
#pragma once

#include <string>
#include <vector>

namespace probelights::cli {

int bakeCommand(const std::vector<std::string>& argv);      // bake_command.cpp
int shCommand(const std::vector<std::string>& argv);        // sh_commands.cpp
int sampleCommand(const std::vector<std::string>& argv);    // sh_commands.cpp
int tradeoffCommand(const std::vector<std::string>& argv);  // tradeoff_command.cpp

}  // namespace probelights::cli
