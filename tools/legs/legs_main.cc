// slammtt-legs: trains the leg classifier on imported leg_tracker recordings and measures leg
// and person detection on them (docs/perception.md, "Learned leg classifier").
//
//   slammtt-legs train --labelled NAME=LOG ... [--static-map NAME=LOG] [--negatives NAME=LOG]
//                      [--arc NAME=MIN:MAX:RANGE] -o perception/leg_model.cc
//   slammtt-legs evaluate --labelled NAME=LOG ... [--arc ...] [--unlabelled NAME=LOG ...]
//                         [--config FILE] [--strides 1,2,3]
//   slammtt-legs world --simulated NAME=SCENARIO.yaml ... [--seeds 1-20] [--simulated-every K]
//                      [--max-range 4,...] [--config FILE] [--causes]
#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "perception/segmenter_stage.h"
#include "runtime/command_line.h"
#include "runtime/log.h"
#include "runtime/output_file.h"
#include "runtime/process.h"
#include "tools/legs/leg_training.h"
#include "tools/legs/simulated_recording.h"
#include "tools/legs/world_figures.h"
#include "tools/world/scenario_loader.h"

namespace slammtt {
namespace {

std::pair<std::string, std::string> NameValue(const std::string& text, const std::string& option) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw UsageError("--" + option + " wants NAME=VALUE, got '" + text + "'");
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::vector<double> Numbers(const std::string& text, char separator, const std::string& what) {
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, separator);) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end == nullptr || *end != '\0' || !std::isfinite(v)) {
      throw UsageError(what + ": '" + text + "' is not a list of numbers");
    }
    out.push_back(v);
  }
  return out;
}

std::vector<int> Strides(const CommandLine& cl) {
  std::vector<int> strides;
  for (double v : Numbers(cl.ValueOr("strides", "1,2,3"), ',', "--strides")) {
    if (v < 1 || v > 10 || v != std::floor(v)) throw UsageError("--strides: whole numbers 1-10");
    strides.push_back(static_cast<int>(v));
  }
  return strides;
}

std::map<std::string, LabelArc> Arcs(const CommandLine& cl) {
  std::map<std::string, LabelArc> arcs;
  for (const std::string& text : cl.Values("arc")) {
    const auto [name, value] = NameValue(text, "arc");
    const std::vector<double> v = Numbers(value, ':', "--arc " + name);
    if (v.size() != 3 || !(v[0] < v[1]) || !(v[2] > 0.0)) {
      throw UsageError("--arc " + name + ": MIN_DEG:MAX_DEG:RANGE_M with MIN < MAX, RANGE > 0");
    }
    arcs[name] = LabelArc{v[0], v[1], v[2]};
  }
  return arcs;
}

// --exclude-features NAME,... (names of kLegFeatureNames).
BoostingOptions Boosting(const CommandLine& cl) {
  BoostingOptions boosting;
  const std::optional<std::string> list = cl.Value("exclude-features");
  if (!list) return boosting;
  std::stringstream in(*list);
  for (std::string name; std::getline(in, name, ',');) {
    bool known = false;
    for (int f = 0; f < kNumLegFeatures; ++f) {
      if (name == kLegFeatureNames[static_cast<size_t>(f)]) {
        boosting.excluded_features[static_cast<size_t>(f)] = true;
        known = true;
      }
    }
    if (!known) throw UsageError("--exclude-features: no feature '" + name + "'");
  }
  return boosting;
}

// --part NAME=BEGIN:END of the command line, [0, 1) by default.
std::map<std::string, std::pair<double, double>> g_parts;

Recording Load(const std::string& name, const std::string& path) {
  Recording r = ReadRecording(name, path);
  const auto part = g_parts.find(name);
  if (part != g_parts.end()) r = PartOf(r, part->second.first, part->second.second);
  if (r.undecodable > 0) LogWarning() << path << ": " << r.undecodable << " undecodable events";
  if (r.labels_without_scan > 0) {
    LogWarning() << path << ": " << r.labels_without_scan << " LEG_LABELS without their scan";
  }
  return r;
}

