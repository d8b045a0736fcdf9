#include "core/common/Rounding.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <vector>

using scanpick::core::roundHalfAway;

namespace {
template <typename Real> std::vector<Real> awkwardValues() {
  const Real big = Real(1ll << (std::numeric_limits<Real>::digits - 1));
  std::vector<Real> values{Real(0),
                           Real(-0.0),
                           Real(0.5),
                           Real(-0.5),
                           Real(1.5),
                           Real(-1.5),
                           Real(2.5),
                           Real(-2.5),
                           Real(0.49999997),
                           big,
                           -big,
                           big / 2 + Real(0.5),
                           -(big / 2 + Real(0.5)),
                           2 * big,
                           std::nextafter(Real(0.5), Real(0)),
                           std::nextafter(Real(0.5), Real(1)),
                           std::nextafter(Real(-0.5), Real(0)),
                           std::nextafter(Real(-0.5), Real(-1))};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> pixels(Real(-2000), Real(2000));
  for (int k = 0; k < 100000; ++k) {
    values.push_back(pixels(rng));
    values.push_back(std::floor(pixels(rng)) + Real(0.5)); // exact halves
  }
  return values;
}
} // namespace

TEST(Rounding, GivesWhatLroundGivesForDoubles) {
  for (const double x : awkwardValues<double>())
    EXPECT_EQ(roundHalfAway(x), std::lround(x)) << x;
}

TEST(Rounding, GivesWhatLroundGivesForFloats) {
  for (const float x : awkwardValues<float>())
    EXPECT_EQ(roundHalfAway(x), std::lround(x)) << x;
}
