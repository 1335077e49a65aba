#pragma once
// Agent transfer coefficients for the agent tests: alpha1..alpha3, beta and gamma by value, the
// Poisson decay fixed at 0.5 so that hand-computed pushes do not follow alpha2.
#include <agent/load_transfer.h>

namespace test_support {

inline agent::Coefficients coefficients(double a1, double a2, double a3, double beta, double gamma) {
  agent::Coefficients k;
  k.alpha1 = a1;
  k.alpha2 = a2;
  k.alpha3 = a3;
  k.beta = beta;
  k.gamma = gamma;
  k.poisson_decay = 0.5;
  return k;
}

}  // namespace test_support
