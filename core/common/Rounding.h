#pragma once
/// @file Rounding.h
/// Rounding to the nearest integer, halves away from zero, as std::lround does, inline.

#include <cmath>
#include <limits>

namespace scanpick::core {

/// std::lround(x) (halves away from zero) without a call into the maths library: the hot loops
/// that project points to pixels round two coordinates per point. Below 2^(digits − 1) in
/// magnitude x − trunc(x) is exact, so the result is std::lround's; larger, infinite and NaN
/// values are left to std::lround.
template <typename Real> [[gnu::always_inline]] inline long roundHalfAway(Real x) {
  constexpr Real kExactBelow = Real(1ll << (std::numeric_limits<Real>::digits - 1));
  if (!(std::abs(x) < kExactBelow))
    return std::lround(x);
  const long whole = static_cast<long>(x); // toward zero
  const Real rest = x - static_cast<Real>(whole);
  return whole + (rest >= Real(0.5) ? 1 : 0) - (rest <= Real(-0.5) ? 1 : 0);
}

} // namespace scanpick::core
