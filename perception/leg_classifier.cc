#include "perception/leg_classifier.h"

#include <cmath>

namespace slammtt {

double LegModelMargin(const LegModel& model, const LegFeatureVector& x) {
  double margin = model.bias;
  for (size_t t = 0; t < model.num_trees; ++t) {
    int32_t k = model.tree_roots[t];
    while (model.nodes[k].feature >= 0) {
      const LegTreeNode& node = model.nodes[k];
      k = x[static_cast<size_t>(node.feature)] <= node.threshold ? node.left : node.right;
    }
    margin += static_cast<double>(model.nodes[k].value);
  }
  return margin;
}

double LegProbability(const LegModel& model, const LegFeatureVector& x) {
  return 1.0 / (1.0 + std::exp(-LegModelMargin(model, x)));
}

const char* CheckLegModel(const LegModel& model) {
  if (model.num_trees > 0 && (model.tree_roots == nullptr || model.nodes == nullptr)) {
    return "leg model: trees without a node table";
  }
  if (!std::isfinite(model.bias)) return "leg model: bias is not finite";
  if (!(model.suggested_threshold >= 0.0 && model.suggested_threshold <= 1.0)) {
    return "leg model: suggested threshold outside [0, 1]";
  }
  const auto n = static_cast<int64_t>(model.num_nodes);
  for (size_t t = 0; t < model.num_trees; ++t) {
    int64_t k = model.tree_roots[t];
    // A walk down any path of a tree is at most num_nodes long; check every node instead.
    if (k < 0 || k >= n) return "leg model: a tree root outside the node table";
  }
  for (size_t i = 0; i < model.num_nodes; ++i) {
    const LegTreeNode& node = model.nodes[i];
    if (node.feature < 0) {
      if (!std::isfinite(node.value)) return "leg model: a leaf value is not finite";
      continue;
    }
    if (node.feature >= kNumLegFeatures) return "leg model: a feature index out of range";
    if (!std::isfinite(node.threshold)) return "leg model: a threshold is not finite";
    // Children come after their parent: every walk ends at a leaf.
    const auto self = static_cast<int64_t>(i);
    if (node.left <= self || node.left >= n || node.right <= self || node.right >= n) {
      return "leg model: a child index outside the node table or not after its parent";
    }
  }
  return "";
}

}  // namespace slammtt
