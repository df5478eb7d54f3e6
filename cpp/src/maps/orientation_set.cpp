#include "octoreach/orientation_set.hpp"

#include "common/cancel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <set>
#include <stdexcept>

namespace octoreach {
namespace {

// Cube-map cell of a unit vector: face (0..5) and cell coordinates in [0, n).
inline int cube_cell(const Eigen::Vector3d& d, int n) {
  Eigen::Vector3d a = d.cwiseAbs();
  int axis;
  if (a.x() >= a.y() && a.x() >= a.z()) axis = 0;
  else if (a.y() >= a.z()) axis = 1;
  else axis = 2;
  double m = a[axis];
  int face = axis * 2 + (d[axis] < 0 ? 1 : 0);
  double u = d[(axis + 1) % 3] / m, v = d[(axis + 2) % 3] / m;  // in [-1, 1]
  int iu = std::min(n - 1, std::max(0, static_cast<int>((u + 1) * 0.5 * n)));
  int iv = std::min(n - 1, std::max(0, static_cast<int>((v + 1) * 0.5 * n)));
  return (face * n + iu) * n + iv;
}

// Unit directions bucketed in a uniform grid over [-1, 1]^3 (about 4 per occupied cell), so that
// the directions near a point are found without looking at all of them.
class DirectionGrid {
 public:
  explicit DirectionGrid(const std::vector<Eigen::Vector3d>& d)
      : g_(std::max(1, static_cast<int>(std::sqrt(double(d.size()) / 12.0)))) {
    const std::size_t cells = std::size_t(g_) * g_ * g_;
    start_.assign(cells + 1, 0);
    std::vector<std::size_t> cell(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      cell[i] = id(coord(d[i].x()), coord(d[i].y()), coord(d[i].z()));
      ++start_[cell[i] + 1];
    }
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    idx_.resize(d.size());
    for (std::size_t i = 0; i < d.size(); ++i) idx_[std::size_t(fill[cell[i]]++)] = int(i);
  }
  double cell_size() const { return 2.0 / g_; }
  // f(j) for every direction j within distance r of p (and some more: those of the cells the box touches).
  template <class F>
  void near(const Eigen::Vector3d& p, double r, F&& f) const {
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = coord(p[a] - r);
      hi[a] = coord(p[a] + r);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const std::size_t c = id(x, y, z);
          for (int k = start_[c]; k < start_[c + 1]; ++k) f(idx_[std::size_t(k)]);
        }
  }

