// The evaluation report as JSON (nlohmann-json) and as a few lines of text for people.
//
// JSON top-level keys, always all present (null when the log lacks what they need, with a note
// in detail.notes, or when a warning withholds them, see ReportWarning; "warnings" is always an
// array): ate_rmse_m, odometry_ate_rmse_m, ospa_mean_m, gospa_mean_m, mota, motp_m,
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

// What keeps a report from meaning what its headline figures say, found from the report and the
// log's damage report. In the JSON as "warnings": [{"code", "message"}], in file order of the
// checks; slammtt-eval exits 3 when one of them `withholds` a figure.
//  - log_truncated: the log ends inside its last event (what a killed logger leaves); the
//    complete events were scored. Withholds nothing.
//  - pose_coverage: POSE of the same utime at fewer than kMinScoredFraction of the ground-truth
//    scans: the top-level ate_rmse_m is null (detail.robot keeps what was computed).
//  - tracks_coverage: TRACKS of the same utime at fewer than kMinScoredFraction of the scans
//    tracking scored (a TRACKS that matches no scan is scored as an empty output): the
//    top-level tracking figures (ospa, gospa, mota, motp, id_switches, fragmentations, idf1,
//    hota) are null.
struct ReportWarning {
  std::string code;
  std::string message;
  bool withholds = false;
};
inline constexpr double kMinScoredFraction = 0.5;
// `log_problem`: LogReadResult::problem of a log that was read (a truncated tail), or "".
std::vector<ReportWarning> ReportWarnings(const EvaluationReport& report,
                                          const std::string& log_problem);

// The report; `warnings` (from ReportWarnings) null the figures they withhold.
nlohmann::json ReportToJson(const EvalInput& input, const EvaluationReport& report,
                            const std::vector<ReportWarning>& warnings = {});

// The JSON as slammtt-eval writes it: indented by 2, a newline at the end, bytes that are no
// UTF-8 (a log's path can hold any) each replaced by U+FFFD.
std::string ReportJsonText(const nlohmann::json& report);

// A short human summary: one line per part, then the notes, then "warning: " lines.
std::string ReportSummaryText(const EvaluationReport& report,
                              const std::vector<ReportWarning>& warnings = {});

}  // namespace slammtt
