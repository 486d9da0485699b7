// High-order sawtooth smoothing of a closed marker chain (see sawtooth_filter.h).
#include "ehd_capsule/ib/sawtooth_filter.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ehd {

SawtoothFilter::SawtoothFilter(int order) : order_(order) {
  if (order < 1) {
    throw std::invalid_argument("SawtoothFilter: order must be >= 1, got " + std::to_string(order));
  }
}

void SawtoothFilter::Apply(Eigen::Matrix2Xd& X) {
  const int m = static_cast<int>(X.cols());
  if (m < 2 * order_ + 1) {
    throw std::invalid_argument("SawtoothFilter: order " + std::to_string(order_) +
                                " needs at least " + std::to_string(2 * order_ + 1) +
                                " markers, got " + std::to_string(m));
  }
  diff_ = X;
  for (int pass = 0; pass < order_; ++pass) {  // diff_ = D^(2p) X
    work_ = diff_;
    for (int k = 0; k < m; ++k) {
      diff_.col(k) = work_.col(k == 0 ? m - 1 : k - 1) - 2.0 * work_.col(k) +
                     work_.col(k + 1 == m ? 0 : k + 1);
    }
  }
  const double scale = std::pow(0.25, order_) * (order_ % 2 == 0 ? 1.0 : -1.0);
  X -= scale * diff_;
}

double SawtoothFilter::Gain(double theta) const {
  return 1.0 - std::pow(0.5 * (1.0 - std::cos(theta)), order_);
}

}  // namespace ehd
