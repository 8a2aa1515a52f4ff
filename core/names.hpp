#pragma once
// The names of a choice (an enum class) as the design file and the reports spell them: one table
// per choice, beside the enum, read by the design file and written by the reports.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fibermold {

template <typename E> struct Named {
  E value;
  std::string_view name;
};

/// The name of `value` in `names`.
template <typename E, std::size_t N> constexpr std::string_view name_in(const std::array<Named<E>, N>& names, E value)
{
  for (const Named<E>& n : names)
    if (n.value == value) return n.name;
  return "?";
}

/// The value named `name`, or nothing.
template <typename E, std::size_t N>
constexpr std::optional<E> value_in(const std::array<Named<E>, N>& names, std::string_view name)
{
  for (const Named<E>& n : names)
    if (n.name == name) return n.value;
  return std::nullopt;
}

/// Every name, in order: what the design file allows.
template <typename E, std::size_t N> std::vector<std::string> names_of(const std::array<Named<E>, N>& names)
{
  std::vector<std::string> out;
  for (const Named<E>& n : names) out.emplace_back(n.name);
  return out;
}

} // namespace fibermold
