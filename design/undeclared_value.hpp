#pragma once
// What a stage's view of the design (design_view.hpp) holds for a value the stage did not declare:
// not the default, which passes for a setting, but a value that makes a use fail or show.
//   double, and each component of a vector or point: NaN. It spreads through whatever is computed
//     from it, and every output refuses it (json_file.hpp, the STL and VTU writers), so a stage that
//     writes what it computed fails. A NaN that only steers (`if (x > 0)`, std::max) acts as false
//     there: such a read passes unseen.
//   int and enum: kUndeclaredInt, below every key's range. As a size it throws (std::length_error), as
//     a count of a loop it runs none; an enum compared against its values matches none of them, and
//     has no name (choice_name gives "?").
//   string and path: undeclared_text(key), "<undeclared design.name>": a path that opens no file, a
//     name that no lookup finds and that shows in every output that writes it.
//   optional: engaged, holding the above (an absent optional means "auto", which would pass).
//   array section ([[fiber]], [[target]], ...) and list: one element, every member of it undeclared
//     (two points for a polyline), so that a loop over it meets NaN and the undeclared name instead of
//     doing nothing, as it would over an empty one.
//   bool: left at its default; no bool fails.

#include <array>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "design/design.hpp"

namespace fibermold {

/// The int or enum of an undeclared key: below the range of every int key of the design file.
inline constexpr int kUndeclaredInt = std::numeric_limits<int>::min();

/// The text of an undeclared string or path: "<undeclared design.name>".
std::string undeclared_text(std::string_view key);

void make_undeclared(double& v, std::string_view key);
void make_undeclared(int& v, std::string_view key);
void make_undeclared(bool& v, std::string_view key); ///< leaves it: no bool fails
void make_undeclared(std::string& v, std::string_view key);
void make_undeclared(std::filesystem::path& v, std::string_view key);
void make_undeclared(Eigen::Vector3d& v, std::string_view key);

void make_undeclared(TwoPieceLine& v, std::string_view key);
void make_undeclared(PartingPlane& v, std::string_view key);
void make_undeclared(Region& v, std::string_view key);
void make_undeclared(FixedRegion& v, std::string_view key);
void make_undeclared(Fiber& v, std::string_view key);
void make_undeclared(TrackingCurve& v, std::string_view key);
void make_undeclared(Load& v, std::string_view key);
void make_undeclared(FiberActuation& v, std::string_view key);
void make_undeclared(Pose& v, std::string_view key);
void make_undeclared(Target& v, std::string_view key);

template <typename E>
requires std::is_enum_v<E>
void make_undeclared(E& v, std::string_view) { v = static_cast<E>(kUndeclaredInt); }

template <typename T> void make_undeclared(std::optional<T>& v, std::string_view key);
template <typename T, std::size_t N> void make_undeclared(std::array<T, N>& v, std::string_view key);
template <typename T> void make_undeclared(std::vector<T>& v, std::string_view key);

template <typename T> void make_undeclared(std::optional<T>& v, std::string_view key)
{
  make_undeclared(v.emplace(), key);
}

template <typename T, std::size_t N> void make_undeclared(std::array<T, N>& v, std::string_view key)
{
  for (T& x : v) make_undeclared(x, key);
}

template <typename T> void make_undeclared(std::vector<T>& v, std::string_view key)
{
  v.assign(1, T{});
  make_undeclared(v.front(), key);
}

} // namespace fibermold
