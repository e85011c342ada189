#include "geardyn/transient/ida_integrator.hpp"

#include <fmt/format.h>
#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "geardyn/transient/run_input.hpp"
#include "geardyn/transient/tangent_solver.hpp"

namespace geardyn::transient {

namespace {

// --- RAII for the SUNDIALS objects (freed on every path, in reverse order of creation) ---------

struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {  // content is not owned: free the shell only
  void operator()(SUNMatrix m) const { SUNMatFreeEmpty(m); }
};
struct LinearSolverDeleter {  // content is not owned: free the shell only
  void operator()(SUNLinearSolver s) const { SUNLinSolFreeEmpty(s); }
};
struct IdaDeleter {
  void operator()(void* mem) const { IDAFree(&mem); }
};
using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr =
    std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using IdaPtr = std::unique_ptr<void, IdaDeleter>;

std::string flag_name(int flag) {
  char* name = IDAGetReturnFlagName(flag);
  std::string s = name ? name : fmt::format("IDA flag {}", flag);
  std::free(name);
  return s;
}

Eigen::Map<Eigen::VectorXd> view(N_Vector x, int n, int offset) {
  return {N_VGetArrayPointer(x) + offset, n};
}

// Everything the C callbacks see (IDA's user data and the linear solver's content). No C++
// exception leaves a callback: it is caught, kept here and turned into a failure code.
struct IdaProblem {
  IdaProblem(SecondOrderSystem& s, int size)
      : system(s), n(size), q(size), v(size), a(size), r(size), bq(size), rhs(size), xq(size) {}

  SecondOrderSystem& system;
  int n;
  Eigen::VectorXd q, v, a, r, g;  // work vectors of the callbacks

  // The iteration matrix: the point of IDA's last Jacobian request, its factor, and the sparse
  // and low-rank parts of C_t + c_j M at that point.
  double t_jac = 0.0, cj = 0.0;
  Eigen::VectorXd q_jac, v_jac;
  TangentSolver solver;
  SparseMatrix damping_mass;
  Eigen::MatrixXd low_rank_u;
  Eigen::VectorXd low_rank_d;
  Eigen::VectorXd bq, rhs, xq;

  long long factorizations = 0;
  long long residual_evaluations = 0;
  std::string callback_error;  // first exception from a callback (with its time)
  std::string solver_failure;  // last singular factorisation
  double non_finite_time = AdaptiveOptions::kNaN;  // last time the residual was not finite
  std::string ida_message;                         // IDA's last error message