std::string Fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

void AddCommon(CommandLine* cl) {
  cl->AddRepeatedOption("labelled", "NAME=LOG", "an imported recording with LEG_LABELS");
  cl->AddRepeatedOption("arc", "NAME=MIN:MAX:RANGE",
                        "where NAME's labeller labelled every leg (default -15:15:5)");
  cl->AddOption("strides", "LIST", "beam strides (every k-th beam), default 1,2,3");
  cl->AddRepeatedOption("part", "NAME=BEGIN:END",
                        "use only that part of NAME's scans (fractions, e.g. 0:0.5)");
}

void ReadParts(const CommandLine& cl) {
  for (const std::string& text : cl.Values("part")) {
    const auto [name, value] = NameValue(text, "part");
    const std::vector<double> v = Numbers(value, ':', "--part " + name);
    if (v.size() != 2 || !(v[0] >= 0.0 && v[0] < v[1] && v[1] <= 1.0)) {
      throw UsageError("--part " + name + ": BEGIN:END with 0 <= BEGIN < END <= 1");
    }
    g_parts[name] = {v[0], v[1]};
  }
}

int Train(const CommandLine& cl) {
  const std::vector<int> strides = Strides(cl);
  const std::map<std::string, LabelArc> arcs = Arcs(cl);
  std::map<std::string, std::string> static_maps;
  for (const std::string& text : cl.Values("static-map")) {
    static_maps.insert(NameValue(text, "static-map"));
  }
  std::vector<Recording> recordings;
  std::vector<Recording> maps;
  std::vector<bool> labelled;
  std::vector<bool> empty;
  std::vector<bool> simulated;
  for (const std::string& text : cl.Values("labelled")) {
    const auto [name, path] = NameValue(text, "labelled");
    recordings.push_back(Load(name, path));
    labelled.push_back(true);
    empty.push_back(false);
    simulated.push_back(false);
  }
  for (const std::string& text : cl.Values("negatives")) {
    const auto [name, path] = NameValue(text, "negatives");
    recordings.push_back(Load(name, path));
    labelled.push_back(false);
    empty.push_back(false);
    simulated.push_back(false);
  }
  for (const std::string& text : cl.Values("empty")) {
    const auto [name, path] = NameValue(text, "empty");
    recordings.push_back(Load(name, path));
    labelled.push_back(false);
    empty.push_back(true);
    simulated.push_back(false);
  }
  const int every = static_cast<int>(cl.IntValue("simulated-every").value_or(10));
  for (const std::string& text : cl.Values("simulated")) {
    const auto [name, path] = NameValue(text, "simulated");
    const Scenario scenario = LoadScenario(path);
    for (double seed : Numbers(cl.ValueOr("simulated-seeds", "101,102"), ',',
                               "--simulated-seeds")) {
      const std::string seed_name = name + "-seed" + std::to_string(static_cast<int>(seed));
      recordings.push_back(
          SimulateRecording(seed_name, scenario, static_cast<uint64_t>(seed), every));
      labelled.push_back(false);
      empty.push_back(false);
      simulated.push_back(true);
    }
  }
  if (recordings.empty()) throw UsageError("train: no --labelled recording");
  // Static background of each recording: its --static-map recording, else its own scans.
  std::vector<StaticBackground> backgrounds;
  backgrounds.reserve(recordings.size());
  for (const Recording& r : recordings) {
    const auto found = static_maps.find(r.name);
    if (found == static_maps.end()) {
      backgrounds.emplace_back(r.scans);
    } else {
      backgrounds.emplace_back(Load(r.name + "-map", found->second).scans);
    }
  }
  std::vector<TrainingRecording> inputs;
  std::vector<size_t> folds;
  std::vector<LabelArc> fold_arcs;
  for (size_t i = 0; i < recordings.size(); ++i) {
    inputs.push_back(
        TrainingRecording{&recordings[i], &backgrounds[i], empty[i], simulated[i]});
    if (labelled[i]) {
      folds.push_back(i);
      const auto arc = arcs.find(recordings[i].name);
      fold_arcs.push_back(arc == arcs.end() ? LabelArc{} : arc->second);
    }
  }
  const SegmenterOptions options;
  const BoostingOptions boosting = Boosting(cl);
  const double recall_margin = cl.DoubleValue("recall-margin").value_or(0.02);
  std::vector<double> thresholds;
  for (int k = 1; k < 20; ++k) thresholds.push_back(0.05 * k);

  std::ostringstream provenance;
  provenance << "Gradient-boosted trees: " << boosting.rounds << " rounds, depth "
             << boosting.max_depth << ", learning rate " << boosting.learning_rate
             << ",\nlambda " << boosting.lambda << ", min child Hessian "
             << boosting.min_child_hessian << ", min child samples " << boosting.min_child_samples
             << (boosting.balance_classes ? ", classes balanced" : "") << ".\nFeatures left out:";
  bool any_excluded = false;
  for (int f = 0; f < kNumLegFeatures; ++f) {
    if (!boosting.excluded_features[static_cast<size_t>(f)]) continue;
    provenance << " " << kLegFeatureNames[static_cast<size_t>(f)];
    any_excluded = true;
  }
  if (!any_excluded) provenance << " none";
  provenance << ".\nBeam strides:";
  for (int s : strides) provenance << " " << s;
  provenance << ". Samples (legs / static background / left out):\n";
  std::vector<TrainingSample> all;
  for (const TrainingRecording& input : inputs) {
    SampleCounts counts;
    std::vector<TrainingSample> s = ExtractSamples(input, options, strides, &counts);
    all.insert(all.end(), s.begin(), s.end());
    provenance << "  " << input.recording->name << ": " << input.recording->scans.size()
               << " scans, " << counts.legs << " / " << counts.background << " / "
               << counts.unknown << "\n";
    LogInfo() << input.recording->name << ": " << counts.legs << " legs, " << counts.background
              << " background, " << counts.unknown << " left out";
  }
  const ThresholdChoice choice = CrossValidateThreshold(inputs, folds, fold_arcs, options,
                                                        strides, boosting, thresholds,
                                                        recall_margin);
  const double threshold = cl.DoubleValue("threshold").value_or(choice.threshold);
  if (!(threshold >= 0.0 && threshold <= 1.0)) throw UsageError("--threshold: in [0, 1]");
  provenance << "Leave-one-recording-out threshold (labelled recordings, stride 1): the largest\n"
                "within " << recall_margin << " of the best recall: " << Fixed(choice.threshold, 2)
             << "\n  threshold  recall  precision (in the labelled arc)\n";
  for (const ThresholdCurvePoint& p : choice.curve) {
    provenance << "  " << Fixed(p.threshold, 2) << "  " << Fixed(p.pooled.recall(), 4) << "  "
               << Fixed(p.pooled.precision(), 4) << "\n";
  }
  TrainedTrees trees = TrainBoostedTrees(all, boosting);
  trees.suggested_threshold = threshold;
  if (cl.DoubleValue("threshold")) {
    provenance << "The model's threshold is " << Fixed(threshold, 2)
               << " (--threshold), not the cross-validated one.\n";
  }
  const std::string out_path = *cl.Value("output");
  const std::string source = ModelSource(trees, provenance.str());
  OutputFile out(out_path);  // complete or absent, never written through a planted link
  if (std::fwrite(source.data(), 1, source.size(), out.stream()) != source.size()) {
    throw std::runtime_error("cannot write " + out_path);
  }
  out.Commit();
  std::cout << provenance.str() << "wrote " << out_path << ": " << trees.roots.size()
            << " trees, " << trees.nodes.size() << " nodes, " << all.size() << " samples\n";
  return 0;
}

