// Tests of the VTU and Gmsh-view writers (meshio/vtu_writer.hpp, meshio/gmsh_view_writer.hpp).
//
// A hand-built mesh holds one straight-sided element of each type (tet4, tet10, hex8, hex20,
// wedge6, wedge15; Gmsh node order of solid/mesh.hpp). The VTU is read back (its compressed
// binary arrays decoded by the test itself) and its cells are checked against the VTK
// documentation's node order (vtkQuadraticTetra, vtkQuadraticHexahedron, vtkQuadraticWedge class
// docs): every VTK mid-edge node must be the midpoint of the corners of the edge VTK lists for it,
// and the corners must be oriented as VTK's parametric coordinates are. The .msh is read back by
// Gmsh itself (gmsh::open) and its views compared value by value.
#include <fmt/format.h>
#include <gmsh.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "geardyn/meshgen/gmsh_session.hpp"
#include "geardyn/meshio/gmsh_view_writer.hpp"
#include "geardyn/meshio/vtu_writer.hpp"
#include "meshgen/mesh_checks.hpp"

namespace geardyn::meshio {
namespace {

namespace fs = std::filesystem;
using solid::ElementType;

/// Adds an element of `type` with corners `corners` (Gmsh order) and straight mid-edge nodes.
void add_element(solid::Mesh& mesh, ElementType type, const std::vector<Eigen::Vector3d>& corners,
                 int material) {
  solid::Element e;
  e.type = type;
  e.material = material;
  e.id = 100 + mesh.num_elements();
  std::vector<Eigen::Vector3d> points = corners;
  for (const auto& [a, b] : test::mid_edges(type))
    points.push_back(0.5 * (corners[a] + corners[b]));
  for (const Eigen::Vector3d& x : points) {
    e.nodes.push_back(mesh.num_nodes());
    mesh.coords.push_back(x);
    mesh.node_ids.push_back(1000 + mesh.num_nodes());
  }
  mesh.elements.push_back(e);
}

solid::Mesh all_types_mesh() {
  solid::Mesh mesh;
  mesh.materials = {{"steel", 1, 210e9, 0.3, 7850, {}}, {"bronze", 2, 110e9, 0.34, 8800, {}}};
  const std::vector<Eigen::Vector3d> tet{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<Eigen::Vector3d> hex{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<Eigen::Vector3d> wedge{{0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                           {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  // Distinct, slightly skewed positions so that no two elements share coordinates.
  auto moved = [](std::vector<Eigen::Vector3d> x, double dx) {
    for (Eigen::Vector3d& p : x) p += Eigen::Vector3d(dx + 0.1 * p.z(), 0.05 * p.x(), 0.0);
    return x;
  };
  add_element(mesh, ElementType::Tet4, moved(tet, 0), 0);
  add_element(mesh, ElementType::Tet10, moved(tet, 2), 0);
  add_element(mesh, ElementType::Hex8, moved(hex, 4), 1);
  add_element(mesh, ElementType::Hex20, moved(hex, 6), 1);
  add_element(mesh, ElementType::Wedge6, moved(wedge, 8), 0);
  add_element(mesh, ElementType::Wedge15, moved(wedge, 10), 1);
  return mesh;
}

std::vector<Field> test_fields(const solid::Mesh& mesh) {
  Field re{"mode_1_re", 3, {}}, mag{"amplitude", 1, {}};
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    const Eigen::Vector3d& x = mesh.coords[static_cast<std::size_t>(i)];
    re.values.insert(re.values.end(), {x.x() * 0.1, -x.y() / 3.0, 1e-7 * (i + 1)});
    mag.values.push_back(std::sqrt(1.0 + i));
  }
  return {re, mag};
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The attribute `name` of the XML tag starting at `tag` ("" when absent).
std::string attribute(const std::string& xml, std::size_t tag, const std::string& name) {
  const std::size_t end = xml.find('>', tag);
  const std::size_t at = xml.find(" " + name + "=\"", tag);
  if (at == std::string::npos || at > end) return "";
  const std::size_t begin = at + name.size() + 3;
  return xml.substr(begin, xml.find('"', begin) - begin);
}

/// Numbers of the DataArray whose opening tag contains `marker`, decoded from the appended
/// data as the VTK XML format defines it (independently of the writer): header_type UInt64,
/// vtkZLibDataCompressor header [blocks, block size, last block size, compressed sizes...],
/// then the zlib blocks, little-endian values of the array's type.
std::vector<double> data_array(const std::string& xml, const std::string& marker) {
  std::size_t at = xml.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  if (at == std::string::npos) return {};
  at = marker.front() == '<' ? xml.find("<DataArray", at)  // a section: its first array
                             : xml.rfind("<DataArray", at);
  EXPECT_EQ(attribute(xml, at, "format"), "appended");
  const std::string type = attribute(xml, at, "type");
  const std::size_t offset = std::stoul(attribute(xml, at, "offset"));
  const std::size_t base = xml.find('_', xml.find("<AppendedData encoding=\"raw\">")) + 1;
  const unsigned char* p = reinterpret_cast<const unsigned char*>(xml.data()) + base + offset;
  auto u64 = [&](std::size_t k) {
    std::uint64_t v = 0;
    std::memcpy(&v, p + 8 * k, 8);
    return static_cast<std::size_t>(v);
  };
  const std::size_t blocks = u64(0), block = u64(1), last = u64(2);
  std::string raw;
  std::size_t position = 8 * (3 + blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    uLongf size = static_cast<uLongf>(b + 1 == blocks && last != 0 ? last : block);
    std::string chunk(size, '\0');
    EXPECT_EQ(uncompress(reinterpret_cast<Bytef*>(chunk.data()), &size, p + position,
                         static_cast<uLong>(u64(3 + b))),
              Z_OK);
    raw += chunk;
    position += u64(3 + b);
  }
  std::vector<double> out;
  auto read = [&](auto zero) {
    for (std::size_t i = 0; i + sizeof(zero) <= raw.size(); i += sizeof(zero)) {
      decltype(zero) v;
      std::memcpy(&v, raw.data() + i, sizeof(v));
      out.push_back(static_cast<double>(v));
    }
  };
  if (type == "Float64")
    read(double{});
  else if (type == "Int64")
    read(std::int64_t{});
  else if (type == "Int32")
    read(std::int32_t{});
  else if (type == "UInt8")
    read(std::uint8_t{});
  else
    ADD_FAILURE() << "unexpected type " << type;
  return out;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "test_scratch" / "meshio_writers";
  fs::create_directories(dir);
  return dir / name;
}

// VTK node order, typed from the VTK class documentation: mid-edge node k of the quadratic cell
// lies on the listed corner pair.
std::vector<std::pair<int, int>> vtk_mid_edges(int vtk_type) {
  switch (vtk_type) {
    case 24:
      return {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
    case 25:
      return {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
              {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    case 26:
      return {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
    default:
      return {};
  }
}

TEST(VtuWriter, CellsFollowTheVtkNodeOrder) {
  const solid::Mesh mesh = all_types_mesh();
  const std::vector<Field> fields = test_fields(mesh);
  const fs::path path = scratch("all_types.vtu");
  write_vtu(path, mesh, fields);
  const std::string xml = read_text(path);
  EXPECT_NE(xml.find("NumberOfPoints=\"" + std::to_string(mesh.num_nodes()) + "\""),
            std::string::npos);
  EXPECT_NE(xml.find("NumberOfCells=\"6\""), std::string::npos);

  const std::vector<double> points = data_array(xml, "<Points>");
  const std::vector<double> connectivity = data_array(xml, "Name=\"connectivity\"");
  const std::vector<double> offsets = data_array(xml, "Name=\"offsets\"");
  const std::vector<double> types = data_array(xml, "Name=\"types\"");
  ASSERT_EQ(points.size(), 3u * static_cast<std::size_t>(mesh.num_nodes()));
  EXPECT_EQ(types, (std::vector<double>{10, 24, 12, 25, 13, 26}));
  EXPECT_EQ(offsets, (std::vector<double>{4, 14, 22, 42, 48, 63}));
  ASSERT_EQ(connectivity.size(), 63u);
  auto point = [&](double index) {
    const std::size_t i = static_cast<std::size_t>(index);
    return Eigen::Vector3d(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
  };
  std::size_t start = 0;
  for (std::size_t c = 0; c < types.size(); ++c) {
    const int type = static_cast<int>(types[c]);
    const std::size_t end = static_cast<std::size_t>(offsets[c]);
    std::vector<Eigen::Vector3d> x;
    for (std::size_t k = start; k < end; ++k) x.push_back(point(connectivity[k]));
    start = end;
    const auto edges = vtk_mid_edges(type);
    const std::size_t corners = x.size() - edges.size();
    for (std::size_t k = 0; k < edges.size(); ++k)
      EXPECT_LT((x[corners + k] - 0.5 * (x[static_cast<std::size_t>(edges[k].first)] +
                                         x[static_cast<std::size_t>(edges[k].second)]))
                    .norm(),
                1e-14)
          << "VTK type " << type << " mid-edge node " << corners + k;
    // Orientation per VTK's parametric coordinates: tetra and wedge, (x1 - x0) x (x2 - x0)
    // points to x3; hexahedron, the (0,1,2,3) face's normal points to node 4.
    const Eigen::Vector3d n = (x[1] - x[0]).cross(x[type == 12 || type == 25 ? 3 : 2] - x[0]);
    EXPECT_GT(n.dot(x[type == 12 || type == 25 ? 4 : 3] - x[0]), 0.0) << "VTK type " << type;
  }

  // Point data read back exactly (binary: the very doubles).
  const std::vector<double> re = data_array(xml, "Name=\"mode_1_re\"");
  EXPECT_EQ(re, fields[0].values);
  EXPECT_EQ(data_array(xml, "Name=\"amplitude\""), fields[1].values);
  EXPECT_NE(xml.find("Name=\"mode_1_re\" NumberOfComponents=\"3\""), std::string::npos);
  EXPECT_EQ(data_array(xml, "Name=\"material\""), (std::vector<double>{0, 0, 1, 1, 0, 1}));
  // No temporary file left behind.
  for (const auto& entry : fs::directory_iterator(path.parent_path()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos);
}

// A field larger than one compression block (32 KiB): 12 000 nodes x 3 doubles = 288 000 bytes,
// nine blocks, the last one partial.
TEST(VtuWriter, LargeArraysSpanSeveralCompressedBlocks) {
  solid::Mesh mesh;
  mesh.materials = {{"steel", 1, 210e9, 0.3, 7850, {}}};
  const std::vector<Eigen::Vector3d> tet{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int k = 0; k < 3000; ++k) {
    std::vector<Eigen::Vector3d> x = tet;
    for (Eigen::Vector3d& p : x) p += Eigen::Vector3d(2.0 * k, 0.0, 0.0);
    add_element(mesh, ElementType::Tet4, x, 0);
  }
  Field u{"displacement", 3, {}};
  for (int i = 0; i < mesh.num_nodes(); ++i)
    u.values.insert(u.values.end(), {std::sin(0.01 * i), std::cos(0.02 * i), 1e-3 * i});
  const fs::path path = scratch("large.vtu");
  write_vtu(path, mesh, {u});
  const std::string xml = read_text(path);
  EXPECT_EQ(data_array(xml, "Name=\"displacement\""), u.values);
  const std::vector<double> connectivity = data_array(xml, "Name=\"connectivity\"");
  ASSERT_EQ(connectivity.size(), 12000u);
  for (std::size_t i = 0; i < connectivity.size(); ++i)
    ASSERT_EQ(connectivity[i], static_cast<double>(i));
  // Compressed: far smaller than the ASCII it replaces (~1 MB here).
  EXPECT_LT(fs::file_size(path), 400000u);
}

TEST(VtuWriter, SeriesWritesOneFilePerStateAndACollection) {
  const solid::Mesh mesh = all_types_mesh();
  const fs::path pvd = scratch("modes.pvd");
  const std::vector<fs::path> files = write_vtu_series(
      pvd, mesh, {test_fields(mesh), test_fields(mesh), test_fields(mesh)}, {101.5, 230.25, 512.0});
  ASSERT_EQ(files.size(), 3u);
  const std::string collection = read_text(pvd);
  for (const fs::path& f : files) {
    EXPECT_TRUE(fs::exists(f));
    EXPECT_NE(collection.find("file=\"" + f.filename().string() + "\""), std::string::npos);
  }
  EXPECT_NE(collection.find("timestep=\"230.25\""), std::string::npos);
}

TEST(VtuWriter, FieldOfWrongSizeIsAnInputError) {
  const solid::Mesh mesh = all_types_mesh();
  std::vector<Field> fields = test_fields(mesh);
  fields[1].values.pop_back();
  try {
    write_vtu(scratch("bad.vtu"), mesh, fields);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "fields[1].values");
  }
  EXPECT_FALSE(fs::exists(scratch("bad.vtu")));
  fields = test_fields(mesh);
  fields[0].num_components = 4;
  fields[0].values.resize(4 * static_cast<std::size_t>(mesh.num_nodes()));
  EXPECT_THROW(write_gmsh_views(scratch("bad.msh"), mesh, fields), InputError);
}

// Gmsh reads the file back: the mesh (node and element counts per type) and one view per field
// with the same values per node tag (node tag = index + 1).
TEST(GmshViewWriter, GmshReadsTheMeshAndTheViews) {
  const solid::Mesh mesh = all_types_mesh();
  const std::vector<Field> fields = test_fields(mesh);
  const fs::path path = scratch("all_types.msh");
  write_gmsh_views(path, mesh, fields, 0.5);

  meshgen::GmshSession session("read_back");
  gmsh::open(path.string());
  std::vector<std::size_t> node_tags;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params);
  ASSERT_EQ(node_tags.size(), static_cast<std::size_t>(mesh.num_nodes()));
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    for (int d = 0; d < 3; ++d)
      EXPECT_EQ(coords[3 * i + static_cast<std::size_t>(d)], mesh.coords[node_tags[i] - 1](d));
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, 3);
  std::sort(types.begin(), types.end());
  EXPECT_EQ(types, (std::vector<int>{4, 5, 6, 11, 17, 18}));
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, 3);
  for (std::size_t k = 0; k < types.size(); ++k)
    for (std::size_t e = 0; e < element_tags[k].size(); ++e) {
      const solid::Element& element = mesh.elements[element_tags[k][e] - 1];
      const std::size_t n = element.nodes.size();
      for (std::size_t i = 0; i < n; ++i)
        EXPECT_EQ(element_nodes[k][e * n + i], static_cast<std::size_t>(element.nodes[i] + 1));
    }

  std::vector<int> views;
  gmsh::view::getTags(views);
  ASSERT_EQ(views.size(), fields.size());
  for (std::size_t v = 0; v < views.size(); ++v) {
    std::string name;
    gmsh::option::getString(fmt::format("View[{}].Name", v), name);
    EXPECT_EQ(name, fields[v].name);
    std::string data_type;
    std::vector<std::size_t> tags;
    std::vector<std::vector<double>> data;
    double time = 0;
    int components = 0;
    gmsh::view::getModelData(views[v], 0, data_type, tags, data, time, components);
    EXPECT_EQ(data_type, "NodeData");
    EXPECT_EQ(time, 0.5);
    EXPECT_EQ(components, fields[v].num_components);
    ASSERT_EQ(tags.size(), static_cast<std::size_t>(mesh.num_nodes()));
    for (std::size_t i = 0; i < tags.size(); ++i)
      for (int c = 0; c < components; ++c)
        EXPECT_EQ(data[i][static_cast<std::size_t>(c)],
                  fields[v].values[(tags[i] - 1) * static_cast<std::size_t>(components) +
                                   static_cast<std::size_t>(c)]);
  }
  std::vector<std::pair<int, int>> groups;
  gmsh::model::getPhysicalGroups(groups, 3);
  ASSERT_EQ(groups.size(), 2u);
  std::string group_name;
  gmsh::model::getPhysicalName(3, 2, group_name);
  EXPECT_EQ(group_name, "bronze");
}

}  // namespace
}  // namespace geardyn::meshio
