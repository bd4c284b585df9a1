// What the target tests read from slammtt-eval's report (docs/evaluation.md), shared by the
// program of the targets the estimator meets (estimator_targets_test, label `target`) and the
// program of the open ones (estimator_targets_open_test, label `target_open`, docs/targets.md).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "tests/estimator/pipeline_runner.h"

namespace slammtt::testing {

inline constexpr int kTargetSeeds[] = {1, 2, 3, 4, 5};

// A headline number of the report; a failure (and NaN) when it is missing.
inline double Number(const nlohmann::json& report, const char* key) {
  if (!report.contains(key) || !report[key].is_number()) {
    ADD_FAILURE() << "report has no number " << key;
    return std::numeric_limits<double>::quiet_NaN();
  }
  return report[key].get<double>();
}

inline void Print(const std::string& what, const PipelineRun& run) {
  std::cout << what << ": " << Headline(run.report) << "hypotheses " << run.hypotheses << "\n";
}

// Classification details: movers' delays and the share of static objects labelled static.
struct ClassificationFigures {
  std::vector<double> mover_delays_s;  // NaN when a mover never settled on "moving"
  int statics = 0;
  int statics_labelled_static = 0;
};

inline ClassificationFigures Classification(const nlohmann::json& report) {
  ClassificationFigures figures;
  for (const nlohmann::json& o : report["detail"]["classification"]["objects"]) {
    if (o["true_class"] == "moving") {
      figures.mover_delays_s.push_back(o["delay_s"].is_number()
                                           ? o["delay_s"].get<double>()
                                           : std::numeric_limits<double>::quiet_NaN());
    } else {
      ++figures.statics;
      if (o["final_label"] == "static") ++figures.statics_labelled_static;
    }
  }
  return figures;
}

// The run of `scenario`/`seed` in `mode`, printed once when first made.
inline const PipelineRun& TargetRun(const std::string& scenario, int seed,
                                    const std::string& mode) {
  PipelineRunner& runner = SharedPipelineRunner();
  const PipelineRun& run = runner.Run(scenario, seed, mode);
  return run;
}

}  // namespace slammtt::testing
