#include "lub/sweep/hash.hpp"

#include <openssl/evp.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace lub::sweep {

std::string sha256_hex(const std::string& data) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(data.data(), data.size(), digest, &size, EVP_sha256(), nullptr) != 1 || size != 32)
    throw std::runtime_error("SHA-256 (OpenSSL EVP_Digest) failed");
  static const char* hex = "0123456789abcdef";
  std::string out;
  out.reserve(2 * size);
  for (unsigned int i = 0; i < size; ++i) {
    out.push_back(hex[digest[i] >> 4]);
    out.push_back(hex[digest[i] & 0xf]);
  }
  return out;
}

namespace {

/// Integral floating-point values become integers (5000.0 → 5000): a scene reads both
/// the same way, and a grid that writes 5000 must find the base scene's 5000.0.
nlohmann::json normalized(const nlohmann::json& v) {
  if (v.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (auto it = v.begin(); it != v.end(); ++it) out[it.key()] = normalized(it.value());
    return out;
  }
  if (v.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& x : v) out.push_back(normalized(x));
    return out;
  }
  if (v.is_number_float()) {
    const double x = v.get<double>();
    if (std::isfinite(x) && std::floor(x) == x && std::fabs(x) <= 9007199254740992.0 && !(x == 0.0 && std::signbit(x)))
      return static_cast<std::int64_t>(x);
  }
  if (v.is_number_unsigned() && v.get<std::uint64_t>() <= 9223372036854775807ULL)
    return static_cast<std::int64_t>(v.get<std::uint64_t>());
  return v;
}

}  // namespace

std::string canonical_json(const nlohmann::json& doc) {
  return normalized(doc).dump(-1, ' ', false, nlohmann::json::error_handler_t::strict);
}

std::string scene_hash(const nlohmann::json& scene) { return sha256_hex(canonical_json(scene)); }

}  // namespace lub::sweep
