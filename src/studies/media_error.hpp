#pragma once
// The standard error of a mean T pooled over the passed droplets of several media, taking each
// medium as a cluster. Droplets dropped into one medium share its throats and dead ends, so their
// T are correlated, and the droplet-level error (sample sd / sqrt(passed)) understates how much
// the mean would move on other media of the same porosity. This is the cluster-robust (CR1)
// estimator of the pooled mean's variance:
//     var = G / (G - 1) * sum_g (s_g - n_g * mean)^2 / n^2,
// with n_g droplets of medium g passed, s_g the sum of their T, n = sum n_g, mean = sum s_g / n and
// G the media with at least one passed droplet. With one passed droplet per medium it is the
// droplet-level error exactly.
//
// The other averaging, per medium first: each medium's own mean T, then the plain mean of those
// over the G media, with the standard error of a mean of G independent values (sample sd /
// sqrt(G)). It weighs every medium alike, where the pooled mean weighs a medium by its passed
// droplets (so by how open it is).

#include <cmath>
#include <vector>

namespace softdrop::detail {

class MediaMean {
 public:
  /// One medium's passed droplets: how many, and the sum of their T. A medium where none passed
  /// is no cluster and changes nothing.
  void add_medium(int passed, double sum_t) {
    if (passed > 0) media_.push_back({passed, sum_t}), n_ += passed, sum_ += sum_t;
  }
  /// Media with at least one passed droplet.
  int media() const { return static_cast<int>(media_.size()); }
  /// The cluster-robust standard error of the pooled mean; 0 with fewer than two such media.
  double standard_error() const {
    const double g = static_cast<double>(media_.size());
    if (g < 2) return 0;
    const double n = static_cast<double>(n_), mean = sum_ / n;
    double ss = 0;
    for (const Medium& m : media_) {
      const double r = m.sum_t - m.passed * mean;
      ss += r * r;
    }
    return std::sqrt(g / (g - 1) * ss) / n;
  }
  /// The mean over media of each medium's mean T; 0 with no such medium.
  double per_medium_mean() const {
    double sum = 0;
    for (const Medium& m : media_) sum += m.sum_t / m.passed;
    return media_.empty() ? 0 : sum / static_cast<double>(media_.size());
  }
  /// Its standard error over the media (two-pass); 0 with fewer than two.
  double per_medium_standard_error() const {
    const double g = static_cast<double>(media_.size());
    if (g < 2) return 0;
    const double mean = per_medium_mean();
    double ss = 0;
    for (const Medium& m : media_) {
      const double r = m.sum_t / m.passed - mean;
      ss += r * r;
    }
    return std::sqrt(ss / (g - 1) / g);
  }

 private:
  struct Medium {
    int passed;
    double sum_t;
  };
  std::vector<Medium> media_;
  long n_ = 0;
  double sum_ = 0;
};

}  // namespace softdrop::detail
