#include "geardyn/response/cyclic_forced_response.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::response {
namespace {

using Complex = std::complex<double>;
constexpr double kRpmPerRadS = 60.0 / units::kTwoPi;

[[noreturn]] void input_error(const std::string& key, const std::string& expected,
                              const std::string& found, const std::string& hint = {}) {
  throw InputError({}, key, expected, found, hint);
}

std::int64_t dof_key(long node_id, int component) {
  return static_cast<std::int64_t>(node_id) * 8 + component;
}

// Linear functionals on the sector DOFs (loads, sensors) built from node DOFs, with the
// Craig-Bampton recovery x = T q when a sensor or load sits on an interior DOF of the component.
class SectorDofs {
 public:
  SectorDofs(const cyclic::CyclicSector& sector, const reduce::ReducedComponent* recovery)
      : sector_(sector), recovery_(recovery) {
    const auto& dofs = sector.dofs();
    for (std::size_t i = 0; i < dofs.size(); ++i)
      if (dofs[i].component >= 0)
        index_.emplace(dof_key(dofs[i].node_id, dofs[i].component), static_cast<Eigen::Index>(i));
    if (recovery_ != nullptr) {
      if (recovery_->size() != sector.num_dofs())
        input_error("forced.recovery",
                    fmt::format("a reduced component with {} reduced coordinates (the sector's "
                                "DOFs)",
                                sector.num_dofs()),
                    std::to_string(recovery_->size()),
                    "build the CyclicSector on recovery.reduced_dofs()");
      for (std::size_t j = 0; j < recovery_->interior_index.size(); ++j) {
        const auto& d =
            recovery_->full_dofs[static_cast<std::size_t>(recovery_->interior_index[j])];
        if (d.component >= 0)
          interior_.emplace(dof_key(d.node_id, d.component), static_cast<Eigen::Index>(j));
      }
    }
  }

  bool has_node(long node_id) const {
    for (int c = 0; c < 6; ++c)
      if (index_.count(dof_key(node_id, c)) || interior_.count(dof_key(node_id, c))) return true;
    return false;
  }

  // Adds `value` times the functional of DOF (node, component) to `row` (length num_dofs):
  // unit vector for a sector DOF, [Psi_j, Phi_j] for an interior DOF j. False if absent.
  bool add(long node_id, int component, Complex value, Eigen::VectorXcd& row) const {
    const auto it = index_.find(dof_key(node_id, component));
    if (it != index_.end()) {
      row[it->second] += value;
      return true;
    }
    const auto jt = interior_.find(dof_key(node_id, component));
    if (jt == interior_.end()) return false;
    const Eigen::Index j = jt->second;
    const Eigen::Index nb = recovery_->n_masters();
    for (Eigen::Index b = 0; b < nb; ++b) row[b] += value * recovery_->Psi(j, b);
    for (Eigen::Index m = 0; m < recovery_->n_modal; ++m)
      row[nb + m] += value * recovery_->Phi(j, m);
    return true;
  }

  Eigen::VectorXcd load_vector(const std::vector<ToothLoad>& loads) const {
    Eigen::VectorXcd f = Eigen::VectorXcd::Zero(sector_.num_dofs());
    if (loads.empty()) input_error("forced.loads", "at least one tooth load", "none");
    for (std::size_t i = 0; i < loads.size(); ++i) {
      const ToothLoad& load = loads[i];
      const std::string key = fmt::format("forced.loads[{}]", i);
      if (!load.force.allFinite())
        input_error(key + ".force", "a finite complex force amplitude [N]", "a non-finite value");
      if (!has_node(load.node_id))
        input_error(key + ".node_id", "a node of the sector (a master of a reduced sector)",
                    fmt::format("node {}, which has no DOF in the sector", load.node_id),
                    recovery_ == nullptr
                        ? "for a Craig-Bampton sector pass the ReducedComponent as recovery"
                        : "check the node id against the mesh");
      for (int c = 0; c < 3; ++c) {
        if (load.force[c] == Complex(0.0)) continue;
        if (!add(load.node_id, c, load.force[c], f))
          input_error(key, fmt::format("a free DOF u{} at node {}", "xyz"[c], load.node_id),
                      "the DOF is absent (constrained or not in the sector)",
                      "a load on a fixed DOF does no work: remove that component");
      }
    }
    return f;
  }

