#include "tests/estimator/pipeline_runner.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "runtime/lcm_io.h"
#include "runtime/log_reader.h"
#include "slammtt_msgs/estimator_status_t.hpp"

namespace slammtt::testing {
namespace {

std::string Quote(const std::string& text) { return "'" + text + "'"; }

void Execute(const std::string& command) {
  std::string output;
  const int status = Shell(command, &output);
  if (status != 0) {
    throw std::runtime_error("command failed (" + std::to_string(status) + "): " + command +
                             "\n" + output);
  }
}

}  // namespace

bool PipelineRunner::ScanScenario(const std::string& scenario) {
  return scenario != "s1-crossing";
}

std::string PipelineRunner::WorldLog(const std::string& scenario, int seed) {
  const std::string log = directory_.File(scenario + "-" + std::to_string(seed) + ".lcm");
  if (!std::filesystem::exists(log)) {
    Execute(std::string(SLAMMTT_BIN_DIR) + "/slammtt-world --quiet --scenario " + scenario +
            " --seed " + std::to_string(seed) + " --log " + Quote(log));
  }
  return log;
}

PipelineRunner& SharedPipelineRunner() {
  static PipelineRunner runner;
  return runner;
}

const PipelineRun& PipelineRunner::Run(const std::string& scenario, int seed,
                                       const std::string& mode,
                                       const std::vector<std::string>& extra_yaml,
                                       const std::string& replay_arguments) {
  std::string key = scenario + "|" + std::to_string(seed) + "|" + mode + "|" + replay_arguments;
  for (const std::string& line : extra_yaml) key += "|" + line;
  if (const auto it = runs_.find(key); it != runs_.end()) return it->second;
  const std::string input = WorldLog(scenario, seed);
  const std::string name =
      scenario + "-" + std::to_string(seed) + "-" + mode + "-" + std::to_string(runs_.size());
  const std::string config = directory_.File(name + ".yaml");
  {
    std::ifstream shipped(std::string(SLAMMTT_SOURCE_DIR) + "/estimator/config/" + scenario +
                          ".yaml");
    if (!shipped) throw std::runtime_error("no estimator/config/" + scenario + ".yaml");
    std::stringstream text;
    text << shipped.rdbuf();
    std::ofstream out(config);
    out << text.str() << "  mode: " << mode << "\n";
    for (const std::string& line : extra_yaml) out << "  " << line << "\n";
  }
  PipelineRun run;
  run.output_log = directory_.File(name + ".out.lcm");
  const std::string report = directory_.File(name + ".json");
  std::string stages = " --stage estimator";
  if (ScanScenario(scenario)) stages = " --stage segmenter" + stages;
  Execute(std::string(SLAMMTT_BIN_DIR) + "/slammtt-replay --quiet " + Quote(input) + " -o " +
          Quote(run.output_log) + " --config " + Quote(config) + stages +
          (replay_arguments.empty() ? "" : " " + replay_arguments));
  Execute(std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval --quiet " + Quote(run.output_log) +
          " --json " + Quote(report) + " > /dev/null");
  std::ifstream json(report);
  run.report = nlohmann::json::parse(json);
  LogReader reader(run.output_log);
  while (std::optional<LogEvent> event = reader.Next()) {
    if (event->channel != "ESTIMATOR_STATUS") continue;
    slammtt_msgs::estimator_status_t status;
    if (Decode(event->data.data(), static_cast<int>(event->data.size()), &status)) {
      run.hypotheses = status.hypotheses_generated;
    }
  }
  return runs_.emplace(key, std::move(run)).first->second;
}

nlohmann::json PipelineRunner::Rescore(const PipelineRun& run, const std::string& eval_arguments) {
  const std::string report = run.output_log + "." + std::to_string(rescored_++) + ".json";
  Execute(std::string(SLAMMTT_BIN_DIR) + "/slammtt-eval --quiet " + Quote(run.output_log) +
          " " + eval_arguments + " --json " + Quote(report) + " > /dev/null");
  std::ifstream json(report);
  return nlohmann::json::parse(json);
}

std::string Headline(const nlohmann::json& r) {
  std::ostringstream out;
  for (const char* key : {"ate_rmse_m", "odometry_ate_rmse_m", "mota", "motp_m", "id_switches",
                          "fragmentations", "ospa_mean_m", "gospa_mean_m", "movers_in_static_map",
                          "landmark_rmse_m", "static_recall", "classification_accuracy"}) {
    out << key << " " << (r.contains(key) ? r[key].dump() : "absent") << "  ";
  }
  return out.str();
}

}  // namespace slammtt::testing
