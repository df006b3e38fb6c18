// TwoWay: runs a job's two halves at once, half 0 on the calling thread and half 1 on a worker
// thread that spins between jobs (a fork and join costs about 1 µs on the 2-core machines this
// is built on, where a condition variable's wake-up costs tens). After 20 ms without a job the
// worker sleeps on a condition variable, so an idle simulation does not hold a core. Half 1 goes
// to whichever thread claims it first: a caller that finishes half 0 before the worker has
// started (the worker asleep, or descheduled on a loaded machine) runs half 1 itself instead of
// waiting. With fewer than two hardware threads, or `worker` false, there is no worker and both
// halves run one after the other on the caller: the results are the same either way, only the
// time differs.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace beltsim {

// A belt of this many elements or more is split in two halves, elements 0..n/2-1 and n/2..n-1:
// its right-hand side and Jacobian (rhs.hpp) and its ring factorisation (ring_solver.hpp). Below
// it a fork and join costs more than half of the work saves.
constexpr int kHalvesElements = 400;
inline int half_start(int n) { return n / 2; }
// the elements lo..hi-1 of half p (0 or 1)
struct HalfRange {
  int lo, hi;
};
inline HalfRange half_range(int n, int p) { return p == 0 ? HalfRange{0, half_start(n)} : HalfRange{half_start(n), n}; }

class TwoWay {
 public:
  explicit TwoWay(bool worker = true);
  ~TwoWay();
  TwoWay(const TwoWay&) = delete;
  TwoWay& operator=(const TwoWay&) = delete;
  // job(0) here and job(1) on the worker; returns when both are done. An exception from the
  // worker's half is rethrown here.
  void run(const std::function<void(int)>& job);

 private:
  void loop();
  const std::function<void(int)>* job_ = nullptr;
  // the generation of the last job posted, of the last whose half 1 was claimed (by either
  // thread) and of the last whose half 1 the worker finished
  std::atomic<std::uint64_t> posted_{0}, claimed_{0}, done_{0};
  std::atomic<bool> sleeping_{false}, quit_{false};
  std::exception_ptr error_;
  std::mutex m_;
  std::condition_variable cv_;
  std::thread worker_;
};

}  // namespace beltsim
