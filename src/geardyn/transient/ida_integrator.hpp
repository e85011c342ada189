#pragma once
// SUNDIALS IDA (variable-order, variable-step BDF for implicit DAEs; A. C. Hindmarsh et al.,
// "SUNDIALS: Suite of nonlinear and differential/algebraic equation solvers", ACM TOMS 31 (2005)
// 363-396) on the first-order form of a SecondOrderSystem, with geardyn's sparse tangent solver
// as its linear solver (docs/theory.md §16.8). It shares its options, summary and sample
// observer with the generalised-alpha integrator (adaptive.hpp) so that both can be run side by
// side on the same system.
//
// Unknowns y = (q, v), y' = (q', v'); residual F(t, y, y') = [q' - v; r(t, q, v, v')]. IDA's
// Newton matrix dF/dy + c_j dF/dy' is solved exactly through its Schur complement on q:
//   (c_j^2 M + c_j C_t + K_t) x_q = b_v + (C_t + c_j M) b_q,   x_v = c_j x_q - b_q,
// factorised once per IDA setup call (TangentSolver, Woodbury for a low-rank part).
//
// Behaviour:
//   * Error control: IDA's weighted RMS norm over all 2n unknowns with the scalar
//     relative_tolerance, absolute_tolerance on q and absolute_tolerance / h_max on v (h_max =
//     max_step, or 1 / sample_rate): a velocity error that moves q by absolute_tolerance within
//     one longest step.
//   * The initial acceleration is made consistent by IDACalcIC (q, v held fixed).
//   * IDA is driven one internal step at a time: the system's commit_step is called with every
//     accepted state; samples at t_0 + k / sample_rate (and t_end) are IDA's interpolant
//     (IDAGetDky) at those times, a from its y'. IDA never steps beyond end_time (stop time).
//   * Events (locate_events and num_events() > 0): IDA's root finding on the event functions
//     (to round-off in t; event_tolerance is not used). At a root IDA is restarted there (order
//     1, consistent acceleration recomputed) so that its BDF history does not span the
//     discontinuity.
//   * Failures (IDA return < 0, a singular iteration matrix, a non-finite residual, an exception
//     from the system) end the run with a status and a message naming IDA's flag, the time
//     reached and the system's describe_state; the samples before it were delivered. q and v
//     hold the last accepted state.
// No global state: every call has its own SUNDIALS context and IDA memory.
#include <Eigen/Dense>

#include "geardyn/core/progress.hpp"
#include "geardyn/transient/adaptive.hpp"
#include "geardyn/transient/second_order_system.hpp"

namespace geardyn::transient {

/// Integrates `system` from (q, v) at options.start_time to options.end_time with IDA. Throws
/// std::invalid_argument for invalid options or initial vectors of the wrong size. Reports
/// progress per sample.
AdaptiveSummary integrate_ida(SecondOrderSystem& system, const AdaptiveOptions& options,
                              Eigen::VectorXd& q, Eigen::VectorXd& v,
                              const SampleObserver& observer, Progress& progress);

}  // namespace geardyn::transient
