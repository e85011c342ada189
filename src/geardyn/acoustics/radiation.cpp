#include "geardyn/acoustics/radiation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace geardyn::acoustics {

namespace {

void check_size(const Surface& s, Eigen::Index size, Eigen::Index per_node, const char* what) {
  if (size != per_node * s.num_nodes())
    throw std::invalid_argument(fmt::format("{}: {} values for {} surface nodes (expected {})",
                                            what, size, s.num_nodes(), per_node * s.num_nodes()));
}

}  // namespace

double erp(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
           double radiation_efficiency) {
  check_size(s, normal_velocity.size(), 1, "erp: normal velocity");
  return 0.5 * air.impedance() * radiation_efficiency *
         s.node_area.dot(normal_velocity.cwiseAbs2());
}

Eigen::VectorXd face_erp(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
                         double radiation_efficiency) {
  check_size(s, normal_velocity.size(), 1, "face_erp: normal velocity");
  const double factor = 0.5 * air.impedance() * radiation_efficiency;
  Eigen::VectorXd power(static_cast<Eigen::Index>(s.faces.size()));
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const SurfaceFace& face = s.faces[f];
    double sum = 0;
    for (std::size_t k = 0; k < face.nodes.size(); ++k)
      sum += face.node_weight[k] * std::norm(normal_velocity[face.nodes[k]]);
    power[static_cast<Eigen::Index>(f)] = factor * sum;
  }
  return power;
}

Eigen::VectorXcd normal_velocity(const Surface& s, const Eigen::VectorXcd& displacement,
                                 double omega) {
  check_size(s, displacement.size(), 3, "normal_velocity: displacement");
  Eigen::VectorXcd v(s.num_nodes());
  const std::complex<double> iw(0.0, omega);
  for (int i = 0; i < s.num_nodes(); ++i)
    v[i] = iw *
           (s.node_normal.col(i).cast<std::complex<double>>().dot(displacement.segment<3>(3 * i)));
  return v;
}

ErpOperator::ErpOperator(const Surface& s, const Eigen::MatrixXd& recovery) {
  check_size(s, recovery.rows(), 3, "ErpOperator: recovery rows");
  const Eigen::Index n = s.num_nodes(), m = recovery.cols();
  Rn_.resize(n, m);
  for (Eigen::Index j = 0; j < m; ++j) {  // column by column: contiguous reads
    const Eigen::Map<const Eigen::Matrix3Xd> u(recovery.col(j).data(), 3, n);
    Rn_.col(j) = u.cwiseProduct(s.node_normal).colwise().sum().transpose();
  }
  area_ = s.node_area.sum();
  // W = sum over blocks of rows of B^T B, B = diag(sqrt(A)) R_n (a symmetric rank update: half
  // the flops of a general product, and a bounded temporary).
  W_ = Eigen::MatrixXd::Zero(m, m);
  constexpr Eigen::Index kBlock = 2048;
  Eigen::MatrixXd B;
  for (Eigen::Index start = 0; start < n; start += kBlock) {
    const Eigen::Index rows = std::min(kBlock, n - start);
    B = s.node_area.segment(start, rows).cwiseSqrt().asDiagonal() * Rn_.middleRows(start, rows);
    W_.selfadjointView<Eigen::Lower>().rankUpdate(B.transpose());
  }
  W_ = W_.selfadjointView<Eigen::Lower>();
}

double ErpOperator::power(const Eigen::VectorXcd& q, double omega, const Air& air,
                          double sigma) const {
  if (q.size() != W_.rows())
    throw std::invalid_argument(
        fmt::format("ErpOperator::power: {} reduced coordinates for an "
                    "operator of {}",
                    q.size(), W_.rows()));
  // q^H W q = a^T W a + b^T W b for q = a + i b and symmetric W.
  const Eigen::VectorXd a = q.real(), b = q.imag();
  const double quadratic = a.dot(W_ * a) + b.dot(W_ * b);
  return 0.5 * air.impedance() * sigma * omega * omega * quadratic;
}

Eigen::VectorXcd ErpOperator::normal_velocity(const Eigen::VectorXcd& q, double omega) const {
  if (q.size() != Rn_.cols())
    throw std::invalid_argument(
        fmt::format("ErpOperator::normal_velocity: {} reduced "
                    "coordinates for an operator of {}",
                    q.size(), Rn_.cols()));
  Eigen::VectorXcd v(Rn_.rows());
  v.real() = Rn_ * q.real();
  v.imag() = Rn_ * q.imag();
  return std::complex<double>(0.0, omega) * v;
}

