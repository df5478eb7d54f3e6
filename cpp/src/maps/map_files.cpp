#include "octoreach/map_files.hpp"

#include <optional>
#include <utility>

#include "maps/map_io.hpp"

namespace octoreach {
namespace {

constexpr std::size_t kKinds = std::variant_size_v<AnyMap>;

template <std::size_t I = 0>
void add_kinds(std::vector<MapKind>& out) {
  if constexpr (I < kKinds) {
    using Map = std::variant_alternative_t<I, AnyMap>;
    out.push_back({Map::kKind, Map::kExtension, static_cast<int>(Map::kFormatVersion)});
    add_kinds<I + 1>(out);
  }
}

std::string kind_list() {
  std::string text;
  const std::vector<MapKind> kinds = map_kinds();
  for (std::size_t i = 0; i < kinds.size(); ++i)
    text += (i == 0 ? "" : i + 1 == kinds.size() ? " and " : ", ") + kinds[i].tag;
  return text;
}

// The map of kind `tag` loaded from `path`; false when no kind of the registry has that tag.
template <std::size_t I = 0>
bool load_kind(const std::string& tag, const std::string& path, std::optional<AnyMap>& out) {
  if constexpr (I < kKinds) {
    using Map = std::variant_alternative_t<I, AnyMap>;
    if (tag != Map::kKind) return load_kind<I + 1>(tag, path, out);
    out.emplace(std::in_place_index<I>, Map::load(path));
    return true;
  } else {
    return false;
  }
}

}  // namespace

std::vector<MapKind> map_kinds() {
  std::vector<MapKind> kinds;
  add_kinds(kinds);
  return kinds;
}

std::string map_kind(const std::string& path) { return detail::read_map_kind(path); }

AnyMap load_any(const std::string& path, const std::string& expected) {
  std::optional<AnyMap> map;
  if (!expected.empty()) {
    // The loader of the expected kind checks the file's kind itself.
    if (!load_kind(expected, path, map))
      throw std::invalid_argument("unknown map kind '" + expected + "' (the kinds are " + kind_list() + ")");
    return std::move(*map);
  }
  const std::string tag = map_kind(path);
  if (!load_kind(tag, path, map))
    throw FileError("'" + path + "' holds a " + tag + " map, a kind this octoreach does not read (it reads " +
                    kind_list() + " maps)");
  return std::move(*map);
}

const char* kind_of(const AnyMap& map) {
  return std::visit([](const auto& m) { return std::decay_t<decltype(m)>::kKind; }, map);
}

const MapProvenance& provenance_of(const AnyMap& map) {
  return std::visit([](const auto& m) -> const MapProvenance& { return m.provenance(); }, map);
}

}  // namespace octoreach
