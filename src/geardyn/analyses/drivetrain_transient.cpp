#include "geardyn/analyses/drivetrain_transient.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>

#include "geardyn/analyses/mesh_force_map.hpp"
#include "geardyn/analyses/pair_model.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/drivetrain/builder.hpp"
#include "geardyn/elements/bolted_joint.hpp"
#include "geardyn/elements/gear_mesh_contact.hpp"
#include "geardyn/transient/adaptive_integrator.hpp"
#include "geardyn/transient/ida_integrator.hpp"

namespace geardyn::analyses {
namespace {

constexpr double kRadPerSToRpm = 60.0 / units::kTwoPi;
/// Largest record kept in memory: samples x channels doubles.
constexpr double kMaxRecordValues = 1.25e8;

using Evaluator = std::function<double(double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                       const Eigen::VectorXd& a)>;

/// Channels and how to compute each from a sample.
struct Recorder {
  std::vector<DrivetrainChannel> channels;
  std::vector<Evaluator> evaluate;
  /// Names keep letters, digits and underscores (others become '_'), as CSV columns and HDF5
  /// datasets need.
  void add(std::string name, std::string unit, std::string group, Evaluator e) {
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
    channels.push_back({std::move(name), std::move(unit), std::move(group)});
    evaluate.push_back(std::move(e));
  }
};

/// The projection of a virtual sensor on the equations: value = sum c_k x[e_k].
struct Projection {
  std::vector<int> equations;
  std::vector<double> coefficients;
  double of(const Eigen::VectorXd& x) const {
    double s = 0.0;
    for (std::size_t k = 0; k < equations.size(); ++k) s += coefficients[k] * x[equations[k]];
    return s;
  }
};

Projection sensor_projection(const model::VirtualSensorSpec& s, const fe::DofMap& dofs,
                             bool& rotation) {
  Projection p;
  const int node = dofs.find_node(s.node);
  if (s.component >= 0) {
    rotation = s.component >= 3;
    const int e = dofs.dof(node, static_cast<model::Component>(s.component));
    if (e >= 0) {
      p.equations.push_back(e);
      p.coefficients.push_back(1.0);
    }
    return p;
  }
  rotation = s.rotation;
  const Eigen::Vector3d d =
      Eigen::Vector3d((*s.direction)[0], (*s.direction)[1], (*s.direction)[2]).normalized();
  const Eigen::Vector3d c = dofs.node(node).frame.transpose() * d;
  for (int i = 0; i < 3; ++i) {
    const int e = dofs.dof(node, static_cast<model::Component>((rotation ? 3 : 0) + i));
    if (e >= 0 && c[i] != 0.0) {
      p.equations.push_back(e);
      p.coefficients.push_back(c[i]);
    }
  }
  return p;
}

void add_sensor_channels(const model::Model& model, const DrivetrainTransientSettings& s,
                         const fe::DofMap& dofs, Recorder& rec,
                         std::vector<std::pair<std::string, Projection>>& projections,
                         std::vector<bool>& rotations) {
  for (const model::VirtualSensorSpec& vs : model.virtual_sensors) {
    if (!s.sensors.empty() &&
        std::find(s.sensors.begin(), s.sensors.end(), vs.name) == s.sensors.end())
      continue;
    bool rot = false;
    const Projection p = sensor_projection(vs, dofs, rot);
    const std::string u = rot ? "rad" : "m";
    projections.emplace_back(vs.name, p);
    rotations.push_back(rot);
    rec.add(vs.name + "_" + u, u, "displacement",
            [p](double, const Eigen::VectorXd& q, const Eigen::VectorXd&, const Eigen::VectorXd&) {
              return p.of(q);
            });
    rec.add(vs.name + "_" + u + "_per_s", u + "/s", "velocity",
            [p](double, const Eigen::VectorXd&, const Eigen::VectorXd& v, const Eigen::VectorXd&) {
              return p.of(v);
            });
    rec.add(vs.name + "_" + u + "_per_s2", u + "/s^2", "acceleration",
            [p](double, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd& a) {
              return p.of(a);
            });
  }
}

/// Force channels of element k (names by kind), and the mesh's transmission error.
void add_element_channels(const model::Model& model, const fe::LinearSystem& sys,
                          const drivetrain::DrivetrainSystem& system, Recorder& rec,
                          std::vector<DrivetrainMeshOrders>& orders) {
  const auto& elements = system.parts().elements;
  std::size_t mesh_index = 0;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const drivetrain::PlacedElement& e = elements[k];
    const drivetrain::DrivetrainSystem* sp = &system;
    auto force = [sp, k](int i) {
      return [sp, k, i](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                        const Eigen::VectorXd&) { return sp->element_force(k, t, q, v)[i]; };
    };
    if (e.kind == "bolt") {
      const auto* bolt = dynamic_cast<const elements::BoltedJoint*>(e.element.get());
      const drivetrain::PlacedElement* pe = &e;
      auto bolt_value = [bolt, pe](bool clamp) {
        return [bolt, pe, clamp](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                                 const Eigen::VectorXd&) {
          Eigen::VectorXd u;
          pe->gather(q, u);
          const elements::BoltForces f = bolt->forces(u[0], t);
          return clamp ? f.clamp_force : f.bolt_force;
        };
      };
      rec.add(e.name + "_bolt_force_n", "N", "force", bolt_value(false));
      rec.add(e.name + "_clamp_force_n", "N", "force", bolt_value(true));
    } else if (e.kind == "bushing") {
      static const char* names[6] = {"fx_n", "fy_n", "fz_n", "mx_nm", "my_nm", "mz_nm"};
      for (int i = 0; i < 6; ++i)
        rec.add(e.name + "_" + names[i], i < 3 ? "N" : "N m", i < 3 ? "force" : "torque", force(i));
    } else if (e.kind == "rolling_bearing") {
      static const char* names[3] = {"fx_n", "fy_n", "fz_n"};
      for (int i = 0; i < 3; ++i) rec.add(e.name + "_" + names[i], "N", "force", force(i));
    } else if (e.kind == "clutch") {
      rec.add(e.name + "_torque_nm", "N m", "torque", force(0));
    } else if (e.kind == "gear_mesh") {
      rec.add(e.name + "_mesh_force_n", "N", "force", force(0));
      const drivetrain::MeshRows rows = drivetrain::mesh_rows(model, sys, mesh_index++);
      const double rb1 = rows.base_radius1;
      auto delta = [rows](const Eigen::VectorXd& q) {
        double s = 0.0;
        for (std::size_t i = 0; i < rows.equations.size(); ++i)
          s += rows.coefficients[i] * q[rows.equations[i]];
        return s;
      };
      rec.add(e.name + "_dte_m", "m", "dte",
              [delta](double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                      const Eigen::VectorXd&) { return delta(q); });
      rec.add(e.name + "_dte_rad", "rad", "dte",
              [delta, rb1](double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                           const Eigen::VectorXd&) { return delta(q) / rb1; });
      if (rows.pinion_spin >= 0) {
        // Gear 1's spin angle in its working sense, and its speed.
        const int e1 = rows.pinion_spin;
        const double sign = rows.pinion_sign;
        rec.add(e.name + "_pinion_angle_rad", "rad", "angle",
                [e1, sign](double, const Eigen::VectorXd& q, const Eigen::VectorXd&,
                           const Eigen::VectorXd&) { return sign * q[e1]; });
        const int teeth1 = model.gear_meshes[mesh_index - 1].teeth1;
        if (teeth1 > 0)
          orders.push_back({e.name, teeth1, rec.channels.size() - 1, rec.channels.size() - 3});
        rec.add(e.name + "_pinion_speed_rpm", "rpm", "speed",
                [e1, sign](double, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                           const Eigen::VectorXd&) { return sign * v[e1] * kRadPerSToRpm; });
      }
    } else {
      const bool rotation =
          model.contacts.size() > 0 &&
          std::any_of(model.contacts.begin(), model.contacts.end(),
                      [&](const model::ContactSpec& c) {
                        return c.name == e.name && c.motion == model::ContactMotion::Rotation;
                      });
      rec.add(e.name + (rotation ? "_torque_nm" : "_force_n"), rotation ? "N m" : "N",
              rotation ? "torque" : "force", force(0));
    }
  }
}

void add_drive_channels(drivetrain::DrivetrainSystem& system, Recorder& rec) {
  const auto& p = system.parts();
  auto speed = [](int e) {
    return [e](double, const Eigen::VectorXd&, const Eigen::VectorXd& v, const Eigen::VectorXd&) {
      return v[e] * kRadPerSToRpm;
    };
  };
  drivetrain::DrivetrainSystem* sp = &system;
  for (const drivetrain::SpeedDriver& d : p.speed_drivers) {
    const int e = d.equation;
    rec.add(d.name + "_speed_rpm", "rpm", "speed", speed(e));
    rec.add(d.name + "_torque_nm", "N m", "torque",
            [sp, e](double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                    const Eigen::VectorXd& a) {
              Eigen::VectorXd r;
              sp->free_residual(t, q, v, a, r);
              return r[e];
            });
  }
  for (const drivetrain::Motor& m : p.motors) {
    const int e = m.equation;
    const drivetrain::Motor* mp = &m;
    rec.add(m.name + "_speed_rpm", "rpm", "speed", speed(e));
    rec.add(m.name + "_torque_nm", "N m", "torque",
            [mp, e](double, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                    const Eigen::VectorXd&) { return mp->torque.value(v[e]); });
  }
  for (const drivetrain::LoadTorque& l : p.loads) {
    const int e = l.equation;
    const drivetrain::LoadTorque* lp = &l;
    rec.add(l.name + "_speed_rpm", "rpm", "speed", speed(e));
    rec.add(l.name + "_torque_nm", "N m", "torque",
            [lp, e](double t, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                    const Eigen::VectorXd&) { return lp->value(t, v[e], nullptr); });
  }
}

/// The FRF's load: a virtual sensor's DOF or direction, or a mesh's line of action.
drivetrain::EquationCombination frf_load(const model::Model& model, const fe::LinearSystem& sys,
                                         const std::string& name, bool& moment) {
  for (const model::VirtualSensorSpec& vs : model.virtual_sensors)
    if (vs.name == name) {
      bool rotation = false;
      const Projection p = sensor_projection(vs, sys.dofs, rotation);
      moment = rotation;
      return {p.equations, p.coefficients};
    }
  for (std::size_t i = 0; i < model.gear_meshes.size(); ++i)
    if (model.gear_meshes[i].name == name) {
      const drivetrain::MeshRows rows = drivetrain::mesh_rows(model, sys, i);
      moment = false;
      return {rows.equations, rows.coefficients};
    }
  return {};
}

/// The modal FRF of every recorded sensor to the load, and a direct solve at the band's middle
/// and top as a check of the truncation.
void compute_frf(const model::Model& model, const fe::LinearSystem& sys,
                 const DrivetrainTransientSettings& s,
                 const std::vector<std::pair<std::string, Projection>>& projections,
                 const std::vector<bool>& rotation, DrivetrainTransientResult& r) {
  const drivetrain::Linearisation& L = r.linearisation;
  static const std::string kForce = "N", kMoment = "N m", kMetre = "m", kRadian = "rad";
  bool moment = false;
  const drivetrain::EquationCombination load = frf_load(model, sys, s.frf_excitation, moment);
  r.frf_load_unit = moment ? kMoment : kForce;
  std::vector<drivetrain::EquationCombination> outputs;
  for (std::size_t j = 0; j < projections.size(); ++j) {
    outputs.push_back({projections[j].second.equations, projections[j].second.coefficients});
    r.frf_outputs.push_back(projections[j].first);
    r.frf_output_units.push_back(rotation[j] ? kRadian : kMetre);
  }
  const std::size_t kept = s.frf_modes > 0
                               ? std::min(L.modes.size(), static_cast<std::size_t>(s.frf_modes))
                               : L.modes.size();
  double f_min = 0.0, f_max = 0.0;
  if (s.frf_band.size() == 2) {
    f_min = units::rad_per_s_to_hz(s.frf_band[0]);
    f_max = units::rad_per_s_to_hz(s.frf_band[1]);
  } else {
    for (std::size_t k = 0; k < kept; ++k)
      f_max = std::max(f_max, 1.25 * L.modes[k].natural_frequency_hz);
    if (!(f_max > 0.0)) f_max = 1.0;
  }
  std::vector<double> f(static_cast<std::size_t>(s.frf_points));
  for (int i = 0; i < s.frf_points; ++i)
    f[static_cast<std::size_t>(i)] = f_min + (f_max - f_min) * i / (s.frf_points - 1.0);
  r.frf = drivetrain::modal_frf(L, load, outputs, f, s.frf_modes, s.frf_static_correction);
  r.has_frf = true;
  if (r.frf.status != Status::Ok || outputs.empty()) return;
  // At the lowest kept mode in the band (its resonance: the sum should hold there), the band's
  // middle and its top.
  for (std::size_t k = 0; k < kept; ++k)
    if (L.modes[k].natural_frequency_hz >= f_min && L.modes[k].natural_frequency_hz <= f_max) {
      r.frf_check_hz.push_back(L.modes[k].natural_frequency_hz);
      break;
    }
  r.frf_check_hz.push_back(0.5 * (f_min + f_max));
  r.frf_check_hz.push_back(f_max);
  const drivetrain::ModalFrf at =
      drivetrain::modal_frf(L, load, outputs, r.frf_check_hz, s.frf_modes, s.frf_static_correction);
  const Eigen::MatrixXcd direct = drivetrain::direct_frf(L, load, outputs, r.frf_check_hz);
  for (Eigen::Index i = 0; i < direct.rows(); ++i) {
    const double ref = direct.row(i).cwiseAbs().maxCoeff();
    r.frf_check_deviation.push_back(
        ref > 0.0 ? (at.receptance.row(i) - direct.row(i)).cwiseAbs().maxCoeff() / ref : 0.0);
  }
}

/// Pairs of sensors on the same node along different directions (translations with
/// translations, rotations with rotations), in the order of [[virtual_sensors]].
std::vector<std::pair<std::size_t, std::size_t>> orbit_pairs(
    const model::Model& model, const std::vector<std::pair<std::string, Projection>>& projections,
    const std::vector<bool>& rotation) {
  auto spec = [&](const std::string& name) {
    return std::find_if(model.virtual_sensors.begin(), model.virtual_sensors.end(),
                        [&](const model::VirtualSensorSpec& v) { return v.name == name; });
  };
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t a = 0; a < projections.size(); ++a)
    for (std::size_t b = a + 1; b < projections.size(); ++b) {
      const auto sa = spec(projections[a].first), sb = spec(projections[b].first);
      if (sa->node != sb->node || rotation[a] != rotation[b]) continue;
      const Projection& pa = projections[a].second;
      const Projection& pb = projections[b].second;
      // Different directions: the projections are not parallel.
      std::map<int, double> ca, cb;
      for (std::size_t k = 0; k < pa.equations.size(); ++k)
        ca[pa.equations[k]] += pa.coefficients[k];
      for (std::size_t k = 0; k < pb.equations.size(); ++k)
        cb[pb.equations[k]] += pb.coefficients[k];
      double dot = 0.0, na = 0.0, nb = 0.0;
      for (const auto& [e, c] : ca) {
        na += c * c;
        if (cb.count(e)) dot += c * cb[e];
      }
      for (const auto& [e, c] : cb) nb += c * c;
      if (na > 0.0 && nb > 0.0 && std::abs(dot) < (1.0 - 1e-9) * std::sqrt(na * nb))
        out.emplace_back(a, b);
    }
  return out;
}

