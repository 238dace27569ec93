// SHA-256 (FIPS 180-4, through Nettle) as lower-case hex, so that outputs name exactly the
// files and code that produced them: a plugin library, the inputs of a campaign.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace moorsim {

/// SHA-256 of `bytes`: 64 lower-case hex digits.
std::string Sha256Hex(std::string_view bytes);

/// The first 64 bits of SHA-256 of `bytes`: a fingerprint of a model or an input.
std::uint64_t Sha256Prefix64(std::string_view bytes);

/// SHA-256 of the file at `path`; nullopt if it cannot be opened or read.
std::optional<std::string> FileSha256(const std::string& path);

}  // namespace moorsim
