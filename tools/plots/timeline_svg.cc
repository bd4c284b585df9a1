#include "tools/plots/timeline_svg.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "tools/plots/picture_style.h"

namespace slammtt {
namespace {

constexpr int kWidthPx = 900;
constexpr double kAxesPx = 68.0;  // title above, axis labels below the rows
constexpr int kLabelPx = 9;
constexpr int64_t kNotInTruthSet = -2;
constexpr int64_t kUntracked = -1;

const LineStyle kMissStyle{"#c8c8c8", 1.0, "", 1.0, "miss"};
const LineStyle kSwitchStyle{"#111111", 1.0, "", 1.0, "id-switch"};
const LineStyle kFragmentStyle{"#d62728", 1.0, "", 1.0, "fragmentation"};

double RowPx(size_t rows) {
  return rows <= 40 ? 16.0 : std::max(4.0, 640.0 / static_cast<double>(rows));
}

// What each mover was at each scored scan: kNotInTruthSet, kUntracked or the matched track id.
std::map<int64_t, std::vector<int64_t>> StatesPerMover(const std::vector<TrackingScan>& scans) {
  std::set<int64_t> ids;
  for (const TrackingScan& s : scans) ids.insert(s.truth_ids.begin(), s.truth_ids.end());
  std::map<int64_t, std::vector<int64_t>> states;
  for (int64_t id : ids) states[id].assign(scans.size(), kNotInTruthSet);
  for (size_t k = 0; k < scans.size(); ++k) {
    for (int64_t id : scans[k].truth_ids) states[id][k] = kUntracked;
    for (const auto& [truth, track] : scans[k].matches) states[truth][k] = track;
  }
  return states;
}

}  // namespace

std::string IdentityTimelineSvg(const EvaluationReport& report) {
  const std::string title = "Identities over time: the track matched to each true mover";
  const std::map<int64_t, std::vector<int64_t>> states =
      report.tracking ? StatesPerMover(report.tracking->scans)
                      : std::map<int64_t, std::vector<int64_t>>{};
  if (states.empty()) {
    SvgDocument doc(kWidthPx, 200);
    PlotPanel panel(&doc, 0, 0, kWidthPx, 200);
    panel.SetRange(0, 1, 0, 1, false);
    panel.DrawAxes(title, "time [s]", "true mover");
    panel.Message(report.log_only   ? "no ground truth in the log: no true movers"
                  : report.tracking ? "no true mover in the truth set of any scored scan"
                                    : "no tracking scores (no TRACKS in the log)");
    AppendLegendAndCaption(&doc, panel, {}, Subtitle(report));
    return doc.ToString();
  }
  const TrackingResult& tracking = *report.tracking;
  const std::vector<TrackingScan>& scans = tracking.scans;
  const size_t rows = states.size();
  const double height = kAxesPx + RowPx(rows) * static_cast<double>(rows);
  SvgDocument doc(kWidthPx, static_cast<int>(height));
  PlotPanel panel(&doc, 0, 0, kWidthPx, height);
  const double t0 = static_cast<double>(report.first_utime);
  auto seconds = [&](int64_t utime) { return (static_cast<double>(utime) - t0) * 1e-6; };
  // Scan k covers [t_k, t_k+1); the last one as long as the one before it.
  std::vector<double> begin_s;
  for (const TrackingScan& s : scans) begin_s.push_back(seconds(s.utime));
  const double last_period = scans.size() > 1 ? begin_s.back() - begin_s[begin_s.size() - 2] : 0.1;
  std::vector<double> end_s(begin_s.begin() + 1, begin_s.end());
  end_s.push_back(begin_s.back() + last_period);
  panel.SetRange(std::min(0.0, begin_s.front()), end_s.back(), -0.5,
                 static_cast<double>(rows) - 0.5, false);
  std::map<int64_t, double> row_y;  // the first mover at the top
  std::vector<std::pair<double, std::string>> row_labels;
  // Row labels of 11 px, every row while they fit, else every few rows.
  const size_t label_every =
      std::max<size_t>(1, static_cast<size_t>(std::ceil(13.0 / RowPx(rows))));
  size_t r = 0;
  for (const auto& [id, unused] : states) {
    row_y[id] = static_cast<double>(rows - 1 - r);
    if (r % label_every == 0) row_labels.emplace_back(row_y[id], std::to_string(id));
    ++r;
  }
  panel.SetYTickLabels(row_labels);
  panel.DrawAxes(title, "time [s]", "true mover (id)");

  const double bar = 0.35;  // half height of a bar, in rows
  for (const auto& [id, state] : states) {
    const double y = row_y.at(id);
    size_t k = 0;
    while (k < state.size()) {
      size_t end = k;
      while (end < state.size() && state[end] == state[k]) ++end;
      if (state[k] != kNotInTruthSet) {
        const LineStyle fill = state[k] == kUntracked
                                   ? kMissStyle
                                   : LineStyle{IdentityColour(state[k]), 1.0, "", 1.0, "tracked"};
        const Eigen::Vector2d from(begin_s[k], y - bar);
        const Eigen::Vector2d to(end_s[end - 1], y + bar);
        panel.Box(from, to, fill);
        const std::string text = std::to_string(state[k]);
        const Eigen::Vector2d a = panel.ToPixel(from);
        const Eigen::Vector2d b = panel.ToPixel(to);
        if (state[k] != kUntracked && b.x() - a.x() >= TextWidthPx(text, kLabelPx) + 3 &&
            a.y() - b.y() >= kLabelPx) {
          panel.LabelAtPixel(Eigen::Vector2d(a.x() + 1.5, 0.5 * (a.y() + b.y()) + 3.5), text,
                             kLabelPx, "#ffffff");
        }
      }
      k = end;
    }
  }
  const double marker_px = std::min(4.5, 0.3 * RowPx(rows) + 1.0);
  std::vector<Eigen::Vector2d> switches;
  // Every event's mover is in the truth set of its scan, so it has a row.
  for (const IdentitySwitchEvent& e : tracking.identity_switches) {
    const auto row = row_y.find(e.what.truth_id);
    if (row != row_y.end()) switches.emplace_back(seconds(e.utime), row->second + bar);
  }
  std::vector<Eigen::Vector2d> fragments;
  for (const FragmentationEvent& e : tracking.fragmentations) {
    const auto row = row_y.find(e.what.truth_id);
    if (row != row_y.end()) fragments.emplace_back(seconds(e.utime), row->second - bar);
  }
  panel.Triangles(switches, marker_px, kSwitchStyle);
  panel.Diamonds(fragments, marker_px, kFragmentStyle);
  const std::vector<LegendEntry> legend = {
      {"matched to a track (colour, and label where there is room: the track's id)",
       LineStyle{"#1f77b4", 6.0}},
      {"in the truth set, untracked (a miss)", LineStyle{kMissStyle.colour, 6.0}},
      {"identity switch, above the bar (" + std::to_string(switches.size()) + ")", kSwitchStyle,
       LegendMark::kTriangle},
      {"fragmentation, below the bar: tracked again (" + std::to_string(fragments.size()) + ")",
       kFragmentStyle, LegendMark::kDiamond}};
  AppendLegendAndCaption(&doc, panel, legend,
                         Subtitle(report) + ": " + std::to_string(states.size()) +
                             " true movers; blank: not in the truth set (invisible or standing)");
  return doc.ToString();
}

}  // namespace slammtt
