#include "core/integrator.h"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <Eigen/Core>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <utility>

#include "core/block_solver.h"
#include "core/error.h"
#include "core/fast_kernels.h"
#include "core/format.h"

namespace moorsim {

static_assert(sizeof(sunindextype) == sizeof(int64_t), "SUNDIALS built with 64-bit indices");

IntegratorStats& IntegratorStats::operator+=(const IntegratorStats& o) {
  steps += o.steps;
  rhs_evals += o.rhs_evals;
  jacobian_evals += o.jacobian_evals;
  linear_setups += o.linear_setups;
  newton_iterations += o.newton_iterations;
  newton_failures += o.newton_failures;
  error_test_failures += o.error_test_failures;
  stability_order_reductions += o.stability_order_reductions;
  last_step = o.last_step;
  last_order = o.last_order;
  rhs_seconds += o.rhs_seconds;
  jacobian_seconds += o.jacobian_seconds;
  linear_setup_seconds += o.linear_setup_seconds;
  linear_solve_seconds += o.linear_solve_seconds;
  return *this;
}

namespace {

void Check(int flag, const char* call) {
  if (flag < 0) {
    std::ostringstream msg;
    msg << "SUNDIALS call " << call << " failed with flag " << flag;
    throw Error(msg.str());
  }
}

template <typename T>
T* CheckPtr(T* p, const char* call) {
  if (p == nullptr) throw Error(std::string("SUNDIALS call ") + call + " returned null");
  return p;
}

// A state vector with the fast element-wise kernels installed (clones inherit them).
N_Vector MakeStateVector(int n, SUNContext ctx) {
  N_Vector v = N_VNew_Serial(n, ctx);
  if (v == nullptr) throw Error("SUNDIALS call N_VNew_Serial returned null");
  internal::InstallFastSerialOps(v);
  return v;
}

}  // namespace

// Named, not anonymous: Integrator::Impl holds a pointer to it (a class with linkage must not
// hold a type of an anonymous namespace once unity builds put this file into another).
namespace internal {

// CVODE's view of BorderedBlockSolver: a direct SUNLinearSolver whose matrix CVODE never
// forms. The integrator's linear-system function (CVodeSetLinSysFn, Impl::LinSys) keeps the
// Jacobian's values here, re-evaluated only when CVODE asks for a new Jacobian, and the
// gamma of M = I - gamma J; setup factors M from them, solve back-substitutes. This saves
// CVODE's copy of the saved Jacobian into the sparse matrix and its scale-add-identity pass
// at every setup (7 % of a coupled run). Exceptions never cross into CVODE.
struct BlockSolverContent {
  BorderedBlockSolver solver;
  std::vector<double> jacobian;  // values in the pattern's order
  double gamma = 0.0;
  long jacobian_evals = 0;
  sunindextype last_flag = 0;
};

}  // namespace internal

namespace {

using internal::BlockSolverContent;

BlockSolverContent& Content(SUNLinearSolver S) {
  return *static_cast<BlockSolverContent*>(S->content);
}

int BlockSetup(SUNLinearSolver S, SUNMatrix) {
  BlockSolverContent& c = Content(S);
  try {
    // A singular or non-finite pivot: recoverable, CVODE retries with a smaller step.
    c.last_flag = c.solver.Factor(c.jacobian.data(), c.gamma) ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
  } catch (const std::exception&) {
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  return static_cast<int>(c.last_flag);
}

int BlockSolve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
  BlockSolverContent& c = Content(S);
  c.solver.Solve(N_VGetArrayPointer(b), N_VGetArrayPointer(x));
  c.last_flag = SUNLS_SUCCESS;
  return SUNLS_SUCCESS;
}

SUNLinearSolver MakeBlockLinearSolver(const SparsityPattern& pattern,
                                      const BlockStructure& structure, SUNContext ctx) {
  auto content = std::make_unique<BlockSolverContent>(BlockSolverContent{
      BorderedBlockSolver(pattern, structure), std::vector<double>(pattern.nnz(), 0.0)});
  SUNLinearSolver S = CheckPtr(SUNLinSolNewEmpty(ctx), "SUNLinSolNewEmpty");
  S->content = content.release();
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  S->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  S->ops->initialize = [](SUNLinearSolver) { return static_cast<int>(SUNLS_SUCCESS); };
  S->ops->setup = &BlockSetup;
  S->ops->solve = &BlockSolve;
  S->ops->lastflag = [](SUNLinearSolver S) { return Content(S).last_flag; };
  S->ops->free = [](SUNLinearSolver S) {
    if (S == nullptr) return static_cast<int>(SUNLS_SUCCESS);
    delete static_cast<BlockSolverContent*>(S->content);
    S->content = nullptr;
    SUNLinSolFreeEmpty(S);
    return static_cast<int>(SUNLS_SUCCESS);
  };
  return S;
}

}  // namespace

namespace {

/// Seconds since an arbitrary epoch, for the time shares in IntegratorStats (~20 ns a call,
/// against ~30 us for the lightest right-hand side).
double Now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// Adds the wall time of its scope to a total.
class ScopedSeconds {
 public:
  explicit ScopedSeconds(double& total) : total_(total), start_(Now()) {}
  ~ScopedSeconds() { total_ += Now() - start_; }
  ScopedSeconds(const ScopedSeconds&) = delete;
  ScopedSeconds& operator=(const ScopedSeconds&) = delete;