 private:
  int coord(double x) const {
    if (!(x > -1.0)) return 0;  // also NaN
    return std::min(g_ - 1, static_cast<int>((std::min(x, 1.0) + 1.0) * 0.5 * g_));
  }
  std::size_t id(int x, int y, int z) const { return (std::size_t(z) * g_ + y) * g_ + x; }
  int g_;
  std::vector<int> start_, idx_;
};

// A search radius (chord distance) covers the whole sphere once it reaches this.
constexpr double kWholeSphere = 2.5;
// Every direction outside the box of half-width r around a unit vector p has p.d < 1 - r^2 / 2 + 1e-12:
// a candidate whose dot product passes this bound beats all of them.
inline bool beats_outside(double dot, double r) { return r >= kWholeSphere || dot >= 1.0 - 0.5 * r * r + 1e-9; }

Eigen::Matrix3d align(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

}  // namespace

int OrientationSet::sphere_directions(std::int64_t count, int symmetry, bool poles) {
  if (count < 1 || count > kMaxDirections)
    throw std::invalid_argument("direction count must be in [1, " + std::to_string(kMaxDirections) + "], got " +
                                std::to_string(count));
  if (symmetry < 1 || symmetry > 64) throw std::invalid_argument("symmetry must be in [1, 64]");
  const std::int64_t spiral = poles ? count - 2 : count;  // the poles come on top of the spiral
  const int per_wedge = int(std::max<std::int64_t>(1, (spiral + symmetry / 2) / symmetry));
  return per_wedge * symmetry + (poles ? 2 : 0);
}

OrientationSet OrientationSet::sphere(std::int64_t count, int rolls, int symmetry, bool poles) {
  const int directions = sphere_directions(count, symmetry, poles);  // (checks count and symmetry)
  if (rolls < 1 || rolls > kMaxRolls)
    throw std::invalid_argument("rolls must be in [1, " + std::to_string(kMaxRolls) + "], got " + std::to_string(rolls));
  OrientationSet s;
  s.rolls_ = rolls;
  s.symmetry_ = symmetry;
  s.poles_ = poles;
  const int per_wedge = (directions - (poles ? 2 : 0)) / symmetry;
  // Fibonacci spiral over the sphere, compressed into one azimuth wedge of 2 pi / symmetry:
  // equal-area in z, golden-ratio spacing in azimuth within the wedge.
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  const double wedge = 2.0 * M_PI / symmetry;
  for (int i = 0; i < per_wedge; ++i) {
    double z = 1.0 - (2.0 * i + 1.0) / per_wedge;
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    double frac = std::fmod(i * golden, 1.0);
    double phi = frac * wedge;
    for (int k = 0; k < symmetry; ++k) {
      double p = phi + k * wedge;
      s.dirs_.emplace_back(r * std::cos(p), r * std::sin(p), z);
    }
  }
  if (poles) {  // fixed by every turn about z: the symmetry holds
    s.dirs_.emplace_back(0.0, 0.0, 1.0);
    s.dirs_.emplace_back(0.0, 0.0, -1.0);
  }
  s.finalize_();
  return s;
}

OrientationSet OrientationSet::from_directions(const std::vector<Eigen::Vector3d>& directions, int rolls) {
  if (directions.empty()) throw std::invalid_argument("an orientation set needs at least one direction");
  if (directions.size() > std::size_t(kMaxDirections))
    throw std::invalid_argument("an orientation set holds at most " + std::to_string(kMaxDirections) + " directions, got " +
                                std::to_string(directions.size()));
  if (rolls < 1 || rolls > kMaxRolls)
    throw std::invalid_argument("rolls must be in [1, " + std::to_string(kMaxRolls) + "], got " + std::to_string(rolls));
  OrientationSet s;
  s.rolls_ = rolls;
  for (const auto& d : directions) {
    if (!d.allFinite() || d.norm() < 1e-12) throw std::invalid_argument("directions must be finite and non-zero");
    s.dirs_.push_back(d.normalized());
  }
  s.finalize_();
  return s;
}

void OrientationSet::finalize_() {
  detail::CancellableScope cancellable;
  const int n = directions();
  const DirectionGrid grid(dirs_);
  // Nearest neighbours (up to 6) by angle, ties by index: the 6 best of the directions within a
  // growing radius, once the 6th beats every direction outside it.
  neighbours_.assign(n, {});
  std::vector<std::pair<double, int>> d;
  for (int i = 0; i < n; ++i) {
    detail::poll_cancel("orientation set construction cancelled");
    for (double r = grid.cell_size();; r *= 2) {
      d.clear();
      grid.near(dirs_[i], r, [&](int j) {
        if (j != i) d.emplace_back(-dirs_[i].dot(dirs_[j]), j);
      });
      const std::size_t k = std::min<std::size_t>(6, d.size());
      std::partial_sort(d.begin(), d.begin() + std::ptrdiff_t(k), d.end());
      if (r >= kWholeSphere || (k == 6 && beats_outside(-d[5].first, r))) break;
    }
    for (std::size_t k = 0; k < std::min<std::size_t>(6, d.size()); ++k) neighbours_[i].push_back(d[k].second);
  }
  // Candidates per cube-map cell: directions nearest to some sample point of the cell,
  // widened by the cell's angular size so that the exact nearest is always among them.
  std::vector<std::vector<int>> table(6 * kCells * kCells);
  for (int face = 0; face < 6; ++face) {
    int axis = face / 2;
    double sign = face % 2 ? -1.0 : 1.0;
    for (int iu = 0; iu < kCells; ++iu)
      for (int iv = 0; iv < kCells; ++iv) {
        auto point = [&](double fu, double fv) {
          Eigen::Vector3d d;
          d[axis] = sign;
          d[(axis + 1) % 3] = -1.0 + 2.0 * (iu + fu) / kCells;
          d[(axis + 2) % 3] = -1.0 + 2.0 * (iv + fv) / kCells;
          return d.normalized();
        };
        Eigen::Vector3d c = point(0.5, 0.5);
        double radius = 0;  // angular radius of the cell around its centre
        for (double fu : {0.0, 1.0})
          for (double fv : {0.0, 1.0}) radius = std::max(radius, std::acos(std::min(1.0, c.dot(point(fu, fv)))));
        // Nearest to the centre at angle a0: any direction within a0 + 2 radius may be nearest somewhere.
        double best = -2;
        for (double r = grid.cell_size();; r *= 2) {
          grid.near(c, r, [&](int j) { best = std::max(best, c.dot(dirs_[j])); });
          if (beats_outside(best, r)) break;
        }
        double limit = std::acos(std::min(1.0, best)) + 2.0 * radius + 1e-9;
        auto& cands = table[cube_cell(c, kCells)];
        const std::size_t first = cands.size();
        const double reach = limit >= kPi ? kWholeSphere : 2.0 * std::sin(0.5 * limit) + 1e-9;
        grid.near(c, reach, [&](int j) {
          if (std::acos(std::max(-1.0, std::min(1.0, c.dot(dirs_[j])))) <= limit) cands.push_back(j);
        });
        std::sort(cands.begin() + std::ptrdiff_t(first), cands.end());
      }
  }
  start_.assign(table.size() + 1, 0);
  candidates_.clear();
  for (std::size_t i = 0; i < table.size(); ++i) {
    candidates_.insert(candidates_.end(), table[i].begin(), table[i].end());
    start_[i + 1] = static_cast<std::uint32_t>(candidates_.size());
  }
  // Rotation table for the z symmetry.
  rotated_.assign(symmetry_, std::vector<int>(n));
  for (int k = 0; k < symmetry_; ++k) {
    Eigen::Matrix3d R = Eigen::AngleAxisd(2.0 * M_PI * k / symmetry_, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    for (int i = 0; i < n; ++i) rotated_[k][i] = nearest_direction(R * dirs_[i]);
  }
}

int OrientationSet::nearest_direction(const Eigen::Vector3d& d) const {
  if (!d.allFinite() || d.isZero(0)) throw std::invalid_argument("nearest_direction needs a finite non-zero direction");
  const int cell = cube_cell(d, kCells);
  const std::int32_t* first = candidates_.data() + start_[cell];
  const std::int32_t* last = candidates_.data() + start_[cell + 1];
  if (first == last) return 0;
  // The largest dot product; where no other candidate comes within 2e-12 of it, it is what the rule below picks
  // (that rule only ever differs from the plain maximum among candidates within 1e-12; the wider margin leaves
  // room for rounding), found without its branches.
  constexpr std::ptrdiff_t kShort = 32;
  if (last - first <= kShort) {
    double dots[kShort];
    double best_dot = -std::numeric_limits<double>::infinity();
    int best = *first;
    for (const std::int32_t* j = first; j != last; ++j) {
      const double v = dirs_[*j].dot(d);
      dots[j - first] = v;
      const bool better = v > best_dot;
      best_dot = better ? v : best_dot;
      best = better ? *j : best;
    }
    int close = 0;
    for (std::ptrdiff_t k = 0; k < last - first; ++k) close += dots[k] > best_dot - 2e-12;
    if (close == 1 && best_dot > -2 + 2e-12) return best;  // (the rule below starts from -2)
  }
  int best = *first;
  double best_dot = -2;
  for (const std::int32_t* it = first; it != last; ++it) {
    const int j = *it;
    double v = dirs_[j].dot(d);
    if (v > best_dot + 1e-12) {
      best_dot = v;
      best = j;
    } else if (v > best_dot - 1e-12) {
      // A tie (rotated queries land exactly between symmetric directions): take the candidate
      // counter-clockwise of the query about z. The rule turns with the set, so the nearest
      // direction of a z-rotated query is the rotated nearest direction (exact yaw symmetry).
      double side_j = d.cross(dirs_[j]).z(), side_best = d.cross(dirs_[best]).z();
      if (side_j > side_best + 1e-12 || (std::abs(side_j - side_best) <= 1e-12 && j < best)) {
        best_dot = std::max(best_dot, v);
        best = j;
      }
    }
  }
  return best;
}

Eigen::Matrix3d OrientationSet::rotation(int o, const Eigen::Vector3d& approach_axis) const {
  if (o < 0 || o >= size()) throw std::invalid_argument("orientation index " + std::to_string(o) + " out of range");
  if (!approach_axis.allFinite() || approach_axis.norm() < 1e-12)
    throw std::invalid_argument("approach_axis must be a finite non-zero vector");
  int di = o / rolls_, ri = o % rolls_;
  Eigen::Vector3d a = approach_axis.normalized();
  Eigen::Matrix3d R = align(a, dirs_[di]);
  if (rolls_ > 1) R = Eigen::AngleAxisd(2.0 * M_PI * ri / rolls_, dirs_[di]).toRotationMatrix() * R;
  return R;
}

int OrientationSet::nearest(const Eigen::Matrix3d& R, const Eigen::Vector3d& approach_axis) const {
  Eigen::Vector3d a = approach_axis.normalized();
  Eigen::Vector3d d = R * a;
  int di = nearest_direction(d);
  if (rolls_ == 1) return di;
  Eigen::Vector3d u = a.unitOrthogonal();
  Eigen::Vector3d canon = align(a, dirs_[di]) * u;
  Eigen::Vector3d actual = R * u;
  double angle = std::atan2(canon.cross(actual).dot(dirs_[di]), canon.dot(actual));
  if (angle < 0) angle += 2.0 * M_PI;
  int ri = static_cast<int>(std::lround(angle / (2.0 * M_PI / rolls_))) % rolls_;
  return di * rolls_ + ri;
}

std::vector<int> OrientationSet::subset(const std::string& name) const {
  std::vector<int> out;
  const double s30 = 0.5, c30 = std::sqrt(3.0) / 2.0, eps = 1e-9;
  for (int i = 0; i < directions(); ++i) {
    double z = dirs_[i].z();
    bool keep;
    if (name == "all") keep = true;
    else if (name == "upper_hemisphere") keep = z <= eps;
    else if (name == "lower_hemisphere") keep = z >= -eps;
    else if (name == "top") keep = z <= -c30 + eps;
    else if (name == "side") keep = std::abs(z) <= s30 + eps;
    else
      throw std::invalid_argument("unknown orientation subset '" + name +
                                  "': expected all, upper_hemisphere, lower_hemisphere, top or side");
    if (keep) out.push_back(i);
  }
  return out;
}

int OrientationSet::rotated(int i, int k) const {
  k = ((k % symmetry_) + symmetry_) % symmetry_;
  return rotated_[k].at(i);
}

}  // namespace octoreach
