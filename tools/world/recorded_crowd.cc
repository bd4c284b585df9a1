#include "tools/world/recorded_crowd.h"

#include <algorithm>
#include <cmath>

namespace slammtt {

std::vector<MoverSpec> MoversFromRecordedTracks(const std::vector<RecordedTrack>& tracks,
                                                const CrowdImportSpec& spec) {
  const double c = std::cos(spec.rotation_rad);
  const double s = std::sin(spec.rotation_rad);
  std::vector<MoverSpec> movers;
  for (const RecordedTrack& track : tracks) {
    MoverSpec mover;
    mover.id = spec.id_offset + track.id;
    mover.radius_m = spec.radius_m;
    mover.kind = MoverKind::kTrajectory;
    for (const TimedPoint& p : track.points) {
      if (p.t_s < spec.window_start_s || p.t_s > spec.window_end_s) continue;
      mover.trajectory.push_back(TimedPoint{p.t_s - spec.window_start_s,
                                            c * p.x_m - s * p.y_m + spec.offset_x_m,
                                            s * p.x_m + c * p.y_m + spec.offset_y_m});
    }
    if (mover.trajectory.size() < 2) continue;
    movers.push_back(std::move(mover));
  }
  // The first people to appear (then by id), so that a cap keeps whoever is there early.
  std::stable_sort(movers.begin(), movers.end(), [](const MoverSpec& a, const MoverSpec& b) {
    if (a.trajectory.front().t_s != b.trajectory.front().t_s) {
      return a.trajectory.front().t_s < b.trajectory.front().t_s;
    }
    return a.id < b.id;
  });
  if (spec.max_people > 0 && movers.size() > static_cast<size_t>(spec.max_people)) {
    movers.resize(static_cast<size_t>(spec.max_people));
  }
  return movers;
}

}  // namespace slammtt
