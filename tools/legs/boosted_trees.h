// Training of the leg classifier's gradient-boosted trees (perception/leg_classifier.h), and
// the generated C++ source that carries a trained model into the segmenter.
//
// Gradient boosting with the logistic loss and Newton leaf values (Friedman, "Greedy function
// approximation", Annals of Statistics 29(5), 2001, section 4.5 "two-class logistic
// regression"; the second-order split gain of Chen and Guestrin, "XGBoost", KDD 2016, eq. 7,
// with L2 penalty lambda): each round fits a tree of at most max_depth levels to the
// gradients g_i = w_i (p_i - y_i) and Hessians h_i = w_i p_i (1 - p_i) of the current model,
// choosing at every node the split (feature, threshold) of largest gain
//   G_L^2 / (H_L + lambda) + G_R^2 / (H_R + lambda) - G^2 / (H + lambda)
// over every threshold between two neighbouring distinct values of a feature in the node
// (exact greedy search), and a leaf gets -learning_rate G / (H + lambda). A split needs
// min_child_hessian and min_child_samples on each side and a positive gain.
//
// Deterministic: no random source at all (every sample and feature is used in every round),
// ties broken by the lower feature index and then the lower threshold, sums in a fixed order:
// the same samples give the same model, bit for bit, on every run.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "perception/leg_classifier.h"
#include "perception/leg_features.h"

namespace slammtt {

struct BoostingOptions {
  int rounds = 150;
  int max_depth = 3;
  double learning_rate = 0.1;
  double lambda = 1.0;
  double min_child_hessian = 1.0;
  int min_child_samples = 10;
  // Legs and non-legs weigh the same in total (each leg's weight multiplied by the ratio of the
  // classes' weights): the training recordings hold 20-30 non-legs per leg, and without this
  // the probabilities would say more about that ratio than about the cluster.
  bool balance_classes = true;
  // Features no split may read (still computed and stored in the samples). A feature whose
  // training values carry an artefact of the labelling rather than of legs is left out this
  // way: the real labels end at 5 m, so the distance to the laser alone would tell "leg" from
  // "background" there (docs/perception.md, "Learned leg classifier").
  std::array<bool, kNumLegFeatures> excluded_features{};
};

struct TrainingSample {
  LegFeatureVector features{};
  bool leg = false;
  double weight = 1.0;
};

// A trained model that owns its tables; model() views them.
struct TrainedTrees {
  std::vector<LegTreeNode> nodes;
  std::vector<int32_t> roots;
  double bias = 0.0;
  double suggested_threshold = 0.5;
  LegModel model() const {
    return LegModel{nodes.data(), nodes.size(), roots.data(), roots.size(), bias,
                    suggested_threshold};
  }
};

// Trains on `samples` (at least one of each class; std::invalid_argument otherwise). The bias
// starts at the weighted log-odds of the classes.
TrainedTrees TrainBoostedTrees(const std::vector<TrainingSample>& samples,
                               const BoostingOptions& options);

// The model as the C++ source of perception/leg_model.cc: TrainedLegModel() over static
// tables, floats written with 9 significant digits (which round-trip a float exactly), and
// `provenance` (lines of text) as a comment at the top.
std::string ModelSource(const TrainedTrees& trees, const std::string& provenance);

}  // namespace slammtt
