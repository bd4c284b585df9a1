// slammtt-eval LOG.lcm --json REPORT.json [--plots DIR]: scores a run against the ground truth
// in the same log (definitions in evaluation.h and docs/evaluation.md), prints a summary and,
// with --plots, draws the pictures (tools/plots/eval_plots.h). Exit status: 0 scored; 1 with one
// line and no report when nothing can be (a corrupt log, no GROUND_TRUTH, an empty file); 2 for a
// bad command line or configuration; 3 when the report is written but a headline figure is
// withheld (report_json.h, ReportWarning). Without GROUND_TRUTH (a robot run, an imported
// recording) --plots still draws what the log holds, and a second line says so.
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/config.h"
#include "runtime/log.h"
#include "runtime/process.h"
#include "tools/eval/eval_log.h"
#include "tools/eval/evaluation.h"
#include "tools/eval/report_json.h"
#include "tools/plots/eval_plots.h"

namespace slammtt {
namespace {

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-eval", "[options] LOG.lcm [--json REPORT.json] [--plots DIR]",
                 "Scores the estimator's output in a log against the GROUND_TRUTH in the same "
                 "log: trajectory error (and that of raw odometry), static map, OSPA/GOSPA and "
                 "CLEAR-MOT tracking, static/moving classification.");
  AddStandardOptions(&cl);
  cl.AddPositional("LOG.lcm",
                   "a log with GROUND_TRUTH (slammtt-world, or slammtt-replay's output); "
                   "without it only --plots does anything (exit status 1)",
                   /*required=*/false);  // not with --options-table
  cl.AddOption("json", "REPORT.json", "write the full report as JSON");
  cl.AddOption("plots", "DIR",
               "write trajectory.svg, map.svg, tracks.svg, identities.svg, errors.svg, scan.svg "
               "into DIR (also for a log without GROUND_TRUTH: what the log holds)");
  AddEvalCommandLineOptions(&cl);
  if (!cl.Parse(argc, argv)) return 0;
  if (cl.Flag("options-table")) {
    std::cout << EvalOptionsTable();
    return 0;
  }
  if (!cl.Positional("LOG.lcm")) throw UsageError("missing argument LOG.lcm (see --help)");
  const std::string path = *cl.Positional("LOG.lcm");
  // A configuration mistake is a usage error (exit 2), as a command-line one is.
  ProcessSettings settings;
  EvalOptions options;
  try {
    settings = LoadProcessSettings(cl);
    options = ReadStackEvalOptions(settings.config);
  } catch (const ConfigError& e) {
    throw UsageError(e.what());
  }
  ApplyEvalCommandLine(cl, &options);

  LogReadResult read;
  const EvalInput input = ReadEvalInput(path, settings.channels, &read);
  if (read.corrupt) {
    LogError() << read.problem << "; no report written";
    return 1;
  }
  if (!read.problem.empty()) LogWarning() << read.problem << "; ignored";
  if (input.truth.empty()) {
    LogError() << path << ": no " << settings.channels.Get("ground_truth")
               << ": nothing can be scored; no report written";
    if (const auto dir = cl.Value("plots")) {
      // What the log holds, drawn from the log alone (tools/eval/log_only_scene.h).
      const std::vector<std::string> written =
          WriteTextFiles(*dir, EvaluationPlots(Evaluate(input, options)));
      std::cout << "pictures of what the log holds, nothing scored: " << *dir << " ("
                << written.size() << " files)\n";
    }
    return 1;
  }
  const EvaluationReport report = Evaluate(input, options);
  const std::vector<ReportWarning> warnings = ReportWarnings(report, read.problem);
  if (const auto json_path = cl.Value("json")) {
    WriteFileAtomically(*json_path, ReportJsonText(ReportToJson(input, report, warnings)));
  }
  std::cout << ReportSummaryText(report, warnings);
  if (const auto json_path = cl.Value("json")) std::cout << "report: " << *json_path << "\n";
  if (const auto dir = cl.Value("plots")) {
    const std::vector<std::pair<std::string, std::string>> files = EvaluationPlots(report);
    WriteTextFiles(*dir, files);
    std::cout << "pictures: " << *dir << " (";
    for (size_t k = 0; k < files.size(); ++k) std::cout << (k > 0 ? ", " : "") << files[k].first;
    std::cout << ")\n";
  }
  // 3: the report is written, but a headline figure is withheld (its warning says why).
  for (const ReportWarning& w : warnings) {
    if (w.withholds) return 3;
  }
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-eval", slammtt::Run);
}
