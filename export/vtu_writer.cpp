#include "export/vtu_writer.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/units.hpp"

namespace fibermold {

namespace {

void append_array(std::string& out, const std::string& attributes, const Eigen::MatrixXd& values)
{
  out += fmt::format("        <DataArray type=\"Float64\" {} NumberOfComponents=\"{}\" format=\"ascii\">\n", attributes,
                     values.cols());
  for (Eigen::Index i = 0; i < values.rows(); ++i) {
    out += "         ";
    for (Eigen::Index j = 0; j < values.cols(); ++j) out += fmt::format(" {:.10g}", values(i, j));
    out += "\n";
  }
  out += "        </DataArray>\n";
}

template <typename T>
void append_ints(std::string& out, const std::string& type, const std::string& name, const std::vector<T>& values)
{
  out += fmt::format("        <DataArray type=\"{}\" Name=\"{}\" format=\"ascii\">\n         ", type, name);
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += fmt::format(" {}", +values[i]);
    if (i % 16 == 15) out += "\n         ";
  }
  out += "\n        </DataArray>\n";
}

void append_fields(std::string& out, const char* tag, const std::vector<VtuField>& fields)
{
  if (fields.empty()) return;
  out += fmt::format("      <{}>\n", tag);
  for (const VtuField& f : fields) append_array(out, fmt::format("Name=\"{}\"", f.name), f.values);
  out += fmt::format("      </{}>\n", tag);
}

} // namespace

void VtuGrid::add_cells(const Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>& cells, VtkCell type)
{
  for (Eigen::Index c = 0; c < cells.rows(); ++c) {
    for (Eigen::Index k = 0; k < cells.cols(); ++k) connectivity_.push_back(cells(c, k));
    offsets_.push_back(static_cast<std::int64_t>(connectivity_.size()));
    types_.push_back(static_cast<std::uint8_t>(type));
  }
}

void VtuGrid::add_cell(const std::vector<int>& nodes, VtkCell type)
{
  connectivity_.insert(connectivity_.end(), nodes.begin(), nodes.end());
  offsets_.push_back(static_cast<std::int64_t>(connectivity_.size()));
  types_.push_back(static_cast<std::uint8_t>(type));
}

void VtuGrid::add_point_field(std::string name, Eigen::MatrixXd values)
{
  point_fields_.push_back({std::move(name), std::move(values)});
}

void VtuGrid::add_cell_field(std::string name, Eigen::MatrixXd values)
{
  cell_fields_.push_back({std::move(name), std::move(values)});
}

void VtuGrid::write(const std::filesystem::path& path) const
{
  for (const VtuField& f : point_fields_)
    if (f.values.rows() != points_.rows())
      throw std::invalid_argument(
          fmt::format("point field {} has {} rows for {} points", f.name, f.values.rows(), points_.rows()));
  for (const VtuField& f : cell_fields_)
    if (f.values.rows() != num_cells())
      throw std::invalid_argument(
          fmt::format("cell field {} has {} rows for {} cells", f.name, f.values.rows(), num_cells()));
  // No NaN or infinity in an output (docs/pipeline.md, "Exit codes"): ParaView would draw nothing, or garbage.
  if (!points_.allFinite())
    throw std::runtime_error(fmt::format("{}: a point is not finite; nothing was written", path.filename().string()));
  for (const auto* fields : {&point_fields_, &cell_fields_})
    for (const VtuField& f : *fields)
      if (!f.values.allFinite())
        throw std::runtime_error(fmt::format("{}: field {} is not finite everywhere; nothing was written",
                                             path.filename().string(), f.name));

  std::string out = "<?xml version=\"1.0\"?>\n"
                    "<!-- fibermold: lengths in mm -->\n"
                    "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                    "header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  out += fmt::format("    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n", points_.rows(), num_cells());
  append_fields(out, "PointData", point_fields_);
  append_fields(out, "CellData", cell_fields_);
  out += "      <Points>\n";
  append_array(out, "Name=\"Points\"", points_ / units::mm);
  out += "      </Points>\n      <Cells>\n";
  append_ints(out, "Int64", "connectivity", connectivity_);
  append_ints(out, "Int64", "offsets", offsets_);
  append_ints(out, "UInt8", "types", types_);
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  write_file_atomic(path, out);
}

} // namespace fibermold
