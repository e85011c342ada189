#include "geardyn/meshio/vtu_writer.hpp"

#include <fmt/format.h>
#include <unistd.h>
#include <zlib.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <stdexcept>

#include "geardyn/core/error.hpp"
#include "geardyn/core/text.hpp"

namespace geardyn::meshio {

int vtk_cell_type(solid::ElementType type) {
  switch (type) {
    case solid::ElementType::Tet4:
      return 10;
    case solid::ElementType::Tet10:
      return 24;
    case solid::ElementType::Hex8:
      return 12;
    case solid::ElementType::Hex20:
      return 25;
    case solid::ElementType::Wedge6:
      return 13;
    case solid::ElementType::Wedge15:
      return 26;
  }
  return 0;
}

const std::vector<int>& vtk_order(solid::ElementType type) {
  // Mid-edge node lists of Gmsh (solid/mesh.hpp) and VTK (header comment) matched edge by edge.
  static const std::vector<int> tet4{0, 1, 2, 3};
  static const std::vector<int> tet10{0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  static const std::vector<int> hex8{0, 1, 2, 3, 4, 5, 6, 7};
  static const std::vector<int> hex20{0,  1, 2,  3,  4,  5,  6,  7,  8,  11,
                                      13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
  static const std::vector<int> wedge6{0, 1, 2, 3, 4, 5};
  static const std::vector<int> wedge15{0, 1, 2, 3, 4, 5, 6, 9, 7, 12, 14, 13, 8, 10, 11};
  switch (type) {
    case solid::ElementType::Tet4:
      return tet4;
    case solid::ElementType::Tet10:
      return tet10;
    case solid::ElementType::Hex8:
      return hex8;
    case solid::ElementType::Hex20:
      return hex20;
    case solid::ElementType::Wedge6:
      return wedge6;
    case solid::ElementType::Wedge15:
      return wedge15;
  }
  return tet4;
}

void check_fields(const solid::Mesh& mesh, const std::vector<Field>& fields) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const Field& f = fields[i];
    const std::string key = fmt::format("fields[{}]", i);
    if (f.name.empty()) throw InputError({}, key + ".name", "a non-empty field name", "''");
    if (!names.insert(f.name).second)
      throw InputError({}, key + ".name", "a unique field name", fmt::format("'{}'", f.name));
    if (f.num_components < 1)
      throw InputError({}, key + ".num_components", ">= 1", fmt::format("{}", f.num_components));
    const std::size_t expected =
        static_cast<std::size_t>(mesh.num_nodes()) * static_cast<std::size_t>(f.num_components);
    if (f.values.size() != expected)
      throw InputError({}, key + ".values",
                       fmt::format("{} values ({} nodes x {} components)", expected,
                                   mesh.num_nodes(), f.num_components),
                       fmt::format("{} values", f.values.size()), "field '" + f.name + "'");
  }
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const solid::Element& element = mesh.elements[e];
    if (static_cast<int>(element.nodes.size()) != solid::num_element_nodes(element.type))
      throw InputError(element.where, fmt::format("mesh.elements[{}]", e),
                       fmt::format("{} nodes for a {}", solid::num_element_nodes(element.type),
                                   solid::to_string(element.type)),
                       fmt::format("{}", element.nodes.size()));
    for (int n : element.nodes)
      if (n < 0 || n >= mesh.num_nodes())
        throw InputError(element.where, fmt::format("mesh.elements[{}].nodes", e),
                         fmt::format("node indices in [0, {})", mesh.num_nodes()),
                         fmt::format("{}", n));
  }
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  const std::filesystem::path temporary =
      path.parent_path() / fmt::format(".{}.tmp-{}", path.filename().string(), ::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(fmt::format("cannot create '{}'", temporary.string()));
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(temporary, ignored);
      throw std::runtime_error(fmt::format("cannot write '{}'", temporary.string()));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(fmt::format("cannot rename '{}' to '{}': {}", temporary.string(),
                                         path.string(), ec.message()));
  }
}

