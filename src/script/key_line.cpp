// The line where a script wrote a table's key (see key_line.hpp): a scan of Lua's tokens, enough
// of them to follow table constructors; everything else (expressions, calls) is stepped over.
#include "script/key_line.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>

namespace beltsim::script {

namespace {

// Lua's tokens, as far as tables need them: a name, a string's contents, a number, or the
// punctuation itself ("{", "=", "==", "..")
struct Token {
  enum Kind { name, string, number, punct, end } kind = end;
  std::string text;
  int line = 0;
};

class Lexer {
 public:
  explicit Lexer(std::string_view s) : s_(s) {}

  Token next() {
    if (peeked_) {
      peeked_ = false;
      return ahead_;
    }
    return read();
  }

  const Token& peek() {
    if (!peeked_) ahead_ = read(), peeked_ = true;
    return ahead_;
  }

 private:
  Token read() {
    skip_space_and_comments();
    Token t;
    t.line = line_;
    if (i_ >= s_.size()) return t;
    const char c = s_[i_];
    if (ident_start(c)) {
      const size_t b = i_;
      while (i_ < s_.size() && ident_char(s_[i_])) ++i_;
      t.kind = Token::name, t.text = s_.substr(b, i_ - b);
    } else if (digit(c) || (c == '.' && i_ + 1 < s_.size() && digit(s_[i_ + 1]))) {
      const size_t b = i_;
      while (i_ < s_.size() && (ident_char(s_[i_]) || s_[i_] == '.' ||
                                ((s_[i_] == '+' || s_[i_] == '-') && std::strchr("eEpP", s_[i_ - 1]))))
        ++i_;
      t.kind = Token::number, t.text = s_.substr(b, i_ - b);
    } else if (c == '"' || c == '\'') {
      t.kind = Token::string, t.text = quoted(c);
    } else if (c == '[' && long_bracket_level() >= 0) {
      t.kind = Token::string, t.text = long_bracket();
    } else {
      t.kind = Token::punct;
      static const char* const two[] = {"==", "~=", "<=", ">=", "..", "::", "//", "<<", ">>"};
      t.text = std::string(1, c);
      for (const char* p : two)
        if (s_.substr(i_, 2) == p) t.text = p;
      i_ += t.text.size();
      if (t.text == ".." && i_ < s_.size() && s_[i_] == '.') t.text = "...", ++i_;
    }
    return t;
  }

  void skip_space_and_comments() {
    while (i_ < s_.size()) {
      if (s_[i_] == '\n') {
        ++line_, ++i_;
      } else if (std::isspace(static_cast<unsigned char>(s_[i_]))) {
        ++i_;
      } else if (s_.substr(i_, 2) == "--") {
        i_ += 2;
        if (i_ < s_.size() && s_[i_] == '[' && long_bracket_level() >= 0) {
          long_bracket();
        } else {
          while (i_ < s_.size() && s_[i_] != '\n') ++i_;
        }
      } else {
        return;
      }
    }
  }

  // "[[" is level 0, "[==[" level 2; -1 when s_[i_] opens no long bracket
  int long_bracket_level() const {
    size_t k = i_ + 1;
    while (k < s_.size() && s_[k] == '=') ++k;
    return k < s_.size() && s_[k] == '[' ? static_cast<int>(k - i_ - 1) : -1;
  }

  std::string long_bracket() {
    const int level = long_bracket_level();
    std::string close(static_cast<size_t>(level) + 2, '=');  // "]==]"
    close.front() = close.back() = ']';
    i_ += static_cast<size_t>(level) + 2;
    const size_t e = std::min(s_.find(close, i_), s_.size());
    std::string body(s_.substr(i_, e - i_));
    for (char ch : body) line_ += ch == '\n';
    i_ = std::min(e + close.size(), s_.size());
    return body;
  }

  std::string quoted(char q) {
    std::string body;
    for (++i_; i_ < s_.size() && s_[i_] != q; ++i_) {
      if (s_[i_] == '\n') ++line_;  // an unfinished string: the loader has refused the script
      if (s_[i_] == '\\' && i_ + 1 < s_.size()) {
        ++i_;
        if (s_[i_] == '\n') ++line_;
      }
      body += s_[i_];
    }
    if (i_ < s_.size()) ++i_;
    return body;
  }

