#pragma once
// Internal: the one text form of numbers and vectors in map headers and messages.
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include <Eigen/Core>

namespace octoreach::detail {

/// \brief Shortest round-trip text of a double ("0.05", "1e-09").
inline std::string format_number(double v) {
  std::ostringstream s;
  s << std::setprecision(std::numeric_limits<double>::max_digits10) << v;
  return s.str();
}

/// \brief Entries of a vector separated by `sep`, each with full round-trip precision.
template <class Derived>
std::string format_vector(const Eigen::DenseBase<Derived>& v, const char* sep = " ") {
  std::ostringstream s;
  s << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (Eigen::Index i = 0; i < v.size(); ++i) s << (i ? sep : "") << v(i);
  return s.str();
}

/// \brief "(x, y, z)" with the stream's default precision, for error messages.
inline std::string format_point(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

}  // namespace octoreach::detail
