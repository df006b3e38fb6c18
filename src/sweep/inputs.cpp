#include "sweep/inputs.hpp"

#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "beltsim_version.hpp"
#include "io/sha256.hpp"

namespace beltsim::sweep {

namespace {

constexpr const char* kProgram = "program: ";
constexpr const char* kOptions = "options: ";
constexpr const char* kFile = "file ";

bool starts(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

// the same path, or two paths of one file (a symlinked folder, a hard link)

}  // namespace

std::string inputs_text(const Inputs& in) {
  std::string t = kProgram + in.program + "\n" + kOptions + in.options + "\n";
  for (const auto& [path, hash] : in.files) t += kFile + hash + " " + path + "\n";
  return t;
}

std::optional<Inputs> parse_inputs(const std::string& text) {
  std::istringstream s(text);
  std::string line;
  Inputs in;
  if (!std::getline(s, line) || !starts(line, kProgram)) return std::nullopt;
  in.program = line.substr(std::string(kProgram).size());
  if (!std::getline(s, line) || !starts(line, kOptions)) return std::nullopt;
  in.options = line.substr(std::string(kOptions).size());
  while (std::getline(s, line)) {
    const std::size_t at = std::string(kFile).size(), space = at + 64;
    if (!starts(line, kFile) || line.size() <= space + 1 || line[space] != ' ') return std::nullopt;
    in.files.emplace_back(line.substr(space + 1), line.substr(at, 64));
  }
  return in;
}

std::string this_program() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find this program's path (/proc/self/exe): " + ec.message());
  return p.string();
}

std::string program_identity() {
  const std::string exe = this_program();
  const std::string hash = file_sha256(exe);
  return std::string("beltsim ") + kBeltsimVersion + ", executable SHA-256 " + (hash.empty() ? "unreadable" : hash);
}

std::string changed_inputs(const std::string& recorded, Definition& now) {
  if (recorded.empty()) return "point.csv has no record of what defined the point (an older beltsim wrote it)";
  const std::optional<Inputs> in = parse_inputs(recorded);
  if (!in) return "point.csv's record of what defined the point is unreadable";
  if (in->program != now.program) return "the program has changed (was " + in->program + ")";
  if (in->options != now.options)
    return "the options have changed (were '" + in->options + "', now '" + now.options + "')";
  if (!now.sweep_file.empty() && (in->files.empty() || !same_file(in->files.front().first, now.sweep_file)))
    return "the sweep file has changed (was " + (in->files.empty() ? std::string("none") : in->files.front().first) +
           ", now " + now.sweep_file + ")";
  for (const auto& [path, hash] : in->files) {
    auto it = now.hashes.find(path);
    if (it == now.hashes.end()) it = now.hashes.emplace(path, file_sha256(path)).first;
    if (it->second.empty()) return "the file " + path + ", which the point loaded, is gone or unreadable";
    if (it->second != hash) return "the file " + path + " has changed";
  }
  return "";
}

// the same file: the same path, or two paths to one file
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return a == b || (std::filesystem::equivalent(a, b, ec) && !ec);
}

}  // namespace beltsim::sweep
