// A relative tolerance at every size. doctest's Approx(x).epsilon(e) accepts a when
// |a - x| < e (1 + max(|a|, |x|)): relative for numbers of 1 or more, but for the metres, joules
// and seconds of a liver, far below 1, an absolute tolerance of e itself (Approx(0.18).epsilon(0.02)
// accepts 13 %, not 2 %). kerf_test::relative(x, e) accepts |a - x| < e (1e-300 + max(|a|, |x|)):
// relative at every size that a test measures, the 1e-300 only so that 0 equals 0.
#pragma once

#include <doctest/doctest.h>

#include <limits>

namespace kerf_test {

inline doctest::Approx relative(double x, double e = 100.0 * std::numeric_limits<float>::epsilon()) {
  return doctest::Approx(x).epsilon(e).scale(1e-300);
}

} // namespace kerf_test
