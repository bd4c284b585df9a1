// slammtt-smooth-dataset: solves a pose-landmark text file (pose_landmark_dataset.h) with the
// smoother, batch or incrementally keyframe by keyframe, and prints one JSON object: final
// chi-square, wall times, per-update percentiles, peak memory (getrusage: run one mode per
// process to measure each alone). Used by scripts/compare-victoria-park.py.
//
//   slammtt-smooth-dataset FILE [--mode batch|incremental] [--reading bearing-range|relative]
//                               [--max-keyframes N] [--method lm|gn] [--solution OUT] [--trace]
//                               [--initial SOLUTION] [--polish]
//                               [--pose-update additive|exponential]
// --initial (batch): start from a solution file (POSE id x y theta / POINT id x y lines, the
// format --solution writes) instead of the odometry chain. --polish (incremental): after the
// last keyframe, Optimize from the incremental estimate (chi-square and time reported apart).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "runtime/command_line.h"
#include "runtime/output_file.h"
#include "runtime/process.h"
#include "smoother/pose_landmark_dataset.h"
#include "smoother/smoother.h"

namespace slammtt {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct DatasetRunOptions {
  std::string file;
  bool incremental = false;
  std::string reading_name = "bearing-range";
  LandmarkReading reading = LandmarkReading::kBearingRange;
  SmootherOptions::Method method = SmootherOptions::Method::kLevenbergMarquardt;
  SmootherOptions::PoseUpdate pose_update = SmootherOptions{}.pose_update;
  std::string solution_path;
  std::string initial_path;
  int64_t max_keyframes = -1;
  bool trace = false;
  bool polish = false;
};

// What one run measured, for the JSON line.
struct DatasetRunFigures {
  size_t keyframes = 0;
  SolveReport report;
  double solve_seconds = 0.0;
  double total_seconds = 0.0;
  std::vector<double> step_seconds;
  double polished_chi_square = 0.0;
  double polish_seconds = 0.0;
};

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t index = std::min(values.size() - 1, static_cast<size_t>(q * values.size()));
  return values[index];
}

// Empty when --help or --version was asked for (already printed).
std::optional<DatasetRunOptions> ParseArguments(int argc, char** argv) {
  CommandLine cl("slammtt-smooth-dataset", "[options] FILE",
                 "Solves a pose-landmark text file with the sparse smoother (batch or "
                 "incremental) and prints one JSON object of its figures.");
  cl.AddPositional("FILE", "a pose-landmark file (Victoria Park's format, docs/smoother.md)");
  cl.AddOption("mode", "batch|incremental", "solve once at the end, or keyframe by keyframe");
  cl.AddOption("reading", "bearing-range|relative", "how the file's landmark lines read");
  cl.AddOption("method", "lm|gn", "Levenberg-Marquardt (default) or Gauss-Newton");
  cl.AddOption("pose-update", "additive|exponential",
               "a step moves a pose by adding to (x, y, theta) (default) or by pose * exp(step), "
               "GTSAM's Pose2 retraction");
  cl.AddOption("max-keyframes", "N", "only the first N keyframes");
  cl.AddOption("solution", "OUT", "write the solution (POSE / POINT lines) to OUT");
  cl.AddOption("initial", "SOLUTION", "batch: start from a solution file, not the odometry");
  cl.AddFlag("polish", "incremental: one batch solve from the incremental estimate at the end");
  cl.AddFlag("trace", "stderr: every re-factorising or slow (> 50 ms) update");
  if (!cl.Parse(argc, argv)) return std::nullopt;
  DatasetRunOptions o;
  o.file = *cl.Positional("FILE");
  const std::string mode = cl.ValueOr("mode", "batch");
  if (mode != "batch" && mode != "incremental") throw UsageError("--mode batch or incremental");
  o.incremental = mode == "incremental";
  o.reading_name = cl.ValueOr("reading", o.reading_name);
  if (o.reading_name != "bearing-range" && o.reading_name != "relative") {
    throw UsageError("--reading bearing-range or relative");
  }
  if (o.reading_name == "relative") o.reading = LandmarkReading::kRelativePosition;
  const std::string method = cl.ValueOr("method", "lm");
  if (method != "lm" && method != "gn") throw UsageError("--method lm or gn");
  if (method == "gn") o.method = SmootherOptions::Method::kGaussNewton;
  const std::string pose_update = cl.ValueOr("pose-update", "additive");
  if (pose_update != "additive" && pose_update != "exponential") {
    throw UsageError("--pose-update additive or exponential");
  }
  if (pose_update == "exponential") o.pose_update = SmootherOptions::PoseUpdate::kExponential;
  if (const std::optional<int64_t> n = cl.IntValue("max-keyframes")) {
    if (*n < 1) throw UsageError("--max-keyframes takes a positive number");
    o.max_keyframes = *n;
  }
  o.solution_path = cl.ValueOr("solution", "");
  o.initial_path = cl.ValueOr("initial", "");
  o.polish = cl.Flag("polish");
  o.trace = cl.Flag("trace");
  return o;
}

