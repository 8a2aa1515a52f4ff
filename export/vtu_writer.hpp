#pragma once
// VTK XML unstructured grids (.vtu) that ParaView opens: points in millimetres, any mix of cells,
// named point and cell fields.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace fibermold {

/// VTK cell type ids used here.
enum class VtkCell : std::uint8_t { line = 3, poly_line = 4, triangle = 5, tetra = 10, quadratic_tetra = 24 };

struct VtuField {
  std::string name;
  Eigen::MatrixXd values; ///< one row per point (or cell), one column per component
};

class VtuGrid {
public:
  /// Points in metres; written in millimetres.
  explicit VtuGrid(Eigen::MatrixX3d points) : points_(std::move(points)) {}

  /// Adds one cell per row of `cells` (indices into the points).
  void add_cells(const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>& cells, VtkCell type);
  void add_cell(const std::vector<int>& nodes, VtkCell type);
  void add_point_field(std::string name, Eigen::MatrixXd values);
  void add_cell_field(std::string name, Eigen::MatrixXd values);

  Eigen::Index num_cells() const { return static_cast<Eigen::Index>(types_.size()); }

  /// Writes atomically; throws std::runtime_error naming the path, std::invalid_argument when a
  /// field's row count does not match.
  void write(const std::filesystem::path& path) const;

private:
  Eigen::MatrixX3d points_;
  std::vector<std::int64_t> connectivity_, offsets_;
  std::vector<std::uint8_t> types_;
  std::vector<VtuField> point_fields_, cell_fields_;
};

} // namespace fibermold
