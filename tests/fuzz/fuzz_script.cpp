// The fuzz target over the scene API (issue 12, item 7): the fuzzer's bytes are a scenario script,
// run by the real interpreter in its sandbox (docs/limits-and-safety.md) with small limits, so
// that it explores beltsim.scene{...} tables, scene:run{}, scene:start{} and sim:run_to for a few
// steps. Every outcome but a ScriptError ("file:line: reason") is a finding: a crash, a sanitizer
// report, an exception of another type, a hang (libFuzzer's -timeout).
//
// Built two ways from this one file: with clang's -fsanitize=fuzzer as beltsim_fuzz (CMake option
// BELTSIM_FUZZ, scripts/setup.sh test), and with the normal build as beltsim_fuzz_replay, which
// runs the inputs it is given (tests/fuzz/regressions/, scripts/*.lua) through it as a ctest test.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

#include <unistd.h>

#include "script/interpreter.hpp"

namespace {

namespace fs = std::filesystem;

// Caps that keep one execution short (the scripts of scripts/ are the seeds: 60 and 150
// elements, t_end 1 s and more). Run before the input, in the same interpreter: a belt of more
// than kMaxElements is built with kMaxElements (a scene build grows with the elements: 0.6 s for
// 60 under the sanitizers, and the seeds stay valid at 24).
constexpr const char* kPrelude = R"(
local scene = beltsim.scene
beltsim.scene = function(d, ...)
  if type(d) == "table" and type(rawget(d, "belt")) == "table" then
    local n = rawget(d.belt, "elements")
    if type(n) == "number" and n > 24 then rawset(d.belt, "elements", 24) end
  end
  return scene(d, ...)
end
)";

struct Folder {
  fs::path dir, prelude, input, out;
  Folder() {
    dir = fs::temp_directory_path() / ("beltsim_fuzz_" + std::to_string(getpid()));
    fs::create_directories(dir / "in");
    prelude = dir / "in" / "prelude.lua";
    input = dir / "in" / "input.lua";
    out = dir / "out";
    std::ofstream(prelude) << kPrelude;
  }
  // at a normal exit (a finding aborts first, and its files stay)
  ~Folder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

// Ctrl-C after kBudget of wall time, as a user would press it: the stop flag ends a run or a
// scene build and the interpreter's interrupt ends Lua code, so a script that loops over short
// runs ends too. Whatever then runs past libFuzzer's -timeout is a hang of beltsim's own.
constexpr auto kBudget = std::chrono::seconds(5);

class Watchdog {
 public:
  explicit Watchdog(beltsim::script::Interpreter& lua) : thread_([this, &lua] {
      std::unique_lock<std::mutex> lock(m_);
      if (!cv_.wait_for(lock, kBudget, [this] { return done_; })) {
        stop_.store(true);
        lua.interrupt();
      }
    }) {}
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(m_);
      done_ = true;
    }
    cv_.notify_one();
    thread_.join();
  }
  const std::atomic<bool>* stop() const { return &stop_; }

 private:
  std::mutex m_;
  std::condition_variable cv_;
  bool done_ = false;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string g_refusal;  // the ScriptError of the last input, "" when it ran through

}  // namespace

extern "C" const char* BeltsimFuzzRefusal() {
  return g_refusal.c_str();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Folder f;
  g_refusal.clear();
  {
    std::ofstream in(f.input, std::ios::binary | std::ios::trunc);
    in.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  {
    beltsim::script::Safety safety;
    safety.max_instructions = 2'000'000;       // a few ms of Lua per call from the host
    safety.max_lua_memory = std::size_t(64) << 20;
    beltsim::script::Interpreter lua(safety);
    beltsim::script::Overrides o;
    o.out = f.out.string();  // every run's outputs, whatever the script's out = says
    o.t_end = 2e-3;          // scene:run{}: a few steps
    o.max_wall = 0.5;        // [s] each sim:run_to / advance / run (the watchdog's own limit)
    o.no_frames = true;      // frames = {...} is read and checked, not rendered
    lua.set_overrides(o);
    {
      Watchdog watchdog(lua);
      lua.set_stop_flag(watchdog.stop());
      try {
        lua.run_file(f.prelude.string());
        lua.run_file(f.input.string());
      } catch (const beltsim::script::ScriptError& e) {
        g_refusal = e.what();  // the expected outcome of a bad input
      }
      lua.set_stop_flag(nullptr);
    }
  }  // the interpreter closes its simulations (their outputs) before the folder goes
  std::error_code ec;
  fs::remove_all(f.out, ec);
  return 0;
}
