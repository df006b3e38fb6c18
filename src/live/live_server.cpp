#include "live/live_server.hpp"

#include <httplib.h>
#include <netdb.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "io/suggest.hpp"
#include "io/units.hpp"

namespace beltsim::live {

namespace {

// 128 bits from the system's random source, in hex
std::string random_token() {
  std::random_device rd;
  std::string t;
  char hex[9];
  for (int k = 0; k < 4; ++k) std::snprintf(hex, sizeof hex, "%08x", static_cast<unsigned>(rd())), t += hex;
  return t;
}

std::string read_asset(const std::string& dir, const char* name) {
  const std::string path = dir + "/" + name;
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw std::runtime_error("live view: cannot read " + path +
                             " (the page's plotting library: install the Debian "
                             "package libjs-dygraphs)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// s as a JSON string, appended to out
void add_string(std::string& out, const std::string& s) {
  out += '"';
  for (const char c : s) {
    if (c == '"' || c == '\\')
      out += '\\', out += c;
    else if (static_cast<unsigned char>(c) < 0x20)
      out += ' ';
    else
      out += c;
  }
  out += '"';
}

void add_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out += "null";
    return;
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  out += buf;
}

// [t, ratio, h, values...]
void add_row(std::string& out, const Sample& s) {
  out += '[';
  add_number(out, s.t), out += ',', add_number(out, s.ratio), out += ',', add_number(out, s.h);
  for (const double v : s.values) out += ',', add_number(out, v);
  out += ']';
}

// why host:port cannot be bound, as a bind of its own finds it (cpp-httplib says only that it failed)
std::string bind_problem(const std::string& host, int port) {
  addrinfo hints{}, *found = nullptr;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_NUMERICSERV;
  if (const int e = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found); e != 0)
    return "host '" + host + "': " + gai_strerror(e);
  int error = 0;
  for (const addrinfo* a = found; a; a = a->ai_next) {
    const int sock = socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (sock < 0) {
      error = errno;
      continue;
    }
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    const bool bound = bind(sock, a->ai_addr, a->ai_addrlen) == 0 && listen(sock, 1) == 0;
    if (!bound) error = errno;
    close(sock);
    if (bound) break;
  }
  freeaddrinfo(found);
  if (error == EADDRINUSE) return "port " + std::to_string(port) + " is in use";
  if (error == EADDRNOTAVAIL) return "'" + host + "' is not an address of this machine";
  if (error == EACCES) return "port " + std::to_string(port) + " needs privileges (ports below 1024)";
  if (error != 0) return std::strerror(error);
  return "cpp-httplib could not listen there";
}

// s as a finite decimal number into x ([+-]digits[.digits][e[+-]digits]); false when it is not one
// (empty, spaces, text after it, hex, inf, nan: strtod alone read "0x10" as 16)
bool finite_number(const std::string& s, double& x) {
  size_t k = 0, digits = 0;
  const auto run = [&] {
    size_t n = 0;
    while (k < s.size() && s[k] >= '0' && s[k] <= '9') ++k, ++n;
    return n;
  };
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
  digits = run();
  if (k < s.size() && s[k] == '.') ++k, digits += run();
  if (digits == 0) return false;
  if (k < s.size() && (s[k] == 'e' || s[k] == 'E')) {
    ++k;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
    if (run() == 0) return false;
  }
  if (k != s.size()) return false;
  x = std::strtod(s.c_str(), nullptr);
  return std::isfinite(x);
}

}  // namespace

std::string read_command(const std::function<std::string(const char*)>& param, Command& c) {
  c.what = param("do");
  c.pulley = param("pulley");
  c.name = param("name");
  const std::string v = param("value"), from = param("from"), to = param("to");
  if (c.what == "pause" || c.what == "continue") return "";
  if (c.what == "torque") {
    if (c.pulley.empty() || !finite_number(v, c.value))
      return "torque needs pulley=NAME and value=N·m (a finite decimal number), got pulley='" + c.pulley + "' value='" +
             v + "'";
    return "";
  }
  if (c.what == "run_to") {
    if (!finite_number(v, c.value)) return "run_to needs value=t [s] (a finite decimal number), got value='" + v + "'";
    return "";
  }
  if (c.what == "wet") {
    if (!finite_number(from, c.from) || !finite_number(to, c.to) || !finite_number(v, c.value))
      return "wet needs from=s0 and to=s1 [m] and value=mu (finite decimal numbers), got from='" + from + "' to='" +
             to + "' value='" + v + "'";
    return "";
  }
  if (c.what == "save") {
    // a bare file name in the run's folder: no path, no hidden file
    const bool plain = !c.name.empty() && c.name.size() <= 100 && c.name[0] != '.' &&
                       c.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") ==
                           std::string::npos;
    if (!plain) return "save needs name=FILE (letters, digits, '.', '_', '-'; no folder), got name='" + c.name + "'";
    return "";
  }
  return "do must be pause, continue, run_to, torque, wet or save, got '" + c.what + "'";
}

LiveServer::LiveServer(const ServeSettings& s) : settings_(s), token_(random_token()) {
  // the two files the page loads, read once: no request reaches the file system
  assets_js_ = read_asset(s.assets, "dygraph.js");
  assets_css_ = read_asset(s.assets, "dygraph.css");
  http_ = std::make_unique<httplib::Server>();
  // cpp-httplib's default options add SO_REUSEPORT, with which a second server (another beltsim,
  // or a second sim:serve) bound the same port and the kernel split the requests between the two:
  // SO_REUSEADDR alone, which lets a port whose last server has just ended be bound again
  http_->set_socket_options([](int sock) {
    const int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  routes();
  const std::string where = s.host + ":" + std::to_string(s.port);
  port_ = s.port == 0 ? http_->bind_to_any_port(s.host) : (http_->bind_to_port(s.host, s.port) ? s.port : -1);
  if (port_ <= 0)
    throw std::runtime_error("live view: cannot listen on " + where + ": " + bind_problem(s.host, s.port));
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::runtime_error("live view: cannot make an eventfd");
  thread_ = std::thread([this] { http_->listen_after_bind(); });
  // stop() before the thread has begun to listen would leave it listening: wait for it
  while (!http_->is_running()) std::this_thread::yield();
}

LiveServer::~LiveServer() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    stopping_ = true;
  }
  cv_.notify_all();
  http_->stop();
  if (thread_.joinable()) thread_.join();
  if (wake_fd_ >= 0) close(wake_fd_);
}

void LiveServer::wake() {
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t w = write(wake_fd_, &one, sizeof one);  // fails only when full: readable
}

bool LiveServer::take_page_opened() {
  const std::lock_guard<std::mutex> lock(m_);
  return std::exchange(page_opened_, false);
}

void LiveServer::clear_wake() {
  std::uint64_t n;
  if (read(wake_fd_, &n, sizeof n) < 0) return;  // EAGAIN: nothing came
}

std::string LiveServer::url() const {
  return "http://" + settings_.host + ":" + std::to_string(port_) + "/?token=" + token_;
}

void LiveServer::begin_run(std::uint64_t key, const std::string& name, std::vector<std::string> columns,
                           std::vector<std::string> pulleys) {
  {
    const std::lock_guard<std::mutex> lock(m_);
    ++status_serial_;
    status_ = "running";
    refusal_.clear();
    if (key == key_) return;
    key_ = key;
    ++run_;
    run_name_ = name;
    columns_ = std::move(columns);
    pulleys_ = std::move(pulleys);
    history_.clear(), recent_.clear();
    thin_ = 1, skipped_ = 0;
  }
  cv_.notify_all();
}

void LiveServer::publish(Sample s) {
  {
    const std::lock_guard<std::mutex> lock(m_);
    ++seq_;
    if (recent_.size() >= kBehind) recent_.pop_front();
    recent_.push_back({seq_, s});
    if (++skipped_ >= thin_) {
      skipped_ = 0;
      history_.push_back({seq_, std::move(s)});
      if (history_.size() >= kHistory) {  // keep every other one, and from now one in twice as many
        std::deque<Entry> kept;
        for (size_t k = 0; k < history_.size(); k += 2) kept.push_back(std::move(history_[k]));
        history_ = std::move(kept);
        thin_ *= 2;
      }
    }
  }
  cv_.notify_all();
}

void LiveServer::set_status(const std::string& status) {
  {
    const std::lock_guard<std::mutex> lock(m_);
    status_ = status;
    ++status_serial_;
  }
  cv_.notify_all();
}

void LiveServer::refuse_controls(const std::string& why) {
  {
    const std::lock_guard<std::mutex> lock(m_);
    refusal_ = why;
    for (const Command& c : commands_) status_ = "refused: " + c.what + ": " + why, ++status_serial_;
    pending_ -= static_cast<int>(commands_.size());
    commands_.clear();
  }
  cv_.notify_all();
}

void LiveServer::set_frame(std::string jpeg, double t, const std::vector<ElementAt>& elements, double length) {
  auto f = std::make_shared<const std::string>(std::move(jpeg));
  std::string json = "{\"t\":";
  add_number(json, t);
  json += ",\"length\":";
  add_number(json, length);
  json += ",\"elements\":[";
  char buf[64];
  for (size_t k = 0; k < elements.size(); ++k) {
    // s to the last bit: a stretch picked from it holds the element at its end (lua_run.hpp in_stretch)
    std::snprintf(buf, sizeof buf, "%s[%.1f,%.1f,%.17g]", k ? "," : "", elements[k].x, elements[k].y, elements[k].s);
    json += buf;
  }
  json += "]}";
  auto j = std::make_shared<const std::string>(std::move(json));
  {
    const std::lock_guard<std::mutex> lock(m_);
    frame_ = std::move(f);
    frame_json_ = std::move(j);
    frame_t_ = t;
    ++frame_serial_;
  }
  cv_.notify_all();
}

std::optional<Command> LiveServer::take(bool wait) {
  std::unique_lock<std::mutex> lock(m_);
  if (wait) cv_.wait_for(lock, std::chrono::milliseconds(200), [&] { return stopping_ || !commands_.empty(); });
  if (commands_.empty()) return std::nullopt;
  Command c = std::move(commands_.front());
  commands_.pop_front();
  --pending_;
  return c;
}

bool LiveServer::frame_wanted() const {
  const std::lock_guard<std::mutex> lock(m_);
  return fetched_serial_ == frame_serial_;
}

bool LiveServer::stopping() const {
  const std::lock_guard<std::mutex> lock(m_);
  return stopping_;
}

int LiveServer::clients() const {
  const std::lock_guard<std::mutex> lock(m_);
  return clients_;
}

// what a stream sends next (waits up to half a second for something new; "" when nothing came)
std::string LiveServer::stream_text(Cursor& c) {
  std::unique_lock<std::mutex> lock(m_);
  cv_.wait_for(lock, std::chrono::milliseconds(500), [&] {
    return stopping_ || c.run != run_ || c.seq != seq_ || c.status != status_serial_ || c.frame != frame_serial_;
  });
  if (stopping_) return {};
  std::string out;
  if (c.run != run_) {  // a new run (or a new client): the columns, then the history
    c.run = run_;
    out += "event: run\ndata: {\"name\":";
    add_string(out, run_name_);
    out += ",\"columns\":[";
    for (size_t k = 0; k < columns_.size(); ++k) out += k ? "," : "", add_string(out, columns_[k]);
    out += "],\"units\":[";
    for (size_t k = 0; k < columns_.size(); ++k) out += k ? "," : "", add_string(out, unit_of(columns_[k]));
    out += "],\"pulleys\":[";
    for (size_t k = 0; k < pulleys_.size(); ++k) out += k ? "," : "", add_string(out, pulleys_[k]);
    out += "]}\n\nevent: samples\ndata: [";
    for (size_t k = 0; k < history_.size(); ++k) out += k ? "," : "", add_row(out, history_[k].s);
    out += "]\n\n";
    c.seq = history_.empty() ? 0 : history_.back().seq;
  }
  if (c.seq != seq_ && !recent_.empty()) {  // what came since (a slow client skips what it missed)
    out += "event: samples\ndata: [";
    bool any = false;
    for (const Entry& e : recent_)
      if (e.seq > c.seq) out += any ? "," : "", add_row(out, e.s), any = true;
    out += "]\n\n";
    c.seq = seq_;
  }
  if (c.status != status_serial_) {
    c.status = status_serial_;
    out += "event: status\ndata: ";
    add_string(out, status_);
    out += "\n\n";
  }
  if (c.frame != frame_serial_) {  // a new picture: the page asks for it
    c.frame = frame_serial_;
    out += "event: frame\ndata: ";
    add_number(out, frame_t_);
    out += "\n\n";
  }
  if (out.empty()) out = ": idle\n\n";  // a comment: finds a closed client
  return out;
}

void LiveServer::routes() {
  httplib::Server& h = *http_;
  h.set_keep_alive_timeout(1);
  // a control (POST /control): queued for the loop that owns the simulation, or refused naming what
  // is wrong (400: a pulley the run has not, in the console's words, too), or that there is nothing
  // left to change (409, refuse_controls)
  const auto control = [this](const httplib::Request& req, httplib::Response& res) {
    Command c;
    const std::string bad = read_command([&req](const char* key) { return req.get_param_value(key); }, c);
    if (!bad.empty()) {
      res.status = 400;
      res.set_content(bad + "\n", "text/plain");
      return;
    }
    {
      const std::lock_guard<std::mutex> lock(m_);
      if (!refusal_.empty()) {  // nothing left to change: said now, not after "queued"
        res.status = 409;
        res.set_content("refused: " + c.what + ": " + refusal_ + "\n", "text/plain");
        return;
      }
      if (c.what == "torque" && !pulleys_.empty() &&
          std::find(pulleys_.begin(), pulleys_.end(), c.pulley) == pulleys_.end()) {
        res.status = 400;
        res.set_content("torque: " + no_such("pulley", c.pulley, pulleys_) + "\n", "text/plain");
        return;
      }
      if (commands_.size() >= kCommands) {
        res.status = 503;
        res.set_content("too many controls waiting\n", "text/plain");
        return;
      }
      commands_.push_back(std::move(c));
      ++pending_;
    }
    cv_.notify_all();
    wake();
    res.status = 202;
    res.set_content("queued\n", "text/plain");
  };
  h.set_pre_routing_handler([this, control](const httplib::Request& req, httplib::Response& res) {
    if (req.get_param_value("token") != token_) {
      res.status = 403;
      res.set_content("403: this page needs the address beltsim printed, with its token\n", "text/plain");
      return httplib::Server::HandlerResponse::Handled;
    }
    // a POST without a body says so with no Content-Length at all (curl -X POST URL): cpp-httplib
    // would read a body until the client closes, and answer 400 after its read timeout. A control
    // has everything in its query: answered here, before any body is read
    if (req.method == "POST" && req.path == "/control" && !req.has_header("Content-Length") &&
        !req.has_header("Transfer-Encoding")) {
      control(req, res);
      return httplib::Server::HandlerResponse::Handled;
    }
    return httplib::Server::HandlerResponse::Unhandled;
  });
  // an error cpp-httplib answers itself has an empty body: say what it is
  h.set_error_handler(httplib::Server::HandlerWithResponse([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty()) return httplib::Server::HandlerResponse::Unhandled;
    std::string said = std::to_string(res.status) + ": ";
    if (res.status == 404)
      said += "not served: " + req.method + " " + req.path +
              " (the live view serves GET /, /dygraph.js, /dygraph.css, /frame.jpg, /frame.json, /events and "
              "POST /control)";
    else if (res.status == 400)
      said += "the request could not be read (a body needs its Content-Length; a control needs none)";
    else if (res.status == 413)
      said += "the request is too large";
    else
      said += "the request was not served";
    res.set_content(said + "\n", "text/plain");
    return httplib::Server::HandlerResponse::Handled;
  }));
  h.Get("/", [this](const httplib::Request&, httplib::Response& res) {
    std::string page = page_html();
    for (size_t at = page.find("@TOKEN@"); at != std::string::npos; at = page.find("@TOKEN@", at))
      page.replace(at, 7, token_);
    res.set_content(page, "text/html");
  });
  h.Get("/dygraph.js",
        [this](const httplib::Request&, httplib::Response& res) { res.set_content(assets_js_, "text/javascript"); });
  h.Get("/dygraph.css",
        [this](const httplib::Request&, httplib::Response& res) { res.set_content(assets_css_, "text/css"); });
  // the latest frame and its elements' places (a frame's t is in both: the page matches them)
  for (const bool json : {false, true})
    h.Get(json ? "/frame.json" : "/frame.jpg", [this, json](const httplib::Request&, httplib::Response& res) {
      std::shared_ptr<const std::string> f;
      {
        const std::lock_guard<std::mutex> lock(m_);
        f = json ? frame_json_ : frame_;
        if (!json) fetched_serial_ = frame_serial_;
      }
      res.set_header("Cache-Control", "no-store");
      if (!f) {
        res.status = 503;
        res.set_content("no frame yet\n", "text/plain");
        return;
      }
      res.set_content(*f, json ? "application/json" : "image/jpeg");
    });
  h.Post("/control", control);
  h.Get("/events", [this](const httplib::Request&, httplib::Response& res) {
    {
      const std::lock_guard<std::mutex> lock(m_);
      ++clients_;
      page_opened_ = true;
    }
    wake();  // a console at its prompt draws the picture for it
    auto cursor = std::make_shared<Cursor>();
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, cursor](size_t, httplib::DataSink& sink) {
          const std::string text = stream_text(*cursor);
          if (text.empty()) {  // stopping
            sink.done();
            return true;
          }
          return sink.write(text.data(), text.size());
        },
        [this](bool) {
          const std::lock_guard<std::mutex> lock(m_);
          --clients_;
        });
  });
}

}  // namespace beltsim::live
