#include "tools/world/scenario_options.h"

namespace slammtt {

void VisitScenarioSettings(OptionVisitor* v, Scenario* s) {
  using R = OptionRange;
  v->Double("duration_s", &s->duration_s, R::AboveUpTo(0, kMaxScenarioDurationS),
            "simulated seconds");
  v->Int("start_utime", &s->start_utime, R::Between(0, 4e18),
         "utime of simulated time 0 in logs (a fixed epoch: logs are byte-identical)");
  int output = static_cast<int>(s->output);
  v->Choice("output", &output, {"features", "scans", "both"},
            "point features straight from the objects, ray-cast laser scans, or both");
  s->output = static_cast<SensorOutput>(output);
}

void VisitLaserSpec(OptionVisitor* v, LaserSpec* l) {
  using R = OptionRange;
  v->Double("fov_deg", &l->fov_deg, R::AboveUpTo(0, 360), "field of view");
  v->Double("resolution_deg", &l->resolution_deg, R::Above(0),
            "angle between beams (at most 100000 beams per scan)");
  v->Double("min_range_m", &l->min_range_m, R::AtLeast(0), "nearer returns are invalid");
  v->Double("max_range_m", &l->max_range_m, R::Above(0),
            "farther surfaces give no return; above `min_range_m`");
  v->Double("rate_hz", &l->rate_hz, R::Between(0.01, 1000), "scans per second");
  v->Double("range_noise_m", &l->range_noise_m, R::AtLeast(0),
            "per-beam range noise (standard deviation)");
  v->Double("mount_a_m", &l->mount_a_m, R::Between(-kMaxCoordinateM, kMaxCoordinateM),
            "sensor position on the robot, forward of the axle centre (eq. 11: a)");
  v->Double("mount_b_m", &l->mount_b_m, R::Between(-kMaxCoordinateM, kMaxCoordinateM),
            "...and left of it (b)");
  v->Double("mount_yaw_deg", &l->mount_yaw_deg, R::Between(-180, 180),
            "the laser's heading, CCW from the robot's (a rotated mount: the beams' angles and "
            "the features' bearings are in the laser's frame; the estimator's `sensor_yaw_deg`)");
  LaserArtefactSpec& a = l->artefacts;
  v->Double("mixed_pixel_probability", &a.mixed_pixel_probability, R::Between(0, 1),
            "chance that a beam straddling a depth edge returns a range between the two "
            "surfaces (0: off)");
  v->Double("beam_divergence_deg", &a.beam_divergence_deg, R::AboveUpTo(0, 10),
            "width of a beam's footprint for mixed pixels");
  v->Double("mixed_pixel_min_gap_m", &a.mixed_pixel_min_gap_m, R::Above(0),
            "range difference that makes a depth edge");
  v->Double("grazing_dropout_deg", &a.grazing_dropout_deg, R::AboveUpTo(0, 90),
            "no return beyond this incidence angle (0 head-on; 90: off)");
  v->Double("range_noise_per_m", &a.range_noise_per_m, R::Between(0, 1),
            "range noise growing with range: sigma = range_noise_m + this x range");
  v->Double("sample_rate_hz", &a.sample_rate_hz, R::Between(0, 1e6),
            "RPLIDAR-like sampled beam angles: samples per second (A2 express mode: 4000, "
            "standard: 2000), 0 (even beams) or at least 10; 360-degree lasers only");
  v->Double("rotation_jitter", &a.rotation_jitter, R::Between(0, 0.2),
            "relative standard deviation of each revolution's turn rate");
  v->Double("angle_jitter_deg", &a.angle_jitter_deg, R::Between(0, 5),
            "standard deviation of each sample's angle");
}

void VisitFeatureSpec(OptionVisitor* v, FeatureSpec* f) {
  using R = OptionRange;
  v->Double("range_noise_m", &f->range_noise_m, R::AtLeast(0),
            "point-feature range noise, standard deviation (paper: 0.2)");
  v->Double("bearing_noise_deg", &f->bearing_noise_deg, R::AtLeast(0),
            "point-feature bearing noise, standard deviation (paper: 2)");
  v->Double("detection_probability", &f->detection_probability, R::Between(0, 1),
            "a visible object yields a feature with this probability");
}

void VisitOdometrySpec(OptionVisitor* v, OdometrySpec* o) {
  using R = OptionRange;
  v->Double("rate_hz", &o->rate_hz, R::Between(0.01, 1000), "readings per second");
  v->Double("wheel_radius_m", &o->wheel_radius_m, R::Above(0),
            "r of eq. 1 (P3-DX: 195 mm wheels)");
  v->Double("axle_length_m", &o->axle_length_m, R::Above(0),
            "D of eq. 1: distance between the wheels");
  v->Double("encoder_noise_rad", &o->encoder_noise_rad, R::AtLeast(0),
            "additive noise per reading and wheel, in radians of wheel rotation");
  v->Double("slip_std", &o->slip_std, R::AtLeast(0), "relative noise per reading and wheel");
  v->Double("left_slip_bias", &o->left_slip_bias, R::Between(-0.5, 0.5),
            "systematic relative error of the left wheel");
  v->Double("right_slip_bias", &o->right_slip_bias, R::Between(-0.5, 0.5),
            "...and of the right wheel");
}

void VisitLegSpec(OptionVisitor* v, LegSpec* legs) {
  using R = OptionRange;
  v->Double("radius_m", &legs->radius_m, R::Between(1e-3, 0.5), "leg radius of legged people");
  v->Double("hip_width_m", &legs->hip_width_m, R::Between(0, 2),
            "distance between the leg centres across the heading");
  v->Double("sway_m", &legs->sway_m, R::Between(0, 0.2), "standing sway amplitude");
}

void VisitScatteredLandmarksSpec(OptionVisitor* v, ScatteredLandmarksSpec* g) {
  using R = OptionRange;
  v->Int("count", &g->count, R::Between(0, 100000),
         "posts scattered along the robot's waypoint path, drawn from the seed (0: none)");
  v->Double("min_offset_m", &g->min_offset_m, R::Above(0),
            "nearest distance of a post from the path; below `max_offset_m`");
  v->Double("max_offset_m", &g->max_offset_m, R::AboveUpTo(0, 1000),
            "farthest distance of a post from the path");
  v->Double("min_spacing_m", &g->min_spacing_m, R::Between(0, 100),
            "least distance between two posts");
  v->Double("radius_m", &g->radius_m, R::AboveUpTo(0, 10), "post radius");
  v->Int("first_id", &g->first_id, R::Between(-1e17, 1e17),
         "id of the first post (0: after the statics' ids)");
}

void VisitRobotMotionSettings(OptionVisitor* v, RobotMotionSpec* r) {
  using R = OptionRange;
  v->Double("speed_mps", &r->speed_mps, R::AboveUpTo(0, kMaxRobotSpeedMps),
            "waypoint mode: driving speed");
  v->Double("max_angular_radps", &r->max_angular_radps, R::Above(0),
            "waypoint mode: turn-rate limit", OptionUnit::kDegrees);
  v->Double("turn_gain_per_s", &r->turn_gain_per_s, R::Above(0),
            "waypoint mode: yaw rate per radian of heading error");
  v->Double("waypoint_tolerance_m", &r->waypoint_tolerance_m, R::Above(0),
            "waypoint mode: a waypoint within this is reached");
  v->Bool("loop", &r->loop, "repeat the profile or the waypoints; else stop at the end");
}

std::pair<std::string, std::string> FindScenarioSettingsProblem(const Scenario& scenario) {
  Scenario copy = scenario;
  std::vector<std::pair<std::string, OptionRangeCheck>> checks;
  checks.reserve(6);
  VisitScenarioSections(&copy, [&checks](const std::string& section) -> OptionVisitor* {
    checks.emplace_back(section, OptionRangeCheck());
    return &checks.back().second;
  });
  for (const auto& [section, check] : checks) {
    if (!check.problem().empty()) {
      return {(section.empty() ? "" : section + ".") + check.problem_key(),
              check.problem_detail()};
    }
  }
  return {};
}

std::vector<std::pair<std::string, std::string>> ScenarioOptionsTables() {
  Scenario defaults;
  std::vector<std::pair<std::string, OptionsMarkdownTable>> tables;
  tables.reserve(7);
  VisitScenarioSections(&defaults, [&tables](const std::string& section) -> OptionVisitor* {
    tables.emplace_back(section, OptionsMarkdownTable());
    return &tables.back().second;
  });
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [section, table] : tables) out.emplace_back(section, table.Table());
  return out;
}

std::string ScenarioOptionsMarkdown() {
  std::string text;
  for (const auto& [section, table] : ScenarioOptionsTables()) {
    text += (text.empty() ? "" : "\n") +
            (section.empty() ? std::string("Top level:") : "`" + section + ":`") + "\n\n" +
            table;
  }
  return text;
}

}  // namespace slammtt