 private:
  double& total_;
  double start_;
};

}  // namespace

struct Integrator::Impl {
  OdeSystem* system = nullptr;
  double rhs_seconds = 0.0, jacobian_seconds = 0.0;
  double setup_seconds = 0.0, solve_seconds = 0.0;
  // KLU's own setup and solve, wrapped by timing functions in the solver's ops table. The
  // wrappers find this Impl through `active`, set around each CVode() call.
  int (*klu_setup)(SUNLinearSolver, SUNMatrix) = nullptr;
  int (*klu_solve)(SUNLinearSolver, SUNMatrix, N_Vector, N_Vector, sunrealtype) = nullptr;
  static thread_local Impl* active;

  static int TimedSetup(SUNLinearSolver S, SUNMatrix A) {
    const double start = Now();
    const int flag = active->klu_setup(S, A);
    active->setup_seconds += Now() - start;
    return flag;
  }
  static int TimedSolve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, sunrealtype tol) {
    const double start = Now();
    const int flag = active->klu_solve(S, A, x, b, tol);
    active->solve_seconds += Now() - start;
    return flag;
  }
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  N_Vector abstol = nullptr;
  double rtol = 0.0;
  std::vector<double> reference;
  SUNMatrix A = nullptr;
  SUNLinearSolver LS = nullptr;
  void* cvode = nullptr;
  // Why the last RHS/Jacobian call failed, reported after CVode() returns.
  std::string callback_error;
  std::function<bool()> interrupt;  // Integrator::SetInterruptCheck
  bool interrupted = false;

  ~Impl() {
    if (cvode) CVodeFree(&cvode);
    if (LS) SUNLinSolFree(LS);
    if (A) SUNMatDestroy(A);
    if (abstol) N_VDestroy(abstol);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }

  // CVODE trampolines: exceptions never cross the C boundary. A recoverable state error
  // returns +1 so CVODE retries with a smaller step; anything else stops the run.
  template <typename Body>
  static int Guarded(Impl* self, Body&& body) {
    try {
      return body();
    } catch (const RecoverableStateError& e) {
      self->callback_error = e.what();
      return 1;
    } catch (const std::exception& e) {
      self->callback_error = e.what();
      return -1;
    }
  }

