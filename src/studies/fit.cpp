#include "fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <istream>
#include <limits>
#include <nlopt.hpp>
#include <sstream>
#include <stdexcept>

#include "util/validation.hpp"

namespace softdrop {
using detail::num;

namespace {
// What makes a point unusable for a fit ("" if nothing).
std::string point_problem(const FitPoint& q) {
  if (!std::isfinite(q.phi) || q.phi <= 0 || q.phi > 1) return "phi = " + num(q.phi) + " is not in (0, 1]";
  if (!std::isfinite(q.t)) return "T is not finite";
  if (!std::isfinite(q.se) || q.se <= 0) return "se = " + num(q.se) + " must be > 0";
  return "";
}
}  // namespace

std::vector<FitPoint> read_fit_points(std::istream& in, const std::string& name, FitErrors errors, bool* used_errors,
                                      FitAveraging averaging) {
  const bool per_medium = averaging == FitAveraging::per_medium;
  std::string line;
  std::vector<FitPoint> out;
  int number = 0;
  bool header = false;
  auto bad = [&](const std::string& what) {
    return std::runtime_error("--points '" + name + "' line " + std::to_string(number) + ": " + what);
  };
  auto split = [](const std::string& text) {
    std::vector<std::string> fields;
    std::istringstream s(text);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    if (!text.empty() && text.back() == ',') fields.emplace_back();
    return fields;
  };
  std::size_t columns = 0, phi = 0, t = 0, se = 0;
  bool sweep_report = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const std::vector<std::string> f = split(line);
    if (!header) {
      // porosity,tortuosity,standard_error; or sweep-report --format csv: porosity, mean_tortuosity
      // and both errors. The names of older softdrops (phi,t,se; phi, mean_t, per_medium_t) still read.
      auto at = [&](const char* column, const char* older) {
        const auto i = std::size_t(std::find(f.begin(), f.end(), column) - f.begin());
        return i < f.size() ? i : std::size_t(std::find(f.begin(), f.end(), older) - f.begin());
      };
      sweep_report = at("tortuosity", "t") == f.size() && at("mean_tortuosity", "mean_t") < f.size();
      phi = at("porosity", "phi");
      if (!sweep_report) {
        t = at("tortuosity", "t"), se = at("standard_error", "se");
      } else {
        t = per_medium ? at("per_medium_tortuosity", "per_medium_t") : at("mean_tortuosity", "mean_t");
        const char* error = per_medium                   ? "per_medium_standard_error"
                            : errors == FitErrors::media ? "media_standard_error"
                                                         : "standard_error";
        se = at(error, error);
        if (phi < f.size() && per_medium && (t == f.size() || se == f.size()))
          throw bad(
              "no per_medium_tortuosity and per_medium_standard_error columns (a sweep-report of an "
              "older softdrop? fit its pooled mean)");
        if (phi < f.size() && se == f.size())
          throw bad(std::string("no ") + error + " column (a sweep-report of an older softdrop? fit it with --errors " +
                    (errors == FitErrors::media ? "droplets" : "media") + ")");
      }
      if (phi == f.size() || t == f.size() || se == f.size())
        throw bad("expected the header porosity,tortuosity,standard_error (or sweep-report --format csv's columns)");
      header = true;
      columns = f.size();
      if (used_errors) *used_errors = sweep_report;
      continue;
    }
    if (f.size() != columns) throw bad("expected " + std::to_string(columns) + " fields, as the header");
    // sweep-report leaves T and its error empty where fewer than two droplets passed: not a point
    if (sweep_report && (f[t].empty() || f[se].empty())) continue;
    if (out.size() == kMaxFitPoints) throw bad("more than the limit of " + std::to_string(kMaxFitPoints) + " points");
    FitPoint p;
    std::size_t used = 0;
    try {
      p.phi = std::stod(f[phi], &used);
      if (used != f[phi].size()) throw std::invalid_argument("");
      p.t = std::stod(f[t], &used);
      if (used != f[t].size()) throw std::invalid_argument("");
      p.se = std::stod(f[se], &used);
      if (used != f[se].size()) throw std::invalid_argument("");
    } catch (const std::exception&) {
      throw bad("expected numbers for porosity, tortuosity and standard_error");
    }
    if (const std::string why = point_problem(p); !why.empty()) throw bad(why);
    out.push_back(p);
  }
  return out;
}

