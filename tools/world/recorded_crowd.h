// Recorded pedestrian tracks as movers: the people of a crowd recording (data/pedestrians/,
// ETH/UCY format t_s, id, x_m, y_m) walk the synthetic world along their recorded paths.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "tools/world/scenario.h"

namespace slammtt {

// One person of a recording: samples with strictly increasing t_s.
struct RecordedTrack {
  int64_t id = 0;
  std::vector<TimedPoint> points;
};

// Which part of a recording to use and where to put it in the world.
struct CrowdImportSpec {
  double window_start_s = 0.0;  // recording time that becomes simulated time 0
  double window_end_s = std::numeric_limits<double>::infinity();
  // world = R(rotation) * recorded + offset
  double rotation_rad = 0.0;
  double offset_x_m = 0.0;
  double offset_y_m = 0.0;
  int max_people = 0;           // 0: everyone; else the first people to appear (ties: lower id)
  double radius_m = 0.25;       // body radius of every person
  int64_t id_offset = 1000;     // mover id = id_offset + recorded id (both within +-1e15)
};

// Movers of kind kTrajectory, one per person with at least two samples inside the window, with
// times shifted by -window_start_s (so a person exists from their first to their last sample in
// the window: they enter and leave). People with fewer samples in the window are skipped.
std::vector<MoverSpec> MoversFromRecordedTracks(const std::vector<RecordedTrack>& tracks,
                                                const CrowdImportSpec& spec);

}  // namespace slammtt
