// slammtt-smooth-dataset: solves a pose-landmark text file (pose_landmark_dataset.h) with the
// smoother, batch or incrementally keyframe by keyframe, and prints one JSON object: final
// chi-square, wall times, per-update percentiles, peak memory (getrusage: run one mode per
// process to measure each alone). Used by scripts/compare-victoria-park.py.
//
//   slammtt-smooth-dataset FILE [--mode batch|incremental] [--reading bearing-range|relative]
//                               [--max-keyframes N] [--method lm|gn] [--solution OUT] [--trace]
//                               [--initial SOLUTION] [--polish]
// --initial (batch): start from a solution file (POSE id x y theta / POINT id x y lines, the
// format --solution writes) instead of the odometry chain. --polish (incremental): after the
// last keyframe, Optimize from the incremental estimate (chi-square and time reported apart).
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "common/number_text.h"
#include "runtime/output_file.h"
#include "smoother/pose_landmark_dataset.h"
#include "smoother/smoother.h"

namespace {

int Usage(const std::string& why) {
  std::cerr << "slammtt-smooth-dataset: " << why << "\n"
            << "usage: slammtt-smooth-dataset FILE [--mode batch|incremental]"
               " [--reading bearing-range|relative] [--max-keyframes N] [--method lm|gn]"
               " [--solution OUT]\n";
  return 2;
}

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t index = std::min(values.size() - 1, static_cast<size_t>(q * values.size()));
  return values[index];
}

}  // namespace

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  std::string file;
  std::string mode = "batch";
  std::string reading_name = "bearing-range";
  std::string method = "lm";
  std::string solution_path;
  int64_t max_keyframes = -1;
  bool trace = false;
  bool polish = false;
  std::string initial_path;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    const auto value = [&]() -> std::string { return k + 1 < argc ? argv[++k] : ""; };
    if (arg == "--mode") {
      mode = value();
    } else if (arg == "--reading") {
      reading_name = value();
    } else if (arg == "--method") {
      method = value();
    } else if (arg == "--trace") {
      trace = true;  // stderr: every re-factorising or slow (> 50 ms) update
    } else if (arg == "--polish") {
      polish = true;
    } else if (arg == "--initial") {
      initial_path = value();
    } else if (arg == "--solution") {
      solution_path = value();
    } else if (arg == "--max-keyframes") {
      const auto parsed = slammtt::ParseWholeNumber(value());
      if (!parsed || *parsed < 1) return Usage("--max-keyframes takes a positive number");
      max_keyframes = *parsed;
    } else if (!arg.empty() && arg[0] == '-') {
      return Usage("unknown option " + arg);
    } else if (file.empty()) {
      file = arg;
    } else {
      return Usage("one FILE only");
    }
  }
  if (file.empty()) return Usage("no FILE");
  if (mode != "batch" && mode != "incremental") return Usage("--mode batch or incremental");
  if (reading_name != "bearing-range" && reading_name != "relative") {
    return Usage("--reading bearing-range or relative");
  }
  if (method != "lm" && method != "gn") return Usage("--method lm or gn");
  const slammtt::LandmarkReading reading = reading_name == "relative"
                                               ? slammtt::LandmarkReading::kRelativePosition
                                               : slammtt::LandmarkReading::kBearingRange;
  std::ifstream in(file);
  if (!in) return Usage("cannot open " + file);
  const slammtt::DatasetParseResult parsed = slammtt::ParsePoseLandmarkDataset(in);
  if (!parsed.dataset) {
    std::cerr << "slammtt-smooth-dataset: " << file << ": " << parsed.error << "\n";
    return 1;
  }
  const slammtt::PoseLandmarkDataset& dataset = *parsed.dataset;
  size_t keyframes = dataset.keyframes.size();
  if (max_keyframes > 0) keyframes = std::min<size_t>(keyframes, max_keyframes);

  slammtt::SmootherOptions options;
  if (method == "gn") options.method = slammtt::SmootherOptions::Method::kGaussNewton;
  slammtt::Smoother smoother(options);
  std::vector<double> step_seconds;
  slammtt::SolveReport report;
  const Clock::time_point start = Clock::now();
  double solve_seconds = 0.0;
  if (mode == "batch") {
    for (size_t k = 0; k < keyframes; ++k) {
      if (auto error = slammtt::AddKeyframe(dataset, k, reading, &smoother)) {
        std::cerr << "slammtt-smooth-dataset: keyframe " << k << ": " << *error << "\n";
        return 1;
      }
    }
    if (!initial_path.empty()) {
      std::ifstream initial(initial_path);
      if (!initial) return Usage("cannot open " + initial_path);
      std::string tag;
      int64_t id = 0;
      double x = 0.0;
      double y = 0.0;
      double theta = 0.0;
      while (initial >> tag >> id >> x >> y) {
        std::optional<std::string> error;
        if (tag == "POSE" && initial >> theta) {
          error = smoother.SetPoseEstimate(id, Eigen::Vector3d(x, y, theta));
        } else if (tag == "POINT") {
          error = smoother.SetLandmarkEstimate(id, Eigen::Vector2d(x, y));
        } else {
          error = "bad line " + tag;
        }
        if (error) {
          std::cerr << "slammtt-smooth-dataset: " << initial_path << ": " << *error << "\n";
          return 1;
        }
      }
      if (!initial.eof()) {
        std::cerr << "slammtt-smooth-dataset: " << initial_path << ": unreadable line after "
                  << tag << " " << id << "\n";
        return 1;
      }
    }
    const Clock::time_point solve_start = Clock::now();
    report = smoother.Optimize();
    solve_seconds = std::chrono::duration<double>(Clock::now() - solve_start).count();
  } else {
    for (size_t k = 0; k < keyframes; ++k) {
      const Clock::time_point step_start = Clock::now();
      if (auto error = slammtt::AddKeyframe(dataset, k, reading, &smoother)) {
        std::cerr << "slammtt-smooth-dataset: keyframe " << k << ": " << *error << "\n";
        return 1;
      }
      report = smoother.Update();
      step_seconds.push_back(std::chrono::duration<double>(Clock::now() - step_start).count());
      if (trace && (report.refactorized || step_seconds.back() > 0.05)) {
        std::fprintf(stderr, "k %zu refactor %d relin %d nnz %.0f t %.4f\n", k,
                     report.refactorized, report.relinearized_variables,
                     smoother.factor_nonzeros(), step_seconds.back());
      }
      if (!report.ok) break;
    }
    solve_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  const double total_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  double polished_chi_square = report.chi_square;
  double polish_seconds = 0.0;
  if (polish && report.ok && mode == "incremental") {
    const Clock::time_point polish_start = Clock::now();
    const slammtt::SolveReport polished = smoother.Optimize();
    polish_seconds = std::chrono::duration<double>(Clock::now() - polish_start).count();
    if (!polished.ok) {
      std::cerr << "slammtt-smooth-dataset: polish: " << polished.error << "\n";
      return 1;
    }
    polished_chi_square = polished.chi_square;
  }
  if (!report.ok) {
    std::cerr << "slammtt-smooth-dataset: " << report.error << "\n";
    return 1;
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "{\"mode\": \"%s\", \"reading\": \"%s\", \"keyframes\": %zu, \"poses\": %d, "
      "\"landmarks\": %d, \"factors\": %d, \"chi_square\": %.17g, "
      "\"initial_chi_square\": %.17g, \"iterations\": %d, \"converged\": %s, "
      "\"solve_seconds\": %.6f, \"total_seconds\": %.6f, \"step_p50_seconds\": %.6g, "
      "\"step_p99_seconds\": %.6g, \"step_max_seconds\": %.6g, \"polished_chi_square\": %.17g, "
      "\"polish_seconds\": %.6f, \"peak_rss_kib\": %ld}\n",
      mode.c_str(), reading_name.c_str(), keyframes, smoother.num_poses(),
      smoother.num_landmarks(), smoother.num_factors(), report.chi_square,
      report.initial_chi_square, report.iterations, report.converged ? "true" : "false",
      solve_seconds, total_seconds, Percentile(step_seconds, 0.5),
      Percentile(step_seconds, 0.99), Percentile(step_seconds, 1.0), polished_chi_square,
      polish_seconds, usage.ru_maxrss);
  if (!solution_path.empty()) {
    // Written like every tool output (runtime/output_file.h): complete or absent, never
    // through a link planted at its name.
    try {
      slammtt::OutputFile out(solution_path);
      for (const slammtt::PoseId id : smoother.PoseIds()) {
        const Eigen::Vector3d pose = *smoother.PoseEstimate(id);
        std::fprintf(out.stream(), "POSE %lld %.17g %.17g %.17g\n", static_cast<long long>(id), pose(0),
                     pose(1), pose(2));
      }
      for (const slammtt::LandmarkId id : smoother.LandmarkIds()) {
        const Eigen::Vector2d point = *smoother.LandmarkEstimate(id);
        std::fprintf(out.stream(), "POINT %lld %.17g %.17g\n", static_cast<long long>(id), point(0),
                     point(1));
      }
      out.Commit();
    } catch (const std::exception& error) {
      std::fprintf(stderr, "slammtt-smooth-dataset: %s\n", error.what());
      return 1;
    }
  }
  return 0;
}
