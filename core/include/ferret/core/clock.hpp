#pragma once
// The time a controller sees. Controllers never read std::chrono: in simulation the
// world advances a SimClock by its step (runs far ahead of real time and repeat
// exactly), on a robot a SteadyClock reads the monotonic clock.

#include <chrono>

namespace ferret {

class Clock {
 public:
  virtual ~Clock() = default;
  /// Seconds since the clock's start (monotonic, never decreasing).
  [[nodiscard]] virtual double now_s() const = 0;
};

/// Simulated time, advanced by whoever owns the simulated world.
class SimClock final : public Clock {
 public:
  [[nodiscard]] double now_s() const override { return now_s_; }
  /// @pre dt_s >= 0 (a negative step is ignored: time never runs backwards)
  void advance(double dt_s) {
    if (dt_s > 0) now_s_ += dt_s;
  }
  /// Sets the time; a value before now is ignored. Stepping by a fixed dt with
  /// set(k * dt) keeps the time exact where repeated advance(dt) would drift.
  void set(double t_s) {
    if (t_s > now_s_) now_s_ = t_s;
  }

 private:
  double now_s_ = 0.0;
};

/// The monotonic clock of the machine, from construction.
class SteadyClock final : public Clock {
 public:
  SteadyClock() : start_(std::chrono::steady_clock::now()) {}
  [[nodiscard]] double now_s() const override {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace ferret