PoseLandmarkDataset ReadDataset(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw UsageError("cannot open " + path);
  DatasetParseResult parsed = ParsePoseLandmarkDataset(in);
  if (!parsed.dataset) throw std::runtime_error(path + ": " + parsed.error);
  return std::move(*parsed.dataset);
}

void AddKeyframeOrThrow(const PoseLandmarkDataset& dataset, size_t k, LandmarkReading reading,
                        Smoother* smoother) {
  if (auto error = AddKeyframe(dataset, k, reading, smoother)) {
    throw std::runtime_error("keyframe " + std::to_string(k) + ": " + *error);
  }
}

// POSE id x y theta / POINT id x y lines, as --solution writes them.
void SetInitialSolution(const std::string& path, Smoother* smoother) {
  std::ifstream initial(path);
  if (!initial) throw UsageError("cannot open " + path);
  std::string tag;
  int64_t id = 0;
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;
  while (initial >> tag >> id >> x >> y) {
    std::optional<std::string> error;
    if (tag == "POSE" && initial >> theta) {
      error = smoother->SetPoseEstimate(id, Eigen::Vector3d(x, y, theta));
    } else if (tag == "POINT") {
      error = smoother->SetLandmarkEstimate(id, Eigen::Vector2d(x, y));
    } else {
      error = "bad line " + tag;
    }
    if (error) throw std::runtime_error(path + ": " + *error);
  }
  if (!initial.eof()) {
    throw std::runtime_error(path + ": unreadable line after " + tag + " " +
                             std::to_string(id));
  }
}

void SolveBatch(const PoseLandmarkDataset& dataset, const DatasetRunOptions& o,
                Smoother* smoother, DatasetRunFigures* figures) {
  for (size_t k = 0; k < figures->keyframes; ++k) {
    AddKeyframeOrThrow(dataset, k, o.reading, smoother);
  }
  if (!o.initial_path.empty()) SetInitialSolution(o.initial_path, smoother);
  const Clock::time_point solve_start = Clock::now();
  figures->report = smoother->Optimize();
  figures->solve_seconds = SecondsSince(solve_start);
}

void SolveIncrementally(const PoseLandmarkDataset& dataset, const DatasetRunOptions& o,
                        Smoother* smoother, DatasetRunFigures* figures) {
  const Clock::time_point start = Clock::now();
  for (size_t k = 0; k < figures->keyframes; ++k) {
    const Clock::time_point step_start = Clock::now();
    AddKeyframeOrThrow(dataset, k, o.reading, smoother);
    figures->report = smoother->Update();
    figures->step_seconds.push_back(SecondsSince(step_start));
    if (o.trace && (figures->report.refactorized || figures->step_seconds.back() > 0.05)) {
      std::fprintf(stderr, "k %zu refactor %d relin %d nnz %.0f t %.4f\n", k,
                   figures->report.refactorized, figures->report.relinearized_variables,
                   smoother->factor_nonzeros(), figures->step_seconds.back());
    }
    if (!figures->report.ok) break;
  }
  figures->solve_seconds = SecondsSince(start);
}