void validate(const model::Model& model, const DrivetrainTransientSettings& s,
              const Context& context) {
  auto fail = [&](const std::string& key, const std::string& expected, const std::string& found) {
    throw context.error(key, expected, found);
  };
  if (!(s.duration > 0.0) || !std::isfinite(s.duration))
    fail("duration", "a positive duration [s]", fmt::format("{}", s.duration));
  if (!(s.sample_rate() > 0.0) || !std::isfinite(s.sample_rate()))
    fail("sample_rate_hz", "a positive sample rate [Hz]", fmt::format("{}", s.sample_rate()));
  if (s.sample_rate() * s.duration < 1.0)
    fail("sample_rate_hz", "at least one sample after t = 0 (sample_rate_hz x duration >= 1)",
         fmt::format("{} Hz x {} s", s.sample_rate(), s.duration));
  if (!(s.spectrum_start >= 0.0 && s.spectrum_start < s.duration))
    fail("spectrum_start", fmt::format("a time in [0, duration = {} s)", s.duration),
         fmt::format("{}", s.spectrum_start));
  for (const auto& name : s.sensors)
    if (std::none_of(model.virtual_sensors.begin(), model.virtual_sensors.end(),
                     [&](const model::VirtualSensorSpec& x) { return x.name == name; }))
      fail("sensors", "names of [[virtual_sensors]] of the model", "'" + name + "'");
  if (model.drivers.empty())
    fail("type", "a model with at least one [[drivers]] entry (what turns the drivetrain)",
         "no drivers");
  if (const auto p = frf_settings_problem(model, s))
    throw context.error(p->key, p->expected, p->found, p->hint);
}