  std::string_view s_;
  size_t i_ = 0;
  int line_ = 1;
  Token ahead_;
  bool peeked_ = false;
};

bool is(const Token& t, std::string_view punct) {
  return t.kind == Token::punct && t.text == punct;
}

// a table constructor being read: the key or list position it is the value of, and the value of
// its own `name` key (known only when its `name =` has been read: kept by id, filled in later)
struct Table {
  std::string key;
  int position = 0;  // from 1 in the enclosing list; 0 when keyed or inside an expression
  std::string name;
  int line = 0;              // where its "{" is
  std::vector<int> parents;  // ids of the enclosing tables, the outermost (the call's) first
};

struct Occurrence {
  std::string key;
  int line;
  std::vector<int> tables;  // ids of the enclosing tables, the outermost (the call's) first
};

// Reads the constructor that starts at the lexer's next "{": every `key =` in it, nested ones too
class ConstructorScan {
 public:
  explicit ConstructorScan(Lexer& lex) : lex_(lex) {}

  void table(const std::string& key, int position, int line) {
    // deeper than Lua's parser nests (LUAI_MAXCCALLS, 200): the file is not the script Lua read
    if (open_.size() >= 200) {
      gave_up_ = true;
      return;
    }
    const int id = static_cast<int>(tables_.size());
    tables_.push_back({key, position, "", line, open_});
    open_.push_back(id);
    int positions = 0;
    for (;;) {
      // one field: `name = value`, `[expr] = value` or a list entry `value`
      Token t = lex_.next();
      if (t.kind == Token::end || is(t, "}")) break;
      std::string item_key;
      int item_position = 0;
      if (t.kind == Token::name && is(lex_.peek(), "=")) {
        lex_.next();
        item_key = t.text;
        found_.push_back({t.text, t.line, open_});
        t = lex_.next();
        if (item_key == "name" && t.kind == Token::string) tables_[static_cast<size_t>(id)].name = t.text;
      } else if (is(t, "[")) {
        skip_until_close("[", "]");
        lex_.next();  // "="
        t = lex_.next();
      } else {
        item_position = ++positions;
      }
      t = value(t, item_key, item_position);
      if (t.kind == Token::end || is(t, "}")) break;
    }
    open_.pop_back();
  }

  const std::vector<Table>& tables() const { return tables_; }
  const std::vector<Occurrence>& found() const { return found_; }
  bool gave_up() const { return gave_up_; }

 private:
  // steps over one field's value from its first token t; returns the token that ends it ("," ";"
  // "}" or the end). Tables inside it are read as the value of `key` (the one at the value's
  // start also as the list entry `position`; later ones, a call's arguments, as the key's only).
  Token value(Token t, const std::string& key, int position) {
    for (int depth = 0, first = 1;; t = lex_.next(), first = 0) {  // depth: ( [ nesting
      if (t.kind == Token::end) return t;
      if (depth == 0 && (is(t, ",") || is(t, ";") || is(t, "}"))) return t;
      if (is(t, "{")) {
        table(key, first ? position : 0, t.line);
      } else if (is(t, "(") || is(t, "[")) {
        ++depth;
      } else if (is(t, ")") || is(t, "]")) {
        --depth;
      } else if (t.kind == Token::name && t.text == "function") {
        skip_function_body();
      }
    }
  }

  void skip_until_close(const char* open, const char* close) {
    for (int depth = 1; depth > 0;) {
      const Token t = lex_.next();
      if (t.kind == Token::end) return;
      if (t.kind == Token::punct) depth += (t.text == open) - (t.text == close);
    }
  }

  // after `function`: up to its `end`, counting the blocks that `end` closes
  void skip_function_body() {
    for (int depth = 1; depth > 0;) {
      const Token t = lex_.next();
      if (t.kind == Token::end) return;
      if (t.kind != Token::name) continue;
      if (t.text == "function" || t.text == "if" || t.text == "do" || t.text == "repeat") ++depth;
      if (t.text == "end" || t.text == "until") --depth;
    }
  }

