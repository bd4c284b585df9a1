// Runs the shipped pipeline on a shipped scenario the way a user does: slammtt-world writes the
// log, slammtt-replay runs the segmenter (scan scenarios) and the estimator with
// estimator/config/<scenario>.yaml (plus extra estimator keys), slammtt-eval --json scores it.
// Used by the target tests; every figure comes from slammtt-eval's report.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tests/support/child_process.h"

namespace slammtt::testing {

struct PipelineRun {
  nlohmann::json report;           // slammtt-eval --json
  int64_t hypotheses = 0;          // last ESTIMATOR_STATUS.hypotheses_generated
  std::string output_log;          // slammtt-replay's output
};

class PipelineRunner {
 public:
  // Works in a fresh temporary directory, removed with the runner (testing::TempDir).
  PipelineRunner() = default;
  PipelineRunner(const PipelineRunner&) = delete;
  PipelineRunner& operator=(const PipelineRunner&) = delete;

  // Runs scenario/seed in `mode` (ml_ransac, static_nn, ransac_all_pairs). `extra_yaml` lines go
  // into the estimator section ("key: value"); `replay_arguments` are added to slammtt-replay's
  // command line (e.g. "--drop-channel ODOMETRY"). Throws std::runtime_error naming the failing
  // command. The same arguments run once per runner (the pipeline is deterministic): later
  // calls return the first run.
  const PipelineRun& Run(const std::string& scenario, int seed, const std::string& mode,
                         const std::vector<std::string>& extra_yaml = {},
                         const std::string& replay_arguments = "");

  // slammtt-eval --json of `run`'s output with `eval_arguments` added (e.g.
  // "--match-threshold-m 0.75").
  nlohmann::json Rescore(const PipelineRun& run, const std::string& eval_arguments);

  static bool ScanScenario(const std::string& scenario);

 private:
  std::string WorldLog(const std::string& scenario, int seed);
  TempDir directory_{"slammtt-targets"};
  std::map<std::string, PipelineRun> runs_;
  int rescored_ = 0;
};

// One runner for the whole test program (its directory is removed at exit).
PipelineRunner& SharedPipelineRunner();

// "name value" lines of the report's headline metrics, for logs and the docs.
std::string Headline(const nlohmann::json& report);

}  // namespace slammtt::testing