transient::AdaptiveOptions integrator_options(const DrivetrainTransientSettings& s) {
  transient::AdaptiveOptions o;
  o.start_time = 0.0;
  o.end_time = s.duration;
  o.sample_rate = s.sample_rate();
  o.relative_tolerance = s.relative_tolerance;
  o.absolute_tolerance = s.absolute_tolerance;
  o.max_step = std::isnan(s.max_step) ? 1.0 / s.sample_rate() : s.max_step;
  o.rho_infinity = s.rho_infinity;
  return o;
}

/// Initial reference speed: the first speed driver's speed at t = 0 over its node's ratio.
double initial_speed(const model::Model& model, const fe::LinearSystem& sys) {
  for (const model::DriverSpec& d : model.drivers) {
    if (d.kind != model::DriverKind::Speed || d.speeds.empty()) continue;
    const double ratio = sys.dofs.node(sys.dofs.node_index(d.node)).speed_ratio;
    if (ratio != 0.0) return d.speeds.front() / ratio;
  }
  return 0.0;
}

/// The tooth-contact element of every [[gear_meshes]] entry: its pair's force map (or the
/// constant stiffness), backlash, law and the mesh damping.
/// Tooth friction of a mesh whose contact names an external cylindrical pair (the path of
/// contact from its tip geometry, docs/theory.md §16.6); a located error for other pairs.
elements::ToothFriction tooth_friction(const model::Model& m, const model::GearMesh& g,
                                       const std::string& key) {
  const model::MeshContactSpec& c = *g.contact;
  const SourceLocation where = c.where.line > 0 ? c.where : g.where;
  if (c.gear_pair.empty())
    throw InputError(where, key + ".contact.friction",
                     "a contact that names its [[gear_pairs]] entry (gear_pair): the path of "
                     "contact comes from the pair's tip geometry",
                     fmt::format("friction = {} without gear_pair", c.friction),
                     "set gear_pair, or friction = 0");
  const PairModel pm = build_pair_model(m, pair_index(m, c.gear_pair));
  const gear::GearPairGeometry& geo = pm.geometry;
  const bool cylindrical =
      geo.spec.type == gear::GearType::Spur || geo.spec.type == gear::GearType::Helical;
  if (!cylindrical || geo.spec.mesh != gear::MeshType::External)
    throw InputError(where, key + ".contact.friction",
                     "tooth friction on an external spur or helical pair",
                     fmt::format("pair '{}', not an external cylindrical pair", c.gear_pair),
                     "set friction = 0 for bevel, hypoid and internal pairs");
  return elements::spur_tooth_friction(c.friction, c.friction_velocity, geo.pinion.base_radius_m,
                                       geo.wheel.base_radius_m, geo.pinion.tip_radius_m,
                                       geo.wheel.tip_radius_m, geo.centre_distance_m);
}

