#include "tools/legs/leg_training.h"

#include <algorithm>

namespace slammtt {

SegmenterOptions ExtractionOptions(const SegmenterOptions& options) {
  SegmenterOptions o = options;
  o.leg_classifier = LegClassifier::kShape;
  o.leg_model = nullptr;
  return o;
}

std::vector<TrainingSample> ExtractSamples(const TrainingRecording& input,
                                           const SegmenterOptions& options,
                                           const std::vector<int>& strides,
                                           SampleCounts* counts) {
  std::vector<TrainingSample> samples;
  Segmenter segmenter(ExtractionOptions(options));
  const std::vector<Eigen::Vector2d> no_labels;
  for (int stride : strides) {
    for (const RecordedScan& full : input.recording->scans) {
      const RecordedScan scan = Decimate(full, stride);
      segmenter.Segment(scan.view());
      for (const LegClusterRecord& record : segmenter.leg_clusters()) {
        const ClusterTruth truth =
            input.empty       ? ClusterTruth::kBackground
            : input.simulated ? ClassifySimulatedCluster(record, scan)
                              : ClassifyCluster(record, scan.labelled ? scan.labels_m : no_labels,
                                                input.background);
        if (truth == ClusterTruth::kUnknown) {
          ++counts->unknown;
          continue;
        }
        TrainingSample sample;
        sample.features = record.features;
        sample.leg = truth == ClusterTruth::kLeg;
        ++(sample.leg ? counts->legs : counts->background);
        samples.push_back(sample);
      }
    }
  }
  return samples;
}

LegDetectionScore EvaluateRecording(const Recording& recording, const SegmenterOptions& options,
                                    int stride, const LabelArc& arc) {
  LegDetectionScore score;
  Segmenter segmenter(options);
  for (const RecordedScan& full : recording.scans) {
    const RecordedScan scan = Decimate(full, stride);
    segmenter.Segment(scan.view());
    ScoreScan(scan, segmenter, options.leg_threshold, arc, &score);
  }
  return score;
}

namespace {

void Pool(const LegDetectionScore& s, LegDetectionScore* into) {
  into->scans += s.scans;
  into->labels += s.labels;
  into->labels_found += s.labels_found;
  into->candidates_in_arc += s.candidates_in_arc;
  into->candidates_matched += s.candidates_matched;
  into->people += s.people;
  into->people_one_leg += s.people_one_leg;
}

}  // namespace

ThresholdChoice CrossValidateThreshold(const std::vector<TrainingRecording>& inputs,
                                       const std::vector<size_t>& folds,
                                       const std::vector<LabelArc>& fold_arcs,
                                       const SegmenterOptions& options,
                                       const std::vector<int>& strides,
                                       const BoostingOptions& boosting,
                                       const std::vector<double>& thresholds,
                                       double recall_margin) {
  std::vector<std::vector<TrainingSample>> samples(inputs.size());
  for (size_t i = 0; i < inputs.size(); ++i) {
    SampleCounts counts;
    samples[i] = ExtractSamples(inputs[i], options, strides, &counts);
  }
  ThresholdChoice choice;
  choice.curve.resize(thresholds.size());
  for (size_t t = 0; t < thresholds.size(); ++t) choice.curve[t].threshold = thresholds[t];
  for (size_t f = 0; f < folds.size(); ++f) {
    std::vector<TrainingSample> training;
    for (size_t i = 0; i < inputs.size(); ++i) {
      if (i == folds[f]) continue;
      training.insert(training.end(), samples[i].begin(), samples[i].end());
    }
    const TrainedTrees trees = TrainBoostedTrees(training, boosting);
    const LegModel model = trees.model();
    for (size_t t = 0; t < thresholds.size(); ++t) {
      SegmenterOptions o = options;
      o.leg_classifier = LegClassifier::kTrained;
      o.leg_model = &model;
      o.leg_threshold = thresholds[t];
      o.person.single_leg_threshold = thresholds[t];
      // Scored at the recording's own resolution: the recall aim is the Hokuyo bags'.
      Pool(EvaluateRecording(*inputs[folds[f]].recording, o, 1, fold_arcs[f]),
           &choice.curve[t].pooled);
    }
  }
  double best_recall = 0.0;
  for (const ThresholdCurvePoint& point : choice.curve) {
    best_recall = std::max(best_recall, point.pooled.recall());
  }
  choice.threshold = thresholds.empty() ? 0.5 : thresholds.front();
  for (const ThresholdCurvePoint& point : choice.curve) {
    if (point.pooled.recall() >= best_recall - recall_margin) choice.threshold = point.threshold;
  }
  return choice;
}

}  // namespace slammtt
