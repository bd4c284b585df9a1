// The leg classifier's training pipeline over imported recordings (pure: recordings in memory
// in, samples, models and scores out): extraction of the training samples through the very
// segmenter that runs on the robot, the threshold chosen by cross-validation over recordings,
// and the detection figures of a recording. `slammtt-legs` (legs_main.cc) drives it.
#pragma once

#include <vector>

#include "perception/segmenter_options.h"
#include "tools/legs/boosted_trees.h"
#include "tools/legs/leg_dataset.h"
#include "tools/legs/recording_log.h"

namespace slammtt {

// A recording as training data: legs from its labels (if it has any), non-legs from its
// static background (`background`: the scans of the whole recording of a standing scanner;
// null: no negatives); clusters that are neither are not used.
struct TrainingRecording {
  const Recording* recording = nullptr;
  const StaticBackground* background = nullptr;
  // Nobody is present (negative_2): every cluster is a non-leg.
  bool empty = false;
  // Simulated (simulated_recording.h): truth from the world, ClassifySimulatedCluster.
  bool simulated = false;
};

struct SampleCounts {
  int64_t legs = 0;
  int64_t background = 0;
  int64_t unknown = 0;  // clusters left out
};

// The segmenter's options for extraction: `options` with the hand-written shape score, so that
// which clusters are extracted never depends on a model (the records of every evaluated
// cluster are made before any decision that reads the score, segmenter.h).
SegmenterOptions ExtractionOptions(const SegmenterOptions& options);

// Every evaluated cluster (Segmenter::leg_clusters()) of every scan of the recording, at every
// beam stride of `strides` (Decimate), that ClassifyCluster calls a leg or background.
std::vector<TrainingSample> ExtractSamples(const TrainingRecording& input,
                                           const SegmenterOptions& options,
                                           const std::vector<int>& strides, SampleCounts* counts);

// Detection figures of `recording` through a Segmenter with `options` (its leg_model and
// leg_threshold), at beam stride `stride`.
LegDetectionScore EvaluateRecording(const Recording& recording, const SegmenterOptions& options,
                                    int stride, const LabelArc& arc);

// Leave-one-recording-out cross-validation of the leg threshold: for every labelled recording
// in `folds`, a model is trained on the samples of every other recording of `inputs` (those
// not in `folds` are always in training; samples at every stride of `strides`) and its
// recording is scored, at its own resolution (stride 1), at each threshold of
// `thresholds`; the scores are pooled per threshold. The choice is the largest threshold whose
// pooled recall is within `recall_margin` of the best pooled recall of any threshold: the
// recall that the clustering allows is kept, and every threshold below that buys false legs
// (the precision inside the labelled arc hardly moves, but false people elsewhere do).
struct ThresholdCurvePoint {
  double threshold = 0.0;
  LegDetectionScore pooled;
};
struct ThresholdChoice {
  double threshold = 0.5;
  std::vector<ThresholdCurvePoint> curve;
};
ThresholdChoice CrossValidateThreshold(const std::vector<TrainingRecording>& inputs,
                                       const std::vector<size_t>& folds,
                                       const std::vector<LabelArc>& fold_arcs,
                                       const SegmenterOptions& options,
                                       const std::vector<int>& strides,
                                       const BoostingOptions& boosting,
                                       const std::vector<double>& thresholds, double recall_margin);

}  // namespace slammtt