std::vector<std::shared_ptr<const elements::ForceElement>> mesh_elements(const model::Model& m) {
  std::vector<std::shared_ptr<const elements::ForceElement>> out;
  for (std::size_t i = 0; i < m.gear_meshes.size(); ++i) {
    const model::GearMesh& g = m.gear_meshes[i];
    const std::string key = fmt::format("gear_meshes[{}]", i);
    auto map = std::make_shared<const elements::MeshForceMap>(mesh_force_map(m, i));
    elements::GearMeshContactOptions o;
    o.damping = g.damping;
    SourceLocation where = g.where;
    if (g.contact) {
      where = g.contact->where.line > 0 ? g.contact->where : g.where;
      o.backlash = g.contact->backlash;
      o.vary_stiffness = g.contact->vary_stiffness;
      if (g.contact->friction > 0.0) o.friction = tooth_friction(m, g, key);
      if (g.contact->law)
        o.law = drivetrain::make_contact_law(
            *g.contact->law,
            {g.contact->law->where.line > 0 ? g.contact->law->where : where, key + ".contact.law"});
    }
    out.push_back(std::make_shared<elements::GearMeshContact>(
        g.name, std::move(map), o, elements::LawSource{where, key + ".contact"}));
  }
  return out;
}

void static_rows(const drivetrain::DrivetrainSystem& system, const fe::DofMap& dofs,
                 const Eigen::VectorXd& v0, DrivetrainTransientResult& r) {
  for (const drivetrain::StaticRow& row :
       drivetrain::static_table(system, dofs, 0.0, v0, r.equilibrium, r.held_names)) {
    r.static_rows_element.push_back(row.element);
    r.static_rows_quantity.push_back(row.quantity);
    r.static_rows_unit.push_back(row.unit);
    r.static_rows_value.push_back(row.value);
  }
}

