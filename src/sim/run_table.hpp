// The run settings: one table of every setting a run takes (the keys of scene:run{} and
// scene:start{}, and keep_samples, which beltsim wp sets), with its unit, its default, its rule,
// the command-line option that overrides it, whether a checkpoint keeps it and where its value
// lives in a RunSettings, as kParameters is for the scene (scene/parameters.hpp). The Lua reader
// (script/lua_run.cpp), the command line's overrides (app/options.cpp, app/cli.cpp), the check
// (check(), settings_check.hpp), parameters.csv's run.* rows (sim/outputs.cpp), the checkpoint's
// settings (sim/checkpoint.cpp) and the run-settings table of docs/lua-api.md
// (run_settings_markdown) all come from it.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace beltsim {

struct RunSettings;

// how a setting's value is given
enum class RunKind {
  number,  // a number (in Lua and on the command line)
  flag,    // true or false (a command-line flag sets it)
  text,    // a string
  other    // a list or a table: read, checked, written and kept by its own code (probe, snapshots,
           // events, frames)
};

// where a setting is taken (bits)
enum RunWhere : unsigned {
  kRunKey = 1,    // a key of scene:run{}
  kStartKey = 2,  // a key of scene:start{}
  kSaved = 4      // a checkpoint keeps it
};

// where a setting's value lives in a RunSettings
using RunSlot = std::variant<std::monostate, double*, bool*, std::string*>;

struct RunSetting {
  std::string_view key;  // the key of scene:run{}; parameters.csv's row is run.<key>
  RunKind kind;
  std::string_view unit;          // SI; "" when none
  std::string_view fallback;      // the default, as the docs show it
  unsigned where;                 // RunWhere bits
  std::string_view option;        // the command-line option that overrides it in every run ("" when none)
  std::string_view note;          // what it is
  RunSlot (*slot)(RunSettings&);  // nullptr for RunKind::other
  // a number's value that means "not given" (atol's -1: rtol; max_wall's 0: no limit), which check()
  // takes without the rule; NaN when every value is checked
  double unset;
  // why v cannot be this number's value ("must be > 0 s and finite (got -1 s)"), "" when it can;
  // a text's through text_problem; nullptr: no rule of its own
  std::string (*number_problem)(double v);
  std::string (*text_problem)(const std::string& v);
  // the value as parameters.csv gives it; nullptr: from the slot (a number, 1 or 0, the text)
  std::string (*csv)(const RunSettings& rs);
};

// every setting, in the order the docs, the Lua reader (keep_states before frames, which may then
// give only times) and a checkpoint list them
std::span<const RunSetting> run_settings();
// the setting of a key; nullptr when none
const RunSetting* find_run_setting(std::string_view key);
// the keys of scene:run{} (batch) or scene:start{}, as a valid-key list
std::vector<std::string> run_keys(bool batch);

// where the setting's value lives in rs (an empty slot for RunKind::other)
RunSlot run_slot(const RunSetting& s, const RunSettings& rs);
// the setting's value in rs as parameters.csv gives it
std::string run_value_text(const RunSetting& s, const RunSettings& rs);
// why the setting's value in rs is not one it takes, "" when it is; given: a value given by a
// script or on the command line, whose unset value is refused too (max_wall = 0)
std::string run_problem(const RunSetting& s, const RunSettings& rs, bool given);
// copies the setting's value from `from` to `to` (a number, flag or text)
void copy_run_setting(const RunSetting& s, const RunSettings& from, RunSettings& to);

// The run-settings table of docs/lua-api.md (key, unit, default, command line, checkpoint,
// meaning), as `beltsim help run-settings` prints it and the docs hold it.
std::string run_settings_markdown();

}  // namespace beltsim
