// 26-connected components of a set of cells.
#include "exploration/cell_sets.hpp"

namespace octoreach::detail {

const N26 kN26;

std::vector<std::vector<CellKey>> components26(std::vector<CellKey> cells) {
  std::sort(cells.begin(), cells.end());
  KeyTable<int> pos(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) pos.at(cells[i]) = int(i);
  UnionFind uf(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (int o = 13; o < 26; ++o) {
      const auto& d = kN26.d[o];
      CellKey n;
      if (!neighbour(cells[i], d[0], d[1], d[2], n)) continue;
      if (const int* j = pos.find(n)) uf.unite(int(i), *j);
    }
  std::vector<int> root_to_comp(cells.size(), -1);
  std::vector<std::vector<CellKey>> out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    int r = uf.find(int(i));
    if (root_to_comp[r] < 0) {
      root_to_comp[r] = int(out.size());
      out.emplace_back();
    }
    out[root_to_comp[r]].push_back(cells[i]);
  }
  return out;  // cells were sorted, so each component is sorted and components are ordered by first cell
}

}  // namespace octoreach::detail
