#include "model/two_way.hpp"

#include <chrono>
#include <pthread.h>
#include <utility>

namespace beltsim {

namespace {
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#else
  std::this_thread::yield();
#endif
}
}  // namespace

TwoWay::TwoWay(bool worker) {
  if (worker && std::thread::hardware_concurrency() >= 2) worker_ = std::thread([this] { loop(); });
}

TwoWay::~TwoWay() {
  if (!worker_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(m_);
    quit_ = true;
  }
  cv_.notify_one();
  worker_.join();
}

void TwoWay::run(const std::function<void(int)>& job) {
  if (!worker_.joinable()) {
    job(0);
    job(1);
    return;
  }
  job_ = &job;
  const std::uint64_t g = posted_.load(std::memory_order_relaxed) + 1;
  posted_.store(g, std::memory_order_seq_cst);
  if (sleeping_.load(std::memory_order_seq_cst)) {
    std::lock_guard<std::mutex> lock(m_);
    cv_.notify_one();
  }
  std::exception_ptr mine;
  try {
    job(0);
  } catch (...) {
    mine = std::current_exception();
  }
  std::uint64_t expected = g - 1;
  if (claimed_.compare_exchange_strong(expected, g, std::memory_order_seq_cst)) {
    try {
      job(1);  // the worker has not started it: run it here
    } catch (...) {
      if (!mine) mine = std::current_exception();
    }
  } else {
    for (int k = 0; done_.load(std::memory_order_acquire) != g; ++k) {
      if (k < 4096) relax();
      else std::this_thread::yield();  // the worker was descheduled mid-job
    }
  }
  job_ = nullptr;
  if (mine) std::rethrow_exception(mine);
  if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void TwoWay::loop() {
  pthread_setname_np(pthread_self(), "beltsim-half");  // as top -H and perf name it
  using clock = std::chrono::steady_clock;
  std::uint64_t seen = 0;
  auto idle_since = clock::now();
  for (;;) {
    const std::uint64_t g = posted_.load(std::memory_order_acquire);
    if (g != seen) {
      seen = g;
      std::uint64_t expected = g - 1;
      if (claimed_.compare_exchange_strong(expected, g, std::memory_order_seq_cst)) {
        try {
          (*job_)(1);
        } catch (...) {
          error_ = std::current_exception();
        }
        done_.store(g, std::memory_order_release);
      }
      idle_since = clock::now();
      continue;
    }
    if (quit_.load(std::memory_order_acquire)) return;
    for (int k = 0; k < 256 && posted_.load(std::memory_order_relaxed) == seen; ++k) relax();
    if (clock::now() - idle_since < std::chrono::milliseconds(20)) continue;
    std::unique_lock<std::mutex> lock(m_);
    sleeping_.store(true, std::memory_order_seq_cst);
    cv_.wait(lock, [&] { return posted_.load(std::memory_order_seq_cst) != seen || quit_.load(); });
    sleeping_.store(false, std::memory_order_seq_cst);
    idle_since = clock::now();
  }
}

}  // namespace beltsim
