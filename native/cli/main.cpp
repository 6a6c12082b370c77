// The probelights program: the command line (command_line.cpp) with this process's arguments.
#include <string>
#include <vector>

#include "commands.h"

int main(int argc, char** argv) {
  return probelights::cli::run(std::vector<std::string>(argv + 1, argv + argc));
}