namespace {

static_assert(std::endian::native == std::endian::little,
              "the VTU writer stores arrays in the machine's byte order, declared LittleEndian");

// The appended-data block of a VTU file: arrays one after the other, each zlib-compressed in
// blocks with its header; add() returns the array's offset for its DataArray element.
class AppendedData {
 public:
  template <class T>
  std::size_t add(const std::vector<T>& values) {
    return add_bytes(reinterpret_cast<const unsigned char*>(values.data()),
                     values.size() * sizeof(T));
  }
  const std::string& bytes() const { return data_; }

 private:
  static constexpr std::size_t kBlock = 32768;
  std::size_t add_bytes(const unsigned char* bytes, std::size_t size) {
    const std::size_t offset = data_.size();
    const std::size_t blocks = (size + kBlock - 1) / kBlock;
    // As VTK writes it: the last block's size is 0 when that block is full.
    std::vector<std::uint64_t> header{blocks, kBlock, size % kBlock};
    std::string compressed;
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t n = std::min(kBlock, size - b * kBlock);
      uLongf length = compressBound(static_cast<uLong>(n));
      std::string block(length, '\0');
      if (compress2(reinterpret_cast<Bytef*>(block.data()), &length, bytes + b * kBlock,
                    static_cast<uLong>(n), Z_DEFAULT_COMPRESSION) != Z_OK)
        throw std::runtime_error("VTU output: zlib compression failed");
      header.push_back(length);
      compressed.append(block.data(), length);
    }
    data_.append(reinterpret_cast<const char*>(header.data()),
                 header.size() * sizeof(std::uint64_t));
    data_ += compressed;
    return offset;
  }
  std::string data_;
};

template <class T>
void data_array(fmt::memory_buffer& b, AppendedData& appended, const char* type,
                const std::string& name, int components, const std::vector<T>& values) {
  fmt::format_to(std::back_inserter(b),
                 "<DataArray type=\"{}\"{}{} format=\"appended\" offset=\"{}\"/>\n", type,
                 name.empty() ? "" : fmt::format(" Name=\"{}\"", escape_xml(name)),
                 components > 1 ? fmt::format(" NumberOfComponents=\"{}\"", components) : "",
                 appended.add(values));
}

std::string vtu_text(const solid::Mesh& mesh, const std::vector<Field>& fields) {
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  AppendedData appended;
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
                 "<UnstructuredGrid>\n"
                 "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 mesh.num_nodes(), mesh.num_elements());

  fmt::format_to(out, "<PointData>\n");
  for (const Field& f : fields)
    data_array(b, appended, "Float64", f.name, f.num_components, f.values);
  std::vector<std::int64_t> node_id(static_cast<std::size_t>(mesh.num_nodes()));
  for (int i = 0; i < mesh.num_nodes(); ++i)
    node_id[static_cast<std::size_t>(i)] = i < static_cast<int>(mesh.node_ids.size())
                                               ? mesh.node_ids[static_cast<std::size_t>(i)]
                                               : i + 1L;
  data_array(b, appended, "Int64", "node_id", 1, node_id);
  fmt::format_to(out, "</PointData>\n<CellData>\n");
  std::vector<std::int32_t> material;
  std::vector<std::int64_t> element_id, connectivity, offsets;
  std::vector<std::uint8_t> types;
  for (const solid::Element& e : mesh.elements) {
    material.push_back(e.material);
    element_id.push_back(e.id);
    for (int k : vtk_order(e.type)) connectivity.push_back(e.nodes[static_cast<std::size_t>(k)]);
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    types.push_back(static_cast<std::uint8_t>(vtk_cell_type(e.type)));
  }
  data_array(b, appended, "Int32", "material", 1, material);
  data_array(b, appended, "Int64", "element_id", 1, element_id);
  fmt::format_to(out, "</CellData>\n<Points>\n");
  std::vector<double> points;
  points.reserve(3 * mesh.coords.size());
  for (const Eigen::Vector3d& x : mesh.coords) points.insert(points.end(), {x.x(), x.y(), x.z()});
  data_array(b, appended, "Float64", "", 3, points);
  fmt::format_to(out, "</Points>\n<Cells>\n");
  data_array(b, appended, "Int64", "connectivity", 1, connectivity);
  data_array(b, appended, "Int64", "offsets", 1, offsets);
  data_array(b, appended, "UInt8", "types", 1, types);
  fmt::format_to(out,
                 "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");
  std::string text = fmt::to_string(b);
  text += appended.bytes();
  text += "\n</AppendedData>\n</VTKFile>\n";
  return text;
}