  // Row vectors (sensors x num_dofs) such that the sensor values are rows * u_0.
  Eigen::MatrixXcd sensor_rows(const std::vector<CyclicSensor>& sensors) const {
    Eigen::MatrixXcd rows =
        Eigen::MatrixXcd::Zero(static_cast<Eigen::Index>(sensors.size()), sector_.num_dofs());
    for (std::size_t s = 0; s < sensors.size(); ++s) {
      const CyclicSensor& sensor = sensors[s];
      const std::string key = fmt::format("forced.sensors[{}]", s);
      if (sensor.component < 0 || sensor.component > 5)
        input_error(key + ".component", "a component 0..5 (ux uy uz rx ry rz)",
                    std::to_string(sensor.component));
      Eigen::VectorXcd row = Eigen::VectorXcd::Zero(sector_.num_dofs());
      if (!add(sensor.node_id, sensor.component, 1.0, row))
        input_error(key, "a DOF of the sector (or of the reduced component's full model)",
                    fmt::format("node {} component {} ({}), which is not there", sensor.node_id,
                                sensor.component, sensor.name));
      rows.row(static_cast<Eigen::Index>(s)) = row.transpose();
    }
    return rows;
  }

 private:
  const cyclic::CyclicSector& sector_;
  const reduce::ReducedComponent* recovery_;
  std::unordered_map<std::int64_t, Eigen::Index> index_;
  std::unordered_map<std::int64_t, Eigen::Index> interior_;
};

std::string order_rule(int n_sectors, int h, int k, bool minus) {
  const int q = minus ? (k + h) / n_sectors : (k - h) / n_sectors;
  const std::string qn = q == 1 ? "N" : fmt::format("{}N", q);
  if (h == 0) return qn;
  if (minus) return qn + "-h";
  return q == 0 ? "h" : qn + "+h";
}

}  // namespace

ToothLoad tooth_load(long node_id, Complex amplitude, const Eigen::Vector3d& direction) {
  ToothLoad load;
  load.node_id = node_id;
  load.force = amplitude * direction.cast<Complex>();
  return load;
}

std::vector<std::string> ModalDamping::validate() const {
  std::vector<std::string> problems;
  const int given = (std::isnan(damping_ratio) ? 0 : 1) + (std::isnan(q_factor) ? 0 : 1) +
                    (damping_ratios.size() > 0 ? 1 : 0);
  if (given != 1)
    problems.push_back(fmt::format(
        "give exactly one of damping_ratio, q_factor, damping_ratios (found {})", given));
  if (!std::isnan(damping_ratio) && !(damping_ratio > 0.0 && std::isfinite(damping_ratio)))
    problems.push_back(fmt::format("damping_ratio must be finite and > 0, is {}", damping_ratio));
  if (!std::isnan(q_factor) && !(q_factor > 0.0 && std::isfinite(q_factor)))
    problems.push_back(fmt::format("q_factor must be finite and > 0, is {}", q_factor));
  for (Eigen::Index i = 0; i < damping_ratios.size(); ++i)
    if (!(damping_ratios[i] >= 0.0) || !std::isfinite(damping_ratios[i]))
      problems.push_back(
          fmt::format("damping_ratios[{}] must be finite and >= 0, is {}", i, damping_ratios[i]));
  return problems;
}

double ModalDamping::ratio(Eigen::Index mode) const {
  if (!std::isnan(damping_ratio)) return damping_ratio;
  if (!std::isnan(q_factor)) return 0.5 / q_factor;
  if (mode >= damping_ratios.size())
    input_error("forced.damping.damping_ratios", fmt::format("a ratio for mode {}", mode + 1),
                fmt::format("{} ratios", damping_ratios.size()),
                "give one ratio per mode used, or a single damping_ratio / q_factor");
  return damping_ratios[mode];
}

