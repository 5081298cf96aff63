// mesh_hash (document.h): FNV-1a 64 over explicit little-endian bytes, so
// the number does not depend on the host's byte order or int width.
#include <algorithm>
#include <cstdio>
#include <cstring>

#include "anisoform/document.h"

namespace aniso {
namespace {

constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr std::uint64_t kFnvPrime = 0x100000001b3ull;

void hash_bytes_le(std::uint64_t& hash, std::uint64_t value, int bytes) {
  for (int b = 0; b < bytes; ++b) {
    hash ^= (value >> (8 * b)) & 0xffu;
    hash *= kFnvPrime;
  }
}

}  // namespace

std::uint64_t mesh_hash(const Positions& V, const Triangles& F) {
  std::uint64_t hash = kFnvOffset;
  hash_bytes_le(hash, static_cast<std::uint64_t>(V.rows()), 8);
  hash_bytes_le(hash, static_cast<std::uint64_t>(F.rows()), 8);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double x = V(i, k);
      std::uint64_t bits = 0;
      std::memcpy(&bits, &x, sizeof bits);
      hash_bytes_le(hash, bits, 8);
    }
  }
  for (Eigen::Index t = 0; t < F.rows(); ++t) {
    for (int k = 0; k < 3; ++k) hash_bytes_le(hash, static_cast<std::uint32_t>(F(t, k)), 4);
  }
  return hash;
}

bool is_mesh_hash_text(const std::string& text) {
  const std::string prefix = "fnv1a64:";
  if (text.size() != prefix.size() + 16 || text.compare(0, prefix.size(), prefix) != 0) return false;
  return std::all_of(text.begin() + static_cast<std::ptrdiff_t>(prefix.size()), text.end(),
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

std::string mesh_hash_text(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace aniso
