#pragma once
/// \file fit.hpp
/// Weighted least-squares fits of <T>(phi), with NLopt: the paper's law T = a - c phi^b and the
/// hydrodynamic law T = 1 - p ln(phi). Uncertainties come from the covariance (J^T W J)^-1 at the
/// optimum (the standard errors are taken as true, absolute errors); the two fits are compared by
/// chi^2 and Akaike's information criterion AIC = chi^2 + 2 k.

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace softdrop {

/// One data point: porosity, mean tortuosity and its standard error (> 0).
struct FitPoint {
  double phi = 0, t = 0, se = 0;
};

enum class FitLaw {
  power,  ///< T = a - c phi^b (parameters a, b, c)
  log     ///< T = 1 - p ln(phi) (parameter p)
};
const char* to_string(FitLaw law);

/// The law's value at phi for parameters `p` (power: a, b, c; log: p).
double fit_law_value(FitLaw law, const std::vector<double>& p, double phi);

/// A fit and why it ended.
struct FitResult {
  FitLaw law = FitLaw::power;
  std::vector<std::string> names;  ///< parameter names
  std::vector<double> values;      ///< best parameters
  std::vector<double> errors;      ///< their standard errors
  std::vector<double> residuals;   ///< (T_i - f(phi_i)) / se_i, per point
  double chi2 = 0;
  int dof = 0;              ///< points - parameters
  double reduced_chi2 = 0;  ///< chi2 / dof (0 if dof = 0)
  double aic = 0;           ///< chi2 + 2 k
  std::string message;      ///< how NLopt ended
  /// Non-empty when the result is not a usable fit although NLopt ended normally: the power law
  /// running to b -> 0, where a - c phi^b becomes (a - c) - c b ln(phi) and only a - c and c b
  /// are determined (the data prefer the log law's shape).
  std::string warning;
};

/// Most points a points file may hold.
constexpr std::size_t kMaxFitPoints = 1'000'000;

/// Which standard error of a sweep's per-porosity points weighs a fit.
enum class FitErrors {
  media,     ///< media_standard_error: the porosity's media as clusters (the error to quote)
  droplets,  ///< standard_error: every passed droplet taken as independent
};

/// Which mean T of a sweep's porosity is fitted.
enum class FitAveraging {
  pooled,      ///< mean_tortuosity: over every passed droplet of the porosity (a medium counts by its droplets)
  per_medium,  ///< per_medium_tortuosity: each medium's mean first, then over media (each counts once),
               ///< weighed by its error over media (FitErrors::media is the only error it has)
};

/// Reads a points file: optional `#` comment lines, a header naming the columns porosity,
/// tortuosity and standard_error (others are ignored; older files' phi, t and se read too), then
/// one point per line; or the output of `sweep-report --format csv` (porosity, mean_tortuosity,
/// and media_standard_error or standard_error as `errors` says; with FitAveraging::per_medium
/// per_medium_tortuosity and per_medium_standard_error; rows without that
/// error are skipped). Throws std::runtime_error naming `name` and the line on a bad line, a
/// sweep-report file without the chosen error's column, or more than kMaxFitPoints points (the
/// values themselves are checked by fit_law). `*used_errors`, if given, is set to whether the file
/// was a sweep-report's, whose errors `errors` chose (a points file brings its own).
std::vector<FitPoint> read_fit_points(std::istream& in, const std::string& name, FitErrors errors = FitErrors::media,
                                      bool* used_errors = nullptr, FitAveraging averaging = FitAveraging::pooled);

/// Fits one law. Throws std::invalid_argument for fewer points than parameters, a non-finite
/// value, phi outside (0, 1] or se <= 0 (naming the point).
FitResult fit_law(FitLaw law, const std::vector<FitPoint>& points);

}  // namespace softdrop
