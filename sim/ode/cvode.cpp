// Method cvode_bdf: SUNDIALS CVODE's variable-order BDF (orders 1-5) behind pronk's Stepper
// interface. One CVODE step per step() (CV_ONE_STEP, never past t_limit: CVodeSetStopTime),
// dense output from CVODE's Nordsieck history (CVodeGetDky), the system's analytic Jacobian
// when it has one (sparse: KLU on a pattern that only grows, sim/ode/sundials_jacobian.hpp;
// or SUNDIALS' dense LU), CVODE's difference quotients with dense LU otherwise. A scaled error
// norm becomes CVODE's per-state atol. Events, samples and the energy accounting work on
// dense() as for rodas4 and radau5.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "sim/ode/steppers.hpp"
#include "sim/ode/sundials_jacobian.hpp"

namespace pronk::ode::detail {

namespace {

/// Owns the SUNDIALS objects of one stepper.
struct CvodeHandles {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  N_Vector dky = nullptr;
  N_Vector atol = nullptr;  ///< per-state atol (scaled norms)
  SUNMatrix a = nullptr;
  SUNLinearSolver ls = nullptr;
  void* mem = nullptr;
  CvodeHandles() = default;
  CvodeHandles(const CvodeHandles&) = delete;
  CvodeHandles& operator=(const CvodeHandles&) = delete;
  ~CvodeHandles() {
    if (mem != nullptr) CVodeFree(&mem);
    if (ls != nullptr) SUNLinSolFree(ls);
    if (a != nullptr) SUNMatDestroy(a);
    if (dky != nullptr) N_VDestroy(dky);
    if (atol != nullptr) N_VDestroy(atol);
    if (y != nullptr) N_VDestroy(y);
    if (ctx != nullptr) SUNContext_Free(&ctx);
  }
};

/// CVODE's error and warning messages: kept for nothing (a failed step reports through its
/// status and the run's reason), not printed to stderr.
void quiet(int, const char*, const char*, char*, void*) {}

class CvodeStepper final : public Stepper {
 public:
  CvodeStepper(const SolverOptions& o, int n, ErrorNorm norm)
      : o_(o), n_(n), norm_(std::move(norm)), y_(n), work_(n), dydt_(n) {
    if (SUNContext_Create(nullptr, &h_.ctx) != 0) throw std::runtime_error("SUNContext_Create");
    h_.y = N_VNew_Serial(n, h_.ctx);
    h_.dky = N_VNew_Serial(n, h_.ctx);
    h_.mem = CVodeCreate(CV_BDF, h_.ctx);
    if (h_.y == nullptr || h_.dky == nullptr || h_.mem == nullptr) {
      throw std::runtime_error("cvode_bdf: SUNDIALS could not allocate its objects");
    }
  }

  void reset(const OdeSystem& sys, double t, const Vec& y) override {
    sys_ = &sys;
    y_ = y;
    std::memcpy(N_VGetArrayPointer(h_.y), y.data(), sizeof(double) * static_cast<size_t>(n_));
    if (!initialised_) {
      init(sys, t);
    } else {
      bank_counters();
      // Keep the adapted step across the restart (CVODE restarts at order 1).
      double h_last = 0.0;
      if (CVodeGetLastStep(h_.mem, &h_last) == CV_SUCCESS && h_last > 0.0) {
        CVodeSetInitStep(h_.mem, h_last);
      }
      CVodeReInit(h_.mem, t, h_.y);
    }
    t_ = t_prev_ = t;
  }

  StepStatus step(const OdeSystem& sys, double t_limit) override {
    sys_ = &sys;
    if (!(t_limit > t_)) return StepStatus::kOk;
    CVodeSetStopTime(h_.mem, t_limit);
    double t_ret = t_;
    const int flag = CVode(h_.mem, t_limit, h_.y, &t_ret, CV_ONE_STEP);
    sync_counters();
    if (flag < 0) {
      return non_finite_ ? StepStatus::kNonFinite : StepStatus::kStepSizeCollapse;
    }
    t_prev_ = t_;
    t_ = t_ret;
    std::memcpy(y_.data(), N_VGetArrayPointer(h_.y), sizeof(double) * static_cast<size_t>(n_));
    if (!y_.allFinite()) return StepStatus::kNonFinite;
    return StepStatus::kOk;
  }

