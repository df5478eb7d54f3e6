#include "maps/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "common/cancel.hpp"

namespace octoreach::detail {
namespace {

bool on_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double eps) {
  return std::abs(cross2(b - a, p - a)) <= eps * (b - a).norm() && (p - a).dot(p - b) <= eps * eps;
}

// True when the closed segments touch or cross (eps: a length tolerance).
bool segments_intersect(const Eigen::Vector2d& p1, const Eigen::Vector2d& p2, const Eigen::Vector2d& q1,
                        const Eigen::Vector2d& q2, double eps) {
  double d1 = cross2(p2 - p1, q1 - p1), d2 = cross2(p2 - p1, q2 - p1);
  double d3 = cross2(q2 - q1, p1 - q1), d4 = cross2(q2 - q1, p2 - q1);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  return on_segment(q1, p1, p2, eps) || on_segment(q2, p1, p2, eps) || on_segment(p1, q1, q2, eps) ||
         on_segment(p2, q1, q2, eps);
}

bool point_in_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       const Eigen::Vector2d& c) {
  double d1 = cross2(b - a, p - a), d2 = cross2(c - b, p - b), d3 = cross2(a - c, p - c);
  return d1 >= 0 && d2 >= 0 && d3 >= 0;
}

// The sweep of crossing_edges: a vertical line moves left to right over the edges; the edges it cuts are
// kept ordered by height (ties: by slope, the order just right of a shared point). A new edge is tested
// against its two neighbours, and an edge leaving makes its two neighbours neighbours: the leftmost
// crossing of a non-simple polygon is between two edges that are neighbours just before it.
class CrossingSweep {
 public:
  CrossingSweep(const std::vector<Eigen::Vector2d>& polygon, double eps) : p_(polygon), eps_(eps), n_(polygon.size()) {
    edges_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) {
      Eigen::Vector2d a = p_[i], b = p_[(i + 1) % n_];
      if (b.x() < a.x() || (b.x() == a.x() && b.y() < a.y())) std::swap(a, b);
      edges_[i] = {a, b, i};
    }
  }

  std::pair<std::size_t, std::size_t> run() {
    struct Event {
      double x, y;
      int leaving;  // 0: the edge enters the sweep, 1: it leaves (entries first where both happen)
      std::size_t edge;
    };
    std::vector<Event> events;
    events.reserve(2 * n_);
    for (const Edge& e : edges_) {
      events.push_back({e.a.x(), e.a.y(), 0, e.id});
      events.push_back({e.b.x(), e.b.y(), 1, e.id});
    }
    std::sort(events.begin(), events.end(), [](const Event& u, const Event& v) {
      if (u.x != v.x) return u.x < v.x;
      if (u.leaving != v.leaving) return u.leaving < v.leaving;
      if (u.y != v.y) return u.y < v.y;
      return u.edge < v.edge;
    });
    const Below below{eps_};
    std::multiset<Edge, Below> cut(below);
    std::vector<std::multiset<Edge, Below>::iterator> where(n_);
    std::size_t done = 0;
    for (const Event& ev : events) {
      if ((++done & 4095) == 0) poll_cancel("surface construction cancelled");
      if (!ev.leaving) {
        const Edge& e = edges_[ev.edge];
        auto next = cut.lower_bound(e);
        if (next != cut.end() && crosses(next->id, e.id)) return ordered(next->id, e.id);
        if (next != cut.begin() && crosses(std::prev(next)->id, e.id)) return ordered(std::prev(next)->id, e.id);
        where[e.id] = cut.insert(next, e);
      } else {
        auto it = where[ev.edge];
        auto next = std::next(it);
        if (it != cut.begin() && next != cut.end() && crosses(std::prev(it)->id, next->id))
          return ordered(std::prev(it)->id, next->id);
        cut.erase(it);
      }
    }
    return {n_, n_};
  }

 private:
  struct Edge {
    Eigen::Vector2d a, b;  // a: the left (then lower) end
    std::size_t id;
    double y_at(double x) const {
      if (b.x() == a.x()) return a.y();
      return a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
    }
    double slope() const {
      return b.x() == a.x() ? std::numeric_limits<double>::infinity() : (b.y() - a.y()) / (b.x() - a.x());
    }
  };
  // The order of two edges the sweep line cuts, at the later of their left ends.
  struct Below {
    double eps;
    bool operator()(const Edge& u, const Edge& v) const {
      const double x = std::max(u.a.x(), v.a.x());
      const double yu = u.y_at(x), yv = v.y_at(x);
      if (yu < yv - eps) return true;
      if (yv < yu - eps) return false;
      const double su = u.slope(), sv = v.slope();
      if (su != sv) return su < sv;
      return u.id < v.id;
    }
  };

  bool crosses(std::size_t i, std::size_t j) const {
    if (i > j) std::swap(i, j);
    if (j == i + 1 || (i == 0 && j == n_ - 1)) return false;  // neighbours share their vertex
    return segments_intersect(p_[i], p_[(i + 1) % n_], p_[j], p_[(j + 1) % n_], eps_);
  }
  static std::pair<std::size_t, std::size_t> ordered(std::size_t i, std::size_t j) {
    return {std::min(i, j), std::max(i, j)};
  }

  const std::vector<Eigen::Vector2d>& p_;
  const double eps_;
  const std::size_t n_;
  std::vector<Edge> edges_;
};

}  // namespace