const char* to_string(FitLaw law) { return law == FitLaw::power ? "power" : "log"; }

double fit_law_value(FitLaw law, const std::vector<double>& p, double phi) {
  return law == FitLaw::power ? p[0] - p[2] * std::pow(phi, p[1]) : 1 - p[0] * std::log(phi);
}

namespace {

// d f / d p_k at phi.
Eigen::VectorXd gradient(FitLaw law, const std::vector<double>& p, double phi) {
  if (law == FitLaw::log) return Eigen::VectorXd::Constant(1, -std::log(phi));
  const double pb = std::pow(phi, p[1]);
  Eigen::VectorXd g(3);
  g << 1.0, -p[2] * pb * std::log(phi), -pb;
  return g;
}

struct Problem {
  FitLaw law;
  const std::vector<FitPoint>* points;
};

double chi2_of(const std::vector<double>& p, std::vector<double>& grad, void* data) {
  const Problem& pr = *static_cast<const Problem*>(data);
  double chi2 = 0;
  if (!grad.empty()) std::fill(grad.begin(), grad.end(), 0.0);
  for (const FitPoint& q : *pr.points) {
    const double r = (q.t - fit_law_value(pr.law, p, q.phi)) / q.se;
    chi2 += r * r;
    if (!grad.empty()) {
      const Eigen::VectorXd g = gradient(pr.law, p, q.phi);
      for (std::size_t k = 0; k < grad.size(); ++k) grad[k] += -2 * r * g(static_cast<Eigen::Index>(k)) / q.se;
    }
  }
  return chi2;
}

// Starting point of the power law: for fixed b the model is linear in (a, c), so scan b and
// solve the weighted linear problem; NLopt then polishes all three.
std::vector<double> power_start(const std::vector<FitPoint>& pts) {
  double best = std::numeric_limits<double>::infinity();
  std::vector<double> start{1, 1, 0};
  const auto n = static_cast<Eigen::Index>(pts.size());
  for (double b = 0.25; b <= 20; b *= 1.05) {
    Eigen::MatrixXd A(n, 2);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const FitPoint& q = pts[static_cast<std::size_t>(i)];
      A(i, 0) = 1 / q.se;
      A(i, 1) = -std::pow(q.phi, b) / q.se;
      y(i) = q.t / q.se;
    }
    const Eigen::VectorXd x = A.colPivHouseholderQr().solve(y);
    const double chi2 = (A * x - y).squaredNorm();
    if (chi2 < best) best = chi2, start = {x(0), b, x(1)};
  }
  return start;
}

