// The learned leg classifier: gradient-boosted decision trees over the cluster features of
// leg_features.h, giving the probability that a cluster is a person's leg.
//
// Model (Friedman, "Greedy function approximation: a gradient boosting machine", Annals of
// Statistics 29(5), 2001; the logistic loss with Newton steps of Friedman, Hastie, Tibshirani,
// "Additive logistic regression", Annals of Statistics 28(2), 2000): F(x) = bias + sum over
// trees of the value of the leaf that x reaches; P(leg | x) = 1 / (1 + exp(-F(x))). A node
// sends x to `left` when x[feature] <= threshold (float comparison, the very floats that the
// features come as), otherwise to `right`. Arras et al. (ICRA 2007) boost decision stumps
// (AdaBoost) and Leigh et al. (ICRA 2015) train a random forest on the same features; small
// boosted trees are the same family: a few hundred comparisons per cluster, no allocation, the
// same result on every platform (no libm call but one exp).
//
// The model the segmenter uses by default, TrainedLegModel(), is generated source
// (perception/leg_model.cc) written by `slammtt-legs train` (tools/legs) from the leg_tracker
// training bags: docs/perception.md says how it was trained, on which data, and the command
// that writes the same bytes again.
#pragma once

#include <cstddef>
#include <cstdint>

#include "perception/leg_features.h"

namespace slammtt {

struct LegTreeNode {
  int32_t feature = -1;     // LegFeatureIndex, or -1 for a leaf
  float threshold = 0.0f;   // x[feature] <= threshold goes left
  int32_t left = -1;        // node indices within the model's node array
  int32_t right = -1;
  float value = 0.0f;       // a leaf's contribution to F(x)
};

// A view of a model's tables (static storage for the generated model; a trainer's vectors).
struct LegModel {
  const LegTreeNode* nodes = nullptr;
  size_t num_nodes = 0;
  const int32_t* tree_roots = nullptr;  // index of each tree's root in `nodes`
  size_t num_trees = 0;
  double bias = 0.0;
  // The probability at which the training program's cross-validation reached its recall aim;
  // the segmenter's default leg_threshold is this value (segmenter_options.h).
  double suggested_threshold = 0.5;
};

// F(x) (see above). A malformed model (a node index outside the table, a feature index out of
// range) is a programming error of the trainer: CheckLegModel() finds it, and the segmenter
// checks its model once, at construction.
double LegModelMargin(const LegModel& model, const LegFeatureVector& x);
// P(leg | x) in [0, 1].
double LegProbability(const LegModel& model, const LegFeatureVector& x);

// Empty when every tree of the model reaches a leaf from its root within the table and every
// threshold and value is finite; otherwise one line saying what is wrong.
const char* CheckLegModel(const LegModel& model);

// The model trained from the leg_tracker bags (perception/leg_model.cc, generated).
const LegModel& TrainedLegModel();

}  // namespace slammtt