// Checks a list of fields against `count` entities (points or cells); `what` names them.
void check_field_sizes(const std::vector<Field>& fields, std::size_t count, const char* what,
                       const char* key) {
  std::set<std::string> names;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const Field& f = fields[i];
    const std::string where = fmt::format("{}[{}]", key, i);
    if (f.name.empty()) throw InputError({}, where + ".name", "a non-empty field name", "''");
    if (!names.insert(f.name).second)
      throw InputError({}, where + ".name", "a unique field name", fmt::format("'{}'", f.name));
    if (f.num_components < 1)
      throw InputError({}, where + ".num_components", ">= 1", fmt::format("{}", f.num_components));
    const std::size_t expected = count * static_cast<std::size_t>(f.num_components);
    if (f.values.size() != expected)
      throw InputError(
          {}, where + ".values",
          fmt::format("{} values ({} {} x {} components)", expected, count, what, f.num_components),
          fmt::format("{} values", f.values.size()), "field '" + f.name + "'");
  }
}

void check_surface(const solid::Mesh& mesh, const SurfaceCells& s) {
  for (std::size_t i = 0; i < s.points.size(); ++i)
    if (s.points[i] < 0 || s.points[i] >= mesh.num_nodes())
      throw InputError({}, fmt::format("points[{}]", i),
                       fmt::format("a node index in [0, {})", mesh.num_nodes()),
                       fmt::format("{}", s.points[i]));
  for (std::size_t c = 0; c < s.cells.size(); ++c) {
    const std::size_t n = s.cells[c].size();
    if (n != 3 && n != 4 && n != 6 && n != 8)
      throw InputError({}, fmt::format("cells[{}]", c), "3, 4, 6 or 8 nodes", fmt::format("{}", n));
    for (int k : s.cells[c])
      if (k < 0 || static_cast<std::size_t>(k) >= s.points.size())
        throw InputError({}, fmt::format("cells[{}]", c),
                         fmt::format("point indices in [0, {})", s.points.size()),
                         fmt::format("{}", k));
  }
  if (!s.cell_ids.empty() && s.cell_ids.size() != s.cells.size())
    throw InputError({}, "cell_ids", fmt::format("{} ids (one per cell) or none", s.cells.size()),
                     fmt::format("{}", s.cell_ids.size()));
}

