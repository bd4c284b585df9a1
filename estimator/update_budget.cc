#include "estimator/update_budget.h"

#include <algorithm>

namespace slammtt {

std::vector<uint8_t> ObjectsThatMayUpdate(const SlamState& state,
                                          const std::vector<Candidate>& gated, int budget) {
  const size_t num_objects = static_cast<size_t>(state.num_objects());
  std::vector<uint8_t> may_update(num_objects, 1);
  if (budget <= 0) return may_update;
  std::vector<uint8_t> listed(num_objects, 0);
  std::vector<int> landmarks;
  for (const Candidate& c : gated) {
    const size_t j = static_cast<size_t>(c.object);
    if (listed[j] || state.object(c.object).has_velocity()) continue;
    listed[j] = 1;
    landmarks.push_back(c.object);
  }
  if (static_cast<int>(landmarks.size()) <= budget) return may_update;
  auto staler = [&state](int a, int b) {
    const int64_t ta = state.object(a).record.last_update_utime;
    const int64_t tb = state.object(b).record.last_update_utime;
    return ta != tb ? ta < tb : a < b;
  };
  std::nth_element(landmarks.begin(), landmarks.begin() + budget, landmarks.end(), staler);
  for (size_t k = static_cast<size_t>(budget); k < landmarks.size(); ++k) {
    may_update[static_cast<size_t>(landmarks[k])] = 0;
  }
  return may_update;
}

}  // namespace slammtt