  static int Rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user_data) {
    auto* self = static_cast<Impl*>(user_data);
    const ScopedSeconds clock(self->rhs_seconds);
    if (self->interrupt && self->interrupt()) {
      self->interrupted = true;
      return -1;  // unrecoverable: CVode() returns at once
    }
    return Guarded(self, [&] {
      self->system->Derivatives(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      const double* d = N_VGetArrayPointer(ydot);
      const sunindextype n = N_VGetLength(ydot);
      for (sunindextype i = 0; i < n; ++i) {
        if (!std::isfinite(d[i])) {
          self->callback_error = "non-finite derivative in state component " + std::to_string(i);
          return 1;
        }
      }
      return 0;
    });
  }

  // Error weights relative to a reference state (IntegratorOptions::reference).
  static int ErrorWeights(N_Vector y, N_Vector ewt, void* user_data) {
    auto* self = static_cast<Impl*>(user_data);
    const double* x = N_VGetArrayPointer(y);
    const double* atol = N_VGetArrayPointer(self->abstol);
    double* w = N_VGetArrayPointer(ewt);
    const Eigen::Index n = static_cast<Eigen::Index>(self->reference.size());
    // Whole-array expressions, so the compiler vectorises the divisions (once per step).
    const Eigen::Map<const Eigen::ArrayXd> xs(x, n), ref(self->reference.data(), n), at(atol, n);
    Eigen::Map<Eigen::ArrayXd> weights(w, n);
    weights = self->rtol * (xs - ref).abs() + at;
    if (!(weights > 0.0).all()) return -1;  // also false for NaN
    weights = weights.inverse();
    return 0;
  }

  static int Jac(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user_data, N_Vector,
                 N_Vector, N_Vector) {
    auto* self = static_cast<Impl*>(user_data);
    const ScopedSeconds clock(self->jacobian_seconds);
    return Guarded(self, [&] {
      // CVODE zeroes the whole sparse matrix (pattern included) before each call, so the
      // fixed pattern is written back every time; KLU then only refactors numerically.
      const SparsityPattern& p = self->system->JacobianPattern();
      std::memcpy(SUNSparseMatrix_IndexPointers(J), p.row_start.data(),
                  p.row_start.size() * sizeof(sunindextype));
      std::memcpy(SUNSparseMatrix_IndexValues(J), p.column.data(),
                  p.column.size() * sizeof(sunindextype));
      self->system->Jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy),
                             SUNSparseMatrix_Data(J));
      return 0;
    });
  }

  // With the block solver: CVODE's linear-system function. It only records gamma and, when
  // CVODE does not accept the last Jacobian (jok false), evaluates a new one into the block
  // solver's own array; the solver's setup then factors I - gamma J (BlockSolverContent).
  internal::BlockSolverContent* block = nullptr;
  static int LinSys(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix, sunbooleantype jok,
                    sunbooleantype* jcur, sunrealtype gamma, void* user_data, N_Vector, N_Vector,
                    N_Vector) {
    auto* self = static_cast<Impl*>(user_data);
    internal::BlockSolverContent& block = *self->block;
    block.gamma = gamma;
    if (jok) {
      *jcur = SUNFALSE;
      return 0;
    }
    *jcur = SUNTRUE;
    const ScopedSeconds clock(self->jacobian_seconds);
    ++block.jacobian_evals;
    return Guarded(self, [&] {
      self->system->Jacobian(t, N_VGetArrayPointer(y), N_VGetArrayPointer(fy),
                             block.jacobian.data());
      return 0;
    });
  }
};

thread_local Integrator::Impl* Integrator::Impl::active = nullptr;