std::pair<std::size_t, std::size_t> all_pairs_crossing(const std::vector<Eigen::Vector2d>& polygon, double eps) {
  const std::size_t N = polygon.size();
  for (std::size_t i = 0; i < N; ++i) {
    if ((i & 63) == 0) poll_cancel("surface construction cancelled");
    for (std::size_t j = i + 2; j < N; ++j) {
      if (i == 0 && j == N - 1) continue;
      if (segments_intersect(polygon[i], polygon[(i + 1) % N], polygon[j], polygon[(j + 1) % N], eps)) return {i, j};
    }
  }
  return {N, N};
}

std::pair<std::size_t, std::size_t> sweep_crossing(const std::vector<Eigen::Vector2d>& polygon, double eps) {
  return CrossingSweep(polygon, eps).run();
}

std::pair<std::size_t, std::size_t> crossing_edges(const std::vector<Eigen::Vector2d>& polygon, double eps) {
  return polygon.size() > kAllPairsEdges ? sweep_crossing(polygon, eps) : all_pairs_crossing(polygon, eps);
}

void check_simple(const std::vector<Eigen::Vector2d>& polygon, double eps) {
  const std::size_t N = polygon.size();
  std::size_t spike = N;  // adjacent edges folding back onto each other make a spike of zero width
  for (std::size_t i = 0; i < N && spike == N; ++i) {
    Eigen::Vector2d e0 = polygon[(i + 1) % N] - polygon[i], e1 = polygon[(i + 2) % N] - polygon[(i + 1) % N];
    if (std::abs(cross2(e0, e1)) <= eps * e0.norm() && e0.dot(e1) < 0) spike = i;
  }
  const auto [i, j] = crossing_edges(polygon, eps);
  if (spike < N && spike <= i)
    throw std::invalid_argument("surface polygon is self-intersecting: edges " + std::to_string(spike) + " and " +
                                std::to_string((spike + 1) % N) + " fold back onto each other");
  if (i < N)
    throw std::invalid_argument("surface polygon is self-intersecting: edges " + std::to_string(i) + " and " +
                                std::to_string(j) + " cross or touch");
}

// Triangles (vertex indices) of a simple 2D polygon by ear clipping; `clockwise` polygons are
// walked backwards so that ears are convex corners. The ear clipped next is always the first one in
// walking order. Only corners that are not strictly convex at the start can lie inside an ear's triangle
// (any polygon vertex inside it means a reflex one is), so only they are tested; clipping an ear changes
// whether its two neighbours are ears, no other corner's: O(N R) tests for R reflex corners (a convex
// polygon: O(N log N)).
std::vector<std::array<int, 3>> ear_clip(const std::vector<Eigen::Vector2d>& polygon, bool clockwise) {
  const int N = static_cast<int>(polygon.size());
  // Walk position r visits vertex at(r); prev/next link the positions still in the polygon.
  auto at = [&](int r) { return clockwise ? N - 1 - r : r; };
  std::vector<int> prev(N), next(N);
  for (int r = 0; r < N; ++r) prev[r] = (r + N - 1) % N, next[r] = (r + 1) % N;
  auto convex = [&](int r) {
    const auto &a = polygon[at(prev[r])], &b = polygon[at(r)], &c = polygon[at(next[r])];
    return cross2(b - a, c - b) > 1e-15;
  };
  std::vector<int> blockers;  // positions of the corners that are reflex or flat at the start
  for (int r = 0; r < N; ++r)
    if (!convex(r)) blockers.push_back(r);
  std::vector<char> gone(N, 0);
  auto is_ear = [&](int r) {
    if (!convex(r)) return false;
    const int ra = prev[r], rc = next[r];
    const auto &a = polygon[at(ra)], &b = polygon[at(r)], &c = polygon[at(rc)];
    for (int o : blockers)
      if (!gone[o] && o != ra && o != r && o != rc && point_in_triangle(polygon[at(o)], a, b, c)) return false;
    return true;
  };
  std::set<int> ears;
  for (int r = 0; r < N; ++r) {
    if ((r & 63) == 0) poll_cancel("surface construction cancelled");
    if (is_ear(r)) ears.insert(r);
  }
  std::vector<std::array<int, 3>> triangles;
  int first = 0;  // the first position still in the polygon
  for (int left = N; left > 3; --left) {
    if ((left & 63) == 0) poll_cancel("surface construction cancelled");
    if (ears.empty()) throw std::invalid_argument("surface polygon could not be triangulated (degenerate shape)");
    const int r = *ears.begin();
    ears.erase(ears.begin());
    const int ra = prev[r], rc = next[r];
    triangles.push_back({at(ra), at(r), at(rc)});
    gone[r] = 1;
    next[ra] = rc;
    prev[rc] = ra;
    if (r == first) first = rc;
    for (int n : {ra, rc}) {
      if (is_ear(n)) ears.insert(n);
      else ears.erase(n);
    }
  }
  triangles.push_back({at(first), at(next[first]), at(next[next[first]])});
  return triangles;
}

}  // namespace octoreach::detail