void Polish(Smoother* smoother, DatasetRunFigures* figures) {
  const Clock::time_point polish_start = Clock::now();
  const SolveReport polished = smoother->Optimize();
  figures->polish_seconds = SecondsSince(polish_start);
  if (!polished.ok) throw std::runtime_error("polish: " + polished.error);
  figures->polished_chi_square = polished.chi_square;
}

void PrintFigures(const DatasetRunOptions& o, const Smoother& smoother,
                  const DatasetRunFigures& f) {
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "{\"mode\": \"%s\", \"reading\": \"%s\", \"keyframes\": %zu, \"poses\": %d, "
      "\"landmarks\": %d, \"factors\": %d, \"chi_square\": %.17g, "
      "\"initial_chi_square\": %.17g, \"iterations\": %d, \"converged\": %s, "
      "\"solve_seconds\": %.6f, \"total_seconds\": %.6f, \"step_p50_seconds\": %.6g, "
      "\"step_p99_seconds\": %.6g, \"step_max_seconds\": %.6g, \"polished_chi_square\": %.17g, "
      "\"polish_seconds\": %.6f, \"peak_rss_kib\": %ld}\n",
      o.incremental ? "incremental" : "batch", o.reading_name.c_str(), f.keyframes,
      smoother.num_poses(), smoother.num_landmarks(), smoother.num_factors(),
      f.report.chi_square, f.report.initial_chi_square, f.report.iterations,
      f.report.converged ? "true" : "false", f.solve_seconds, f.total_seconds,
      Percentile(f.step_seconds, 0.5), Percentile(f.step_seconds, 0.99),
      Percentile(f.step_seconds, 1.0), f.polished_chi_square, f.polish_seconds,
      usage.ru_maxrss);
}

// Written like every tool output (runtime/output_file.h): complete or absent, never through a
// link planted at its name.
void WriteSolution(const std::string& path, const Smoother& smoother) {
  OutputFile out(path);
  for (const PoseId id : smoother.PoseIds()) {
    const Eigen::Vector3d pose = *smoother.PoseEstimate(id);
    std::fprintf(out.stream(), "POSE %lld %.17g %.17g %.17g\n", static_cast<long long>(id),
                 pose(0), pose(1), pose(2));
  }
  for (const LandmarkId id : smoother.LandmarkIds()) {
    const Eigen::Vector2d point = *smoother.LandmarkEstimate(id);
    std::fprintf(out.stream(), "POINT %lld %.17g %.17g\n", static_cast<long long>(id), point(0),
                 point(1));
  }
  out.Commit();
}

int Run(int argc, char** argv) {
  const std::optional<DatasetRunOptions> o = ParseArguments(argc, argv);
  if (!o) return 0;
  const PoseLandmarkDataset dataset = ReadDataset(o->file);
  DatasetRunFigures figures;
  figures.keyframes = dataset.keyframes.size();
  if (o->max_keyframes > 0) {
    figures.keyframes = std::min<size_t>(figures.keyframes, o->max_keyframes);
  }
  SmootherOptions options;
  options.method = o->method;
  options.pose_update = o->pose_update;
  // The updates compute no chi^2 (as ISAM2's update() by default); the final one is computed
  // once, after the timed loop.
  options.update_chi_square = false;
  Smoother smoother(options);
  const Clock::time_point start = Clock::now();
  if (o->incremental) {
    SolveIncrementally(dataset, *o, &smoother, &figures);
  } else {
    SolveBatch(dataset, *o, &smoother, &figures);
  }
  figures.total_seconds = SecondsSince(start);
  if (o->incremental && figures.report.ok) figures.report.chi_square = smoother.ChiSquare();
  figures.polished_chi_square = figures.report.chi_square;
  if (o->polish && figures.report.ok && o->incremental) Polish(&smoother, &figures);
  if (!figures.report.ok) throw std::runtime_error(figures.report.error);
  PrintFigures(*o, smoother, figures);
  if (!o->solution_path.empty()) WriteSolution(o->solution_path, smoother);
  return 0;
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-smooth-dataset", slammtt::Run);
}
