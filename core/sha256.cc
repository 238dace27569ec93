#include "core/sha256.h"

#include <nettle/sha2.h>

#include <cstdint>
#include <fstream>
#include <string>

namespace moorsim {
namespace {

std::string Hex(sha256_ctx& context) {
  std::uint8_t digest[SHA256_DIGEST_SIZE];
  sha256_digest(&context, SHA256_DIGEST_SIZE, digest);
  static const char kHex[] = "0123456789abcdef";
  std::string hex;
  for (const std::uint8_t byte : digest) {
    hex += kHex[byte >> 4];
    hex += kHex[byte & 15];
  }
  return hex;
}

}  // namespace

std::uint64_t Sha256Prefix64(std::string_view bytes) {
  return std::stoull(Sha256Hex(bytes).substr(0, 16), nullptr, 16);
}

std::string Sha256Hex(std::string_view bytes) {
  sha256_ctx context;
  sha256_init(&context);
  sha256_update(&context, bytes.size(), reinterpret_cast<const std::uint8_t*>(bytes.data()));
  return Hex(context);
}

std::optional<std::string> FileSha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  sha256_ctx context;
  sha256_init(&context);
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    sha256_update(&context, static_cast<std::size_t>(in.gcount()),
                  reinterpret_cast<const std::uint8_t*>(buffer));
  }
  if (in.bad()) return std::nullopt;
  return Hex(context);
}

}  // namespace moorsim
