#pragma once
#include <string_view>

namespace geardyn {

/// Outcome of a numerical step or an analysis. Anything but Ok is reported, never hidden.
enum class Status {
  Ok,            ///< converged / completed
  Unstable,      ///< computed, but the system is unstable (a mode with negative damping), so
                 ///< a "steady state" is not what the machine reaches: physically dangerous
  NotConverged,  ///< an iterative solver stopped at its iteration limit
  FewerModes,    ///< an eigen-solve returned fewer modes than asked for
  Singular,      ///< a matrix that must be invertible was singular
  Diverged,      ///< a time integration or iteration blew up
  Failed         ///< any other failure; the message says what
};

constexpr std::string_view to_string(Status s) {
  switch (s) {
    case Status::Ok:
      return "ok";
    case Status::Unstable:
      return "unstable";
    case Status::NotConverged:
      return "not_converged";
    case Status::FewerModes:
      return "fewer_modes";
    case Status::Singular:
      return "singular";
    case Status::Diverged:
      return "diverged";
    case Status::Failed:
      return "failed";
  }
  return "failed";
}

/// Rank of a status for combining the outcomes of several solves: the worse one wins
/// (Ok < Unstable < NotConverged < FewerModes < Diverged < Singular < Failed).
constexpr int severity(Status s) {
  switch (s) {
    case Status::Ok:
      return 0;
    case Status::Unstable:
      return 1;
    case Status::NotConverged:
      return 2;
    case Status::FewerModes:
      return 3;
    case Status::Diverged:
      return 4;
    case Status::Singular:
      return 5;
    case Status::Failed:
      return 6;
  }
  return 6;
}

/// The worse of two statuses.
constexpr Status worse(Status a, Status b) { return severity(b) > severity(a) ? b : a; }

}  // namespace geardyn