  Lexer& lex_;
  std::vector<Table> tables_;
  std::vector<int> open_;
  std::vector<Occurrence> found_;
  bool gave_up_ = false;
};

bool is_digits(std::string_view s) {
  return !s.empty() && digits_end(s, 0) == s.size();
}

// the tables around an occurrence, below the call's own, match `prefix` (keys and positions)
bool tables_match(const std::vector<Table>& tables, const std::vector<int>& ids, size_t from,
                  const std::vector<std::string>& prefix) {
  if (ids.size() - from != prefix.size()) return false;
  for (size_t k = 0; k < prefix.size(); ++k) {
    const Table& t = tables[static_cast<size_t>(ids[from + k])];
    const bool ok =
        is_digits(prefix[k]) ? prefix[k].size() <= 9 && t.position == std::stoi(prefix[k]) : t.key == prefix[k];
    if (!ok) return false;
  }
  return true;
}

bool matches(const std::vector<Table>& tables, const Occurrence& o, const KeyPath& path,
             const std::vector<std::string>& prefix) {
  if (o.key != path.chain.back()) return false;
  if (path.pulley.empty()) return tables_match(tables, o.tables, 1, prefix);
  // below the innermost table named after the pulley
  for (size_t k = o.tables.size(); k-- > 1;)
    if (tables[static_cast<size_t>(o.tables[k])].name == path.pulley)
      return tables_match(tables, o.tables, k + 1, prefix);
  return false;
}

// whether `path` names a table rather than a key: a list entry ("pulleys[2]") or a pulley
// ("pulley 'idler'")
bool names_entry(const KeyPath& path) {
  return path.chain.empty() ? !path.pulley.empty() : is_digits(path.chain.back());
}

// whether table t is the one `path` names (names_entry), the tables around it matching `prefix`
bool is_entry(const std::vector<Table>& tables, const Table& t, const KeyPath& path,
              const std::vector<std::string>& prefix) {
  if (path.chain.empty()) return t.name == path.pulley;
  if (t.position <= 0) return false;
  // as a key's occurrence whose key is its position ("2")
  const Occurrence o{std::to_string(t.position), t.line, t.parents};
  return matches(tables, o, path, prefix);
}

}  // namespace

KeyPath message_path(std::string_view m) {
  std::string_view rest = m;
  std::string unknown;  // "unknown key 'K' in WHERE": the path is WHERE.K
  if (constexpr std::string_view u = "unknown key '"; rest.substr(0, u.size()) == u) {
    const size_t e = rest.find('\'', u.size());
    if (e == std::string_view::npos || rest.substr(e, 5) != "' in ") return {};
    unknown = std::string(rest.substr(u.size(), e - u.size()));
    rest = rest.substr(e + 5);
  }
  KeyPath p = parse_path(rest, unknown.empty());
  if (!unknown.empty()) {
    if (p.empty()) return {};
    p.chain.push_back(unknown);
  }
  return p;
}

std::optional<int> key_line(std::string_view text, int call_line, const KeyPath& path) {
  if (path.empty()) return std::nullopt;
  Lexer lex(text);
  Token t = lex.next();
  while (t.kind != Token::end && t.line < call_line) t = lex.next();
  while (t.kind != Token::end && t.line == call_line && !is(t, "{")) t = lex.next();
  if (t.kind == Token::end || t.line != call_line) return std::nullopt;
  ConstructorScan scan(lex);
  scan.table("", 0, t.line);
  if (scan.gave_up()) return std::nullopt;

  // the lines of the keys (or, for a path that names an entry, of the tables) that match `p`
  const auto lines_of = [&](const KeyPath& p, const std::vector<std::string>& prefix) {
    std::set<int> lines;
    if (names_entry(p)) {
      for (const Table& tb : scan.tables())
        if (is_entry(scan.tables(), tb, p, prefix)) lines.insert(tb.line);
    } else {
      for (const Occurrence& o : scan.found())
        if (matches(scan.tables(), o, p, prefix)) lines.insert(o.line);
    }
    return lines;
  };
  const auto lines_for = [&](const KeyPath& p) {
    const std::vector<std::string> prefix(p.chain.begin(), p.chain.end() - (p.chain.empty() ? 0 : 1));
    std::set<int> lines = lines_of(p, prefix);
    // a leading "scene", "run", "start" or "sweep" names the call's own table
    if (lines.empty() && !prefix.empty() &&
        (prefix[0] == "scene" || prefix[0] == "run" || prefix[0] == "start" || prefix[0] == "sweep"))
      lines = lines_of(p, {prefix.begin() + 1, prefix.end()});
    return lines;
  };
  std::set<int> lines = lines_for(path);
  // a key not written in a list entry or a pulley's table (left out, or written as another
  // spelling): the entry's own line
  if (lines.empty() && !names_entry(path)) {
    KeyPath entry = path;
    entry.chain.pop_back();
    if (names_entry(entry)) lines = lines_for(entry);
  }
  if (lines.size() != 1) return std::nullopt;
  return *lines.begin();
}

std::optional<int> key_line_in_file(const std::string& file, int call_line, const KeyPath& path) {
  constexpr off_t kMaxBytes = 4 << 20;
  struct stat st;
  if (path.empty() || stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > kMaxBytes)
    return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  return key_line(text, call_line, path);
}

}  // namespace beltsim::script
