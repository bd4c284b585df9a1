#include "estimator/update_budget.h"

#include <algorithm>

namespace slammtt {
namespace {

// Of `competitors` (object indices), all but the `budget` least recently updated (ties: lower
// index) lose their permission to update.
void KeepLeastRecentlyUpdated(const SlamState& state, int budget, std::vector<int> competitors,
                              std::vector<uint8_t>* may_update) {
  if (budget <= 0 || static_cast<int>(competitors.size()) <= budget) return;
  auto staler = [&state](int a, int b) {
    const int64_t ta = state.object(a).record.last_update_utime;
    const int64_t tb = state.object(b).record.last_update_utime;
    return ta != tb ? ta < tb : a < b;
  };
  std::nth_element(competitors.begin(), competitors.begin() + budget, competitors.end(), staler);
  for (size_t k = static_cast<size_t>(budget); k < competitors.size(); ++k) {
    (*may_update)[static_cast<size_t>(competitors[k])] = 0;
  }
}

}  // namespace

std::vector<uint8_t> ObjectsThatMayUpdate(const SlamState& state,
                                          const std::vector<Candidate>& gated, int budget,
                                          int mover_budget) {
  const size_t num_objects = static_cast<size_t>(state.num_objects());
  std::vector<uint8_t> may_update(num_objects, 1);
  if (budget <= 0 && mover_budget <= 0) return may_update;
  std::vector<uint8_t> listed(num_objects, 0);
  std::vector<int> landmarks;
  std::vector<int> movers;
  for (const Candidate& c : gated) {
    const size_t j = static_cast<size_t>(c.object);
    if (listed[j]) continue;
    listed[j] = 1;
    (state.object(c.object).has_velocity() ? movers : landmarks).push_back(c.object);
  }
  KeepLeastRecentlyUpdated(state, budget, std::move(landmarks), &may_update);
  KeepLeastRecentlyUpdated(state, mover_budget, std::move(movers), &may_update);
  return may_update;
}

}  // namespace slammtt