// The order analysis's channels and reference are columns of the record (known once the
// channels are built, before anything is integrated).
void check_order_channels(const DrivetrainTransientSettings& s,
                          const std::vector<DrivetrainChannel>& channels, const Context& context) {
  auto known = [&](const std::string& name) {
    return std::any_of(channels.begin(), channels.end(),
                       [&](const DrivetrainChannel& c) { return c.name == name; });
  };
  std::string angles;
  for (const DrivetrainChannel& c : channels)
    if (c.group == "angle") angles += (angles.empty() ? "" : ", ") + c.name;
  for (const std::string& name : s.order_channels)
    if (!known(name))
      throw context.error("order_channels", "channels of the record (columns of time_history)",
                          "\"" + name + "\"");
  if (!s.order_channels.empty() && !known(s.order_reference))
    throw context.error(
        "order_reference",
        fmt::format("an angle channel of the record ({})",
                    angles.empty() ? "none: no mesh with a spinning gear 1" : angles),
        "\"" + s.order_reference + "\"");
}

}  // namespace

std::optional<SettingsProblem> frf_settings_problem(const model::Model& model,
                                                    const DrivetrainTransientSettings& s) {
  if (!s.frf_band.empty()) {
    const double lo = units::rad_per_s_to_hz(s.frf_band.front());
    const double hi = units::rad_per_s_to_hz(s.frf_band.back());
    if (s.frf_band.size() != 2)
      return SettingsProblem{"frf_band_hz",
                             "two frequencies [f_min, f_max] in Hz",
                             fmt::format("{} values", s.frf_band.size()),
                             {}};
    if (!(lo >= 0.0) || !(hi > lo) || !std::isfinite(hi))
      return SettingsProblem{"frf_band_hz",
                             "a band [f_min, f_max] with 0 <= f_min < f_max",
                             fmt::format("[{:.6g}, {:.6g}]", lo, hi),
                             {}};
  }
  if (s.frf_excitation.empty()) return std::nullopt;
  const bool sensor = std::any_of(model.virtual_sensors.begin(), model.virtual_sensors.end(),
                                  [&](const auto& v) { return v.name == s.frf_excitation; });
  const bool mesh = std::any_of(model.gear_meshes.begin(), model.gear_meshes.end(),
                                [&](const auto& g) { return g.name == s.frf_excitation; });
  if (!sensor && !mesh)
    return SettingsProblem{"frf_excitation",
                           "the name of a [[virtual_sensors]] or [[gear_meshes]] entry",
                           fmt::format("'{}'", s.frf_excitation),
                           "name the sensor at the node and along the direction to excite, or "
                           "the mesh whose force excites"};
  if (sensor && mesh)
    return SettingsProblem{"frf_excitation", "a name that is not both a sensor and a mesh",
                           fmt::format("'{}' names both", s.frf_excitation), "rename one of them"};
  if (model.virtual_sensors.empty())
    return SettingsProblem{"frf_excitation", "a model with [[virtual_sensors]] (the FRF's outputs)",
                           "no virtual sensors", "add a sensor where the response is wanted"};
  if (s.modes == 0)
    return SettingsProblem{
        "modes", "at least 1 with frf_excitation (the FRF sums the modes)", "0", {}};
  if (s.frf_modes > s.modes)
    return SettingsProblem{"frf_modes", fmt::format("at most modes = {}", s.modes),
                           fmt::format("{}", s.frf_modes), "raise modes or lower frf_modes"};
  return std::nullopt;
}