Integrator::Integrator(OdeSystem& system, double t0, const double* x0,
                       const IntegratorOptions& options)
    : impl_(std::make_unique<Impl>()), n_(system.StateSize()), t_(t0) {
  Impl& m = *impl_;
  m.system = &system;
  if (static_cast<int>(options.atol.size()) != n_) {
    throw Error("integrator: atol has " + std::to_string(options.atol.size()) +
                " entries for a state of size " + std::to_string(n_));
  }
  const SparsityPattern& pattern = system.JacobianPattern();
  if (pattern.size != n_) throw Error("integrator: Jacobian pattern size mismatch");

  Check(SUNContext_Create(internal::kNoCommunicator, &m.ctx), "SUNContext_Create");
  m.y = MakeStateVector(n_, m.ctx);
  std::copy(x0, x0 + n_, N_VGetArrayPointer(m.y));
  m.abstol = CheckPtr(N_VNew_Serial(n_, m.ctx), "N_VNew_Serial");
  std::copy(options.atol.begin(), options.atol.end(), N_VGetArrayPointer(m.abstol));

  m.cvode = CheckPtr(CVodeCreate(CV_BDF, m.ctx), "CVodeCreate");
  Check(CVodeInit(m.cvode, &Impl::Rhs, t0, m.y), "CVodeInit");
  Check(CVodeSetUserData(m.cvode, &m), "CVodeSetUserData");
  if (options.reference.empty()) {
    Check(CVodeSVtolerances(m.cvode, options.rtol, m.abstol), "CVodeSVtolerances");
  } else {
    if (static_cast<int>(options.reference.size()) != n_) {
      throw Error("integrator: tolerance reference has the wrong size");
    }
    m.rtol = options.rtol;
    m.reference = options.reference;
    Check(CVodeWFtolerances(m.cvode, &Impl::ErrorWeights), "CVodeWFtolerances");
  }
  Check(CVodeSetMaxOrd(m.cvode, options.max_order), "CVodeSetMaxOrd");
  Check(CVodeSetStabLimDet(m.cvode, options.stability_limit_detection ? SUNTRUE : SUNFALSE),
        "CVodeSetStabLimDet");
  Check(CVodeSetMaxNumSteps(m.cvode, options.max_steps_per_call), "CVodeSetMaxNumSteps");
  if (options.max_step > 0) Check(CVodeSetMaxStep(m.cvode, options.max_step), "CVodeSetMaxStep");
    // CVODE's own error messages go to our exception text, not stderr. SUNDIALS 7 replaced
    // the per-solver handler by the context's handler stack (its default prints to stderr).
#if SUNDIALS_VERSION_MAJOR >= 7
  Check(SUNContext_ClearErrHandlers(m.ctx), "SUNContext_ClearErrHandlers");
#else
  Check(CVodeSetErrHandlerFn(
            m.cvode, [](int, const char*, const char*, char*, void*) {}, nullptr),
        "CVodeSetErrHandlerFn");
#endif

  m.A = CheckPtr(SUNSparseMatrix(n_, n_, pattern.nnz(), CSR_MAT, m.ctx), "SUNSparseMatrix");
  internal::InstallFastSparseOps(m.A);
  const BlockStructure* blocks = system.Blocks();
  const bool use_blocks =
      blocks != nullptr && options.linear_solver == IntegratorOptions::LinearSolver::kBlock;
  m.LS = use_blocks ? MakeBlockLinearSolver(pattern, *blocks, m.ctx)
                    : CheckPtr(SUNLinSol_KLU(m.y, m.A, m.ctx), "SUNLinSol_KLU");
  if (use_blocks) m.block = &Content(m.LS);
  m.klu_setup = m.LS->ops->setup;
  m.klu_solve = m.LS->ops->solve;
  m.LS->ops->setup = &Impl::TimedSetup;
  m.LS->ops->solve = &Impl::TimedSolve;
  Check(CVodeSetLinearSolver(m.cvode, m.LS, m.A), "CVodeSetLinearSolver");
  if (use_blocks) {
    Check(CVodeSetLinSysFn(m.cvode, &Impl::LinSys), "CVodeSetLinSysFn");
  } else {
    Check(CVodeSetJacFn(m.cvode, &Impl::Jac), "CVodeSetJacFn");
  }
  // No row scaling and no input check in KLU (Davis & Palamadai Natarajan 2010, KLU's
  // Common.scale = -1). Both passes run over every entry at each numerical refactorisation
  // (checked: ~7 % of a coupled run's wall time, in klu_scale). The check guards against
  // malformed column pointers and indices, which the fixed pattern built and tested here
  // never has; the scaling serves pivoting, which KLU does only in the first factorisation:
  // the Newton matrices I - gamma J have a unit diagonal in every row whatever the state's
  // unit, since J holds rates. Measured on the thesis line-6 case: the same step count
  // within 0.4 %, 8 % faster (benchmarks/README.md).
  if (!use_blocks) SUNLinSol_KLUGetCommon(m.LS)->scale = -1;
}

Integrator::~Integrator() = default;

void Integrator::SetStopTime(double t_stop) {
  Check(CVodeSetStopTime(impl_->cvode, t_stop), "CVodeSetStopTime");
}

