// Where the surface inside an occupied cell lies (surface_extents.hpp).
#include "exploration/surface_extents.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "exploration/exploration_state.hpp"

namespace octoreach::detail {

namespace {

// A record: lo x y z, hi x y z (a byte each, in 1/255 of the cell from its lower corner), bit 48 set, bits 49-54
// the sides the hits were seen from (per axis: a sensor below the hit, a sensor above it), then the count of hits
// (9 bits, saturating).
constexpr std::uint64_t kRecorded = std::uint64_t(1) << 48;
constexpr int kSidesShift = 49, kCountShift = 55;
constexpr std::uint64_t kMaxCount = (std::uint64_t(1) << 9) - 1;
std::uint64_t side_bit(int axis, bool above) { return std::uint64_t(1) << (kSidesShift + 2 * axis + (above ? 1 : 0)); }
constexpr double kSteps = 255.0;

std::uint64_t byte_at(std::uint64_t v, int i) { return (v >> (8 * i)) & 0xff; }

// The box of record v's hits in cell units, one quantisation step wider on each side.
void hits_box(std::uint64_t v, double l[3], double h[3]) {
  const double step = 1.0 / kSteps;
  for (int a = 0; a < 3; ++a) {
    l[a] = double(byte_at(v, a)) * step - step;
    h[a] = double(byte_at(v, a + 3)) * step + step;
  }
}

// The line o + t d against the box [lo, hi] (slabs; a zero component of d meets a slab only from inside it).
bool line_meets_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
                    const Eigen::Vector3d& hi) {
  double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double u = (lo[a] - o[a]) / d[a], v = (hi[a] - o[a]) / d[a];
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u);
    t1 = std::min(t1, v);
  }
  return t0 <= t1;
}

}  // namespace

void SurfaceExtents::record(const octomap::OcTree& tree, const std::vector<octomap::point3d>& cloud,
                            const octomap::point3d& origin, double max_range) {
  const bool unlimited = !(max_range > 0) || std::isinf(max_range);
  const double inv = 1.0 / tree.getResolution();  // (OcTree::coordToKey's resolution_factor: the same keys)
  const double o[3] = {origin.x(), origin.y(), origin.z()};
  CellKey last = KeyTable<std::uint64_t>::kEmpty;
  std::uint64_t* box = nullptr;
  for (const octomap::point3d& p : cloud) {
    if (!unlimited && (p - origin).norm() > max_range) continue;  // a max-range ray: no hit
    std::uint32_t key[3];
    std::uint64_t q[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const double u = std::floor(inv * double(p(a))), f = inv * double(p(a)) - u;  // cell and place in it
      inside = inside && u >= -32768.0 && u < 32768.0;
      key[a] = std::uint32_t(std::int64_t(u) + 32768);
      q[a] = std::uint64_t(std::clamp(std::lround(f * kSteps), 0L, 255L));
    }
    if (!inside) continue;
    const CellKey k = pack_key(key[0], key[1], key[2]);
    if (k != last || !box) {
      box = &boxes_.at(k);  // (only a new key rehashes: the pointer is taken again for every new cell)
      last = k;
      recorded_.push_back(k);
    }
    std::uint64_t v = *box;
    if (!(v & kRecorded)) {
      v = kRecorded;
      for (int a = 0; a < 3; ++a) v |= q[a] << (8 * a) | q[a] << (8 * (a + 3));
    } else {
      for (int a = 0; a < 3; ++a) {
        const std::uint64_t l = std::min(byte_at(v, a), q[a]), h = std::max(byte_at(v, a + 3), q[a]);
        v = (v & ~(std::uint64_t(0xff) << (8 * a)) & ~(std::uint64_t(0xff) << (8 * (a + 3)))) | l << (8 * a) |
            h << (8 * (a + 3));
      }
    }
    for (int a = 0; a < 3; ++a)
      if (o[a] != double(p(a))) v |= side_bit(a, o[a] > double(p(a)));
    const std::uint64_t n = std::min(kMaxCount, (v >> kCountShift) + 1);
    *box = (v & ((std::uint64_t(1) << kCountShift) - 1)) | n << kCountShift;
  }
}

