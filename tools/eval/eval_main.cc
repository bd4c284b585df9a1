// slammtt-eval LOG.lcm --json REPORT.json [--plots DIR]: scores a run against the ground truth
// in the same log (definitions in evaluation.h and docs/evaluation.md), prints a summary and,
// with --plots, draws the pictures (tools/plots/eval_plots.h).
#include <cstdio>
#include <iostream>
#include <string>

#include "runtime/command_line.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/eval/report_json.h"
#include "tools/plots/eval_plots.h"

namespace slammtt {
namespace {

void WriteText(const std::string& path, const std::string& text) {
  const std::string partial = path + ".partial";
  std::FILE* f = std::fopen(partial.c_str(), "wb");
  if (f == nullptr) throw std::runtime_error(path + ": cannot create");
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok) {
    std::remove(partial.c_str());
    throw std::runtime_error(path + ": write failed");
  }
  if (std::rename(partial.c_str(), path.c_str()) != 0) {
    std::remove(partial.c_str());
    throw std::runtime_error(path + ": cannot move the report into place");
  }
}

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-eval", "[options] LOG.lcm [--json REPORT.json] [--plots DIR]",
                 "Scores the estimator's output in a log against the GROUND_TRUTH in the same "
                 "log: trajectory error (and that of raw odometry), static map, OSPA/GOSPA and "
                 "CLEAR-MOT tracking, static/moving classification.");
  AddStandardOptions(&cl);
  cl.AddPositional("LOG.lcm",
                   "a log with GROUND_TRUTH (slammtt-world, or slammtt-replay's output)");
  cl.AddOption("json", "REPORT.json", "write the full report as JSON");
  cl.AddOption("plots", "DIR", "write trajectory.svg, map.svg, tracks.svg, errors.svg into DIR");
  if (!cl.Parse(argc, argv)) return 0;
  const std::string path = *cl.Positional("LOG.lcm");
  const ProcessSettings settings = LoadProcessSettings(cl);
  const Config section = settings.config.Child("eval");
  EvalOptions options;
  options.match_threshold_m = section.GetDouble("match_threshold_m", options.match_threshold_m);
  options.ospa_cutoff_m = section.GetDouble("ospa_cutoff_m", options.ospa_cutoff_m);
  options.ospa_order = section.GetDouble("ospa_order", options.ospa_order);
  options.gospa_alpha = section.GetDouble("gospa_alpha", options.gospa_alpha);
  section.CheckUnused();
  if (!(options.match_threshold_m > 0.0)) section.FailKey("match_threshold_m", "must be > 0");
  if (!(options.ospa_cutoff_m > 0.0)) section.FailKey("ospa_cutoff_m", "must be > 0");
  if (!(options.ospa_order >= 1.0)) section.FailKey("ospa_order", "must be >= 1");
  if (!(options.gospa_alpha > 0.0 && options.gospa_alpha <= 2.0)) {
    section.FailKey("gospa_alpha", "must be in (0, 2]");
  }

  LogReadResult read;
  const EvalInput input = ReadEvalInput(path, settings.channels, &read);
  if (read.corrupt) {
    LogError() << read.problem << "; no report written";
    return 1;
  }
  if (!read.problem.empty()) LogWarning() << read.problem;
  const EvaluationReport report = Evaluate(input, options);
  if (const auto json_path = cl.Value("json")) {
    WriteText(*json_path, ReportToJson(input, report).dump(2) + "\n");
  }
  std::cout << ReportSummaryText(report);
  if (const auto json_path = cl.Value("json")) std::cout << "report: " << *json_path << "\n";
  if (const auto dir = cl.Value("plots")) {
    const std::vector<std::string> files = WriteEvaluationPlots(report, *dir);
    std::cout << "pictures: " << *dir << " (";
    for (size_t k = 0; k < files.size(); ++k) {
      std::cout << (k > 0 ? ", " : "") << files[k].substr(files[k].rfind('/') + 1);
    }
    std::cout << ")\n";
  }
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-eval", slammtt::Run);
}
