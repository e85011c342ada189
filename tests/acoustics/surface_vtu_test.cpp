// The surface VTU (meshio::write_surface_vtu through acoustics::write_surface_vtu): read back
// and decoded by the test as the VTK XML format defines it (VTK file-formats documentation, "XML
// File Formats": appended raw data, UInt64 header, vtkZLibDataCompressor blocks), independently
// of the writer: the counts, the cell types and connectivity, the per-face ERP cell fields and
// the |v_n| point field equal what was computed (exact binary doubles).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "geardyn/acoustics/radiation.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/solid/structured_mesh.hpp"

namespace geardyn::acoustics {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string attribute(const std::string& xml, std::size_t tag, const std::string& name) {
  const std::size_t end = xml.find('>', tag);
  const std::size_t at = xml.find(" " + name + "=\"", tag);
  if (at == std::string::npos || at > end) return "";
  const std::size_t begin = at + name.size() + 3;
  return xml.substr(begin, xml.find('"', begin) - begin);
}

/// The values of the DataArray named `name` (or, for name "", the Points array).
std::vector<double> data_array(const std::string& xml, const std::string& name) {
  std::size_t at = name.empty() ? xml.find("<DataArray", xml.find("<Points>"))
                                : xml.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  if (at == std::string::npos) return {};
  at = xml.rfind("<DataArray", at);
  const std::string type = attribute(xml, at, "type");
  const std::size_t offset = std::stoul(attribute(xml, at, "offset"));
  const std::size_t base = xml.find('_', xml.find("<AppendedData encoding=\"raw\">")) + 1;
  const auto* p = reinterpret_cast<const unsigned char*>(xml.data()) + base + offset;
  auto u64 = [&](std::size_t k) {
    std::uint64_t value = 0;
    std::memcpy(&value, p + 8 * k, 8);
    return static_cast<std::size_t>(value);
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
    raw += chunk.substr(0, size);
    position += u64(3 + b);
  }
  std::vector<double> out;
  auto read = [&](auto zero) {
    for (std::size_t i = 0; i + sizeof(zero) <= raw.size(); i += sizeof(zero)) {
      decltype(zero) value;
      std::memcpy(&value, raw.data() + i, sizeof(value));
      out.push_back(static_cast<double>(value));
    }
  };
  if (type == "Float64")
    read(double{});
  else if (type == "Int64")
    read(std::int64_t{});
  else if (type == "UInt8")
    read(std::uint8_t{});
  else
    ADD_FAILURE() << "unexpected type " << type;
  return out;
}

TEST(SurfaceVtu, ReadsBackTheFacesAndTheErpFields) {
  // A hex20 / wedge15 mixture is not generated; a wedge15 box has both face kinds (6-node
  // triangles on z, 8-node quads on the sides), a tet4 box the linear triangles.
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "test_scratch" / "acoustics";
  fs::create_directories(dir);
  for (const solid::ElementType type : {solid::ElementType::Wedge15, solid::ElementType::Tet4}) {
    const solid::Mesh mesh =
        solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(0.3, 0.2, 0.1), 3, 2, 1, type,
                        {"steel", 1, 2.1e11, 0.3, 7850, {}});
    const Surface s = exterior_surface(mesh);
    Eigen::VectorXcd vn(s.num_nodes());
    for (int i = 0; i < s.num_nodes(); ++i) vn[i] = {1e-3 * (i + 1), -2e-4 * i};
    const Air air;
    const ErpFields fields = erp_fields(s, vn, air, 0.8);
    const fs::path path = dir / ("surface_" + std::string(solid::to_string(type)) + ".vtu");
    write_surface_vtu(path, mesh, s, fields.cells, fields.points);
    const std::string xml = read_text(path);
    EXPECT_NE(xml.find(fmt::format("NumberOfPoints=\"{}\" NumberOfCells=\"{}\"", s.num_nodes(),
                                   s.faces.size())),
              std::string::npos);
    const Eigen::VectorXd face = face_erp(s, vn, air, 0.8);
    const std::vector<double> erp_w = data_array(xml, "erp_w");
    const std::vector<double> density = data_array(xml, "erp_density_w_per_m2");
    ASSERT_EQ(erp_w.size(), s.faces.size());
    ASSERT_EQ(density.size(), s.faces.size());
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      EXPECT_EQ(erp_w[f], face[static_cast<Eigen::Index>(f)]);
      EXPECT_EQ(density[f], face[static_cast<Eigen::Index>(f)] / s.faces[f].area);
    }
    const std::vector<double> v = data_array(xml, "normal_velocity_m_per_s");
    ASSERT_EQ(v.size(), static_cast<std::size_t>(s.num_nodes()));
    for (int i = 0; i < s.num_nodes(); ++i)
      EXPECT_EQ(v[static_cast<std::size_t>(i)], std::abs(vn[i]));
    const std::vector<double> points = data_array(xml, "");
    ASSERT_EQ(points.size(), 3u * static_cast<std::size_t>(s.num_nodes()));
    for (int i = 0; i < s.num_nodes(); ++i)
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(points[3 * static_cast<std::size_t>(i) + static_cast<std::size_t>(c)],
                  mesh.coords[static_cast<std::size_t>(s.nodes[static_cast<std::size_t>(i)])][c]);
    const std::vector<double> types = data_array(xml, "types");
    const std::vector<double> connectivity = data_array(xml, "connectivity");
    ASSERT_EQ(types.size(), s.faces.size());
    std::size_t k = 0;
    for (std::size_t f = 0; f < s.faces.size(); ++f) {
      const std::size_t n = s.faces[f].nodes.size();
      EXPECT_EQ(types[f], n == 3 ? 5 : n == 4 ? 9 : n == 6 ? 22 : 23);
      for (int node : s.faces[f].nodes) EXPECT_EQ(connectivity[k++], node);
    }
    EXPECT_EQ(k, connectivity.size());
    const std::vector<double> ids = data_array(xml, "element_id");
    for (std::size_t f = 0; f < s.faces.size(); ++f)
      EXPECT_EQ(ids[f], mesh.elements[static_cast<std::size_t>(s.faces[f].element)].id);
  }
}

TEST(SurfaceVtu, FieldOfWrongSizeIsAnInputError) {
  const solid::Mesh mesh =
      solid::box_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), 1, 1, 1,
                      solid::ElementType::Hex8, {"steel", 1, 2.1e11, 0.3, 7850, {}});
  const Surface s = exterior_surface(mesh);
  const fs::path path = fs::path(GEARDYN_BINARY_DIR) / "test_scratch" / "bad_surface.vtu";
  fs::create_directories(path.parent_path());
  try {
    write_surface_vtu(path, mesh, s, {{"erp_w", 1, std::vector<double>(5, 0.0)}}, {});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("6 values (6 cells x 1 components)"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace geardyn::acoustics