int Evaluate(const CommandLine& cl, const ProcessSettings& settings) {
  const std::vector<int> strides = Strides(cl);
  const std::map<std::string, LabelArc> arcs = Arcs(cl);
  Config section = settings.config.Child("segmenter");
  const SegmenterOptions options = ReadSegmenterOptions(section);
  section.CheckUnused();
  std::cout << "| recording | stride | scans | leg recall | leg precision (arc) | labelled legs "
               "in a person | people per scan | people per minute | one-leg people | scans with 0 "
               "/ 1 / 2 / 3 / 4 / 5+ people |\n|---|---|---|---|---|---|---|---|---|---|\n";
  const auto row = [&](const std::string& name, const std::string& path) {
    const Recording r = Load(name, path);
    const auto arc = arcs.find(name);
    for (int stride : strides) {
      const LegDetectionScore s =
          EvaluateRecording(r, options, stride, arc == arcs.end() ? LabelArc{} : arc->second);
      std::cout << "| " << name << " | " << stride << " | " << s.scans << " | "
                << Fixed(s.recall(), 4) << " | " << Fixed(s.precision(), 4) << " | "
                << Fixed(s.person_leg_recall(), 4) << " | " << Fixed(s.people_per_scan(), 3)
                << " | " << Fixed(s.people_per_minute(), 1) << " | " << s.people_one_leg << " |";
      for (size_t k = 0; k < s.people_per_scan_histogram.size(); ++k) {
        std::cout << (k ? " / " : " ") << s.people_per_scan_histogram[k];
      }
      std::cout << " |\n";
    }
  };
  for (const std::string& text : cl.Values("labelled")) {
    const auto [name, path] = NameValue(text, "labelled");
    row(name, path);
  }
  for (const std::string& text : cl.Values("unlabelled")) {
    const auto [name, path] = NameValue(text, "unlabelled");
    row(name, path);
  }
  return 0;
}

