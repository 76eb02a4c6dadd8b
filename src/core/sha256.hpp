// SHA-256 (FIPS 180-4) of a byte string, for model content hashes.
#pragma once

#include <string>
#include <string_view>

namespace hipair::detail {

/// Lower-case hexadecimal SHA-256 digest of `bytes`.
std::string sha256_hex(std::string_view bytes);

}  // namespace hipair::detail
