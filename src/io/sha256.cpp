#include "io/sha256.hpp"

#include <nettle/sha2.h>

#include <fstream>

namespace beltsim {

struct Sha256::State {
  sha256_ctx ctx;
};

Sha256::Sha256() : s_(std::make_unique<State>()) {
  sha256_init(&s_->ctx);
}
Sha256::~Sha256() = default;

void Sha256::update(const void* data, std::size_t n) {
  sha256_update(&s_->ctx, n, static_cast<const std::uint8_t*>(data));
}

std::string Sha256::hex() {
  std::uint8_t d[SHA256_DIGEST_SIZE];
  sha256_digest(&s_->ctx, sizeof d, d);  // (and starts again)
  static const char* const digits = "0123456789abcdef";
  std::string h;
  for (std::uint8_t b : d) {
    h += digits[b >> 4];
    h += digits[b & 15];
  }
  return h;
}

std::string file_sha256(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return "";
  Sha256 h;
  char buf[65536];
  while (f.read(buf, sizeof buf) || f.gcount() > 0) h.update(buf, static_cast<std::size_t>(f.gcount()));
  return f.bad() ? "" : h.hex();
}

}  // namespace beltsim