  void dense(double t, Vec& y_out) const override {
    y_out.resize(n_);
    if (t >= t_) {
      y_out = y_;
      return;
    }
    if (CVodeGetDky(h_.mem, t, 0, h_.dky) != CV_SUCCESS) {
      y_out = y_;  // outside the last step's history: cannot happen inside [t_prev, t]
      return;
    }
    std::memcpy(y_out.data(), N_VGetArrayPointer(h_.dky), sizeof(double) * static_cast<size_t>(n_));
  }

  double t() const override { return t_; }
  double t_prev() const override { return t_prev_; }
  const Vec& y() const override { return y_; }
  double h() const override {
    double h = 0.0;
    if (CVodeGetCurrentStep(h_.mem, &h) != CV_SUCCESS || !(h > 0.0)) return o_.h_initial;
    return h;
  }
  const SolverCounters& counters() const override { return counters_; }
  SolverCounters& mutable_counters() override { return counters_; }

 private:
  /// The matrix and linear solver for sys: KLU on the analytic Jacobian's pattern, or dense.
  void make_linear_solver(const OdeSystem& sys) {
    sparse_ = sys.has_jacobian() && o_.cvode_linear_solver != CvodeLinearSolver::kDense;
    if (sparse_) {
      // Room for the diagonal; the first Jacobian reallocates it to its pattern.
      h_.a = SUNSparseMatrix(n_, n_, n_, CSC_MAT, h_.ctx);
      if (h_.a != nullptr) h_.ls = SUNLinSol_KLU(h_.y, h_.a, h_.ctx);
    } else {
      h_.a = SUNDenseMatrix(n_, n_, h_.ctx);
      if (h_.a != nullptr) h_.ls = SUNLinSol_Dense(h_.y, h_.a, h_.ctx);
    }
    if (h_.a == nullptr || h_.ls == nullptr) {
      throw std::runtime_error("cvode_bdf: SUNDIALS could not allocate its linear solver");
    }
  }

  /// rtol and atol, per state for a scaled norm.
  bool set_tolerances() {
    const Vec& scale = norm_.atol_scale();
    if (scale.size() != n_) return CVodeSStolerances(h_.mem, o_.rtol, o_.atol) == CV_SUCCESS;
    h_.atol = N_VNew_Serial(n_, h_.ctx);
    if (h_.atol == nullptr) return false;
    for (int i = 0; i < n_; ++i) N_VGetArrayPointer(h_.atol)[i] = o_.atol * scale[i];
    return CVodeSVtolerances(h_.mem, o_.rtol, h_.atol) == CV_SUCCESS;
  }

  void init(const OdeSystem& sys, double t) {
    make_linear_solver(sys);
    void* m = h_.mem;
    bool ok = CVodeInit(m, &CvodeStepper::rhs_fn, t, h_.y) == CV_SUCCESS;
    ok = ok && set_tolerances();
    ok = ok && CVodeSetUserData(m, this) == CV_SUCCESS;
    ok = ok && CVodeSetErrHandlerFn(m, quiet, nullptr) == CV_SUCCESS;
    ok = ok && CVodeSetMaxStep(m, o_.h_max) == CV_SUCCESS;
    ok = ok && CVodeSetMinStep(m, o_.h_min) == CV_SUCCESS;
    ok = ok && CVodeSetMaxNumSteps(m, -1) == CV_SUCCESS;  // integrate() keeps the budgets
    ok = ok && (o_.h_initial <= 0.0 || CVodeSetInitStep(m, o_.h_initial) == CV_SUCCESS);
    ok = ok && CVodeSetLinearSolver(m, h_.ls, h_.a) == CV_SUCCESS;
    if (ok && sys.has_jacobian()) {
      ok = CVodeSetJacFn(m, sparse_ ? &CvodeStepper::jac_sparse_fn : &CvodeStepper::jac_fn) ==
           CV_SUCCESS;
    }
    if (!ok) throw std::runtime_error("cvode_bdf: CVODE rejected its settings");
    initialised_ = true;
  }

  static int rhs_fn(double t, N_Vector y, N_Vector ydot, void* user) {
    auto* s = static_cast<CvodeStepper*>(user);
    const size_t bytes = sizeof(double) * static_cast<size_t>(s->n_);
    std::memcpy(s->work_.data(), N_VGetArrayPointer(y), bytes);
    s->non_finite_ = false;
    if (!s->work_.allFinite()) {
      s->non_finite_ = true;
      return 1;  // recoverable: CVODE cuts the step
    }
    s->sys_->rhs(t, s->work_, s->dydt_);
    if (!s->dydt_.allFinite()) {
      s->non_finite_ = true;
      return 1;
    }
    std::memcpy(N_VGetArrayPointer(ydot), s->dydt_.data(), bytes);
    return 0;
  }