  void load_state(N_Vector y) {
    q = view(y, n, 0);
    v = view(y, n, n);
  }
  void keep_exception(const char* where, double t) {
    if (!callback_error.empty()) return;
    try {
      throw;
    } catch (const std::exception& e) {
      callback_error = fmt::format("{} at t = {:.9g} s threw: {}", where, t, e.what());
    } catch (...) {
      callback_error = fmt::format("{} at t = {:.9g} s threw an unknown exception", where, t);
    }
  }
};

IdaProblem& problem_of(void* user_data) { return *static_cast<IdaProblem*>(user_data); }

// F = [q' - v; r(t, q, v, v')]. A non-finite r is a recoverable failure (IDA retries with a
// smaller step: a contact driven too deep in one step may overflow).
int residual_callback(realtype t, N_Vector y, N_Vector yp, N_Vector rr, void* user_data) {
  IdaProblem& p = problem_of(user_data);
  try {
    p.load_state(y);
    p.a = view(yp, p.n, p.n);
    ++p.residual_evaluations;
    p.system.residual(t, p.q, p.v, p.a, p.r);
    if (p.r.size() != p.n)
      throw std::runtime_error(
          fmt::format("the residual has size {}, the system {} unknowns", p.r.size(), p.n));
    view(rr, p.n, 0) = view(yp, p.n, 0) - p.v;
    view(rr, p.n, p.n) = p.r;
    if (!p.r.allFinite()) {
      p.non_finite_time = t;
      return 1;
    }
    return 0;
  } catch (...) {
    p.keep_exception("the residual", t);
    return -1;
  }
}

int event_callback(realtype t, N_Vector y, N_Vector /*yp*/, realtype* gout, void* user_data) {
  IdaProblem& p = problem_of(user_data);
  try {
    p.load_state(y);
    p.system.event_functions(t, p.q, p.v, p.g);
    const int m = p.system.num_events();
    if (p.g.size() != m)
      throw std::runtime_error(
          fmt::format("event_functions returned {} values, num_events() is {}", p.g.size(), m));
    std::copy(p.g.data(), p.g.data() + m, gout);
    return 0;
  } catch (...) {
    p.keep_exception("the event functions", t);
    return -1;
  }
}

// IDA's Jacobian request: only the point (t, c_j, q, v) is kept; the linear solver's setup,
// which IDA calls right after, assembles and factorises there.
int jacobian_callback(realtype t, realtype cj, N_Vector y, N_Vector /*yp*/, N_Vector /*r*/,
                      SUNMatrix /*J*/, void* user_data, N_Vector, N_Vector, N_Vector) {
  IdaProblem& p = problem_of(user_data);
  p.t_jac = t;
  p.cj = cj;
  p.q_jac = view(y, p.n, 0);
  p.v_jac = view(y, p.n, p.n);
  return 0;
}

void error_callback(int code, const char* /*module*/, const char* function, char* msg,
                    void* user_data) {
  if (code < 0) problem_of(user_data).ida_message = fmt::format("{} ({})", msg, function);
}

// --- The linear solver (SUNDIALS "direct" type: IDA calls setup when it wants a new matrix and
// scales the solution for a changed c_j itself) and its placeholder matrix. --------------------

IdaProblem& problem_of(SUNLinearSolver s) { return *static_cast<IdaProblem*>(s->content); }

SUNLinearSolver_Type solver_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID solver_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }
SUNMatrix_ID matrix_id(SUNMatrix) { return SUNMATRIX_CUSTOM; }
int matrix_zero(SUNMatrix) { return 0; }

// Factorises the Schur complement S = c_j^2 M + c_j C_t + K_t (+ its low-rank part) at IDA's
// Jacobian point and keeps C_t + c_j M (sparse + low-rank) for the right-hand sides.
int solver_setup(SUNLinearSolver s, SUNMatrix) {
  IdaProblem& p = problem_of(s);
  try {
    const double cj = p.cj;
    SparseMatrix S;
    p.system.tangent(p.t_jac, p.q_jac, p.v_jac, cj * cj, cj, 1.0, S);
    Eigen::MatrixXd U;
    Eigen::VectorXd d;
    ++p.factorizations;
    const bool low_rank =
        p.system.tangent_low_rank(p.t_jac, p.q_jac, p.v_jac, cj * cj, cj, 1.0, U, d) &&
        U.cols() > 0;
    if (!(low_rank ? p.solver.factorize(S, U, d) : p.solver.factorize(S))) {
      p.solver_failure =
          fmt::format("at t = {:.9g} s, c_j = {:.6g}: {}", p.t_jac, cj, p.solver.failure());
      return SUNLS_PACKAGE_FAIL_REC;
    }
    p.system.tangent(p.t_jac, p.q_jac, p.v_jac, cj, 1.0, 0.0, p.damping_mass);
    if (!p.system.tangent_low_rank(p.t_jac, p.q_jac, p.v_jac, cj, 1.0, 0.0, p.low_rank_u,
                                   p.low_rank_d)) {
      p.low_rank_u.resize(p.n, 0);
      p.low_rank_d.resize(0);
    }
    return SUNLS_SUCCESS;
  } catch (...) {
    p.keep_exception("the tangent", p.t_jac);
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

// Solves [[c_j I, -I], [K_t, C_t + c_j M]] (x_q, x_v) = (b_q, b_v). The first block row gives
// x_v = c_j x_q - b_q exactly (its v-block is -I); substituted into the second,
//   (c_j^2 M + c_j C_t + K_t) x_q = b_v + (C_t + c_j M) b_q.
// No term is dropped, so the Schur form is the exact solution of IDA's 2n x 2n system with half
// the unknowns and the same tangent the generalised-alpha integrator factorises.
int solver_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, realtype /*tol*/) {
  IdaProblem& p = problem_of(s);
  try {
    p.bq = view(b, p.n, 0);
    p.rhs = view(b, p.n, p.n);
    p.rhs += p.damping_mass * p.bq;
    if (p.low_rank_u.cols() > 0)
      p.rhs += p.low_rank_u * p.low_rank_d.cwiseProduct(p.low_rank_u.transpose() * p.bq);
    p.solver.solve(p.rhs, p.xq);
    view(x, p.n, 0) = p.xq;
    view(x, p.n, p.n) = p.cj * p.xq - p.bq;
    return p.xq.allFinite() ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
  } catch (...) {
    p.keep_exception("the linear solve", p.t_jac);
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

// --- The run ------------------------------------------------------------------------------------

// Output times t_0 + k / sample_rate <= t_end, and t_end itself when it is not one of them.
class SampleSchedule {
 public:
  SampleSchedule(double t0, double t_end, double rate) : t0_(t0), t_end_(t_end), rate_(rate) {
    last_regular_ = static_cast<long long>(std::floor((t_end - t0) * rate));
    while (regular(last_regular_ + 1) <= t_end) ++last_regular_;
    while (last_regular_ > 0 && regular(last_regular_) > t_end) --last_regular_;
    count_ = last_regular_ + 1 + (regular(last_regular_) < t_end ? 1 : 0);
  }
  long long count() const { return count_; }
  double time(long long k) const { return k <= last_regular_ ? regular(k) : t_end_; }

 private:
  double regular(long long k) const { return t0_ + static_cast<double>(k) / rate_; }
  double t0_, t_end_, rate_;
  long long last_regular_ = 0, count_ = 0;
};

class IdaRun {
 public:
  IdaRun(SecondOrderSystem& system, const AdaptiveOptions& options, const SampleObserver& observer,
         Progress& progress)
      : options_(options),
        observer_(observer),
        progress_(progress),
        problem_(system, system.size()),
        n_(system.size()),
        schedule_(options.start_time, options.end_time, options.sample_rate),
        h_max_(std::isnan(options.max_step) ? 1.0 / options.sample_rate : options.max_step) {}

  AdaptiveSummary run(Eigen::VectorXd& q, Eigen::VectorXd& v);

 private:
  bool create(const Eigen::VectorXd& q, const Eigen::VectorXd& v);
  bool ok(int flag, const char* call);
  bool consistent_start(double t);
  void deliver_samples(double t_reached);
  void accept(double t);
  void count_steps();
  void accumulate_counters();
  bool count_roots();
  bool restart(double t_root);
  void fail(int flag, const std::string& what);
  void fail(Status status, const std::string& message);

  const AdaptiveOptions& options_;
  const SampleObserver& observer_;
  Progress& progress_;
  IdaProblem problem_;  // before the SUNDIALS objects, which refer to it
  int n_;
  SampleSchedule schedule_;
  double h_max_;

  ContextPtr context_;
  VectorPtr y_, yp_, y_sample_, yp_sample_;
  MatrixPtr matrix_;
  LinearSolverPtr solver_;
  IdaPtr ida_;

  AdaptiveSummary summary_;
  long long next_sample_ = 0;
  long long steps_before_restart_ = 0;  // IDAReInit resets IDA's counters
  long steps_seen_ = 0;                 // IDA's step count since the last (re)start
  Eigen::VectorXd q_, v_, a_;           // last accepted state
  double t_ = 0.0;
};

bool IdaRun::ok(int flag, const char* call) {
  if (flag >= 0) return true;
  fail(flag, call);
  return false;
}

bool IdaRun::create(const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0 || !ctx) {
    fail(Status::Failed, "SUNContext_Create failed");
    return false;
  }
  context_.reset(ctx);
  for (VectorPtr* x : {&y_, &yp_, &y_sample_, &yp_sample_})
    x->reset(N_VNew_Serial(static_cast<sunindextype>(2 * n_), ctx));
  VectorPtr id(N_VNew_Serial(static_cast<sunindextype>(2 * n_), ctx));
  VectorPtr atol(N_VNew_Serial(static_cast<sunindextype>(2 * n_), ctx));
  matrix_.reset(SUNMatNewEmpty(ctx));
  solver_.reset(SUNLinSolNewEmpty(ctx));
  ida_.reset(IDACreate(ctx));
  if (!y_ || !yp_ || !y_sample_ || !yp_sample_ || !id || !atol || !matrix_ || !solver_ || !ida_) {
    fail(Status::Failed, "SUNDIALS could not allocate its vectors or IDA's memory");
    return false;
  }
  matrix_->ops->getid = matrix_id;
  matrix_->ops->zero = matrix_zero;
  solver_->content = &problem_;
  solver_->ops->gettype = solver_type;
  solver_->ops->getid = solver_id;
  solver_->ops->setup = solver_setup;
  solver_->ops->solve = solver_solve;

  view(y_.get(), n_, 0) = q;
  view(y_.get(), n_, n_) = v;
  view(yp_.get(), n_, 0) = v;  // q' = v; v' is made consistent by IDACalcIC
  view(yp_.get(), n_, n_).setZero();
  N_VConst(1.0, id.get());  // every unknown is differential
  view(atol.get(), n_, 0).setConstant(options_.absolute_tolerance);
  view(atol.get(), n_, n_).setConstant(options_.absolute_tolerance / h_max_);

  void* mem = ida_.get();
  if (!ok(IDASetErrHandlerFn(mem, error_callback, &problem_), "IDASetErrHandlerFn") ||
      !ok(IDASetUserData(mem, &problem_), "IDASetUserData") ||
      !ok(IDAInit(mem, residual_callback, options_.start_time, y_.get(), yp_.get()), "IDAInit") ||
      !ok(IDASVtolerances(mem, options_.relative_tolerance, atol.get()), "IDASVtolerances") ||
      !ok(IDASetLinearSolver(mem, solver_.get(), matrix_.get()), "IDASetLinearSolver") ||
      !ok(IDASetJacFn(mem, jacobian_callback), "IDASetJacFn") ||
      !ok(IDASetId(mem, id.get()), "IDASetId") ||
      !ok(IDASetMaxStep(mem, h_max_), "IDASetMaxStep") ||
      !ok(IDASetMinStep(mem, options_.min_step), "IDASetMinStep") ||
      !ok(IDASetStopTime(mem, options_.end_time), "IDASetStopTime") ||
      !ok(IDASetInitStep(mem, std::isnan(options_.initial_step) ? 0.0 : options_.initial_step),
          "IDASetInitStep"))
    return false;
  const int events = options_.locate_events ? problem_.system.num_events() : 0;
  if (events > 0) {
    if (!ok(IDARootInit(mem, events, event_callback), "IDARootInit") ||
        !ok(IDASetNoInactiveRootWarn(mem), "IDASetNoInactiveRootWarn"))
      return false;
  }
  return true;
}

// Consistent v' at t with q, v fixed (IDA_YA_YDP_INIT with every unknown differential).
bool IdaRun::consistent_start(double t) {
  if (!ok(IDACalcIC(ida_.get(), IDA_YA_YDP_INIT, t + h_max_),
          "IDACalcIC (the consistent acceleration)"))
    return false;
  if (!ok(IDAGetConsistentIC(ida_.get(), y_.get(), yp_.get()), "IDAGetConsistentIC")) return false;
  accept(t);
  return true;
}

void IdaRun::accept(double t) {
  t_ = t;
  q_ = view(y_.get(), n_, 0);
  v_ = view(y_.get(), n_, n_);
  a_ = view(yp_.get(), n_, n_);
  summary_.end_time = t;
}

// Every sample at or before t_reached (the current IDA state), from IDA's interpolant.
void IdaRun::deliver_samples(double t_reached) {
  while (next_sample_ < schedule_.count() && schedule_.time(next_sample_) <= t_reached) {
    const double ts = schedule_.time(next_sample_);
    N_Vector y = y_.get(), yp = yp_.get();
    if (ts != t_reached) {
      if (IDAGetDky(ida_.get(), ts, 0, y_sample_.get()) < 0 ||
          IDAGetDky(ida_.get(), ts, 1, yp_sample_.get()) < 0)
        throw std::logic_error(fmt::format("IDAGetDky failed at sample time {} s", ts));
      y = y_sample_.get();
      yp = yp_sample_.get();
    }
    if (observer_) {
      const Eigen::VectorXd qs = view(y, n_, 0), vs = view(y, n_, n_), as = view(yp, n_, n_);
      observer_(next_sample_, ts, qs, vs, as);
    }
    ++next_sample_;
    summary_.samples = next_sample_;
    progress_.update(static_cast<std::size_t>(next_sample_));
  }
}

void IdaRun::count_steps() {
  long nst = 0;
  IDAGetNumSteps(ida_.get(), &nst);
  if (nst > steps_seen_) {
    realtype h = 0.0;
    IDAGetLastStep(ida_.get(), &h);
    if (!(summary_.min_step_taken <= h)) summary_.min_step_taken = h;
    if (!(summary_.max_step_taken >= h)) summary_.max_step_taken = h;
    steps_seen_ = nst;
  }
  summary_.steps = steps_before_restart_ + steps_seen_;
}

// Adds IDA's counters since the last (re)start to the summary (before IDAReInit resets them).
void IdaRun::accumulate_counters() {
  long nst = 0, netf = 0, ncfn = 0, nni = 0;
  IDAGetNumSteps(ida_.get(), &nst);
  IDAGetNumErrTestFails(ida_.get(), &netf);
  IDAGetNumNonlinSolvConvFails(ida_.get(), &ncfn);
  IDAGetNumNonlinSolvIters(ida_.get(), &nni);
  steps_before_restart_ += nst;
  steps_seen_ = 0;
  summary_.steps = steps_before_restart_;
  summary_.rejected_error += netf;
  summary_.rejected_newton += ncfn;
  summary_.newton_iterations += nni;
}

// The event functions that changed sign at the root IDA located.
bool IdaRun::count_roots() {
  std::vector<int> found(static_cast<std::size_t>(problem_.system.num_events()), 0);
  if (!ok(IDAGetRootInfo(ida_.get(), found.data()), "IDAGetRootInfo")) return false;
  summary_.events += std::count_if(found.begin(), found.end(), [](int f) { return f != 0; });
  return true;
}

// Restarts IDA at a located event (order 1, consistent acceleration), so that its BDF history
// does not span the discontinuity.
bool IdaRun::restart(double t_root) {
  accumulate_counters();
  if (!ok(IDAReInit(ida_.get(), t_root, y_.get(), yp_.get()), "IDAReInit") ||
      !ok(IDASetStopTime(ida_.get(), options_.end_time), "IDASetStopTime"))
    return false;
  return consistent_start(t_root);
}

AdaptiveSummary IdaRun::run(Eigen::VectorXd& q, Eigen::VectorXd& v) {
  summary_.integrator = "ida";
  summary_.end_time = options_.start_time;
  q_ = q;
  v_ = v;
  t_ = options_.start_time;
  progress_.start("time integration (ida)", static_cast<std::size_t>(schedule_.count()));
  if (create(q, v) && consistent_start(options_.start_time)) {
    deliver_samples(options_.start_time);
    const double t_end = options_.end_time;
    // The end is reached when t is t_end to round-off (IDA's stop time or a root there).
    const double t_close =
        4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_end));
    while (summary_.status == Status::Ok) {
      realtype t_ret = t_;
      const int flag = IDASolve(ida_.get(), t_end, &t_ret, y_.get(), yp_.get(), IDA_ONE_STEP);
      if (!ok(flag, "IDASolve")) break;
      count_steps();
      deliver_samples(t_ret);
      accept(t_ret);
      problem_.system.commit_step(t_, q_, v_, a_);
      if (flag == IDA_ROOT_RETURN && !count_roots()) break;
      if (t_end - t_ret <= t_close) {
        deliver_samples(t_end);  // an end sample within round-off of t_ret
        break;
      }
      if (flag == IDA_ROOT_RETURN && !restart(t_ret)) break;
      if (summary_.steps >= options_.max_steps) {
        fail(Status::Failed,
             fmt::format("IDA took max_steps = {} steps and reached t = {:.9g} s of {:.9g} s; "
                         "raise max_steps or loosen the tolerances",
                         options_.max_steps, t_, t_end));
        break;
      }
    }
  }
  if (ida_) accumulate_counters();
  summary_.factorizations = problem_.factorizations;
  summary_.residual_evaluations = problem_.residual_evaluations;
  summary_.solver = problem_.solver.ok() ? problem_.solver.description() : "none";
  q = q_;
  v = v_;
  progress_.finish();
  return summary_;
}

void IdaRun::fail(Status status, const std::string& message) {
  if (summary_.status != Status::Ok) return;  // the first failure is the one reported
  summary_.status = status;
  summary_.message = message;
}

// IDA's flag, the time reached and what the callbacks, the tangent solver, IDA and the system
// say about it.
void IdaRun::fail(int flag, const std::string& what) {
  const IdaProblem& p = problem_;
  Status status = Status::Failed;
  if (flag == IDA_ERR_FAIL || flag == IDA_CONV_FAIL) status = Status::Diverged;
  if (flag == IDA_REP_RES_ERR && !std::isnan(p.non_finite_time)) status = Status::Diverged;
  if (flag == IDA_LSETUP_FAIL && !p.solver_failure.empty()) status = Status::Singular;
  std::string m = fmt::format("{} failed with {} at t = {:.9g} s", what, flag_name(flag), t_);
  if (!std::isnan(summary_.max_step_taken))
    m += fmt::format(" (steps from {:.3g} s to {:.3g} s)", summary_.min_step_taken,
                     summary_.max_step_taken);
  if (!p.callback_error.empty()) m += "; " + p.callback_error;
  if (!std::isnan(p.non_finite_time))
    m += fmt::format("; the residual was not finite at t = {:.9g} s", p.non_finite_time);
  if (status == Status::Singular) m += "; singular iteration matrix " + p.solver_failure;
  if (!p.ida_message.empty()) m += "; IDA: " + p.ida_message;
  if (const std::string state = p.system.describe_state(t_, q_, v_); !state.empty())
    m += "; state: " + state;
  fail(status, m);
}

}  // namespace

AdaptiveSummary integrate_ida(SecondOrderSystem& system, const AdaptiveOptions& options,
                              Eigen::VectorXd& q, Eigen::VectorXd& v,
                              const SampleObserver& observer, Progress& progress) {
  detail::check_run_input(system, options.validate(), "invalid integrator options", q, v);
  IdaRun run(system, options, observer, progress);
  return run.run(q, v);
}

}  // namespace geardyn::transient