std::string_view to_string(TravellingWave w) {
  switch (w) {
    case TravellingWave::Standing:
      return "standing";
    case TravellingWave::Backward:
      return "backward";
    case TravellingWave::Forward:
      return "forward";
  }
  return "standing";
}

OrderRelation relate_order(int n_sectors, int h, int k) {
  if (n_sectors < 2) input_error("forced.n_sectors", "N >= 2", std::to_string(n_sectors));
  if (h < 0 || 2 * h > n_sectors)
    input_error("forced.nodal_diameter", fmt::format("a nodal diameter in 0..{}", n_sectors / 2),
                std::to_string(h));
  if (k < 1) input_error("forced.engine_order", "an engine order k >= 1", std::to_string(k));
  const int m = k % n_sectors;
  OrderRelation r;
  const bool plus = m == h;
  const bool minus = (m + h) % n_sectors == 0;
  if (!plus && !minus)
    input_error(
        "forced.engine_order",
        fmt::format("an order k = +-{} (mod {}) for nodal diameter {}", h, n_sectors, h),
        fmt::format("k = {} (k mod N = {}: nodal diameter {})", k, m, std::min(m, n_sectors - m)),
        fmt::format("orders exciting ND {}: {}", h, [&] {
          std::string list;
          for (int o : gear::nodal_diameter_orders(n_sectors, h, 4))
            list += (list.empty() ? "" : ", ") + std::to_string(o);
          return list;
        }()));
  if (h == 0 || 2 * h == n_sectors) {
    r.conjugate = false;
    r.wave = TravellingWave::Standing;
    r.rule = order_rule(n_sectors, h, k, false);
  } else if (plus) {
    r.conjugate = false;
    r.wave = TravellingWave::Backward;
    r.rule = order_rule(n_sectors, h, k, false);
  } else {
    r.conjugate = true;
    r.wave = TravellingWave::Forward;
    r.rule = order_rule(n_sectors, h, k, true);
  }
  return r;
}

Eigen::VectorXd CyclicOrderModel::resonance_speeds() const {
  return natural_frequency / static_cast<double>(engine_order);
}

Eigen::VectorXcd CyclicOrderModel::modal_term(Eigen::Index r, double speed) const {
  const double w = engine_order * speed;
  const double wr = natural_frequency[r];
  const Complex den(wr * wr - w * w, 2.0 * damping_ratio[r] * wr * w);
  return sensor_shapes.col(r) * (modal_force[r] / den);
}

Eigen::VectorXcd CyclicOrderModel::response(double speed) const {
  const double w = engine_order * speed;
  Eigen::VectorXcd q(num_modes());
  for (Eigen::Index r = 0; r < num_modes(); ++r) {
    const double wr = natural_frequency[r];
    q[r] = modal_force[r] / Complex(wr * wr - w * w, 2.0 * damping_ratio[r] * wr * w);
  }
  return sensor_shapes * q;
}

Eigen::MatrixXcd CyclicOrderModel::response(const Eigen::VectorXd& speeds) const {
  // Q(r, s) = g_r / (w_r^2 - w_s^2 + 2 i zeta_r w_r w_s); U^T = P Q (one GEMM for all speeds).
  Eigen::MatrixXcd Q(num_modes(), speeds.size());
  for (Eigen::Index s = 0; s < speeds.size(); ++s) {
    const double w = engine_order * speeds[s];
    for (Eigen::Index r = 0; r < num_modes(); ++r) {
      const double wr = natural_frequency[r];
      Q(r, s) = modal_force[r] / Complex(wr * wr - w * w, 2.0 * damping_ratio[r] * wr * w);
    }
  }
  return (sensor_shapes * Q).transpose();
}

