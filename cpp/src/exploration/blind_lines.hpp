#pragma once
// Internal: lines of sight that returned nothing. A view announced with expect_view whose rays, walked again
// through the map its insert updated, still meet a void cell (or an unknown cell of the search space) the insert
// left unknown, with no occupied cell
// behind it within the camera's range either, looked along a line with nothing on it: its rays through the
// cell ended on nothing within range (past the end of the scene, a wall beyond the range), or they would have
// turned the cell free. Geometry does not change, so a view from the same eye, or from farther back along the
// same line (its rays reach no farther past the cell), reveals nothing there either; a view from elsewhere, or
// from nearer (its rays reach farther), may. A line is kept per cell as the unit direction from the cell to
// the eye that missed it and that eye's distance; a view counts the cell 0 when its eye lies within the angle
// one cell spans at the cell (at the missed eye's distance, within a cell of that eye's line) and no nearer
// than a cell less than the missed eye. A pan/tilt head, whose eye barely moves, thus stops expecting what its
// rays cannot return; a camera that moves still may look from another side. A cell with a line has had no
// surface on it along that line: count_view takes it as holding none when it weighs whether a ray returns.
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "octoreach/exploration.hpp"

namespace octoreach::detail {

class BlindLines {
 public:
  static constexpr std::size_t kMaxLines = 8;  // per cell: the first ones (an eye's lines are alike anyway)

  // Records that a view from `eye` met cell k (centre `centre`) and its rays returned nothing through it.
  void add(CellKey k, const Eigen::Vector3d& centre, const Eigen::Vector3d& eye, double res) {
    Line l;
    if (!line(centre, eye, res, l) || covers(k, centre, eye)) return;
    std::vector<Line>& v = lines_[k];
    if (v.size() < kMaxLines) v.push_back(l);
  }
  // True when a view from `eye` looks at cell k (centre `centre`) along a line that returned nothing.
  bool covers(CellKey k, const Eigen::Vector3d& centre, const Eigen::Vector3d& eye) const {
    const auto it = lines_.find(k);
    if (it == lines_.end()) return false;
    const Eigen::Vector3d d = eye - centre;
    const double n = d.norm();
    if (!(n > 0)) return false;
    for (const Line& l : it->second)
      if (n >= double(l.min_distance) && d.dot(l.dir.cast<double>()) >= double(l.cos_tolerance) * n) return true;
    return false;
  }
  // True when some view's rays through cell k returned nothing: no surface lies on the lines they crossed it on.
  bool holds(CellKey k) const { return lines_.find(k) != lines_.end(); }
  bool empty() const { return lines_.empty(); }
  std::size_t size() const { return lines_.size(); }  // cells with a line
  template <class F>
  void for_each_cell(F&& f) const {
    for (const auto& kv : lines_) f(kv.first);
  }

 private:
  struct Line {
    Eigen::Vector3f dir;  // unit, cell -> eye
    float cos_tolerance;  // cos of the angle one cell spans from the eye (atan(res / distance))
    float min_distance;   // the eye's distance less a cell: a nearer eye's rays reach farther past the cell
  };
  static bool line(const Eigen::Vector3d& centre, const Eigen::Vector3d& eye, double res, Line& l) {
    const Eigen::Vector3d d = eye - centre;
    const double n = d.norm();
    if (!(n > res)) return false;  // an eye in or next to the cell: no line to speak of
    l.dir = (d / n).cast<float>();
    l.cos_tolerance = float(n / std::hypot(n, res));
    l.min_distance = float(n - res);
    return true;
  }
  std::unordered_map<CellKey, std::vector<Line>> lines_;
};

}  // namespace octoreach::detail
