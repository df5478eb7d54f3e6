// The polygon algorithms of Surface (cpp/src/maps/polygon.hpp): the sweep finds a crossing exactly when
// testing every pair does, on simple and non-simple polygons; ear clipping covers the polygon.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "maps/polygon.hpp"

using octoreach::detail::all_pairs_crossing;
using octoreach::detail::cross2;
using octoreach::detail::ear_clip;
using octoreach::detail::sweep_crossing;
using Polygon = std::vector<Eigen::Vector2d>;

namespace {

// A simple polygon: vertices at sorted random angles around the origin, random radii.
Polygon star(std::mt19937_64& rng, int n, double r_min) {
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), radius(r_min, 1.0);
  std::vector<double> a(n);
  for (auto& x : a) x = angle(rng);
  std::sort(a.begin(), a.end());
  Polygon p;
  for (double t : a) {
    double r = radius(rng);
    p.emplace_back(r * std::cos(t), r * std::sin(t));
  }
  return p;
}

double area(const Polygon& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross2(p[i], p[(i + 1) % p.size()]);
  return a / 2;
}

}  // namespace

TEST(Polygon, SweepAgreesWithAllPairsOnRandomPolygons) {
  std::mt19937_64 rng(7);
  int simple = 0, crossing = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 4 + static_cast<int>(rng() % 300);
    Polygon p = star(rng, n, trial % 2 ? 0.9 : 0.05);
    // Every other polygon made non-simple: two vertices swapped, or one moved across the polygon.
    if (trial % 4 == 1) std::swap(p[rng() % n], p[rng() % n]);
    if (trial % 4 == 3) p[rng() % n] *= -0.5;
    const double eps = 1e-9;
    const auto all = all_pairs_crossing(p, eps), swept = sweep_crossing(p, eps);
    const bool all_simple = all.first == p.size(), swept_simple = swept.first == p.size();
    ASSERT_EQ(all_simple, swept_simple) << "trial " << trial << ", " << n << " vertices";
    if (!swept_simple) {  // the pair the sweep reports crosses indeed: all pairs finds it on those two edges
      Polygon two = {p[swept.first], p[(swept.first + 1) % n], p[swept.second], p[(swept.second + 1) % n]};
      EXPECT_LT(swept.first, swept.second);
      EXPECT_NE(all_pairs_crossing(two, eps).first, two.size()) << "trial " << trial;
    }
    (all_simple ? simple : crossing) += 1;
  }
  EXPECT_GT(simple, 100);
  EXPECT_GT(crossing, 80);
}

TEST(Polygon, SweepFindsTouchingVerticesAndCollinearOverlaps) {
  // A vertex touching a non-adjacent edge; an edge overlapping another along a line; vertical edges.
  const Polygon touch = {{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}};
  const Polygon overlap = {{0, 0}, {3, 0}, {3, 1}, {2, 1}, {2, 0}, {1, 0}, {1, 1}, {0, 1}};
  const Polygon comb_ok = {{0, 0}, {4, 0}, {4, 1}, {3, 1}, {3, 0.5}, {2, 0.5}, {2, 1}, {1, 1}, {1, 0.5}, {0, 0.5}};
  for (const Polygon& p : {touch, overlap}) EXPECT_NE(sweep_crossing(p, 1e-9).first, p.size());
  EXPECT_EQ(sweep_crossing(comb_ok, 1e-9).first, comb_ok.size());
}

TEST(Polygon, EarClippingCoversThePolygon) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const int n = 3 + static_cast<int>(rng() % 200);
    Polygon p = star(rng, n, 0.05);
    if (trial % 2) std::reverse(p.begin(), p.end());
    const double a = area(p);
    const auto tris = ear_clip(p, a < 0);
    ASSERT_EQ(tris.size(), std::size_t(n - 2));
    double sum = 0;
    for (const auto& t : tris) {
      const double ta = cross2(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]]) / 2;  // counter-clockwise either way
      EXPECT_GE(ta, -1e-12);
      sum += ta;
    }
    EXPECT_NEAR(sum, std::abs(a), 1e-9);
  }
}
