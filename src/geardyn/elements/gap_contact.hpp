#pragma once
// A contact between two nodes along one direction (n = 1): an end stop, or end play / backlash
// with a contact on each side and a dead zone between (rattle, gear backlash without the mesh
// stiffness). docs/theory.md §16.2.
//
// With u = (end j) - (end i) along the direction and v = du/dt:
//   * the upper side closes when u > upper: penetration delta = u - upper, rate v, force +F;
//   * the lower side closes when u < lower: penetration delta = lower - u, rate -v, force -F;
// F is that side's ContactLaw. Both tangents are + dF/d delta and + dF/d delta_dot on either
// side (the two sign changes cancel). A side may be absent (a one-sided stop).
#include <memory>
#include <optional>
#include <string>

#include "geardyn/elements/contact_law.hpp"
#include "geardyn/elements/force_element.hpp"

namespace geardyn::elements {

class GapContact final : public ForceElement {
 public:
  /// One side of the contact: where it closes [m] and its law.
  struct Side {
    double position = 0.0;
    std::shared_ptr<const ContactLaw> law;
  };

  /// General form: at least one side; lower.position <= upper.position when both are given.
  /// Bad geometry throws InputError at `source` (keys `<key_path>.gap`, `.law`).
  GapContact(std::string name, std::optional<Side> upper, std::optional<Side> lower,
             const LawSource& source = {});

  /// One-sided stop: contact when u > gap (gap may be negative: an interference fit).
  static GapContact stop(std::string name, double gap, std::shared_ptr<const ContactLaw> law,
                         const LawSource& source = {});
  /// End play / backlash: contacts at u > +b (law `upper`) and u < -b (law `lower`), b >= 0
  /// (key `<key_path>.backlash`), dead zone between.
  static GapContact end_play(std::string name, double b, std::shared_ptr<const ContactLaw> upper,
                             std::shared_ptr<const ContactLaw> lower, const LawSource& source = {});

  Eigen::Index size() const override { return 1; }
  void evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double t,
                ElementForce& out) const override;
  std::string describe() const override;
  /// One switch per side: u - upper (upper side), lower - u (lower side); > 0 closed.
  int num_switches() const override;
  void switches(const Eigen::VectorXd& u, double t, double* g) const override;
  std::string describe_switch(int k) const override;

 private:
  std::string name_;
  std::optional<Side> upper_, lower_;
};

}  // namespace geardyn::elements