  static int jac_fn(double t, N_Vector y, N_Vector, SUNMatrix j, void* user, N_Vector, N_Vector,
                    N_Vector) {
    auto* s = static_cast<CvodeStepper*>(user);
    std::memcpy(s->work_.data(), N_VGetArrayPointer(y),
                sizeof(double) * static_cast<size_t>(s->n_));
    s->sys_->jacobian(t, s->work_, s->jac_);
    return sundials::copy_dense(s->jac_, j) ? 0 : 1;  // recoverable: CVODE cuts the step
  }

  static int jac_sparse_fn(double t, N_Vector y, N_Vector, SUNMatrix j, void* user, N_Vector,
                           N_Vector, N_Vector) {
    auto* s = static_cast<CvodeStepper*>(user);
    std::memcpy(s->work_.data(), N_VGetArrayPointer(y),
                sizeof(double) * static_cast<size_t>(s->n_));
    s->sys_->jacobian(t, s->work_, s->jac_);
    switch (s->pattern_.copy(s->jac_, j)) {
      case sundials::SparsePattern::Copy::kSame:
        return 0;
      case sundials::SparsePattern::Copy::kGrown:
        // A new pattern: KLU analyses it again at the next setup.
        return SUNLinSol_KLUReInit(s->h_.ls, j, s->pattern_.nonzeros(), SUNKLU_REINIT_PARTIAL) ==
                       SUNLS_SUCCESS
                   ? 0
                   : -1;
      case sundials::SparsePattern::Copy::kNonFinite:
        return 1;  // recoverable: CVODE cuts the step
      case sundials::SparsePattern::Copy::kFailed:
        break;
    }
    return -1;
  }

  /// CVODE's own counters since the last (re)initialisation.
  SolverCounters current() const {
    long steps = 0, rhs = 0, rhs_ls = 0, jac = 0, setups = 0, err_fails = 0, conv_fails = 0;
    CVodeGetNumSteps(h_.mem, &steps);
    CVodeGetNumRhsEvals(h_.mem, &rhs);
    CVodeGetNumLinRhsEvals(h_.mem, &rhs_ls);
    CVodeGetNumJacEvals(h_.mem, &jac);
    CVodeGetNumLinSolvSetups(h_.mem, &setups);
    CVodeGetNumErrTestFails(h_.mem, &err_fails);
    CVodeGetNumNonlinSolvConvFails(h_.mem, &conv_fails);
    SolverCounters c;
    c.steps_accepted = steps;
    c.steps_rejected = err_fails + conv_fails;
    c.rhs_evaluations = rhs + rhs_ls;
    c.jacobian_evaluations = jac;
    c.lu_factorizations = setups;
    return c;
  }

  /// CVodeReInit zeroes CVODE's counters: bank them first.
  void bank_counters() {
    const SolverCounters c = current();
    banked_.steps_accepted += c.steps_accepted;
    banked_.steps_rejected += c.steps_rejected;
    banked_.rhs_evaluations += c.rhs_evaluations;
    banked_.jacobian_evaluations += c.jacobian_evaluations;
    banked_.lu_factorizations += c.lu_factorizations;
  }

  void sync_counters() {
    const SolverCounters c = current();
    counters_.steps_accepted = banked_.steps_accepted + c.steps_accepted;
    counters_.steps_rejected = banked_.steps_rejected + c.steps_rejected;
    counters_.rhs_evaluations = banked_.rhs_evaluations + c.rhs_evaluations;
    counters_.jacobian_evaluations = banked_.jacobian_evaluations + c.jacobian_evaluations;
    counters_.lu_factorizations = banked_.lu_factorizations + c.lu_factorizations;
  }

  SolverOptions o_;
  int n_;
  ErrorNorm norm_;
  CvodeHandles h_;
  const OdeSystem* sys_ = nullptr;
  bool initialised_ = false;
  bool non_finite_ = false;
  bool sparse_ = false;
  sundials::SparsePattern pattern_;  ///< KLU: the Jacobians' pattern
  double t_ = 0.0, t_prev_ = 0.0;
  Vec y_, work_, dydt_;
  Eigen::SparseMatrix<double> jac_;
  SolverCounters counters_, banked_;  ///< (events: integrate() counts them in counters_)
};

}  // namespace

std::unique_ptr<Stepper> make_cvode_stepper(const SolverOptions& options, int n, ErrorNorm norm) {
  return std::make_unique<CvodeStepper>(options, n, std::move(norm));
}

}  // namespace pronk::ode::detail