double ErpOperator::mean_normal_velocity(const Eigen::VectorXcd& q, double omega) const {
  const Air unit{1.0, 2.0};  // 1/2 rho c = 1: power() returns w^2 q^H W q = sum A |v_n|^2
  return area_ > 0 ? std::sqrt(power(q, omega, unit) / area_) : 0.0;
}

double spherical_radiator_power(double velocity_amplitude, double radius, double omega,
                                const Air& air) {
  if (!(radius > 0))
    throw std::invalid_argument(
        fmt::format("spherical radiator: radius {} m, expected > 0", radius));
  const double ka = omega * radius / air.speed_of_sound, ka2 = ka * ka;
  return 2 * std::numbers::pi * radius * radius * velocity_amplitude * velocity_amplitude *
         air.impedance() * ka2 / (1 + ka2);
}

double equivalent_sphere_radius(double area) {
  return std::sqrt(std::max(area, 0.0) / (4 * std::numbers::pi));
}

double sound_power_level_db(double power_w) {
  if (power_w <= 0) return -std::numeric_limits<double>::infinity();
  return 10 * std::log10(power_w / 1e-12);
}

double sound_pressure_level_db(double power_w, double distance_m, double directivity) {
  if (!(distance_m > 0) || !(directivity > 0))
    throw std::invalid_argument(
        fmt::format("sound pressure level: distance {} m and "
                    "directivity {}, expected both > 0",
                    distance_m, directivity));
  return sound_power_level_db(power_w) +
         10 * std::log10(directivity / (4 * std::numbers::pi * distance_m * distance_m));
}

RadiationEfficiency::RadiationEfficiency(double sigma) : frequency_hz_{1.0}, sigma_{sigma} {
  if (!(sigma >= 0))
    throw std::invalid_argument(fmt::format("radiation efficiency {}, expected >= 0", sigma));
}

RadiationEfficiency::RadiationEfficiency(std::vector<double> frequency_hz,
                                         std::vector<double> sigma)
    : frequency_hz_(std::move(frequency_hz)), sigma_(std::move(sigma)) {
  if (frequency_hz_.empty() || frequency_hz_.size() != sigma_.size())
    throw std::invalid_argument(
        fmt::format("radiation efficiency table: {} frequencies and {} "
                    "values, expected the same number >= 1",
                    frequency_hz_.size(), sigma_.size()));
  for (std::size_t i = 0; i < sigma_.size(); ++i) {
    if (!(frequency_hz_[i] > 0) || (i > 0 && !(frequency_hz_[i] > frequency_hz_[i - 1])))
      throw std::invalid_argument(
          fmt::format("radiation efficiency table: frequency {} Hz at "
                      "row {}, expected > 0 and increasing",
                      frequency_hz_[i], i + 1));
    if (!(sigma_[i] >= 0))
      throw std::invalid_argument(
          fmt::format("radiation efficiency table: sigma {} at row {}, "
                      "expected >= 0",
                      sigma_[i], i + 1));
  }
}

double RadiationEfficiency::at(double frequency_hz) const {
  if (is_constant() || frequency_hz <= frequency_hz_.front()) return sigma_.front();
  if (frequency_hz >= frequency_hz_.back()) return sigma_.back();
  const auto upper = std::upper_bound(frequency_hz_.begin(), frequency_hz_.end(), frequency_hz);
  const std::size_t k = static_cast<std::size_t>(upper - frequency_hz_.begin());
  const double t = std::log(frequency_hz / frequency_hz_[k - 1]) /
                   std::log(frequency_hz_[k] / frequency_hz_[k - 1]);
  return sigma_[k - 1] + t * (sigma_[k] - sigma_[k - 1]);
}