// Runs one NLopt algorithm from *p. On success (or a round-off limited end, where *p holds the best
// point) sets *p, *chi2 and *message and returns true; otherwise leaves the best point NLopt found
// in *p (if it is finite and no worse than the start) and returns false with the reason.
bool minimize(nlopt::algorithm algorithm, Problem& problem, std::vector<double>* p, double* chi2,
              std::string* message) {
  std::vector<double> none;
  const std::vector<double> start = *p;
  const double start_chi2 = chi2_of(start, none, &problem);
  nlopt::opt opt(algorithm, static_cast<unsigned>(p->size()));
  opt.set_min_objective(chi2_of, &problem);
  opt.set_ftol_rel(1e-14);
  opt.set_xtol_rel(1e-12);
  opt.set_maxeval(20000);
  try {
    const nlopt::result status = opt.optimize(*p, *chi2);
    *message = status == nlopt::FTOL_REACHED   ? "converged (relative chi2 tolerance)"
               : status == nlopt::XTOL_REACHED ? "converged (relative parameter tolerance)"
               : status == nlopt::SUCCESS      ? "converged"
               : status == nlopt::MAXEVAL_REACHED
                   ? "stopped at the evaluation limit"
                   : "ended with NLopt status " + std::to_string(static_cast<int>(status));
    return true;
  } catch (const nlopt::roundoff_limited&) {
    // Cannot improve further in floating point: *p holds the best point found.
    *chi2 = chi2_of(*p, none, &problem);
    *message = "converged (round-off limited)";
    return true;
  } catch (const std::exception& e) {  // nlopt's generic failure, invalid arguments, ...
    *message = e.what();
  }
  bool finite = true;
  for (double v : *p) finite = finite && std::isfinite(v);
  if (!finite || !(chi2_of(*p, none, &problem) <= start_chi2)) *p = start;
  return false;
}

}  // namespace

FitResult fit_law(FitLaw law, const std::vector<FitPoint>& points) {
  const std::size_t k = law == FitLaw::power ? 3 : 1;
  if (points.size() < k)
    throw std::invalid_argument(std::string("fit ") + to_string(law) + ": needs at least " + std::to_string(k) +
                                " points, got " + std::to_string(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i)
    if (const std::string why = point_problem(points[i]); !why.empty())
      throw std::invalid_argument("point " + std::to_string(i) + ": " + why);
  FitResult r;
  r.law = law;
  r.names = law == FitLaw::power ? std::vector<std::string>{"a", "b", "c"} : std::vector<std::string>{"p"};
  std::vector<double> p = law == FitLaw::power ? power_start(points) : std::vector<double>{0.5};

  Problem problem{law, &points};
  double chi2 = 0;
  if (!minimize(nlopt::LD_LBFGS, problem, &p, &chi2, &r.message)) {
    // L-BFGS's line search can fail outright in the long, narrow valley of (a, c) of the power
    // law. Nelder-Mead needs no gradient; it restarts from L-BFGS's best point (or the start).
    std::string first = r.message;
    if (!minimize(nlopt::LN_NELDERMEAD, problem, &p, &chi2, &r.message))
      throw std::runtime_error(std::string("fit ") + to_string(law) + ": NLopt failed (L-BFGS: " + first +
                               "; Nelder-Mead: " + r.message + ")");
    r.message += " by Nelder-Mead after L-BFGS " + first;
  }
  r.values = p;
  if (law == FitLaw::power && std::abs(p[1]) < 1e-3)
    r.warning = "power law: b = " + num(p[1]) +
                " -> 0, where a - c phi^b becomes (a - c) - c b ln(phi); only a - c = " + num(p[0] - p[2]) +
                " and c b = " + num(p[2] * p[1]) + " are determined, not a, b, c (the data follow the log law's shape)";
  r.chi2 = chi2;
  r.dof = static_cast<int>(points.size()) - static_cast<int>(k);
  r.reduced_chi2 = r.dof > 0 ? chi2 / r.dof : 0;
  r.aic = chi2 + 2.0 * static_cast<double>(k);
  // Covariance (J^T W J)^-1 at the optimum.
  Eigen::MatrixXd JtWJ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
  for (const FitPoint& q : points) {
    const Eigen::VectorXd g = gradient(law, p, q.phi);
    JtWJ += g * g.transpose() / (q.se * q.se);
    r.residuals.push_back((q.t - fit_law_value(law, p, q.phi)) / q.se);
  }
  const Eigen::MatrixXd cov = JtWJ.completeOrthogonalDecomposition().pseudoInverse();
  for (std::size_t i = 0; i < k; ++i)
    r.errors.push_back(std::sqrt(std::max(0.0, cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)))));
  return r;
}

}  // namespace softdrop
