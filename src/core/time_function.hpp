// nscd/core/time_function.hpp — scalar functions of time for imposed velocities and forces.
//
//   constant(c)                      f(t) = c
//   cosine(A, B, f, phi, ramp, t0)   f(t) = ramp(s) * (A + B cos(2 pi f s - phi)), s = t - t0 (paper §3.1);
//                                    f(t) = 0 before t0
//   lambda(fn)                       f(t) = fn(t), any user callable
//
// ramp(s) = min(1, s / ramp) when ramp > 0 (a linear ramp-in), else 1.
#pragma once

#include <functional>

namespace nscd {

class TimeFunction {
 public:
  enum class Kind { Constant, Cosine, Lambda };

  TimeFunction() = default;
  static TimeFunction constant(double c);
  static TimeFunction cosine(double A, double B, double frequency, double phase, double ramp_duration = 0.0,
                             double start = 0.0);
  static TimeFunction lambda(std::function<double(double)> fn);

  double operator()(double t) const;
  Kind kind() const { return kind_; }
  /// Parameters as given (A, B, frequency, phase, ramp); `constant` stores c in A.
  double A() const { return a_; }
  double B() const { return b_; }
  double frequency() const { return f_; }
  double phase() const { return phi_; }
  double ramp_duration() const { return ramp_; }
  double start() const { return t0_; }

 private:
  Kind kind_ = Kind::Constant;
  double a_ = 0.0, b_ = 0.0, f_ = 0.0, phi_ = 0.0, ramp_ = 0.0, t0_ = 0.0;
  std::function<double(double)> fn_;
};

}  // namespace nscd