CyclicOrderModel make_cyclic_order_model(const cyclic::CyclicSector& sector,
                                         const cyclic::NodalDiameterModes& modes, int engine_order,
                                         const std::vector<ToothLoad>& loads,
                                         const std::vector<CyclicSensor>& sensors,
                                         const ModalDamping& damping, int modes_used,
                                         const reduce::ReducedComponent* recovery) {
  CyclicOrderModel model;
  model.n_sectors = sector.n_sectors();
  model.nodal_diameter = modes.nodal_diameter;
  model.engine_order = engine_order;
  model.relation = relate_order(sector.n_sectors(), modes.nodal_diameter, engine_order);
  if (const auto problems = damping.validate(); !problems.empty())
    input_error("forced.damping", "valid modal damping", problems.front());
  const Eigen::Index available = modes.eigen.eigenvalues.size();
  if (modes.sector_shapes.rows() != sector.num_dofs() || modes.sector_shapes.cols() != available)
    input_error(
        "forced.modes.sector_shapes",
        fmt::format("{} x {} sector shapes (sector DOFs x modes)", sector.num_dofs(), available),
        fmt::format("{} x {}", modes.sector_shapes.rows(), modes.sector_shapes.cols()));
  if (available == 0)
    input_error("forced.modes", fmt::format("modes of nodal diameter {}", modes.nodal_diameter),
                "none");
  if (modes_used < 0 || modes_used > available)
    input_error("forced.modes_used", fmt::format("0..{} (0: all)", available),
                std::to_string(modes_used));
  const Eigen::Index n = modes_used == 0 ? available : modes_used;

  const SectorDofs lookup(sector, recovery);
  const Eigen::VectorXcd f = lookup.load_vector(loads);
  const Eigen::MatrixXcd rows = lookup.sensor_rows(sensors);
  const auto shapes = modes.sector_shapes.leftCols(n);

  model.natural_frequency.resize(n);
  model.damping_ratio.resize(n);
  for (Eigen::Index r = 0; r < n; ++r) {
    model.natural_frequency[r] = std::sqrt(std::max(modes.eigen.eigenvalues[r], 0.0));
    model.damping_ratio[r] = damping.ratio(r);
  }
  if (model.relation.conjugate) {
    model.modal_force = shapes.transpose() * f;       // psi_r^T f_0        (eq. 3)
    model.sensor_shapes = rows * shapes.conjugate();  // conj(psi_r) at sensors
  } else {
    model.modal_force = shapes.adjoint() * f;  // psi_r^H f_0        (eq. 2)
    model.sensor_shapes = rows * shapes;
  }
  return model;
}

Eigen::MatrixXcd cyclic_direct_response(const Eigen::SparseMatrix<double>& K,
                                        const Eigen::SparseMatrix<double>& M,
                                        const Eigen::SparseMatrix<double>& C,
                                        const cyclic::CyclicSector& sector, int nodal_diameter,
                                        int engine_order, const std::vector<ToothLoad>& loads,
                                        const std::vector<CyclicSensor>& sensors,
                                        const Eigen::VectorXd& speeds) {
  const OrderRelation relation = relate_order(sector.n_sectors(), nodal_diameter, engine_order);
  check_speeds(speeds, "forced.speeds");
  const bool has_c = C.rows() != 0 || C.cols() != 0;
  if (has_c && (C.rows() != sector.num_dofs() || C.cols() != sector.num_dofs()))
    input_error("forced.C",
                fmt::format("a {0}x{0} sector damping matrix or none", sector.num_dofs()),
                fmt::format("{}x{}", C.rows(), C.cols()));
  using ComplexSparse = Eigen::SparseMatrix<Complex>;
  ComplexSparse T = sector.transformation(nodal_diameter);
  ComplexSparse Kh = sector.reduce(K, nodal_diameter);
  ComplexSparse Mh = sector.reduce(M, nodal_diameter);
  ComplexSparse Ch = has_c ? sector.reduce(C, nodal_diameter)
                           : ComplexSparse(sector.num_reduced_dofs(), sector.num_reduced_dofs());
  if (relation.conjugate) {  // T_{-h} = conj(T_h), so every reduced matrix is conjugated
    T = T.conjugate();
    Kh = Kh.conjugate();
    Mh = Mh.conjugate();
    Ch = Ch.conjugate();
  }
  const SectorDofs lookup(sector, nullptr);
  const Eigen::VectorXcd fh = T.adjoint() * lookup.load_vector(loads);
  const Eigen::MatrixXcd sensor_T = lookup.sensor_rows(sensors) * T;

  Eigen::MatrixXcd out(speeds.size(), static_cast<Eigen::Index>(sensors.size()));
  linalg::SparseLU<Complex> lu;
  for (Eigen::Index s = 0; s < speeds.size(); ++s) {
    const double w = engine_order * speeds[s];
    ComplexSparse D = Kh - Complex(w * w) * Mh + Complex(0.0, w) * Ch;
    if (lu.compute(D) != Status::Ok)
      throw NumericalError(
          "cyclic forced response (direct)",
          fmt::format("the dynamic stiffness of nodal diameter {} at speed {} rad/s (w = {} "
                      "rad/s) is singular: {}; an undamped natural frequency was hit exactly, "
                      "add damping or move the speed",
                      nodal_diameter, speeds[s], w, lu.message()));
    const Eigen::VectorXcd q = lu.solve(fh);
    out.row(s) = (sensor_T * q).transpose();
  }
  return out;
}