void Integrator::Restart(double t0, const double* x0, const std::vector<double>& reference) {
  Impl& m = *impl_;
  if (reference.size() != m.reference.size()) {
    throw ContractError("integrator restart: the tolerance reference has the wrong size");
  }
  m.reference = reference;
  std::copy(x0, x0 + n_, N_VGetArrayPointer(m.y));
  Check(CVodeReInit(m.cvode, t0, m.y), "CVodeReInit");
  // KLU refactors with the pivots of its first factorisation; a new integrator's first
  // factorisation chooses them afresh, and so must this one's.
  if (m.block == nullptr) {
    Check(SUNLinSol_KLUReInit(m.LS, m.A, SUNSparseMatrix_NNZ(m.A), SUNKLU_REINIT_PARTIAL),
          "SUNLinSol_KLUReInit");
  }
  m.rhs_seconds = m.jacobian_seconds = m.setup_seconds = m.solve_seconds = 0.0;
  t_ = t0;
}

void Integrator::AdvanceTo(double t_out) {
  if (t_out <= t_) return;
  Impl& m = *impl_;
  m.callback_error.clear();
  m.interrupted = false;
  sunrealtype t_reached = t_;
  Impl* const previous = Impl::active;
  Impl::active = &m;
  const int flag = CVode(m.cvode, t_out, m.y, &t_reached, CV_NORMAL);
  Impl::active = previous;
  if (flag < 0) {
    sunrealtype t_now = t_;
    if (CVodeGetCurrentTime(m.cvode, &t_now) < 0) t_now = t_;
    if (m.interrupted) {
      throw Interrupted("interrupted at t = " + FormatNumber(t_now) + " s");
    }
    std::ostringstream msg;
    // CVodeGetReturnFlagName returns a malloc'd string that the caller frees.
    char* flag_name = CVodeGetReturnFlagName(flag);
    msg << "integrator failed at t = " << t_now << " s with CVODE flag " << flag << " ("
        << (flag_name ? flag_name : "?") << ")";
    std::free(flag_name);
    if (!m.callback_error.empty()) msg << ": " << m.callback_error;
    throw SolverError(msg.str());
  }
  t_ = t_reached;
}

void Integrator::SetInterruptCheck(std::function<bool()> check) {
  impl_->interrupt = std::move(check);
}

const double* Integrator::state() const { return N_VGetArrayPointer(impl_->y); }

IntegratorStats Integrator::stats() const {
  IntegratorStats s;
  void* cv = impl_->cvode;
  long nsteps = 0, nfevals = 0, nlinsetups = 0, netfails = 0;
  int qlast = 0, qcur = 0;
  sunrealtype hinused = 0, hlast = 0, hcur = 0, tcur = 0;
  // The getters fail only for a null or uninitialised CVODE memory, which would be a bug.
  const auto get = [](int flag, const char* call) {
    if (flag < 0) throw ContractError(std::string("SUNDIALS call ") + call + " failed");
  };
  get(CVodeGetIntegratorStats(cv, &nsteps, &nfevals, &nlinsetups, &netfails, &qlast, &qcur,
                              &hinused, &hlast, &hcur, &tcur),
      "CVodeGetIntegratorStats");
  s.steps = nsteps;
  s.rhs_evals = nfevals;
  s.linear_setups = nlinsetups;
  s.error_test_failures = netfails;
  s.last_step = hlast;
  s.last_order = qlast;
  get(CVodeGetNumJacEvals(cv, &s.jacobian_evals), "CVodeGetNumJacEvals");
  // CVODE counts only the Jacobians it evaluates itself; the block solver's LinSys counts its.
  if (impl_->block != nullptr) s.jacobian_evals = impl_->block->jacobian_evals;
  get(CVodeGetNumNonlinSolvIters(cv, &s.newton_iterations), "CVodeGetNumNonlinSolvIters");
  get(CVodeGetNumNonlinSolvConvFails(cv, &s.newton_failures), "CVodeGetNumNonlinSolvConvFails");
  get(CVodeGetNumStabLimOrderReds(cv, &s.stability_order_reductions),
      "CVodeGetNumStabLimOrderReds");
  s.rhs_seconds = impl_->rhs_seconds;
  s.jacobian_seconds = impl_->jacobian_seconds;
  s.linear_setup_seconds = impl_->setup_seconds;
  s.linear_solve_seconds = impl_->solve_seconds;
  return s;
}

}  // namespace moorsim
