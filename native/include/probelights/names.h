// The words of every option: one table per enum, shared by the CLI, the Python module and the JSON, so every
// shell parses, prints and refuses a word the same way ("unknown method 'x': use median-cut, variance or
// sh"). A table lists each value's canonical word first; later rows for the same value are accepted aliases.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "probelights/error.h"

namespace probelights {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<E, std::string_view>, N>;

// Words as a list: "a, b or c".
inline std::string listOf(const std::vector<std::string>& words) {
  std::string out;
  for (std::size_t i = 0; i < words.size(); ++i)
    out += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return out;
}

// The canonical words, "a, b or c".
template <class E, std::size_t N>
std::string choicesOf(const NameTable<E, N>& table) {
  std::vector<std::string> words;
  for (std::size_t i = 0; i < N; ++i)
    if (i == 0 || table[i].first != table[i - 1].first) words.emplace_back(table[i].second);
  return listOf(words);
}

template <class E, std::size_t N>
E parseName(const NameTable<E, N>& table, std::string_view what, std::string_view word) {
  for (const auto& [value, name] : table)
    if (name == word) return value;
  throw Error("unknown " + std::string(what) + " '" + std::string(word) + "': use " + choicesOf(table));
}

template <class E, std::size_t N>
std::string nameOf(const NameTable<E, N>& table, E value) {
  for (const auto& [v, name] : table)
    if (v == value) return std::string(name);
  return "?";
}

}  // namespace probelights
