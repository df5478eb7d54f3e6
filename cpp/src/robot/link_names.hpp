#pragma once
// Internal: reading what a link's or joint's name says (arm discovery, the camera link): lower case and the
// name's words.
#include <set>
#include <string>

namespace octoreach::detail {

/// `s` in lower case (ASCII).
inline std::string lowercase(std::string s) {
  for (char& c : s) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return s;
}

/// A name's words: lower case, split at anything that is not a letter ("head_2_link" -> head, link).
inline std::set<std::string> name_tokens(const std::string& name) {
  std::set<std::string> out;
  std::string cur;
  for (char c : lowercase(name) + " ") {
    if (c >= 'a' && c <= 'z') cur += c;
    else if (!cur.empty()) out.insert(cur), cur.clear();
  }
  return out;
}

}  // namespace octoreach::detail
