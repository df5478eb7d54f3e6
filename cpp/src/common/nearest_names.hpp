#pragma once
// Internal: "did you mean" for names (links, joints, arms, groups): the candidates closest to a
// name by edit distance, for error messages.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace octoreach::detail {

/// \brief Levenshtein distance of two strings, ignoring case.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  auto low = [](char c) { return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c); };
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (low(a[i - 1]) == low(b[j - 1]) ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// \brief "; did you mean 'a', 'b' or 'c'?" with the `k` candidates nearest to `name` (names that
/// contain it or are contained in it first), or "" when there are none.
inline std::string did_you_mean(const std::string& name, const std::vector<std::string>& candidates, std::size_t k = 3) {
  std::vector<std::pair<std::size_t, std::string>> scored;
  for (const std::string& c : candidates) {
    std::size_t d = edit_distance(name, c);
    if (!name.empty() && (c.find(name) != std::string::npos || name.find(c) != std::string::npos)) d = d / 4;
    scored.emplace_back(d, c);
  }
  std::sort(scored.begin(), scored.end());
  std::string out;
  for (std::size_t i = 0; i < scored.size() && i < k; ++i)
    out += (i == 0 ? "" : i + 1 == std::min(k, scored.size()) ? " or " : ", ") + ("'" + scored[i].second + "'");
  return out.empty() ? "" : "; did you mean " + out + "?";
}

}  // namespace octoreach::detail
