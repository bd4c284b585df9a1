// The evaluation report as JSON (nlohmann-json) and as a few lines of text for people.
//
// JSON top-level keys, always all present (null when the log lacks what they need, with a note
// in detail.notes): ate_rmse_m, odometry_ate_rmse_m, ospa_mean_m, gospa_mean_m, mota, motp_m,
// id_switches, fragmentations, movers_in_static_map, landmark_rmse_m, static_recall,
// classification_accuracy; and "detail" with one object per part (input, robot, odometry, map,
// tracking, classification) plus "notes". Keys are sorted, so equal reports are equal bytes.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

#include "tools/eval/eval_input.h"
#include "tools/eval/evaluation.h"

namespace slammtt {

// The names of the top-level metrics, in the order of the issue.
const std::vector<std::string>& TopLevelMetricKeys();

nlohmann::json ReportToJson(const EvalInput& input, const EvaluationReport& report);

// A short human summary: one line per part, then the notes.
std::string ReportSummaryText(const EvaluationReport& report);

}  // namespace slammtt