std::string surface_vtu_text(const solid::Mesh& mesh, const SurfaceCells& s,
                             const std::vector<Field>& cell_fields,
                             const std::vector<Field>& point_fields) {
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  AppendedData appended;
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
                 "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\">\n"
                 "<UnstructuredGrid>\n"
                 "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">\n",
                 s.points.size(), s.cells.size());
  fmt::format_to(out, "<PointData>\n");
  for (const Field& f : point_fields)
    data_array(b, appended, "Float64", f.name, f.num_components, f.values);
  std::vector<std::int64_t> node_id;
  for (int n : s.points)
    node_id.push_back(n < static_cast<int>(mesh.node_ids.size())
                          ? mesh.node_ids[static_cast<std::size_t>(n)]
                          : n + 1L);
  data_array(b, appended, "Int64", "node_id", 1, node_id);
  fmt::format_to(out, "</PointData>\n<CellData>\n");
  for (const Field& f : cell_fields)
    data_array(b, appended, "Float64", f.name, f.num_components, f.values);
  if (!s.cell_ids.empty()) {
    const std::vector<std::int64_t> ids(s.cell_ids.begin(), s.cell_ids.end());
    data_array(b, appended, "Int64", "element_id", 1, ids);
  }
  fmt::format_to(out, "</CellData>\n<Points>\n");
  std::vector<double> points;
  points.reserve(3 * s.points.size());
  for (int n : s.points) {
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(n)];
    points.insert(points.end(), {x.x(), x.y(), x.z()});
  }
  data_array(b, appended, "Float64", "", 3, points);
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  for (const std::vector<int>& cell : s.cells) {
    connectivity.insert(connectivity.end(), cell.begin(), cell.end());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    // VTK_TRIANGLE 5, VTK_QUAD 9, VTK_QUADRATIC_TRIANGLE 22, VTK_QUADRATIC_QUAD 23.
    types.push_back(cell.size() == 3 ? 5 : cell.size() == 4 ? 9 : cell.size() == 6 ? 22 : 23);
  }
  fmt::format_to(out, "</Points>\n<Cells>\n");
  data_array(b, appended, "Int64", "connectivity", 1, connectivity);
  data_array(b, appended, "Int64", "offsets", 1, offsets);
  data_array(b, appended, "UInt8", "types", 1, types);
  fmt::format_to(out,
                 "</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_");
  std::string text = fmt::to_string(b);
  text += appended.bytes();
  text += "\n</AppendedData>\n</VTKFile>\n";
  return text;
}

}  // namespace

void write_surface_vtu(const std::filesystem::path& path, const solid::Mesh& mesh,
                       const SurfaceCells& cells, const std::vector<Field>& cell_fields,
                       const std::vector<Field>& point_fields) {
  check_surface(mesh, cells);
  check_field_sizes(cell_fields, cells.cells.size(), "cells", "cell_fields");
  check_field_sizes(point_fields, cells.points.size(), "points", "point_fields");
  write_file_atomically(path, surface_vtu_text(mesh, cells, cell_fields, point_fields));
}

void write_vtu(const std::filesystem::path& path, const solid::Mesh& mesh,
               const std::vector<Field>& fields) {
  check_fields(mesh, fields);
  write_file_atomically(path, vtu_text(mesh, fields));
}

std::vector<std::filesystem::path> write_vtu_series(const std::filesystem::path& pvd_path,
                                                    const solid::Mesh& mesh,
                                                    const std::vector<std::vector<Field>>& states,
                                                    const std::vector<double>& times) {
  if (times.size() != states.size())
    throw InputError({}, "times", fmt::format("one time per state ({})", states.size()),
                     fmt::format("{}", times.size()));
  for (const std::vector<Field>& fields : states) check_fields(mesh, fields);
  const std::string stem = pvd_path.stem().string();
  const int digits =
      static_cast<int>(fmt::format("{}", states.empty() ? 0 : states.size() - 1).size());
  std::vector<std::filesystem::path> written;
  fmt::memory_buffer b;
  auto out = std::back_inserter(b);
  fmt::format_to(out,
                 "<?xml version=\"1.0\"?>\n"
                 "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
                 "<Collection>\n");
  for (std::size_t k = 0; k < states.size(); ++k) {
    const std::string name = fmt::format("{}_{:0{}}.vtu", stem, k, digits);
    const std::filesystem::path file = pvd_path.parent_path() / name;
    write_file_atomically(file, vtu_text(mesh, states[k]));
    written.push_back(file);
    fmt::format_to(out, "<DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n", times[k],
                   escape_xml(name));
  }
  fmt::format_to(out, "</Collection>\n</VTKFile>\n");
  write_file_atomically(pvd_path, fmt::to_string(b));
  return written;
}

}  // namespace geardyn::meshio