std::vector<uint64_t> Seeds(const std::string& text) {
  const size_t dash = text.find('-');
  std::vector<double> range;
  if (dash == std::string::npos) {
    range = Numbers(text, ',', "--seeds");
  } else {
    range = Numbers(text.substr(0, dash) + "," + text.substr(dash + 1), ',', "--seeds");
    if (range.size() != 2 || !(range[0] <= range[1])) throw UsageError("--seeds: A-B, A <= B");
    const double first = range[0];
    const double last = range[1];
    range.clear();
    for (double s = first; s <= last; s += 1.0) range.push_back(s);
  }
  std::vector<uint64_t> seeds;
  for (double v : range) {
    if (!(v >= 0.0 && v < 1e9 && v == std::floor(v))) throw UsageError("--seeds: whole numbers");
    seeds.push_back(static_cast<uint64_t>(v));
  }
  return seeds;
}

double Median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
}

// The diagnosis of one row (world_figures.h, PersonCauses), as indented text lines.
void PrintCauses(const PersonCauses& c) {
  int64_t one_leg = 0;
  int64_t pairs = 0;
  std::ostringstream singles;
  std::ostringstream pair_text;
  for (int a = 0; a < kLegSources; ++a) {
    one_leg += c.false_one_leg[a];
    if (c.false_one_leg[a] > 0) {
      singles << " " << LegSourceName(static_cast<LegSource>(a)) << " " << c.false_one_leg[a]
              << ";";
    }
    for (int b = a; b < kLegSources; ++b) {
      pairs += c.false_pairs[a][b];
      if (c.false_pairs[a][b] > 0) {
        pair_text << " " << LegSourceName(static_cast<LegSource>(a)) << " + "
                  << LegSourceName(static_cast<LegSource>(b)) << " " << c.false_pairs[a][b]
                  << ";";
      }
    }
  }
  std::cout << "    false one-leg people " << one_leg << ":" << singles.str() << "\n";
  const std::vector<double>& alone = c.false_one_leg_alone_to_centre_m;
  if (!alone.empty()) {
    std::cout << "      on a person's leg and that person's only feature " << alone.size()
              << " (the person missed): feature to the person's centre median "
              << Fixed(Median(alone), 3) << " m, max "
              << Fixed(*std::max_element(alone.begin(), alone.end()), 3)
              << " m; the person's farther leg from its centre median "
              << Fixed(Median(c.false_one_leg_alone_farther_leg_m), 3) << " m\n";
  }
  std::cout << "    false pairs " << pairs << ":" << pair_text.str() << "\n"
            << "    matched one-leg " << c.one_leg_errors_m.size() << " (centre error median "
            << Fixed(Median(c.one_leg_errors_m), 3) << " m; truth minus feature along the sight "
            << "line median " << Fixed(Median(c.one_leg_radial_m), 3) << " m, across "
            << Fixed(Median(c.one_leg_lateral_m), 3) << " m; other leg hidden "
            << c.one_leg_other_hidden << "), pairs " << c.pair_errors_m.size()
            << " (median " << Fixed(Median(c.pair_errors_m), 3) << " m; from the legs' midpoint "
            << Fixed(Median(c.pair_errors_to_legs_m), 3) << " m, which is "
            << Fixed(Median(c.pair_body_to_legs_m), 3) << " m from the body; legs of one person "
            << c.pairs_of_one_person << ", mixed " << c.pairs_mixed << ")\n"
            << "    missed people by the best fate of their legs' clusters: leg candidate "
            << c.missed_by_fate[0] << ", below leg_threshold " << c.missed_by_fate[1]
            << ", on a line " << c.missed_by_fate[2] << ", structure piece "
            << c.missed_by_fate[3] << ", two beams not a leg " << c.missed_by_fate[4]
            << ", no cluster " << c.missed_by_fate[5] << "\n";
}

