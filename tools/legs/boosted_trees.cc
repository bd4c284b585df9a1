#include "tools/legs/boosted_trees.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace slammtt {
namespace {

struct OpenNode {
  int32_t tree_node;  // index in the tree's node list
  double g = 0.0;
  double h = 0.0;
  int64_t count = 0;
};

struct Split {
  double gain = 0.0;
  int32_t feature = -1;
  float threshold = 0.0f;
};

// A float strictly between lo and hi when there is one, else lo: x <= it sends lo left and
// hi right.
float Between(float lo, float hi) {
  const double low = static_cast<double>(lo);
  const float middle = static_cast<float>(low + 0.5 * (static_cast<double>(hi) - low));
  return (middle >= lo && middle < hi) ? middle : lo;
}

double Score(double g, double h, double lambda) { return g * g / (h + lambda); }

// One tree fitted to the gradients; appends its nodes to `tree` (root first, every child
// after its parent) and returns each sample's leaf value in `delta`.
void GrowTree(const std::vector<TrainingSample>& samples,
              const std::vector<std::vector<uint32_t>>& order, const std::vector<double>& g,
              const std::vector<double>& h, const BoostingOptions& options,
              std::vector<LegTreeNode>* tree, std::vector<double>* delta) {
  const size_t n = samples.size();
  tree->clear();
  tree->push_back(LegTreeNode{});
  std::vector<int32_t> node_of(n, 0);  // tree node of every sample
  std::vector<OpenNode> open(1);
  open[0].tree_node = 0;
  for (size_t i = 0; i < n; ++i) {
    open[0].g += g[i];
    open[0].h += h[i];
    ++open[0].count;
  }
  std::vector<int32_t> open_index_of_node(1, 0);
  for (int depth = 0; depth < options.max_depth && !open.empty(); ++depth) {
    const size_t k_open = open.size();
    std::vector<Split> best(k_open);
    std::vector<double> gl(k_open), hl(k_open);
    std::vector<int64_t> cl(k_open);
    std::vector<float> last(k_open);
    std::vector<uint8_t> has_last(k_open);
    for (int f = 0; f < kNumLegFeatures; ++f) {
      if (options.excluded_features[static_cast<size_t>(f)]) continue;
      std::fill(gl.begin(), gl.end(), 0.0);
      std::fill(hl.begin(), hl.end(), 0.0);
      std::fill(cl.begin(), cl.end(), 0);
      std::fill(has_last.begin(), has_last.end(), 0);
      for (uint32_t i : order[static_cast<size_t>(f)]) {
        const int32_t node = node_of[i];
        if (node < 0) continue;
        const int32_t k = open_index_of_node[static_cast<size_t>(node)];
        if (k < 0) continue;
        const float value = samples[i].features[static_cast<size_t>(f)];
        const size_t kk = static_cast<size_t>(k);
        if (has_last[kk] && value > last[kk]) {
          const OpenNode& o = open[kk];
          const double gr = o.g - gl[kk];
          const double hr = o.h - hl[kk];
          const int64_t cr = o.count - cl[kk];
          if (hl[kk] >= options.min_child_hessian && hr >= options.min_child_hessian &&
              cl[kk] >= options.min_child_samples && cr >= options.min_child_samples) {
            const double gain = Score(gl[kk], hl[kk], options.lambda) +
                                Score(gr, hr, options.lambda) -
                                Score(o.g, o.h, options.lambda);
            if (gain > best[kk].gain) best[kk] = Split{gain, f, Between(last[kk], value)};
          }
        }
        gl[kk] += g[i];
        hl[kk] += h[i];
        ++cl[kk];
        last[kk] = value;
        has_last[kk] = 1;
      }
    }
    // Apply the splits: children go to the end of the tree, in the order of the open nodes.
    std::vector<OpenNode> next;
    for (size_t k = 0; k < k_open; ++k) {
      if (best[k].feature < 0) continue;
      LegTreeNode& parent = (*tree)[static_cast<size_t>(open[k].tree_node)];
      parent.feature = best[k].feature;
      parent.threshold = best[k].threshold;
      parent.left = static_cast<int32_t>(tree->size());
      parent.right = parent.left + 1;
      tree->push_back(LegTreeNode{});
      tree->push_back(LegTreeNode{});
      OpenNode left;
      left.tree_node = (*tree)[static_cast<size_t>(open[k].tree_node)].left;
      OpenNode right;
      right.tree_node = left.tree_node + 1;
      next.push_back(left);
      next.push_back(right);
    }
    // Every sample of a node that did not split stays in that node, which is now a leaf.
    open_index_of_node.assign(tree->size(), -1);
    for (size_t k = 0; k < next.size(); ++k) {
      open_index_of_node[static_cast<size_t>(next[k].tree_node)] = static_cast<int32_t>(k);
    }
    for (size_t i = 0; i < n; ++i) {
      const LegTreeNode& node = (*tree)[static_cast<size_t>(node_of[i])];
      if (node.feature < 0) continue;
      node_of[i] = samples[i].features[static_cast<size_t>(node.feature)] <= node.threshold
                       ? node.left
                       : node.right;
      OpenNode& child = next[static_cast<size_t>(open_index_of_node[static_cast<size_t>(
          node_of[i])])];
      child.g += g[i];
      child.h += h[i];
      ++child.count;
    }
    open.swap(next);
  }
  // Leaf values from each leaf's sums.
  std::vector<double> leaf_g(tree->size(), 0.0), leaf_h(tree->size(), 0.0);
  for (size_t i = 0; i < n; ++i) {
    leaf_g[static_cast<size_t>(node_of[i])] += g[i];
    leaf_h[static_cast<size_t>(node_of[i])] += h[i];
  }
  for (size_t k = 0; k < tree->size(); ++k) {
    LegTreeNode& node = (*tree)[k];
    if (node.feature >= 0) continue;
    node.value = static_cast<float>(-options.learning_rate * leaf_g[k] /
                                    (leaf_h[k] + options.lambda));
  }
  delta->resize(n);
  for (size_t i = 0; i < n; ++i) {
    (*delta)[i] = static_cast<double>((*tree)[static_cast<size_t>(node_of[i])].value);
  }
}

std::string FloatLiteral(double value, int digits, bool single) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*g", digits, value);
  std::string s = text;
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  if (single) s += "f";
  return s;
}

}  // namespace