namespace {

// A grown box packed: per side (lo x y z, hi x y z) 2 bits, 0 where it is the hits' box's side, 1 the cell's face
// (lo 0, hi 1), 2 the far face of the cell beyond (lo -1, hi 2), the only places surface_box moves a side to.
std::uint64_t pack_grown(const double l0[3], const double h0[3], const double l[3], const double h[3]) {
  const auto code = [](double v, double own, double face) { return std::uint64_t(v == own ? 0 : v == face ? 1 : 2); };
  std::uint64_t c = 0;
  for (int a = 0; a < 3; ++a) c |= code(l[a], l0[a], 0.0) << (2 * a) | code(h[a], h0[a], 1.0) << (2 * a + 6);
  return c;
}

void unpack_grown(std::uint64_t c, double l[3], double h[3]) {
  for (int a = 0; a < 3; ++a) {
    const std::uint64_t cl = (c >> (2 * a)) & 3, ch = (c >> (2 * a + 6)) & 3;
    if (cl) l[a] = cl == 1 ? 0.0 : -1.0;
    if (ch) h[a] = ch == 1 ? 1.0 : 2.0;
  }
}

// The box of the surface in cell k (record v) grown across the faces it goes on past (the header), packed in
// `grown_box`; false when it is not grown across any face.
bool surface_box(const ExplorationState& S, CellKey k, std::uint64_t v, std::uint64_t& grown_box) {
  double l[3], h[3];
  hits_box(v, l, h);
  const double step = 1.0 / kSteps;
  // The hits sample the surface about sqrt(area / hits) apart (cell units; the area spans the box's two largest
  // extents): a face of the cell the box comes that close to, the surface reaches.
  double e[3] = {h[0] - l[0], h[1] - l[1], h[2] - l[2]};
  std::sort(e, e + 3);
  const double spacing = std::sqrt(std::min(e[1], 1.0) * std::min(e[2], 1.0) / double(v >> kCountShift)) + step;
  const double l0[3] = {l[0], l[1], l[2]}, h0[3] = {h[0], h[1], h[2]};  // the hits' own box
  const GridReader g(S.grid);
  const int c[3] = {int(key_x(k)), int(key_y(k)), int(key_z(k))};
  bool grown = false;
  // Hits spread over a plane across the cell (thin along one axis, at most half their next extent) lie on a
  // surface facing the sensors: the solid behind it, seen from one side only, fills the cell on the far side.
  int thin = 0;
  for (int a = 1; a < 3; ++a)
    if (h[a] - l[a] < h[thin] - l[thin]) thin = a;
  const bool planar = (v >> kCountShift) >= 3 && 2 * (h[thin] - l[thin]) <= e[1];
  if (planar) {
    const bool below = v & side_bit(thin, false), above = v & side_bit(thin, true);
    if (above != below) {
      grown = true;
      if (above) l[thin] = 0.0;
      else h[thin] = 1.0;
    }
  }
  for (int a = 0; a < 3; ++a)
    for (int side : {-1, 1}) {
      int n[3] = {c[0], c[1], c[2]};
      n[a] += side;
      if (n[a] < 0 || n[a] > 0xffff) continue;
      const CellKey nk = pack_key(std::uint32_t(n[0]), std::uint32_t(n[1]), std::uint32_t(n[2]));
      // (a plane lying on a face of the cell does not cross it)
      const bool reaches = !(planar && a == thin) && (side < 0 ? l0[a] <= spacing : h0[a] >= 1.0 - spacing);
      double to;  // how far the surface goes on across the face, in cells beyond it
      if ((g.get(nk) & kStateMask) != std::uint8_t(CellState::Free)) {
        to = 0.0;  // into an occupied cell (its own record) or unknown space
      } else if (reaches || S.surface.find(nk)) {
        to = 1.0;  // through a free cell (rays grazing it freed it): lines crossing it there meet it here
      } else {
        continue;  // the surface ends in this cell
      }
      grown = true;
      if (side < 0) l[a] = std::min(l[a], -to);
      else h[a] = std::max(h[a], 1.0 + to);
    }
  grown_box = pack_grown(l0, h0, l, h);
  return grown;
}

}  // namespace