std::vector<CyclicExcitation> excitations_from_harmonics(
    const std::vector<gear::HarmonicComponents>& harmonics, long node_id,
    const Eigen::Vector3d& tangential, const Eigen::Vector3d& radial,
    const Eigen::Vector3d& axial) {
  std::vector<CyclicExcitation> out;
  for (const gear::HarmonicComponents& c : harmonics) {
    CyclicExcitation e;
    e.nodal_diameter = c.nodal_diameter;
    e.engine_order = c.order;
    ToothLoad load;
    load.node_id = node_id;
    load.force = c.tangential * tangential.cast<Complex>() + c.radial * radial.cast<Complex>() +
                 c.axial * axial.cast<Complex>();
    e.loads.push_back(load);
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<OrderPair> resonant_orders(const std::vector<cyclic::NodalDiameterModes>& modes,
                                       int n_sectors, double speed_min, double speed_max,
                                       int max_order) {
  if (!(speed_min > 0.0) || !(speed_max > speed_min) || !std::isfinite(speed_max))
    input_error("forced.speed_range", "0 < speed_min < speed_max, finite [rad/s]",
                fmt::format("[{}, {}]", speed_min, speed_max));
  if (max_order < 1) input_error("forced.max_order", "max_order >= 1", std::to_string(max_order));
  std::vector<OrderPair> out;
  for (const cyclic::NodalDiameterModes& d : modes) {
    for (int k = 1; k <= max_order; ++k) {
      const int m = k % n_sectors;
      if (m != d.nodal_diameter && (m + d.nodal_diameter) % n_sectors != 0) continue;
      bool hit = false;
      for (Eigen::Index r = 0; r < d.eigen.eigenvalues.size() && !hit; ++r) {
        const double speed = std::sqrt(std::max(d.eigen.eigenvalues[r], 0.0)) / k;
        hit = speed >= speed_min && speed <= speed_max;
      }
      if (hit) out.push_back({d.nodal_diameter, k});
    }
  }
  return out;
}

CyclicForcedResult run_cyclic_forced_response(const cyclic::CyclicSector& sector,
                                              const std::vector<cyclic::NodalDiameterModes>& modes,
                                              const CyclicForcedSettings& settings,
                                              const reduce::ReducedComponent* recovery,
                                              Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  check_speeds(settings.speeds, "forced.speeds");
  if (settings.excitations.empty())
    input_error("forced.excitations", "at least one (nodal diameter, engine order) excitation",
                "none");
  if (settings.sensors.empty()) input_error("forced.sensors", "at least one sensor", "none");
  if (const auto problems = settings.peaks.validate(); !problems.empty())
    input_error("forced.peaks", "valid peak options", problems.front());

  CyclicForcedResult result;
  result.n_sectors = sector.n_sectors();
  result.speeds = settings.speeds;
  result.sensors = settings.sensors;
  const Eigen::Index ns = settings.speeds.size();
  const Eigen::Index nsens = static_cast<Eigen::Index>(settings.sensors.size());
  result.amplitude_sum = Eigen::MatrixXd::Zero(ns, nsens);
  Eigen::MatrixXd squares = Eigen::MatrixXd::Zero(ns, nsens);

  progress.start("cyclic forced response", settings.excitations.size());
  for (std::size_t e = 0; e < settings.excitations.size(); ++e) {
    const CyclicExcitation& ex = settings.excitations[e];
    const auto it = std::find_if(modes.begin(), modes.end(), [&](const auto& d) {
      return d.nodal_diameter == ex.nodal_diameter;
    });
    if (it == modes.end())
      input_error(fmt::format("forced.excitations[{}].nodal_diameter", e),
                  "a nodal diameter whose modes were computed",
                  fmt::format("ND {}, not among the {} given", ex.nodal_diameter, modes.size()),
                  "add it to CyclicModesOptions::nodal_diameters");
    const CyclicOrderModel model =
        make_cyclic_order_model(sector, *it, ex.engine_order, ex.loads, settings.sensors,
                                settings.damping, settings.modes_used, recovery);
    OrderResponse order;
    order.nodal_diameter = ex.nodal_diameter;
    order.engine_order = ex.engine_order;
    order.relation = model.relation;
    order.displacement = model.response(settings.speeds);
    const Eigen::MatrixXd amplitude = order.displacement.cwiseAbs();
    result.amplitude_sum += amplitude;
    squares += amplitude.cwiseAbs2();

    const Eigen::VectorXd resonance_speed = model.resonance_speeds();
    for (Eigen::Index r = 0; r < model.num_modes(); ++r) {
      CyclicResonance res;
      res.nodal_diameter = ex.nodal_diameter;
      res.engine_order = ex.engine_order;
      res.mode = static_cast<int>(r) + 1;
      res.frequency_hz = model.natural_frequency[r] / units::kTwoPi;
      res.speed = resonance_speed[r];
      res.damping_ratio = model.damping_ratio[r];
      res.in_range = res.speed >= settings.speeds[0] && res.speed <= settings.speeds[ns - 1];
      res.amplitude = res.speed > 0.0 ? Eigen::VectorXd(model.response(res.speed).cwiseAbs())
                                      : Eigen::VectorXd::Constant(nsens, kNaN);
      result.resonances.push_back(std::move(res));
    }
    append_speed_peaks(result.peaks, settings.speeds, amplitude, static_cast<int>(e),
                       settings.peaks);
    result.orders.push_back(std::move(order));
    progress.update(e + 1);
  }
  progress.finish();
  result.amplitude_rms = (0.5 * squares).cwiseSqrt();
  if (result.orders.size() > 1)
    append_speed_peaks(result.peaks, settings.speeds, result.amplitude_sum, -1, settings.peaks);
  std::stable_sort(result.peaks.begin(), result.peaks.end(),
                   [](const SpeedPeak& a, const SpeedPeak& b) { return a.sensor < b.sensor; });
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

Table CyclicForcedResult::response_table() const {
  Table t;
  t.name = "cyclic_forced_response";
  t.title = "Forced response of the cyclic gear per engine order (rotating frame)";
  std::vector<double> rpm;
  for (Eigen::Index i = 0; i < speeds.size(); ++i) rpm.push_back(speeds[i] * kRpmPerRadS);
  t.add("speed_rpm", "rpm", rpm);
  const auto unit = [&](std::size_t s) { return sensors[s].component >= 3 ? "rad" : "m"; };
  for (const OrderResponse& o : orders)
    for (std::size_t s = 0; s < sensors.size(); ++s) {
      const std::string base =
          fmt::format("{}_h{}_k{}", sensors[s].name, o.nodal_diameter, o.engine_order);
      std::vector<double> amp, phase;
      for (Eigen::Index i = 0; i < o.displacement.rows(); ++i) {
        const Complex u = o.displacement(i, static_cast<Eigen::Index>(s));
        amp.push_back(std::abs(u));
        phase.push_back(std::arg(u) * 180.0 / units::kPi);
      }
      t.add(fmt::format("{}_amplitude_{}", base, unit(s)), unit(s), amp);
      t.add(base + "_phase_deg", "deg", phase);
    }
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    const auto col = static_cast<Eigen::Index>(s);
    t.add(fmt::format("{}_sum_amplitude_{}", sensors[s].name, unit(s)), unit(s),
          std::vector<double>(amplitude_sum.col(col).data(),
                              amplitude_sum.col(col).data() + amplitude_sum.rows()));
    t.add(fmt::format("{}_rms_{}", sensors[s].name, unit(s)), unit(s),
          std::vector<double>(amplitude_rms.col(col).data(),
                              amplitude_rms.col(col).data() + amplitude_rms.rows()));
  }
  return t;
}

Table CyclicForcedResult::resonance_table() const {
  Table t;
  t.name = "cyclic_resonances";
  t.title = "Resonances of the cyclic gear: mode r of ND h met by engine order k at W = w_r / k";
  std::vector<double> nd, eo, mode, f, rpm, zeta, q, in;
  std::vector<std::string> rule, wave;
  std::vector<std::vector<double>> amp(sensors.size());
  for (const CyclicResonance& r : resonances) {
    nd.push_back(r.nodal_diameter);
    eo.push_back(r.engine_order);
    mode.push_back(r.mode);
    f.push_back(r.frequency_hz);
    rpm.push_back(r.speed * kRpmPerRadS);
    zeta.push_back(r.damping_ratio);
    q.push_back(r.damping_ratio > 0.0 ? 0.5 / r.damping_ratio : kNaN);
    in.push_back(r.in_range ? 1.0 : 0.0);
    const auto o = std::find_if(orders.begin(), orders.end(), [&](const OrderResponse& x) {
      return x.nodal_diameter == r.nodal_diameter && x.engine_order == r.engine_order;
    });
    rule.push_back(o != orders.end() ? o->relation.rule : "");
    wave.push_back(o != orders.end() ? std::string(to_string(o->relation.wave)) : "");
    for (std::size_t s = 0; s < sensors.size(); ++s)
      amp[s].push_back(r.amplitude[static_cast<Eigen::Index>(s)]);
  }
  t.add("nodal_diameter", "", nd);
  t.add("engine_order", "", eo);
  t.add_text("order_rule", rule);
  t.add_text("wave", wave);
  t.add("mode", "", mode);
  t.add("frequency_hz", "Hz", f);
  t.add("resonance_speed_rpm", "rpm", rpm);
  t.add("damping_ratio", "", zeta);
  t.add("q_factor", "", q);
  t.add("in_range", "", in);
  for (std::size_t s = 0; s < sensors.size(); ++s) {
    const char* unit = sensors[s].component >= 3 ? "rad" : "m";
    t.add(fmt::format("{}_amplitude_{}", sensors[s].name, unit), unit, amp[s]);
  }
  return t;
}

Table CyclicForcedResult::peak_table() const {
  std::vector<PeakRow> rows;
  for (const SpeedPeak& p : peaks) {
    const CyclicSensor& sensor = sensors[static_cast<std::size_t>(p.sensor)];
    PeakRow row;
    row.sensor = sensor.name;
    if (p.curve < 0) {
      row.curve = "sum";
    } else {
      const OrderResponse& o = orders[static_cast<std::size_t>(p.curve)];
      row.curve = fmt::format("ND {} EO {}", o.nodal_diameter, o.engine_order);
    }
    row.location = p.speed * kRpmPerRadS;
    row.amplitude = p.amplitude;
    row.amplitude_unit = sensor.component >= 3 ? "rad" : "m";
    row.half_power_low = p.speed1 * kRpmPerRadS;
    row.half_power_high = p.speed2 * kRpmPerRadS;
    row.q_factor = p.q_factor;
    row.points_in_band = p.points_in_band;
    row.resolved = p.resolved;
    rows.push_back(std::move(row));
  }
  return geardyn::peak_table("cyclic_response_peaks",
                             "Peaks of the response curves with their half-power Q (curve: nodal "
                             "diameter and engine order, or the sum of the orders)",
                             speed_axis(), rows);
}

}  // namespace geardyn::response
