#include "maps/cell_slots.hpp"

#include <algorithm>

namespace octoreach::detail {

CellSlots::CellSlots(const CapabilityMap& cap, const std::vector<char>& wanted, double za_lo, double za_hi)
    : orientations_(cap.orientations().size()) {
  std::vector<Eigen::Vector3d> cc;
  std::vector<double> cv;
  cap.voxels(cc, cv);
  for (const auto& c : cc) {
    if (c.z() < za_lo - cap.resolution() || c.z() > za_hi + cap.resolution()) continue;
    Eigen::Vector3d centre;
    const std::int64_t rec = cap.record_at(c, &centre);
    if (rec < 0) continue;
    const auto r = static_cast<std::uint32_t>(rec);
    if (r >= local_.size()) local_.resize(static_cast<std::size_t>(r) + 1, -1);
    if (local_[r] >= 0) continue;  // a record met twice (cannot happen for distinct voxels; be safe)
    local_[r] = static_cast<std::int32_t>(records_.size());
    Record R{r, centre, static_cast<std::uint32_t>(cells_.size()), 0};
    table_.resize(table_.size() + orientations_, kNone);
    std::int32_t* row = table_.data() + static_cast<std::size_t>(local_[r]) * orientations_;
    for (int o = 0; o < orientations_; ++o)
      if (wanted[o] && cap.record_has(r, o)) {
        row[o] = static_cast<std::int32_t>(cells_.size());
        cells_.push_back({r, o});
      }
    R.last = static_cast<std::uint32_t>(cells_.size());
    records_.push_back(R);
  }
}

}  // namespace octoreach::detail
