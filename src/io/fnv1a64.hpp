// FNV-1a, 64 bits: a checkpoint's checksum line (io/checkpoint_text.hpp) and the fingerprints of
// the outputs a checkpoint continues (io/row_file.hpp, sim/outputs.hpp). Not cryptographic: it
// tells a file changed by accident or by another run from the one written, not a forgery.
#pragma once

#include <cstdint>
#include <string_view>

namespace beltsim {

// the hash of no bytes (FNV's offset basis)
inline constexpr std::uint64_t kFnv1a64Empty = 0xcbf29ce484222325ull;

// the hash of `bytes`, or of the bytes hashed to `h` followed by `bytes` (the hash of a file
// taken row by row as it is written)
inline std::uint64_t fnv1a64(std::string_view bytes, std::uint64_t h = kFnv1a64Empty) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

}  // namespace beltsim
