// The warning guard of warning_guard.hpp: a gtest event listener, appended to the test program's
// listeners before main runs, that installs the process-wide warning observer for each test and
// checks what it saw when the test ends (failures raised in OnTestEnd belong to that test, as in
// gtest's own leak-checker sample).
#include "support/warning_guard.hpp"

#include <gtest/gtest.h>

#include <array>
#include <mutex>
#include <string>

namespace beltsim::test {

namespace {

struct Seen {
  std::mutex m;
  std::array<WarningStat, kWarningKinds> fired{};
  std::array<bool, kWarningKinds> expected{};
};

Seen& seen() {
  static Seen s;
  return s;
}

void observe(WarningKind k, double t, long n) {
  Seen& s = seen();
  std::lock_guard<std::mutex> lock(s.m);
  WarningStat& f = s.fired[static_cast<std::size_t>(k)];
  if (f.count == 0) f.first_t = t;
  f.count += n;
}

class Guard : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo&) override {
    Seen& s = seen();
    {
      std::lock_guard<std::mutex> lock(s.m);
      s.fired.fill(WarningStat{});
      s.expected.fill(false);
    }
    set_warning_observer(observe);
  }
  void OnTestEnd(const ::testing::TestInfo&) override {
    set_warning_observer(nullptr);
    Seen& s = seen();
    std::lock_guard<std::mutex> lock(s.m);
    for (const WarningKindInfo& i : warning_kinds()) {
      const std::size_t k = static_cast<std::size_t>(i.kind);
      EXPECT_TRUE(s.fired[k].count == 0 || s.expected[k])
          << "unexpected warning " << describe(i.kind, s.fired[k])
          << "; if the test means it, declare it with beltsim::test::expect_warnings";
    }
  }
};

// appended before main: every test of the program is guarded
const bool installed = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new Guard);
  return true;
}();

}  // namespace

void expect_warnings(std::initializer_list<WarningKind> kinds) {
  Seen& s = seen();
  std::lock_guard<std::mutex> lock(s.m);
  for (WarningKind k : kinds) s.expected[static_cast<std::size_t>(k)] = true;
}

}  // namespace beltsim::test