// The issue-11 figures on world scenarios (world_figures.h), one row per scenario and range.
int World(const CommandLine& cl, const ProcessSettings& settings) {
  Config section = settings.config.Child("segmenter");
  const SegmenterOptions options = ReadSegmenterOptions(section);
  section.CheckUnused();
  const std::vector<uint64_t> seeds = Seeds(cl.ValueOr("seeds", "1-20"));
  const int every = static_cast<int>(cl.IntValue("simulated-every").value_or(1));
  std::vector<double> ranges = {std::numeric_limits<double>::infinity()};
  if (cl.Value("max-range")) {
    ranges = Numbers(*cl.Value("max-range"), ',', "--max-range");
  }
  std::cout << "| scenario | seeds | scans | within | people | person recall (worst seed, median)"
               " | precision (worst, median) | centre error median / p95 | point features on "
               "walls | line angle / distance error median |\n|---|---|---|---|---|---|---|---|"
               "---|---|\n";
  for (const std::string& text : cl.Values("simulated")) {
    const auto [name, path] = NameValue(text, "simulated");
    const Scenario scenario = LoadScenario(path);
    for (double range : ranges) {
      FeatureScoreOptions score;
      score.max_range_m = range;
      const WorldFigures w = MeasureWorldFigures(scenario, seeds, options, every, score);
      const FeatureScore& f = w.pooled;
      std::vector<double> recall = w.seed_recall;
      std::vector<double> precision = w.seed_precision;
      std::sort(recall.begin(), recall.end());
      std::sort(precision.begin(), precision.end());
      const auto median = [](const std::vector<double>& v) {
        return v.empty() ? std::nan("") : 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
      };
      const auto percentile = [](std::vector<double> v, double q) {
        if (v.empty()) return std::nan("");
        std::sort(v.begin(), v.end());
        return v[static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
      };
      std::cout << "| " << name << " | " << seeds.front() << "-" << seeds.back() << " | "
                << w.scans << " | " << (std::isfinite(range) ? Fixed(range, 1) + " m" : "all")
                << " | " << f.people_truth << " | " << Fixed(f.PersonRecall(), 3) << " ("
                << Fixed(recall.front(), 3) << ", " << Fixed(median(recall), 3) << ") | "
                << Fixed(f.PersonPrecision(), 3) << " (" << Fixed(precision.front(), 3) << ", "
                << Fixed(median(precision), 3) << ") | "
                << Fixed(percentile(f.centre_errors_m, 0.5), 3) << " / "
                << Fixed(percentile(f.centre_errors_m, 0.95), 3) << " m | "
                << Fixed(100.0 * f.WallPointShare(), 1) << " % of " << f.point_features << " | "
                << Fixed(percentile(f.line_angle_errors_rad, 0.5) * 180.0 / M_PI, 2) << " deg / "
                << Fixed(percentile(f.line_distance_errors_m, 0.5), 3) << " m |\n";
      if (cl.Flag("causes")) PrintCauses(w.causes);
    }
  }
  return 0;
}

int Run(int argc, char** argv) {
  CommandLine cl("slammtt-legs", "train|evaluate|world [options]",
                 "Trains the leg classifier on imported leg_tracker recordings (train), "
                 "measures leg and person detection on imported recordings (evaluate) and the "
                 "perception figures on world scenarios (world).");
  AddStandardOptions(&cl);
  cl.AddPositional("COMMAND", "train, evaluate or world");
  AddCommon(&cl);
  cl.AddRepeatedOption("static-map", "NAME=LOG",
                       "train: the recording whose static background gives NAME's negatives "
                       "(default: NAME's own scans)");
  cl.AddRepeatedOption("negatives", "NAME=LOG",
                       "train: a recording of a standing scanner used for its static "
                       "background only");
  cl.AddRepeatedOption("empty", "NAME=LOG",
                       "train: a recording where nobody is present: every cluster a non-leg");
  cl.AddRepeatedOption("simulated", "NAME=SCENARIO.yaml",
                       "train: scans of a world scenario, legs labelled by the world's truth");
  cl.AddOption("simulated-seeds", "LIST", "train: seeds of the simulated scenarios (101,102)");
  cl.AddOption("seeds", "A-B|LIST", "world: seeds of the scenarios (default 1-20)");
  cl.AddOption("max-range", "LIST", "world: score within these ranges [m] (default: all)");
  cl.AddFlag("causes", "world: where false and missed people come from, and the centre error "
                       "of one-leg and two-leg people (world_figures.h, PersonCauses)");
  cl.AddOption("simulated-every", "K", "train: every K-th simulated scan (10); world: (1)");
  cl.AddOption("exclude-features", "NAME,...",
               "train: features no split may read (names as in perception/leg_features.cc)");
  cl.AddOption("recall-margin", "R", "train: the threshold keeps the best cross-validated "
                                     "recall but this (default 0.02)");
  cl.AddOption("threshold", "P", "train: the model's threshold instead of the cross-validated "
                                 "one (which is still measured and recorded)");
  cl.AddOption("output", "MODEL.cc", "train: the generated model source", 'o');
  cl.AddRepeatedOption("unlabelled", "NAME=LOG", "evaluate: a recording without labels");
  if (!cl.Parse(argc, argv)) return 0;
  const std::string command = *cl.Positional("COMMAND");
  ReadParts(cl);
  const ProcessSettings settings = LoadProcessSettings(cl);
  if (command == "train") {
    if (!cl.Value("output")) throw UsageError("train: -o MODEL.cc is required");
    return Train(cl);
  }
  if (command == "evaluate") return Evaluate(cl, settings);
  if (command == "world") return World(cl, settings);
  throw UsageError("unknown command '" + command + "' (train, evaluate or world)");
}

}  // namespace
}  // namespace slammtt

int main(int argc, char** argv) {
  return slammtt::ProcessMain(argc, argv, "slammtt-legs", slammtt::Run);
}
