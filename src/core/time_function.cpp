// nscd/core/time_function.cpp — see time_function.hpp.
#include "nscd/core/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "nscd/core/error.hpp"
#include "nscd/core/math.hpp"

namespace nscd {

TimeFunction TimeFunction::constant(double c) {
  if (!std::isfinite(c)) throw Error("TimeFunction::constant: value is not finite");
  TimeFunction f;
  f.kind_ = Kind::Constant;
  f.a_ = c;
  return f;
}

TimeFunction TimeFunction::cosine(double A, double B, double frequency, double phase, double ramp_duration,
                                  double start) {
  if (!std::isfinite(start)) throw Error("TimeFunction::cosine: start time must be finite");
  if (!std::isfinite(A) || !std::isfinite(B) || !std::isfinite(frequency) || !std::isfinite(phase))
    throw Error("TimeFunction::cosine: A, B, frequency and phase must be finite");
  if (frequency < 0.0) throw Error("TimeFunction::cosine: frequency must be >= 0, got " + std::to_string(frequency));
  // an infinite ramp would silently zero the load for ever
  if (!(ramp_duration >= 0.0) || !std::isfinite(ramp_duration))
    throw Error("TimeFunction::cosine: ramp duration must be finite and >= 0");
  TimeFunction f;
  f.kind_ = Kind::Cosine;
  f.a_ = A;
  f.b_ = B;
  f.f_ = frequency;
  f.phi_ = phase;
  f.ramp_ = ramp_duration;
  f.t0_ = start;
  return f;
}

TimeFunction TimeFunction::lambda(std::function<double(double)> fn) {
  if (!fn) throw Error("TimeFunction::lambda: empty function");
  TimeFunction f;
  f.kind_ = Kind::Lambda;
  f.fn_ = std::move(fn);
  return f;
}

double TimeFunction::operator()(double t) const {
  switch (kind_) {
    case Kind::Constant:
      return a_;
    case Kind::Cosine: {
      const double s = t - t0_;
      if (s < 0.0) return 0.0;
      const double ramp = ramp_ > 0.0 ? std::clamp(s / ramp_, 0.0, 1.0) : 1.0;
      return ramp * (a_ + b_ * std::cos(2.0 * kPi * f_ * s - phi_));
    }
    case Kind::Lambda:
      return fn_(t);
  }
  return 0.0;
}

}  // namespace nscd
