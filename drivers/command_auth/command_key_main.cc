// slammtt-command-key: makes and checks the key a robot shares with its base stations
// (command_key.h; docs/robot.md, "Who can drive the robot").
#include <iostream>
#include <string>

#include "drivers/command_auth/command_key.h"
#include "runtime/command_line.h"
#include "runtime/process.h"

namespace slammtt {
namespace {

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-command-key", "new FILE | check FILE",
                 "new: writes a new random command key into FILE (which must not exist; mode "
                 "0600). check: reads FILE as slammtt-p3dx does and says whether it is usable.");
  cl.AddPositional("ACTION", "new or check");
  cl.AddPositional("FILE", "the key file");
  if (!cl.Parse(argc, argv)) return 0;
  const std::string action = *cl.Positional("ACTION");
  const std::string path = *cl.Positional("FILE");
  if (action == "new") {
    WriteNewCommandKeyFile(path, NewCommandKey());
    std::cout << path << ": new command key written (mode 0600)\n";
    return 0;
  }
  if (action == "check") {
    LoadCommandKeyFile(path);
    std::cout << path << ": usable command key\n";
    return 0;
  }
  throw UsageError("unknown action '" + action + "' (new or check)");
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-command-key", slammtt::Run);
}
