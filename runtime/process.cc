#include "runtime/process.h"

#include <exception>

#include "runtime/lcm_io.h"
#include "runtime/log.h"
#include "runtime/shutdown.h"

namespace slammtt {

const std::vector<std::string>& KnownConfigSections() {
  static const std::vector<std::string> sections = {
      "lcm",     "channels", "segmenter", "estimator", "smoother",
      "rplidar", "p3dx",     "robot",     "replay",    "eval"};
  return sections;
}

void AddStandardOptions(CommandLine* command_line) {
  command_line->AddOption("config", "FILE", "stack configuration file (YAML, see config/)", 'c');
  command_line->AddOption("lcm-url", "URL",
                          "LCM bus (default: lcm.url of the config, then $LCM_DEFAULT_URL, then " +
                              std::string(kDefaultLcmUrl) + ")");
  command_line->AddRepeatedOption("channel", "KEY=NAME",
                                  "rename a channel, e.g. --channel features=FEATURES_SIM");
  command_line->AddFlag("verbose", "print debug messages", 'v');
  command_line->AddFlag("quiet", "print only warnings and errors", 'q');
}

ProcessSettings LoadProcessSettings(const CommandLine& command_line) {
  if (command_line.Flag("verbose")) SetLogLevel(LogLevel::kDebug);
  if (command_line.Flag("quiet")) SetLogLevel(LogLevel::kWarning);

  ProcessSettings settings;
  if (const auto path = command_line.Value("config")) {
    settings.config = Config::LoadFile(*path);
    settings.config_path = *path;
    settings.config.CheckKeysAmong(KnownConfigSections());
  }
  const Config lcm_section = settings.config.Child("lcm");
  std::optional<std::string> url_from_config;
  if (lcm_section.Has("url")) url_from_config = lcm_section.RequireString("url");
  lcm_section.CheckUnused();
  settings.lcm_url = ResolveLcmUrl(command_line.Value("lcm-url"), url_from_config);

  const Config channel_section = settings.config.Child("channels");
  settings.channels.ApplyConfig(channel_section);
  settings.channels.ApplyOverrides(command_line.Values("channel"));
  return settings;
}

int ProcessMain(int argc, char** argv, const std::string& program,
                const std::function<int(int, char**)>& body) {
  SetLogProgramName(program);
  InstallShutdownHandlers();
  try {
    return body(argc, argv);
  } catch (const UsageError& e) {
    LogLine(LogLevel::kError, e.what());
    return 2;
  } catch (const std::exception& e) {
    LogLine(LogLevel::kError, e.what());
    return 1;
  } catch (...) {
    LogLine(LogLevel::kError, "unknown fatal error");
    return 1;
  }
}

}  // namespace slammtt