DrivetrainTransientResult run_drivetrain_transient(const model::Model& model,
                                                   const DrivetrainTransientSettings& s,
                                                   const Context& context) {
  const auto started = std::chrono::steady_clock::now();
  validate(model, s, context);
  DrivetrainTransientResult r;
  const model::Model linear_part = drivetrain::without_mesh_springs(model);
  const fe::LinearSystem sys =
      assembly::build_system(linear_part, context.solids(), context.progress());
  drivetrain::BuildOptions bo;
  bo.initial_reference_speed = initial_speed(model, sys);
  bo.mesh_elements = mesh_elements(model);
  drivetrain::DrivetrainSystem system(drivetrain::build_drivetrain(model, sys, bo));
  for (const auto& d : system.parts().speed_drivers)
    r.held_names.push_back("driver '" + d.name + "'");
  for (const auto& m : system.parts().motors)
    r.held_names.push_back("motor '" + m.name + "' (held)");

  Recorder rec;
  std::vector<std::pair<std::string, Projection>> projections;
  std::vector<bool> rotations;
  add_sensor_channels(model, s, sys.dofs, rec, projections, rotations);
  // The sensors' displacement channels come first, three channels per sensor.
  for (const auto& [a, b] : orbit_pairs(model, projections, rotations))
    r.orbits.emplace_back(3 * a, 3 * b);
  add_element_channels(model, sys, system, rec, r.mesh_orders);
  add_drive_channels(system, rec);
  r.channels = rec.channels;
  check_order_channels(s, r.channels, context);
  const double n_samples = std::floor(s.duration * s.sample_rate() + 1e-9) + 2.0;
  if (n_samples * static_cast<double>(rec.channels.size()) > kMaxRecordValues)
    throw context.error(
        "sample_rate_hz",
        fmt::format("a record of at most {:.3g} values (samples x channels)", kMaxRecordValues),
        fmt::format("{:.4g} samples x {} channels", n_samples, rec.channels.size()),
        "lower sample_rate_hz, shorten duration or record fewer sensors");

  // Static equilibrium from the rigid spin at the starting speed.
  const Eigen::VectorXd v0 = drivetrain::rigid_spin(sys, bo.initial_reference_speed);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(system.size());
  if (s.static_start) {
    drivetrain::StaticOptions options;
    options.equation_names = drivetrain::equation_names(sys.dofs);
    r.equilibrium = drivetrain::solve_static(system, 0.0, q, v0, options);
    static_rows(system, sys.dofs, v0, r);
    if (r.equilibrium.status != Status::Ok) {
      r.status = r.equilibrium.status;
      r.message = r.equilibrium.message;
      return r;
    }
    q = r.equilibrium.q;
  }
  if (s.modes > 0) {
    r.linearisation = drivetrain::linearise(system, 0.0, q, v0, s.modes, !s.frf_excitation.empty());
    r.linearised = true;
    if (!s.frf_excitation.empty()) compute_frf(model, sys, s, projections, rotations, r);
    // Mode shapes at the virtual sensors, scaled to 1 at the largest sensor of each mode.
    const auto n_modes = static_cast<Eigen::Index>(r.linearisation.modes.size());
    r.shape_at_sensors.setZero(n_modes, static_cast<Eigen::Index>(projections.size()));
    for (const auto& [name, p] : projections) r.shape_sensors.push_back(name);
    for (Eigen::Index k = 0; k < n_modes; ++k) {
      const Eigen::VectorXcd& x = r.linearisation.modes[static_cast<std::size_t>(k)].shape;
      for (std::size_t j = 0; j < projections.size(); ++j) {
        std::complex<double> sum = 0.0;
        const Projection& p = projections[j].second;
        for (std::size_t i = 0; i < p.equations.size(); ++i)
          sum += p.coefficients[i] * x[p.equations[i]];
        r.shape_at_sensors(k, static_cast<Eigen::Index>(j)) = sum;
      }
      double largest = 0.0;
      std::complex<double> ref = 1.0;
      for (Eigen::Index j = 0; j < r.shape_at_sensors.cols(); ++j)
        if (std::abs(r.shape_at_sensors(k, j)) > largest) {
          largest = std::abs(r.shape_at_sensors(k, j));
          ref = r.shape_at_sensors(k, j);
        }
      if (largest > 0.0) r.shape_at_sensors.row(k) /= ref;
    }
  }

  // Integration with output at the fixed sample rate.
  r.values.resize(static_cast<Eigen::Index>(n_samples),
                  static_cast<Eigen::Index>(rec.channels.size()));
  const int n_events = system.num_events();
  std::vector<long long> closed(static_cast<std::size_t>(n_events), 0);
  Eigen::VectorXd g;
  auto observer = [&](long long, double t, const Eigen::VectorXd& qq, const Eigen::VectorXd& vv,
                      const Eigen::VectorXd& aa) {
    const auto row = static_cast<Eigen::Index>(r.time.size());
    if (row >= r.values.rows()) r.values.conservativeResize(row + 64, r.values.cols());
    for (std::size_t c = 0; c < rec.evaluate.size(); ++c)
      r.values(row, static_cast<Eigen::Index>(c)) = rec.evaluate[c](t, qq, vv, aa);
    r.time.push_back(t);
    if (n_events > 0) {
      system.event_functions(t, qq, vv, g);
      for (int k = 0; k < n_events; ++k)
        if (g[k] > 0.0) ++closed[static_cast<std::size_t>(k)];
    }
  };
  Eigen::VectorXd v = v0;
  const transient::AdaptiveOptions o = integrator_options(s);
  r.integration =
      s.integrator == DrivetrainIntegrator::Ida
          ? transient::integrate_ida(system, o, q, v, observer, context.progress())
          : transient::integrate_adaptive(system, o, q, v, observer, context.progress());
  r.values.conservativeResize(static_cast<Eigen::Index>(r.time.size()), r.values.cols());
  for (int k = 0; k < n_events; ++k) {
    r.switch_names.push_back(system.describe_event(k));
    r.closed_fraction.push_back(r.time.empty()
                                    ? 0.0
                                    : static_cast<double>(closed[static_cast<std::size_t>(k)]) /
                                          static_cast<double>(r.time.size()));
  }
  if (r.integration.status != Status::Ok) {
    r.status = r.integration.status;
    r.message = r.integration.message;
  } else if (r.linearised && r.linearisation.status != Status::Ok) {
    r.status = r.linearisation.status == Status::Unstable ? Status::Unstable : Status::Ok;
  }
  r.run_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace geardyn::analyses