ErpDensityMap erp_density_map(const Surface& s, const Eigen::VectorXd& face_erp_w, int cells) {
  if (face_erp_w.size() != static_cast<Eigen::Index>(s.faces.size()))
    throw std::invalid_argument(fmt::format("erp_density_map: {} face powers for {} faces",
                                            face_erp_w.size(), s.faces.size()));
  if (cells < 1 || s.faces.empty())
    throw std::invalid_argument("erp_density_map: expected cells >= 1 and a non-empty surface");
  Eigen::Vector3d lo = s.faces.front().centroid, hi = lo;
  for (const SurfaceFace& f : s.faces) {
    lo = lo.cwiseMin(f.centroid);
    hi = hi.cwiseMax(f.centroid);
  }
  const Eigen::Vector3d extent = hi - lo;
  std::array<int, 3> axes{0, 1, 2};
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return extent[a] > extent[b]; });
  ErpDensityMap map;
  map.x_axis = axes[0], map.y_axis = axes[1];
  const double ex = extent[map.x_axis], ey = extent[map.y_axis];
  const int nx = cells;
  const int ny = ex > 0 ? std::max(1, static_cast<int>(std::lround(cells * ey / ex))) : 1;
  const double hx = ex > 0 ? ex / nx : 1.0, hy = ey > 0 ? ey / ny : 1.0;
  std::vector<std::vector<double>> power(static_cast<std::size_t>(ny),
                                         std::vector<double>(static_cast<std::size_t>(nx), 0.0));
  std::vector<std::vector<double>> area = power;
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const Eigen::Vector3d& c = s.faces[f].centroid;
    const int k = std::clamp(static_cast<int>((c[map.x_axis] - lo[map.x_axis]) / hx), 0, nx - 1);
    const int i = std::clamp(static_cast<int>((c[map.y_axis] - lo[map.y_axis]) / hy), 0, ny - 1);
    power[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] +=
        face_erp_w[static_cast<Eigen::Index>(f)];
    area[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] += s.faces[f].area;
  }
  Trace& t = map.trace;
  t.name = "ERP density";
  t.z_label = "ERP density [W/m^2]";
  for (int k = 0; k < nx; ++k) t.x.push_back(lo[map.x_axis] + (k + 0.5) * hx);
  for (int i = 0; i < ny; ++i) t.y.push_back(lo[map.y_axis] + (i + 0.5) * hy);
  t.z.assign(static_cast<std::size_t>(ny), std::vector<double>(static_cast<std::size_t>(nx)));
  for (std::size_t i = 0; i < t.z.size(); ++i)
    for (std::size_t k = 0; k < t.z[i].size(); ++k)
      t.z[i][k] =
          area[i][k] > 0 ? power[i][k] / area[i][k] : std::numeric_limits<double>::quiet_NaN();
  static constexpr const char* names[3] = {"x [m]", "y [m]", "z [m]"};
  map.x_label = names[map.x_axis];
  map.y_label = names[map.y_axis];
  return map;
}

void write_surface_vtu(const std::filesystem::path& path, const solid::Mesh& mesh, const Surface& s,
                       const std::vector<meshio::Field>& cell_fields,
                       const std::vector<meshio::Field>& point_fields) {
  meshio::SurfaceCells cells;
  cells.points = s.nodes;
  for (const SurfaceFace& f : s.faces) {
    cells.cells.push_back(f.nodes);
    const auto e = static_cast<std::size_t>(f.element);
    cells.cell_ids.push_back(e < mesh.elements.size() ? mesh.elements[e].id : f.element + 1L);
  }
  meshio::write_surface_vtu(path, mesh, cells, cell_fields, point_fields);
}

ErpFields erp_fields(const Surface& s, const Eigen::VectorXcd& normal_velocity, const Air& air,
                     double radiation_efficiency) {
  const Eigen::VectorXd power = face_erp(s, normal_velocity, air, radiation_efficiency);
  ErpFields fields;
  meshio::Field erp_w{"erp_w", 1, {}}, density{"erp_density_w_per_m2", 1, {}};
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const double p = power[static_cast<Eigen::Index>(f)];
    erp_w.values.push_back(p);
    density.values.push_back(s.faces[f].area > 0 ? p / s.faces[f].area : 0.0);
  }
  meshio::Field vn{"normal_velocity_m_per_s", 1, {}};
  for (Eigen::Index i = 0; i < normal_velocity.size(); ++i)
    vn.values.push_back(std::abs(normal_velocity[i]));
  fields.cells = {std::move(erp_w), std::move(density)};
  fields.points = {std::move(vn)};
  return fields;
}

}  // namespace geardyn::acoustics
