// What view scoring reads per cell, flat for one version of the map (score_cells.hpp).
#include "exploration/score_cells.hpp"

#include <algorithm>
#include <mutex>

namespace octoreach::detail {

namespace {

// Directories of more blocks than this (a map whose cells are spread over a huge box) look blocks up by hash.
constexpr std::uint64_t kMaxDirectory = std::uint64_t(1) << 21;

}  // namespace

ScoreCells::ScoreCells(const ExplorationState& S, std::shared_ptr<const EnclosureTable> enclosure)
    : enclosure_(std::move(enclosure)), grid_(&S.grid), hidden_(&S.hidden), state_(&S) {
  KeyTable<Extra*> extra;
  const auto extra_at = [&](CellKey k) -> Extra& {
    Extra*& e = extra.at(StateGrid::block_of(k));
    if (!e) {
      extras_.push_back(std::make_unique<Extra>());
      e = extras_.back().get();
      std::fill(std::begin(e->mark), std::end(e->mark), std::uint8_t(0));
    }
    return *e;
  };
  S.sealed.for_each([&](CellKey k, std::uint8_t) { extra_at(k).mark[StateGrid::offset(k)] |= kSealed; });
  S.blind.for_each_cell([&](CellKey k) { extra_at(k).mark[StateGrid::offset(k)] |= kBlind; });
  if (enclosure_)
    enclosure_->for_each([&](CellKey k, std::uint8_t h) {
      extra_at(k).mark[StateGrid::offset(k)] |= std::uint8_t(kEnclosed | (h & (kExposed | kHalvesMask)));
    });
  // the directory's box: every block of the grid, of the seeability memory and of the extra entries
  std::uint32_t lo[3] = {0xffffffffu, 0xffffffffu, 0xffffffffu}, hi[3] = {0, 0, 0};
  bool any = false;
  const auto grow = [&](CellKey b) {
    const std::uint32_t x[3] = {key_x(b), key_y(b), key_z(b)};
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], x[a]), hi[a] = std::max(hi[a], x[a]);
    any = true;
  };
  S.grid.for_each_block([&](CellKey b, const StateGrid::Block&) { grow(b); });
  S.hidden.for_each_block([&](CellKey b, const HiddenCells::Block&) { grow(b); });
  extra.for_each([&](CellKey b, Extra*) { grow(b); });
  std::uint64_t cells = any ? 1 : 0;
  for (int a = 0; a < 3 && any; ++a) cells *= std::uint64_t(hi[a] - lo[a] + 1);
  if (any && cells <= kMaxDirectory) {
    for (int a = 0; a < 3; ++a) lo_[a] = lo[a], n_[a] = hi[a] - lo[a] + 1;
    dir_.assign(std::size_t(cells), Entry{});
    S.grid.for_each_block([&](CellKey b, const StateGrid::Block& block) {
      dir_[slot(b)].grid = &block;
    });
    S.hidden.for_each_block([&](CellKey b, const HiddenCells::Block& h) { dir_[slot(b)].hidden = &h; });
    extra.for_each([&](CellKey b, Extra* e) {
      dir_[slot(b)].extra = e;
    });
  } else {
    extra.for_each([&](CellKey b, Extra* e) { extra_of_.at(b) = e; });
  }
}

std::size_t ScoreCells::slot(CellKey b) const {
  const std::uint32_t x = key_x(b) - lo_[0], y = key_y(b) - lo_[1], z = key_z(b) - lo_[2];
  if (x >= n_[0] || y >= n_[1] || z >= n_[2]) return kOutside;  // (unsigned: below lo wraps around)
  return std::size_t((std::uint64_t(z) * n_[1] + y) * n_[0] + x);
}

ScoreCells::Entry ScoreCells::entry(CellKey b) const {
  if (n_[0]) {
    const std::size_t i = slot(b);
    return i == kOutside ? Entry{} : dir_[i];
  }
  Entry e;
  e.grid = grid_->find_block(b);
  e.hidden = hidden_->find_block(b);
  if (const Extra* const* x = extra_of_.find(b)) e.extra = *x;
  return e;
}

std::shared_ptr<const ScoreCells> score_cells(const ExplorationState& S, std::shared_ptr<const EnclosureTable> enclosure) {
  std::lock_guard<std::mutex> lock(S.cache_mutex);
  if (S.score_cells && S.score_cells_generation == S.generation && S.score_cells->enclosure() == enclosure.get())
    return S.score_cells;
  S.score_cells = std::make_shared<const ScoreCells>(S, std::move(enclosure));
  S.score_cells_generation = S.generation;
  return S.score_cells;
}

}  // namespace octoreach::detail