namespace {

// The face neighbours of k inside the key range that `table` holds, appended to `out`.
void push_neighbours(CellKey k, const KeyTable<std::uint64_t>& table, std::vector<CellKey>& out) {
  for (const auto& d : kN6) {
    CellKey nk;
    if (neighbour(k, d[0], d[1], d[2], nk) && table.find(nk)) out.push_back(nk);
  }
}

}  // namespace

void SurfaceExtents::update_grown(const ExplorationState& S, const std::vector<CellChange>& changed) {
  // a cloud records a cell once per run of its points in image order: the distinct cells decide the cost
  std::sort(recorded_.begin(), recorded_.end());
  recorded_.erase(std::unique(recorded_.begin(), recorded_.end()), recorded_.end());
  if (recorded_.size() + changed.size() >= boxes_.size()) {  // (a first insert) every box, at less cost
    KeyTable<std::uint64_t> grown(boxes_.size());
    boxes_.for_each([&](CellKey k, std::uint64_t v) {
      std::uint64_t box;
      if (surface_box(S, k, v, box)) grown.at(k) = box;
    });
    grown_ = std::move(grown);
    recorded_.clear();
    return;
  }
  std::vector<CellKey> dirty;
  for (CellKey k : recorded_) {  // its own box, and a new record beside a recorded cell
    dirty.push_back(k);
    push_neighbours(k, boxes_, dirty);
  }
  for (const CellChange& c : changed)  // a face neighbour that turned free or stopped being free
    if ((c.before == CellState::Free) != (c.after == CellState::Free)) push_neighbours(c.key, boxes_, dirty);
  recorded_.clear();
  std::sort(dirty.begin(), dirty.end());
  dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
  for (CellKey k : dirty) {
    const std::uint64_t* rec = boxes_.find(k);
    std::uint64_t box;
    if (surface_box(S, k, *rec, box)) grown_.at(k) = box;
    else if (std::uint64_t* g = grown_.find(k)) *g = kNotGrown;
  }
}

bool SurfaceExtents::grown_current(const ExplorationState& S) const {
  bool same = true;
  boxes_.for_each([&](CellKey k, std::uint64_t v) {
    std::uint64_t box;
    const bool g = surface_box(S, k, v, box);
    const std::uint64_t* have = grown(k);
    same = same && (g ? have && *have == box : !have);
  });
  return same;
}

bool surface_meets_line(const ExplorationState& S, CellKey k, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const std::uint64_t* rec = S.surface.find(k);
  if (!rec) return true;
  const double res = S.tree.getResolution();
  const Eigen::Vector3d corner = S.center(k) - Eigen::Vector3d::Constant(0.5 * res);
  const auto meets = [&](const double l[3], const double h[3]) {
    Eigen::Vector3d lo, hi;
    for (int a = 0; a < 3; ++a) lo[a] = corner[a] + l[a] * res, hi[a] = corner[a] + h[a] * res;
    return line_meets_box(o, d, lo, hi);
  };
  double l[3], h[3];
  hits_box(*rec, l, h);  // the hits' box alone first: most lines that meet the surface meet it
  if (meets(l, h)) return true;
  const std::uint64_t* g = S.surface.grown(k);
  if (!g) return false;
  unpack_grown(*g, l, h);
  return meets(l, h);
}

}  // namespace octoreach::detail
