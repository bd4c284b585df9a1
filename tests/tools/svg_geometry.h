// Reading back what the pictures drew (tools/plots): the bounding boxes of data elements (those
// clipped to a panel, cut to their clip rectangle) and of legend boxes, and the elements of one
// role (class attribute). Every element of our SVG writer is one line.
#pragma once

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace slammtt::testing {

struct PixelBox {
  double left = 0, top = 0, right = 0, bottom = 0;
  bool Intersects(const PixelBox& o) const {
    return left < o.right && o.left < right && top < o.bottom && o.top < bottom;
  }
};

inline std::vector<std::string> SvgLines(const std::string& svg) {
  std::vector<std::string> lines;
  std::istringstream in(svg);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline double Attribute(const std::string& element, const std::string& name) {
  const std::regex re("[ <]" + name + "=\"(-?[0-9.]+)\"");
  std::smatch m;
  if (!std::regex_search(element, m, re)) return 0.0;
  return std::stod(m[1]);
}

inline std::string TextAttribute(const std::string& element, const std::string& name) {
  const std::regex re(" " + name + "=\"([^\"]*)\"");
  std::smatch m;
  return std::regex_search(element, m, re) ? std::string(m[1]) : std::string();
}

// The bounding box of a path, circle, ellipse, rect or text element (a text taken as 0.62 em
// per character, font size high, from its anchor).
inline PixelBox ElementBox(const std::string& e) {
  PixelBox b;
  if (e.rfind("<circle", 0) == 0) {
    const double cx = Attribute(e, "cx"), cy = Attribute(e, "cy"), r = Attribute(e, "r");
    return {cx - r, cy - r, cx + r, cy + r};
  }
  if (e.rfind("<ellipse", 0) == 0) {
    const double cx = Attribute(e, "cx"), cy = Attribute(e, "cy");
    const double r = std::max(Attribute(e, "rx"), Attribute(e, "ry"));
    return {cx - r, cy - r, cx + r, cy + r};
  }
  if (e.rfind("<rect", 0) == 0) {
    const double x = Attribute(e, "x"), y = Attribute(e, "y");
    return {x, y, x + Attribute(e, "width"), y + Attribute(e, "height")};
  }
  if (e.rfind("<text", 0) == 0) {
    const double x = Attribute(e, "x"), y = Attribute(e, "y"), size = Attribute(e, "font-size");
    const size_t open = e.find('>');
    const size_t close = e.find("</text>");
    const double width = 0.62 * size * static_cast<double>(close - open - 1);
    const std::string anchor = TextAttribute(e, "text-anchor");
    const double left = anchor == "middle" ? x - width / 2 : anchor == "end" ? x - width : x;
    return {left, y - size, left + width, y};
  }
  // A path: absolute M, L, H, V commands (all our writer emits).
  const std::string d = TextAttribute(e, "d");
  b = {1e18, 1e18, -1e18, -1e18};
  double x = 0, y = 0;
  const std::regex command("([MLHVZ])([^MLHVZ]*)");
  for (auto it = std::sregex_iterator(d.begin(), d.end(), command); it != std::sregex_iterator();
       ++it) {
    const char c = (*it)[1].str()[0];
    std::istringstream numbers((*it)[2].str());
    if (c == 'M' || c == 'L') {
      numbers >> x >> y;
    } else if (c == 'H') {
      numbers >> x;
    } else if (c == 'V') {
      numbers >> y;
    } else {
      continue;
    }
    b.left = std::min(b.left, x);
    b.right = std::max(b.right, x);
    b.top = std::min(b.top, y);
    b.bottom = std::max(b.bottom, y);
  }
  return b;
}

// The clip rectangles of a document by id.
inline std::map<std::string, PixelBox> ClipBoxes(const std::string& svg) {
  std::map<std::string, PixelBox> clips;
  for (const std::string& line : SvgLines(svg)) {
    if (line.rfind("<clipPath", 0) != 0) continue;
    clips[TextAttribute(line, "id")] = ElementBox(line.substr(line.find("<rect")));
  }
  return clips;
}

// Every data element (clipped to a panel) as its visible box: its bounding box cut to the clip.
inline std::vector<PixelBox> DataBoxes(const std::string& svg) {
  const std::map<std::string, PixelBox> clips = ClipBoxes(svg);
  std::vector<PixelBox> boxes;
  const std::regex clip("clip-path=\"url\\(#([^)]*)\\)\"");
  for (const std::string& line : SvgLines(svg)) {
    std::smatch m;
    if (!std::regex_search(line, m, clip)) continue;
    const PixelBox c = clips.at(m[1]);
    PixelBox b = ElementBox(line);
    b = {std::max(b.left, c.left), std::max(b.top, c.top), std::min(b.right, c.right),
         std::min(b.bottom, c.bottom)};
    if (b.left <= b.right && b.top <= b.bottom) boxes.push_back(b);
  }
  return boxes;
}

// The frame of every legend (the first rect of each <g class="legend">).
inline std::vector<PixelBox> LegendBoxes(const std::string& svg) {
  std::vector<PixelBox> boxes;
  bool in_legend = false;
  for (const std::string& line : SvgLines(svg)) {
    if (line == "<g class=\"legend\">") {
      in_legend = true;
    } else if (in_legend && line.rfind("<rect", 0) == 0) {
      boxes.push_back(ElementBox(line));
      in_legend = false;
    }
  }
  return boxes;
}

// The elements with class="role".
inline std::vector<std::string> ElementsOfRole(const std::string& svg, const std::string& role) {
  std::vector<std::string> out;
  for (const std::string& line : SvgLines(svg)) {
    if (line.find(" class=\"" + role + "\"") != std::string::npos) out.push_back(line);
  }
  return out;
}

}  // namespace slammtt::testing
