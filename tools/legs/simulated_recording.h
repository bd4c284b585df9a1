// Scans of the synthetic world (tools/world) as a training recording for the leg classifier:
// legs at every range and at the RPLIDAR's 0.9 degrees as well as a Hokuyo's 0.35, where the
// real leg_tracker labels (Hokuyo, within 5 m) have none.
#pragma once

#include <cstdint>
#include <string>

#include "tools/legs/recording_log.h"
#include "tools/world/scenario.h"

namespace slammtt {

// Every `every`-th scan of `scenario` run with `seed` (laser scans only), as the laser_scan_t
// the world publishes (ToLaserScanMessage). Each scan's labels_m are the legs seen by at least
// one beam, people_m every person and leg, in the sensor frame. std::invalid_argument for a
// scenario the world refuses or that has no laser scans.
Recording SimulateRecording(const std::string& name, const Scenario& scenario, uint64_t seed,
                            int every);

}  // namespace slammtt