TrainedTrees TrainBoostedTrees(const std::vector<TrainingSample>& samples,
                               const BoostingOptions& options) {
  double w_leg = 0.0;
  double w_other = 0.0;
  for (const TrainingSample& s : samples) (s.leg ? w_leg : w_other) += s.weight;
  if (!(w_leg > 0.0) || !(w_other > 0.0)) {
    throw std::invalid_argument("boosted trees: need samples of both classes");
  }
  const size_t n = samples.size();
  std::vector<std::vector<uint32_t>> order(kNumLegFeatures);
  for (int f = 0; f < kNumLegFeatures; ++f) {
    auto& o = order[static_cast<size_t>(f)];
    o.resize(n);
    std::iota(o.begin(), o.end(), 0u);
    const size_t ff = static_cast<size_t>(f);
    std::stable_sort(o.begin(), o.end(), [&samples, ff](uint32_t a, uint32_t b) {
      return samples[a].features[ff] < samples[b].features[ff];
    });
  }
  const double leg_factor = options.balance_classes ? w_other / w_leg : 1.0;
  TrainedTrees trees;
  trees.bias = std::log(leg_factor * w_leg / w_other);
  std::vector<double> margin(n, trees.bias);
  std::vector<double> g(n), h(n), delta;
  std::vector<LegTreeNode> tree;
  for (int round = 0; round < options.rounds; ++round) {
    for (size_t i = 0; i < n; ++i) {
      const double p = 1.0 / (1.0 + std::exp(-margin[i]));
      const double w = samples[i].weight * (samples[i].leg ? leg_factor : 1.0);
      g[i] = w * (p - (samples[i].leg ? 1.0 : 0.0));
      h[i] = w * std::max(p * (1.0 - p), 1e-12);
    }
    GrowTree(samples, order, g, h, options, &tree, &delta);
    const auto offset = static_cast<int32_t>(trees.nodes.size());
    trees.roots.push_back(offset);
    for (LegTreeNode node : tree) {
      if (node.feature >= 0) {
        node.left += offset;
        node.right += offset;
      }
      trees.nodes.push_back(node);
    }
    for (size_t i = 0; i < n; ++i) margin[i] += delta[i];
  }
  return trees;
}

std::string ModelSource(const TrainedTrees& trees, const std::string& provenance) {
  std::ostringstream out;
  out << "// Generated by `slammtt-legs train` (tools/legs); do not edit: docs/perception.md,\n"
         "// \"Learned leg classifier\", has the command that writes this file again.\n";
  std::istringstream lines(provenance);
  for (std::string line; std::getline(lines, line);) out << "//" << (line.empty() ? "" : " ")
                                                         << line << "\n";
  out << "#include \"perception/leg_classifier.h\"\n\n"
         "namespace slammtt {\n"
         "namespace {\n\n"
         "// {feature, threshold, left, right, value}; feature -1: a leaf.\n"
         "const LegTreeNode kNodes[] = {\n";
  for (const LegTreeNode& node : trees.nodes) {
    out << "    {" << node.feature << ", " << FloatLiteral(node.threshold, 9, true) << ", "
        << node.left << ", " << node.right << ", " << FloatLiteral(node.value, 9, true)
        << "},\n";
  }
  out << "};\n\n"
         "const int32_t kRoots[] = {";
  for (size_t t = 0; t < trees.roots.size(); ++t) {
    out << (t % 12 == 0 ? "\n    " : " ") << trees.roots[t] << ",";
  }
  out << "\n};\n\n"
         "}  // namespace\n\n"
         "const LegModel& TrainedLegModel() {\n"
         "  static const LegModel model{kNodes, "
      << trees.nodes.size() << ", kRoots, " << trees.roots.size() << ",\n"
      << "                              " << FloatLiteral(trees.bias, 17, false) << ", "
      << FloatLiteral(trees.suggested_threshold, 17, false) << "};\n"
         "  return model;\n"
         "}\n\n"
         "}  // namespace slammtt\n";
  return out.str();
}

}  // namespace slammtt
