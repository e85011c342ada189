#include "geardyn/elements/gap_contact.hpp"

#include <cmath>
#include <utility>

#include "geardyn/elements/parameter_check.hpp"

namespace geardyn::elements {

namespace {

using detail::format_number;

void check_side(const std::optional<GapContact::Side>& side, const detail::ParameterCheck& c) {
  if (!side) return;
  c.require(std::isfinite(side->position), "gap", "a finite gap [m]", side->position);
  if (!side->law) c.fail("law", "a contact law", "none");
}

}  // namespace

GapContact::GapContact(std::string name, std::optional<Side> upper, std::optional<Side> lower,
                       const LawSource& source)
    : name_(std::move(name)), upper_(std::move(upper)), lower_(std::move(lower)) {
  const detail::ParameterCheck c(source.location, source.key_path);
  if (!upper_ && !lower_) c.fail("law", "a contact on at least one side", "none");
  check_side(upper_, c);
  check_side(lower_, c);
  if (upper_ && lower_ && lower_->position > upper_->position)
    c.fail("gap", "the lower contact position <= the upper one",
           format_number(lower_->position) + " > " + format_number(upper_->position));
}

GapContact GapContact::stop(std::string name, double gap, std::shared_ptr<const ContactLaw> law,
                            const LawSource& source) {
  return GapContact(std::move(name), Side{gap, std::move(law)}, std::nullopt, source);
}

GapContact GapContact::end_play(std::string name, double b, std::shared_ptr<const ContactLaw> upper,
                                std::shared_ptr<const ContactLaw> lower, const LawSource& source) {
  if (!(std::isfinite(b) && b >= 0.0))
    detail::ParameterCheck(source.location, source.key_path)
        .fail("backlash", "a finite half play >= 0 [m]", b);
  return GapContact(std::move(name), Side{b, std::move(upper)}, Side{-b, std::move(lower)}, source);
}

void GapContact::evaluate(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double,
                          ElementForce& out) const {
  out.reset(1);
  if (upper_ && u(0) > upper_->position) {
    const ContactForce f = upper_->law->evaluate(u(0) - upper_->position, v(0));
    out.force(0) = f.force;
    out.stiffness(0, 0) = f.d_penetration;
    out.damping(0, 0) = f.d_rate;
  } else if (lower_ && u(0) < lower_->position) {
    const ContactForce f = lower_->law->evaluate(lower_->position - u(0), -v(0));
    out.force(0) = -f.force;
    out.stiffness(0, 0) = f.d_penetration;
    out.damping(0, 0) = f.d_rate;
  }
}

std::string GapContact::describe() const {
  std::string s = "contact '" + name_ + "' (";
  if (upper_ && lower_) {
    s += "two-sided, closes at u > " + format_number(upper_->position) +
         " m: " + upper_->law->describe() + "; at u < " + format_number(lower_->position) +
         " m: " + lower_->law->describe();
  } else if (upper_) {
    s += "stop at u > " + format_number(upper_->position) + " m: " + upper_->law->describe();
  } else {
    s += "stop at u < " + format_number(lower_->position) + " m: " + lower_->law->describe();
  }
  return s + ")";
}

int GapContact::num_switches() const { return (upper_ ? 1 : 0) + (lower_ ? 1 : 0); }

void GapContact::switches(const Eigen::VectorXd& u, double, double* g) const {
  int k = 0;
  if (upper_) g[k++] = u(0) - upper_->position;
  if (lower_) g[k] = lower_->position - u(0);
}

std::string GapContact::describe_switch(int k) const {
  return upper_ && k == 0 ? "upper side" : "lower side";
}

}  // namespace geardyn::elements
